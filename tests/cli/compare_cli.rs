//! `lanecast compare` through the real binary: where the unexcused pixels are, in the report
//! and in the diff picture.

use crate::common;

use common::*;
use std::path::Path;

/// The (x, y) pairs of the report's "unexcused at" line.
fn listed(report: &str) -> Vec<(u32, u32)> {
    let line = report
        .lines()
        .find(|l| l.contains("unexcused at"))
        .unwrap_or_else(|| panic!("no unexcused list: {report}"));
    let pairs = line.split_once(": ").expect("list after the colon").1;
    pairs
        .split(") (")
        .map(|p| {
            let p = p.trim_matches(|c| c == '(' || c == ')');
            let (x, y) = p.split_once(", ").expect("x, y");
            (x.parse().unwrap(), y.parse().unwrap())
        })
        .collect()
}

/// A method that fails on the stress grid (Moller-Trumbore's grazing misses) gets its first 20
/// unexcused pixels listed, and each is marked red in the diff picture with a red outline four
/// pixels out, so a lone pixel is seen at full size.
#[test]
fn unexcused_pixels_are_listed_and_outlined() {
    let dir = TempDir::new("compare-list");
    let grid = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress/grid.sc");
    dir.copy_in(&grid, "grid.sc");
    let o = run(
        &dir.path,
        &["compare", "-i", "grid.sc", "--method", "mt", "-o", "d.png"],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    let pixels = listed(&out);
    assert_eq!(pixels.len(), 20, "{out}");
    assert!(out.contains("first 20"), "{out}");
    let img = image::open(dir.join("d.png")).unwrap().to_rgb8();
    let red = image::Rgb([255, 0, 0]);
    for &(x, y) in &pixels {
        assert_eq!(*img.get_pixel(x, y), red, "({x}, {y})");
        // the outline's right or left side, whichever lies in the image
        let side = if x + 4 < img.width() { x + 4 } else { x - 4 };
        assert_eq!(*img.get_pixel(side, y), red, "outline of ({x}, {y})");
    }
}

/// `compare` of the default precision, auto, on the huge-sphere stress scene: the report counts
/// the pixels re-decided in f64, and the diff picture paints exactly those (where they agree
/// with the oracle) magenta. `--precision f32` re-decides nothing and paints nothing magenta.
#[test]
fn redecided_pixels_are_counted_and_painted() {
    let dir = TempDir::new("compare-auto");
    let ground = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress/ground.sc");
    dir.copy_in(&ground, "ground.sc");
    let magenta = |name: &str| {
        let img = image::open(dir.join(name)).unwrap().to_rgb8();
        img.pixels().filter(|p| p.0 == [255, 0, 255]).count()
    };
    let o = run(&dir.path, &["compare", "-i", "ground.sc", "-o", "auto.png"]);
    assert_success(&o, "compare, auto");
    let out = stdout(&o);
    let line = out
        .lines()
        .find(|l| l.starts_with("re-decided"))
        .unwrap_or_else(|| panic!("no re-decided line: {out}"));
    let n: usize = line.split_whitespace().nth(1).unwrap().parse().unwrap();
    assert!(n > 1000, "{line}");
    assert!(out.contains("unexcused 0"), "{out}");
    assert_eq!(magenta("auto.png"), n, "{out}");
    let o = run(
        &dir.path,
        &[
            "compare",
            "-i",
            "ground.sc",
            "--precision",
            "f32",
            "-o",
            "f32.png",
        ],
    );
    assert_success(&o, "compare, f32");
    assert!(!stdout(&o).contains("re-decided"), "{}", stdout(&o));
    assert_eq!(magenta("f32.png"), 0);
}
