//! `lanecast compare` through the real binary: where the unexcused pixels are, in the report
//! and in the diff picture.

use crate::common;

use common::*;
use std::path::Path;

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
