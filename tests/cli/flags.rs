//! Flag combinations through the real binary (README "Valid flag combinations"): a flag that
//! cannot apply to the others is refused with exit 2 before any work, by a message that names
//! it, says why, and names no flag the user did not type; the consistent combinations run.

use crate::common;

use common::*;
use std::fs;

/// Every flag a combination message may name, longest first so that `--color-mode` is not
/// also counted as some shorter flag.
const FLAGS: [&str; 9] = [
    "--max-mismatch-ppm",
    "--color-mode",
    "--precision",
    "--threads",
    "--method",
    "--kernel",
    "--repeat",
    "--accel",
    "--seed",
];

/// A temp folder holding seed scene 4 (spheres, triangles and quads) as `s.sc`.
fn with_scene(name: &str) -> TempDir {
    let dir = TempDir::new(name);
    dir.copy_in(&seed_scene(4), "s.sc");
    dir
}

/// The render command's arguments: the scene, a small size, `o.png`, then `extra`.
fn render_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut all = vec!["-i", "s.sc", "-o", "o.png", "-size", "48x32"];
    all.extend_from_slice(extra);
    all
}

/// The compare command's arguments: the scene, a small size, then `extra`.
fn compare_args<'a>(extra: &[&'a str]) -> Vec<&'a str> {
    let mut all = vec!["compare", "-i", "s.sc", "-size", "48x32"];
    all.extend_from_slice(extra);
    all
}

/// Runs `args` in `dir` and asserts: exit 2, one `lanecast: error:` line holding every one of
/// `words`, every flag the message names among the typed arguments (`-cm` counts as typed
/// `--color-mode` only when spelled so), and nothing written to the folder. Returns the message.
fn refused(dir: &TempDir, args: &[&str], words: &[&str]) -> String {
    let before = dir.entries();
    let o = run(&dir.path, args);
    let err = stderr(&o);
    assert_eq!(o.status.code(), Some(2), "{args:?}: {err}");
    assert!(err.starts_with("lanecast: error: "), "{args:?}: {err}");
    for w in words {
        assert!(err.contains(w), "{args:?}: message lacks {w:?}: {err}");
    }
    let mut rest = err.clone();
    for flag in FLAGS {
        if rest.contains(flag) {
            assert!(
                args.iter()
                    .any(|a| a == &flag || a.starts_with(&format!("{flag}="))),
                "{args:?}: message names {flag}, which was not typed: {err}"
            );
            rest = rest.replace(flag, "");
        }
    }
    assert!(
        !err.contains("-cm") || args.contains(&"-cm"),
        "{args:?}: names -cm: {err}"
    );
    assert!(!err.contains("panicked"), "{args:?}: {err}");
    assert_eq!(dir.entries(), before, "{args:?}: wrote something");
    err
}

/// Runs `args` in `dir` and asserts success; returns stderr.
fn accepted(dir: &TempDir, args: &[&str]) -> String {
    let o = run(&dir.path, args);
    assert_success(&o, &args.join(" "));
    stderr(&o)
}

/// The `--stats` record of a render with `extra`.
fn stats_of(dir: &TempDir, extra: &[&str]) -> serde_json::Value {
    let mut all = render_args(extra);
    all.extend(["--stats", "run.json"]);
    accepted(dir, &all);
    let text = fs::read_to_string(dir.join("run.json")).unwrap();
    let v = serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"));
    fs::remove_file(dir.join("run.json")).unwrap();
    fs::remove_file(dir.join("o.png")).unwrap();
    v
}

/// `--method` is the accuracy lab's (`lab-render`), not the product's: refused as an unknown
/// argument by render and compare alike, naming it.
#[test]
fn method_is_the_labs_and_refused_here() {
    let dir = with_scene("flags-method");
    for m in ["mt", "eplane+stable", "f64x4"] {
        refused(
            &dir,
            &render_args(&["--method", m]),
            &["--method", "lab-render"],
        );
        refused(
            &dir,
            &compare_args(&["--method", m]),
            &["--method", "lab-render"],
        );
    }
}

