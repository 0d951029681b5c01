//! Tests of [`OutputSet`](super::OutputSet): all or nothing, rollback, refusals.

use super::*;
use crate::output::tests::TestDir;

#[test]
fn extensions_follow_what_is_written() {
    let ok = [
        (OutputKind::Image, "a.png"),
        (OutputKind::Image, "a.BMP"),
        (OutputKind::Npy, "x/ids.NPY"),
        (OutputKind::Json, "s.json"),
    ];
    for (kind, name) in ok {
        kind.check_extension("--f", Path::new(name)).unwrap();
    }
    for (kind, name, want) in [
        (OutputKind::Npy, "x.png", ".npy"),
        (OutputKind::Npy, "x", ".npy"),
        (OutputKind::Json, "s.npy", ".json"),
        (OutputKind::Image, "i.npy", ".png"),
        (OutputKind::Image, "i.jpg", ".bmp"),
    ] {
        let e = kind.check_extension("--f", Path::new(name)).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        let msg = e.to_string();
        assert!(msg.starts_with(&format!("--f {name}: ")), "{msg}");
        assert!(msg.contains(want), "{msg}");
    }
}

#[test]
fn writes_nothing_until_commit_and_all_at_commit() {
    let dir = TestDir::new("commit");
    let (a, b) = (dir.0.join("a.npy"), dir.0.join("b.json"));
    fs::write(&a, b"old a").unwrap();
    let outs = [
        ("--ids", a.as_path(), OutputKind::Npy),
        ("--stats", b.as_path(), OutputKind::Json),
    ];
    let mut set = OutputSet::create(&outs, &[]).unwrap();
    assert_eq!(dir.entries().len(), 3, "{:?}", dir.entries());
    set.write_npy_i32("--ids", 2, 1, &[1, 2]).unwrap();
    set.write_bytes("--stats", b"{}").unwrap();
    assert_eq!(fs::read(&a).unwrap(), b"old a");
    assert!(!b.exists());
    set.commit().unwrap();
    assert_eq!(fs::read(&a).unwrap(), super::super::npy_i32(2, 1, &[1, 2]));
    assert_eq!(fs::read(&b).unwrap(), b"{}");
    assert_eq!(dir.entries(), ["a.npy", "b.json"]);
    let list = pending();
    assert!(!list.iter().any(|p| p.starts_with(&dir.0)), "{list:?}");
}

#[test]
fn dropped_or_unfinished_set_leaves_previous_files() {
    let dir = TestDir::new("drop");
    let (a, b) = (dir.0.join("a.png"), dir.0.join("b.npy"));
    fs::write(&a, b"old a").unwrap();
    fs::write(&b, b"old b").unwrap();
    let outs = [
        ("--output", a.as_path(), OutputKind::Image),
        ("--depth", b.as_path(), OutputKind::Npy),
    ];
    let mut set = OutputSet::create(&outs, &[]).unwrap();
    set.write_image("--output", 1, 1, &[1, 2, 3]).unwrap();
    drop(set);
    assert_eq!(dir.entries(), ["a.png", "b.npy"]);
    // One output never written: commit refuses, nothing renamed.
    let mut set = OutputSet::create(&outs, &[]).unwrap();
    set.write_image("--output", 1, 1, &[1, 2, 3]).unwrap();
    assert!(matches!(set.commit(), Err(Error::Failed(_))));
    assert_eq!(fs::read(&a).unwrap(), b"old a");
    assert_eq!(fs::read(&b).unwrap(), b"old b");
    assert_eq!(dir.entries(), ["a.png", "b.npy"]);
}

#[test]
fn a_failed_rename_puts_back_the_outputs_already_renamed() {
    let dir = TestDir::new("rollback");
    let (a, b, c) = (
        dir.0.join("a.npy"),
        dir.0.join("b.npy"),
        dir.0.join("c.json"),
    );
    fs::write(&a, b"old a").unwrap();
    let outs = [
        ("--ids", a.as_path(), OutputKind::Npy),
        ("--depth", b.as_path(), OutputKind::Npy),
        ("--stats", c.as_path(), OutputKind::Json),
    ];
    let mut set = OutputSet::create(&outs, &[]).unwrap();
    for flag in ["--ids", "--depth", "--stats"] {
        set.write_bytes(flag, b"new").unwrap();
    }
    // The third target turns into a folder after the checks: its rename fails.
    fs::create_dir(&c).unwrap();
    fs::write(c.join("keep"), b"k").unwrap();
    let e = set.commit().unwrap_err();
    assert_eq!(e.exit_code(), 1);
    assert!(e.to_string().contains("c.json"), "{e}");
    assert_eq!(fs::read(&a).unwrap(), b"old a");
    assert!(!b.exists(), "b did not exist before");
    assert_eq!(fs::read(c.join("keep")).unwrap(), b"k");
    assert_eq!(dir.entries(), ["a.npy", "c.json"]);
}

#[test]
fn refuses_reads_each_other_folders_and_missing_folders_before_touching_anything() {
    let dir = TestDir::new("refuse");
    let scene = dir.0.join("s.sc");
    fs::write(&scene, b"scene").unwrap();
    let a = dir.0.join("a.npy");
    let same = dir.0.join(".").join("a.npy");
    let reads = [("the input scene", scene.as_path())];
    let e = OutputSet::create(
        &[
            ("--ids", a.as_path(), OutputKind::Npy),
            ("--depth", same.as_path(), OutputKind::Npy),
        ],
        &reads,
    )
    .unwrap_err();
    assert_eq!(e.exit_code(), 2);
    assert!(e.to_string().contains("--depth") && e.to_string().contains("--ids"));
    let folder = dir.0.join("f.png");
    fs::create_dir(&folder).unwrap();
    let missing = dir.0.join("nope").join("x.json");
    for (flag, path, kind) in [
        ("--output", folder.as_path(), OutputKind::Image),
        ("--stats", missing.as_path(), OutputKind::Json),
    ] {
        let e = OutputSet::create(
            &[("--ids", a.as_path(), OutputKind::Npy), (flag, path, kind)],
            &reads,
        )
        .unwrap_err();
        assert_eq!(e.exit_code(), 1, "{e}");
        assert!(e.to_string().contains(flag), "{e}");
    }
    // A mesh read after creation.
    let mesh = dir.0.join("m.npy");
    fs::write(&mesh, b"mesh").unwrap();
    let set = OutputSet::create(&[("--ids", mesh.as_path(), OutputKind::Npy)], &reads).unwrap();
    let e = set
        .check_reads(&[("the mesh m.npy".into(), dir.0.join(".").join("m.npy"))])
        .unwrap_err();
    assert!(e.to_string().contains("the mesh m.npy"), "{e}");
    drop(set);
    assert_eq!(fs::read(&mesh).unwrap(), b"mesh");
    assert_eq!(dir.entries(), ["f.png", "m.npy", "s.sc"]);
}
