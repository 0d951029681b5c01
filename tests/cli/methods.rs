//! `--method` and `--precision` on the command line: every lab method renders through the
//! binary and `compare` measures it; f64 packets match the oracle; invalid pairings are refused.

use crate::common;

use common::*;

#[test]
fn every_method_renders_and_compares_on_a_seed_scene() {
    let dir = TempDir::new("methods");
    dir.copy_in(&seed_scene(4), "s.sc");
    for m in [
        "eplane+stable",
        "mt",
        "watertight",
        "plane",
        "naive",
        "world-f32",
        "f64x4",
    ] {
        let out = run(
            &dir.path,
            &["-i", "s.sc", "-o", "o.png", "-size", "96x72", "--method", m],
        );
        assert_success(&out, m);
        let img = image::open(dir.join("o.png")).unwrap();
        assert_eq!((img.width(), img.height()), (96, 72), "{m}");
        let cmp = run(
            &dir.path,
            &["compare", "-i", "s.sc", "-size", "96x72", "--method", m],
        );
        assert_success(&cmp, m);
        assert!(
            stdout(&cmp).contains(&format!("method      {m} against")),
            "{}",
            stdout(&cmp)
        );
    }
}

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
fn invalid_method_pairings_are_usage_errors() {
    let dir = TempDir::new("methods-bad");
    dir.copy_in(&seed_scene(1), "s.sc");
    for args in [
        &["--method", "mt", "--kernel", "scalar"][..],
        &["--method", "mt", "--precision", "f64"][..],
        &["--method", "bogus"][..],
        &["--precision", "f16"][..],
    ] {
        let mut all = vec!["-i", "s.sc", "-o", "o.png"];
        all.extend_from_slice(args);
        let out = run(&dir.path, &all);
        assert_eq!(out.status.code(), Some(2), "{args:?}: {}", stderr(&out));
        assert!(!dir.join("o.png").exists());
    }
}