#[test]
fn precision_with_a_scalar_kernel_must_be_the_kernels_own() {
    let dir = with_scene("flags-kernel-precision");
    // the kernel's own precision is accepted and renders exactly the kernel's image
    for (kernel, own) in [("scalar", "f64"), ("scalar-f32", "f32")] {
        accepted(&dir, &render_args(&["--kernel", kernel, "--ids", "a.npy"]));
        accepted(
            &dir,
            &render_args(&["--kernel", kernel, "--precision", own, "--ids", "b.npy"]),
        );
        assert_eq!(
            fs::read(dir.join("a.npy")).unwrap(),
            fs::read(dir.join("b.npy")).unwrap(),
            "--kernel {kernel} --precision {own}"
        );
        for f in ["a.npy", "b.npy", "o.png"] {
            fs::remove_file(dir.join(f)).unwrap();
        }
    }
    // the other precision is refused, naming --precision and --kernel, never --method
    for (kernel, other) in [("scalar", "f32"), ("scalar-f32", "f64")] {
        let msg = refused(
            &dir,
            &render_args(&["--kernel", kernel, "--precision", other]),
            &[
                &format!("--precision {other}"),
                &format!("--kernel {kernel}"),
            ],
        );
        assert!(!msg.contains("--method"), "{msg}");
    }
}

#[test]
fn every_kernel_and_precision_takes_every_acceleration() {
    let dir = with_scene("flags-kernel-accel");
    for accel in ["auto", "none", "tiles", "bvh"] {
        for kernel in ["scalar", "scalar-f32"] {
            let v = stats_of(
                &dir,
                &["--kernel", kernel, "--accel", accel, "--threads", "2"],
            );
            assert_eq!(v["threads"].as_u64(), Some(2), "{kernel} {accel}");
        }
        // every precision of the packets; the record names what ran
        for m in [
            &["--precision", "f64"][..],
            &["--precision", "f32"],
            &["--precision", "auto"],
        ] {
            let v = stats_of(
                &dir,
                &[m, &["--accel", accel, "--threads", "2"][..]].concat(),
            );
            assert_eq!(v["threads"].as_u64(), Some(2), "{m:?} {accel}");
            assert_eq!(v["precision"], m[1]);
            if accel == "bvh" || accel == "tiles" {
                assert_eq!(v["accel"], accel);
            }
            accepted(&dir, &compare_args(&[m, &["--accel", accel][..]].concat()));
        }
    }
    // every acceleration with the simd kernel and the default precision
    for accel in ["auto", "none", "tiles", "bvh"] {
        accepted(&dir, &render_args(&["--kernel", "simd", "--accel", accel]));
        accepted(&dir, &compare_args(&["--accel", accel]));
    }
}

/// Every kernel and precision renders on the pool's threads, and the record says how many.
#[test]
fn every_precision_renders_on_the_threads_asked_for() {
    let dir = with_scene("flags-threads");
    for p in ["auto", "f32", "f64"] {
        let v = stats_of(&dir, &["--precision", p, "--threads", "2"]);
        assert_eq!(v["threads"].as_u64(), Some(2), "{p}");
        let v = stats_of(&dir, &["--precision", p, "--threads", "1"]);
        assert_eq!(v["threads"].as_u64(), Some(1), "{p}");
        accepted(&dir, &compare_args(&["--precision", p, "--threads", "2"]));
    }
}

