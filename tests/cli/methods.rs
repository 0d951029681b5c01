//! `--precision` on the command line: f64 packets match the oracle; a bad precision, and the
//! lab's `--method`, are refused. The lab's methods render through `lab-render`
//! (lab/tests/lab_render.rs).

use crate::common;

use common::*;

#[test]
fn f64_precision_matches_the_oracle_ids() {
    let dir = TempDir::new("precision");
    dir.copy_in(&seed_scene(2), "s.sc");
    let a = run(
        &dir.path,
        &[
            "-i",
            "s.sc",
            "-o",
            "a.png",
            "--precision",
            "f64",
            "--ids",
            "a.npy",
        ],
    );
    let b = run(
        &dir.path,
        &[
            "-i", "s.sc", "-o", "b.png", "--kernel", "scalar", "--ids", "b.npy",
        ],
    );
    assert_success(&a, "f64 packets");
    assert_success(&b, "oracle");
    let (ia, ib) = (
        std::fs::read(dir.join("a.npy")).unwrap(),
        std::fs::read(dir.join("b.npy")).unwrap(),
    );
    assert_eq!(ia, ib, "f64x4 packets give the oracle's ids");
}

#[test]
fn a_bad_precision_and_a_method_are_usage_errors() {
    let dir = TempDir::new("methods-bad");
    dir.copy_in(&seed_scene(1), "s.sc");
    for args in [
        &["--method", "mt"][..],
        &["--method", "eplane+stable", "--kernel", "scalar"][..],
        &["--precision", "f16"][..],
    ] {
        let mut all = vec!["-i", "s.sc", "-o", "o.png"];
        all.extend_from_slice(args);
        let out = run(&dir.path, &all);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(!dir.join("o.png").exists());
    }
}
