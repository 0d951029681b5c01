//! `lab-render` through the real binary: every method renders a seed scene and is compared
//! with the oracle; a method that fails gets its unexcused pixels listed and outlined; bad
//! arguments are usage errors. (These ran through `lanecast --method` and `lanecast compare
//! --method` before the methods moved into the lab.)

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// The workspace root (scenes/ lives there), beside this crate.
fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ has a parent")
        .to_path_buf()
}

/// A fresh folder under the target directory's temp space.
fn temp_dir(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("lab-render-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn lab_render(cwd: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_lab-render"))
        .current_dir(cwd)
        .args(args)
        .output()
        .expect("lab-render runs")
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

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

#[test]
fn every_method_renders_and_compares_on_a_seed_scene() {
    let dir = temp_dir("methods");
    let scene = root().join("scenes/scene4.sc");
    let scene = scene.to_str().unwrap();
    for m in [
        "eplane+stable",
        "mt",
        "watertight",
        "plane",
        "naive",
        "world-f32",
        "f64x4",
        "auto",
    ] {
        let out = lab_render(
            &dir,
            &[
                "-i", scene, "-size", "96x72", "--method", m, "--image", "o.png", "--ids",
                "ids.npy",
            ],
        );
        assert!(out.status.success(), "{m}: {}", stderr(&out));
        let report = stdout(&out);
        assert!(report.contains(&format!("\nmethod      {m} (")), "{report}");
        assert!(
            report.contains("against     the f64 scalar oracle"),
            "{report}"
        );
        let img = std::fs::read(dir.join("o.png")).unwrap();
        assert_eq!(&img[1..4], b"PNG", "{m}");
        // (96, 72) int32: the .npy header, then 4 bytes a pixel
        let ids = std::fs::read(dir.join("ids.npy")).unwrap();
        assert!(ids.len() > 96 * 72 * 4, "{m}");
        std::fs::remove_file(dir.join("o.png")).unwrap();
    }
}

/// A method that fails on the stress grid (Moller-Trumbore's grazing misses) gets its first 20
/// unexcused pixels listed, each marked red in the diff picture with a red outline four pixels
/// out, so a lone pixel is seen at full size; past `--max-mismatch-ppm` it exits 1.
#[test]
fn unexcused_pixels_are_listed_and_outlined() {
    let dir = temp_dir("list");
    let grid = root().join("scenes/stress/grid.sc");
    let o = lab_render(
        &dir,
        &[
            "-i",
            grid.to_str().unwrap(),
            "--method",
            "mt",
            "-o",
            "d.png",
            "--max-mismatch-ppm",
            "0",
        ],
    );
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let out = stdout(&o);
    let pixels = listed(&out);
    assert_eq!(pixels.len(), 20, "{out}");
    assert!(out.contains("first 20"), "{out}");
    let png = std::fs::read(dir.join("d.png")).unwrap();
    let red = [255, 0, 0];
    let (w, rgb) = decode_rgb(&png);
    for &(x, y) in &pixels {
        let at = |x: u32, y: u32| {
            let i = (y * w + x) as usize * 3;
            [rgb[i], rgb[i + 1], rgb[i + 2]]
        };
        assert_eq!(at(x, y), red, "({x}, {y})");
        // the outline's right or left side, whichever lies in the image
        let side = if x + 4 < w { x + 4 } else { x - 4 };
        assert_eq!(at(side, y), red, "outline of ({x}, {y})");
    }
}

/// The width and RGB bytes of a PNG.
fn decode_rgb(png: &[u8]) -> (u32, Vec<u8>) {
    let img = image::load_from_memory(png).expect("a PNG").to_rgb8();
    (img.width(), img.into_raw())
}

#[test]
fn bad_arguments_are_usage_errors() {
    let dir = temp_dir("bad");
    let scene = root().join("scenes/scene1.sc");
    let scene = scene.to_str().unwrap();
    for args in [
        &["-i", scene, "--method", "bogus"][..],
        &["-i", scene, "--method", "mt", "--accel", "bvh"],
        &["--method", "mt"],
        &["-i", scene, "--nonsense", "1"],
    ] {
        let o = lab_render(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(
            stderr(&o).starts_with("lab-render: error: "),
            "{}",
            stderr(&o)
        );
    }
}
