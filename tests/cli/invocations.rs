//! The seven original invocations, the long forms, BMP.

use super::*;

#[test]
fn plain_input_writes_png_beside_it_at_640x480() {
    let dir = with_scene1("plain");
    ok(&dir, &["-i", "scene1.sc"]);
    let img = image_of(&dir.join("scene1.png"), 640, 480);
    assert!(
        img.pixels().any(|p| p.0 != [0, 0, 0]),
        "scene1 renders something"
    );
    assert!(
        img.pixels().any(|p| p.0 == [0, 0, 0]),
        "and some background"
    );
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc"]);
    // "beside the input" is the input's folder, not the working folder
    fs::create_dir(dir.join("sub")).unwrap();
    dir.copy_in(&seed_scene(1), "sub/s.sc");
    ok(&dir, &["-i", "sub/s.sc", "-size", "64x48"]);
    image_of(&dir.join("sub/s.png"), 64, 48);
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc", "sub"]);
}

#[test]
fn explicit_output() {
    let dir = with_scene1("output");
    ok(&dir, &["-i", "scene1.sc", "-o", "scene1.png"]);
    image_of(&dir.join("scene1.png"), 640, 480);
    // in a subfolder too, and the default name is not written
    fs::create_dir(dir.join("sub")).unwrap();
    ok(&dir, &["-i", "scene1.sc", "-o", "sub/other.png"]);
    image_of(&dir.join("sub/other.png"), 640, 480);
    assert_eq!(dir.entries(), ["scene1.png", "scene1.sc", "sub"]);
}

#[test]
fn size_option() {
    let dir = with_scene1("size");
    ok(&dir, &["-i", "scene1.sc", "-size", "800x600"]);
    image_of(&dir.join("scene1.png"), 800, 600);
    ok(&dir, &["-i", "scene1.sc", "-size", "37x5", "-o", "odd.png"]);
    image_of(&dir.join("odd.png"), 37, 5);
}

#[test]
fn fov_option_changes_the_view() {
    let dir = with_scene1("fov");
    ok(&dir, &["-i", "scene1.sc", "-o", "default.png"]);
    ok(&dir, &["-i", "scene1.sc", "-fov", "80", "-o", "fov80.png"]);
    let a = image_of(&dir.join("default.png"), 640, 480);
    let b = image_of(&dir.join("fov80.png"), 640, 480);
    assert_ne!(a, b, "-fov 80 renders a different view");
    // A wider view shows the same objects smaller: fewer covered pixels.
    let covered = |img: &RgbImage| img.pixels().filter(|p| p.0 != [0, 0, 0]).count();
    assert!(
        covered(&b) < covered(&a),
        "{} vs {}",
        covered(&b),
        covered(&a)
    );
}

#[test]
fn ordered_colour_mode_uses_the_palette() {
    let dir = with_scene1("ordered");
    ok(&dir, &["-i", "scene1.sc", "-o", "random.png"]);
    ok(
        &dir,
        &["-i", "scene1.sc", "-cm", "ordered", "-o", "ordered.png"],
    );
    let random = image_of(&dir.join("random.png"), 640, 480);
    let ordered = image_of(&dir.join("ordered.png"), 640, 480);
    assert_ne!(random, ordered);
    // Same coverage: only colours change.
    for (a, b) in random.pixels().zip(ordered.pixels()) {
        assert_eq!(a.0 == [0, 0, 0], b.0 == [0, 0, 0]);
    }
    // Every lit pixel is a palette colour dimmed by one factor b in [B_MIN, 1]: channels that
    // are zero in the palette colour stay zero, the others scale together (within rounding).
    let palette = lanecast::experimental::shade::PALETTE;
    let is_dimmed = |p: [u8; 3], c: [u8; 3]| {
        let k = (0..3).max_by_key(|&k| c[k]).unwrap();
        let b = p[k] as f64 / c[k] as f64;
        (lanecast::experimental::shade::B_MIN - 0.01..=1.0).contains(&b)
            && (0..3).all(|k| (p[k] as f64 - c[k] as f64 * b).abs() <= 1.0)
    };
    for p in ordered.pixels().filter(|p| p.0 != [0, 0, 0]) {
        assert!(
            palette.iter().any(|&c| is_dimmed(p.0, c)),
            "{:?} is not a dimmed palette colour",
            p.0
        );
    }
}

#[test]
fn log_colour_variation_changes_brightness_only() {
    let dir = with_scene1("log");
    ok(&dir, &["-i", "scene1.sc", "-o", "linear.png"]);
    ok(&dir, &["-i", "scene1.sc", "-cv", "log", "-o", "log.png"]);
    let lin = image_of(&dir.join("linear.png"), 640, 480);
    let log = image_of(&dir.join("log.png"), 640, 480);
    assert_ne!(lin, log);
    for (a, b) in lin.pixels().zip(log.pixels()) {
        assert_eq!(a.0 == [0, 0, 0], b.0 == [0, 0, 0]);
    }
}

#[test]
fn time_option_reports_every_phase() {
    let dir = with_scene1("time");
    let o = ok(&dir, &["-i", "scene1.sc", "-time"]);
    image_of(&dir.join("scene1.png"), 640, 480);
    let err = stderr(&o);
    for word in ["parse", "setup", "render", "write", "Mrays/s"] {
        assert!(err.contains(word), "-time output lacks {word:?}: {err}");
    }
    // without -time, nothing on stderr
    let o = ok(&dir, &["-i", "scene1.sc", "-o", "quiet.png"]);
    assert!(o.stderr.is_empty(), "{}", stderr(&o));
}

#[test]
fn gnu_long_forms_match_the_single_dash_forms() {
    let dir = with_scene1("long");
    let short = ok(
        &dir,
        &[
            "-i",
            "scene1.sc",
            "-o",
            "short.png",
            "-size",
            "320x200",
            "-fov",
            "45",
            "-cm",
            "ordered",
            "-cv",
            "log",
            "-time",
        ],
    );
    let long = ok(
        &dir,
        &[
            "--input",
            "scene1.sc",
            "--output",
            "long.png",
            "--size",
            "320x200",
            "--fov",
            "45",
            "--color-mode",
            "ordered",
            "--color-variation",
            "log",
            "--time",
        ],
    );
    let a = image_of(&dir.join("short.png"), 320, 200);
    let b = image_of(&dir.join("long.png"), 320, 200);
    assert_eq!(a, b);
    for o in [&short, &long] {
        assert!(stderr(o).contains("Mrays/s"), "{}", stderr(o));
    }
    // `=` forms too
    ok(
        &dir,
        &[
            "--input=scene1.sc",
            "--output=eq.png",
            "--size=320x200",
            "--fov=45",
            "--color-mode=ordered",
            "--color-variation=log",
        ],
    );
    assert_eq!(image_of(&dir.join("eq.png"), 320, 200), a);
}

#[test]
fn bmp_output_has_the_same_pixels_as_png() {
    let dir = with_scene1("bmp");
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "out.bmp"],
    );
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "out.png"],
    );
    let bytes = fs::read(dir.join("out.bmp")).unwrap();
    assert_eq!(&bytes[..2], b"BM", "a BMP file");
    assert_eq!(
        image_of(&dir.join("out.bmp"), 101, 67),
        image_of(&dir.join("out.png"), 101, 67)
    );
    // extension case does not matter
    ok(
        &dir,
        &["-i", "scene1.sc", "-size", "101x67", "-o", "upper.BMP"],
    );
    assert_eq!(&fs::read(dir.join("upper.BMP")).unwrap()[..2], b"BM");
}