#[test]
fn a_seed_with_the_ordered_palette_or_shade_is_refused() {
    let dir = with_scene("flags-seed");
    refused(
        &dir,
        &render_args(&["-cm", "ordered", "--seed", "3"]),
        &["--seed 3", "-cm ordered", "random"],
    );
    let msg = refused(
        &dir,
        &render_args(&["--color-mode", "ordered", "--seed", "0"]),
        &["--seed 0", "--color-mode ordered"],
    );
    assert!(!msg.contains("-cm"), "{msg}");
    refused(
        &dir,
        &render_args(&["--color-mode=ordered", "--seed=7"]),
        &["--seed 7", "--color-mode ordered"],
    );
    // shade's grey has no seed either
    refused(
        &dir,
        &render_args(&["-cm", "shade", "--seed", "0"]),
        &["--seed 0", "-cm shade", "grey", "random"],
    );
    // the seed applies to the random colours, typed or by default
    for extra in [
        &["--seed", "3"][..],
        &["-cm", "random", "--seed", "3"],
        &["-cm", "ordered"],
        &["-cm", "shade", "-cv", "log"],
    ] {
        accepted(&dir, &render_args(extra));
    }
}

#[test]
fn out_of_range_values_and_flags_of_the_other_command_are_refused() {
    let dir = with_scene("flags-values");
    refused(&dir, &render_args(&["--repeat", "0"]), &["--repeat", "0"]);
    refused(
        &dir,
        &render_args(&["--repeat", "10001"]),
        &["--repeat", "10001"],
    );
    refused(
        &dir,
        &compare_args(&["--max-mismatch-ppm", "nan"]),
        &["--max-mismatch-ppm NaN"],
    );
    refused(
        &dir,
        &compare_args(&["--max-mismatch-ppm=-1"]),
        &["--max-mismatch-ppm -1"],
    );
    accepted(&dir, &compare_args(&["--max-mismatch-ppm", "inf"]));
    // compare renders the simd kernel against the oracle with its own colours: the render
    // command's flags are refused there, saying why
    for extra in [
        &["--kernel", "scalar"][..],
        &["--seed", "1"],
        &["--repeat", "2"],
        &["-cm", "ordered"],
        &["--ids", "i.npy"],
    ] {
        refused(
            &dir,
            &compare_args(extra),
            &[extra[0], "applies to the render command"],
        );
    }
    // clap's messages name a single-dash option as it was typed
    let msg = refused(
        &dir,
        &render_args(&["-cm", "rainbow"]),
        &["'rainbow'", "-cm"],
    );
    assert!(!msg.contains("--color-mode"), "{msg}");
    let msg = refused(&dir, &render_args(&["-fov", "200"]), &["-fov 200"]);
    assert!(!msg.contains("--fov"), "{msg}");
    // and compare's own on the render command
    refused(
        &dir,
        &render_args(&["--max-mismatch-ppm", "3"]),
        &["--max-mismatch-ppm: applies to compare only"],
    );
}

/// `-time`, `--stats` and `compare` report the precision that ran, as `--precision` names it
/// (a scalar kernel's own), and no intersection method: those are the lab's (`lab-render`).
#[test]
fn the_precision_is_reported_and_no_method() {
    let dir = with_scene("flags-report-names");
    for (extra, precision) in [
        (&[][..], "auto"),
        (&["--precision", "f32"], "f32"),
        (&["--precision", "f64"], "f64"),
        (&["--kernel", "scalar"], "f64"),
        (&["--kernel", "scalar-f32"], "f32"),
    ] {
        let v = stats_of(&dir, extra);
        assert_eq!(v["precision"].as_str(), Some(precision), "{extra:?}");
        assert!(v.get("method").is_none(), "{extra:?}: {v}");

        let mut args = render_args(extra);
        args.push("-time");
        let text = accepted(&dir, &args);
        assert!(
            text.contains(&format!("precision {precision}, accel ")),
            "{extra:?}: {text}"
        );
        assert!(!text.contains("method"), "{extra:?}: {text}");

        if !extra.contains(&"--kernel") {
            let args = compare_args(extra);
            let o = run(&dir.path, &args);
            assert_success(&o, &args.join(" "));
            let report = stdout(&o);
            assert!(
                report.contains(&format!(
                    "\nprecision   {precision}\nagainst     the f64 scalar oracle\n"
                )),
                "{extra:?}: {report}"
            );
            assert!(!report.contains("method"), "{extra:?}: {report}");
        }
    }
}
