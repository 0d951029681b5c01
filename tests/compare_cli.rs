//! `lanecast compare` through the real binary: where the unexcused pixels are, in the report
//! and in the diff picture.

mod common;

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
