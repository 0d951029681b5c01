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

#[test]
fn an_acceleration_a_lab_method_cannot_use_is_refused() {
    let dir = with_scene("flags-method-accel");
    for (extra, words) in [
        (
            &["--method", "mt", "--accel", "bvh"][..],
            &[
                "--accel bvh",
                "--method mt",
                "brute-force",
                "no acceleration",
            ][..],
        ),
        (
            &["--method", "watertight", "--accel", "tiles"],
            &["--accel tiles", "--method watertight"],
        ),
    ] {
        refused(&dir, &render_args(extra), words);
        refused(&dir, &compare_args(extra), words);
    }
    // none and auto are what the lab's driver does: accepted, and the record says none
    for accel in ["none", "auto"] {
        let v = stats_of(&dir, &["--method", "mt", "--accel", accel]);
        assert_eq!(
            (v["method"].as_str(), v["accel"].as_str()),
            (Some("mt"), Some("none"))
        );
        accepted(&dir, &compare_args(&["--method", "mt", "--accel", accel]));
    }
}

#[test]
fn a_precision_that_contradicts_the_method_is_refused() {
    let dir = with_scene("flags-method-precision");
    refused(
        &dir,
        &render_args(&["--method", "f64x4", "--precision", "f32"]),
        &["--precision f32", "--method f64x4", "f64"],
    );
    refused(
        &dir,
        &render_args(&["--method", "mt", "--precision", "f64"]),
        &["--precision f64", "--method mt", "f32"],
    );
    refused(
        &dir,
        &compare_args(&["--method", "world-f32", "--precision", "f64"]),
        &["--precision f64", "--method world-f32"],
    );
    // the agreeing pairs run
    for extra in [
        &["--method", "f64x4", "--precision", "f64"][..],
        &["--method", "f64x4"],
        &["--precision", "f64"],
        &["--method", "mt", "--precision", "f32"],
        &["--method", "eplane+stable", "--precision", "f64"],
    ] {
        let v = stats_of(&dir, extra);
        let want = if extra.contains(&"mt") { "mt" } else { "f64x4" };
        assert_eq!(v["method"].as_str(), Some(want), "{extra:?}");
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
fn a_lab_method_with_a_scalar_kernel_is_refused() {
    let dir = with_scene("flags-kernel-method");
    for kernel in ["scalar", "scalar-f32"] {
        for method in ["mt", "f64x4"] {
            refused(
                &dir,
                &render_args(&["--kernel", kernel, "--method", method]),
                &[&format!("--method {method}"), &format!("--kernel {kernel}")],
            );
        }
        // the default method, typed, is what the scalar kernels compute
        accepted(
            &dir,
            &render_args(&["--kernel", kernel, "--method", "eplane+stable"]),
        );
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
        // the f64x4 method, by --precision and by --method; the record names what ran
        for m in [&["--precision", "f64"][..], &["--method", "f64x4"]] {
            let v = stats_of(
                &dir,
                &[m, &["--accel", accel, "--threads", "2"][..]].concat(),
            );
            assert_eq!(v["threads"].as_u64(), Some(2), "{m:?} {accel}");
            assert_eq!(v["precision"], "f64");
            if accel == "bvh" || accel == "tiles" {
                assert_eq!(v["accel"], accel);
            }
            accepted(&dir, &compare_args(&[m, &["--accel", accel][..]].concat()));
        }
    }
    // every acceleration with the simd kernel and the default method
    for accel in ["auto", "none", "tiles", "bvh"] {
        accepted(&dir, &render_args(&["--kernel", "simd", "--accel", accel]));
        accepted(&dir, &compare_args(&["--accel", accel]));
    }
}

#[test]
fn threads_a_one_thread_method_cannot_use_are_refused() {
    let dir = with_scene("flags-threads");
    let msg = refused(
        &dir,
        &render_args(&["--method", "mt", "--threads", "2"]),
        &["--threads 2", "--method mt", "1 thread,", "2 threads"],
    );
    assert!(!msg.contains("1 threads"), "{msg}");
    // one thread is what runs: accepted, and recorded
    let v = stats_of(&dir, &["--method", "mt", "--threads", "1"]);
    assert_eq!(v["threads"].as_u64(), Some(1));
    // without --threads the method still runs on one thread, and the record says so
    let v = stats_of(&dir, &["--method", "naive"]);
    assert_eq!(v["threads"].as_u64(), Some(1));
    // the default method uses them
    let v = stats_of(&dir, &["--threads", "2"]);
    assert_eq!(v["threads"].as_u64(), Some(2));
    // compare: the oracle runs on the pool, so --threads applies there
    accepted(&dir, &compare_args(&["--method", "mt", "--threads", "2"]));
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

/// `-time`, `--stats` and `compare` said "method auto" for the default run, a name `--method`
/// refuses: precision and method are reported under their own names, each a value its flag
/// accepts ("precision auto, method eplane+stable"), and the reported method, given back to
/// `--method`, runs.
#[test]
fn precision_and_method_are_reported_under_their_own_names() {
    let dir = with_scene("flags-report-names");
    for (extra, precision, method) in [
        (&[][..], "auto", "eplane+stable"),
        (&["--precision", "f32"], "f32", "eplane+stable"),
        (&["--precision", "f64"], "f64", "f64x4"),
        (&["--method", "mt"], "f32", "mt"),
        (&["--kernel", "scalar"], "f64", "eplane+stable"),
        (&["--kernel", "scalar-f32"], "f32", "eplane+stable"),
    ] {
        let v = stats_of(&dir, extra);
        assert_eq!(v["precision"].as_str(), Some(precision), "{extra:?}");
        assert_eq!(v["method"].as_str(), Some(method), "{extra:?}");

        let mut args = render_args(extra);
        args.push("-time");
        let text = accepted(&dir, &args);
        assert!(
            text.contains(&format!("precision {precision}, method {method},")),
            "{extra:?}: {text}"
        );
        assert!(!text.contains("method auto"), "{extra:?}: {text}");

        // the name reported is one --method takes
        let mut again = render_args(extra);
        if !extra.contains(&"--method") {
            again.extend(["--method", method]);
        }
        accepted(&dir, &again);

        if !extra.contains(&"--kernel") {
            let args = compare_args(extra);
            let o = run(&dir.path, &args);
            assert_success(&o, &args.join(" "));
            let report = stdout(&o);
            assert!(
                report.contains(&format!("\nprecision   {precision}\n")),
                "{extra:?}: {report}"
            );
            assert!(
                report.contains(&format!(
                    "\nmethod      {method} against the f64 scalar oracle"
                )),
                "{extra:?}: {report}"
            );
        }
    }
}
