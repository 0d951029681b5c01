//! Refusals that come before anything is written.

use super::*;

/// Each refusal: exit 2, the message, and nothing written in the folder.
#[test]
fn bad_views_and_patterns_are_refused_before_anything_is_written() {
    let dir = TempDir::new("views-bad");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    dir.write(
        "good.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\ncamera eye 9 2 0 look 0 0 0 up 0 1 0\n",
    );
    dir.write(
        "bad.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\n# fine\ncamera eye 1 2 x look 0 0 0 up 0 1 0\n",
    );
    dir.write(
        "parallel.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0\ncamera eye 0 9 0 look 0 0 0 up 0 1 0\n",
    );
    dir.write("shape.txt", "sphere 0 0 0 1\n");
    // a focal length that is not positive; a principal point past the limits for 64x48
    // (`limits::MAX_PRINCIPAL_OFFSET` image widths); a matrix that scales; one that reflects
    dir.write(
        "k.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0 K 50 50 32 24\ncamera eye 0 2 9 look 0 0 0 up 0 1 0 K 0 50 32 24\n",
    );
    dir.write(
        "far.txt",
        "camera eye 0 2 9 look 0 0 0 up 0 1 0 K 50 50 1e6 24\n",
    );
    dir.write(
        "scaled.txt",
        "extrinsic 1.01 0 0 0 0 1 0 0 0 0 1 9 0 0 0 1 K 50 50 32 24\n",
    );
    dir.write(
        "mirror.txt",
        "\n  extrinsic -1 0 0 0 0 1 0 0 0 0 1 9 0 0 0 1 K 50 50 32 24\n",
    );
    dir.write(
        "row.txt",
        "extrinsic 1 0 0 0 0 1 0 0 0 0 1 9 0 0 1 1 K 50 50 32 24\n",
    );
    let cases: &[(&[&str], &str)] = &[
        (&["--views", "bad.txt", "-o", "f%d.png"], "bad.txt:3:16:"),
        (
            &["--views", "parallel.txt", "-o", "f%d.png"],
            "parallel.txt:2:1:",
        ),
        (
            &["--views", "shape.txt", "-o", "f%d.png"],
            "shape.txt:1:1: expected a camera line",
        ),
        (
            &["--views", "good.txt", "-o", "f.png"],
            "-o f.png: it holds no %d",
        ),
        (
            &["--views", "good.txt", "-o", "f%d.png", "--ids", "i.npy"],
            "--ids i.npy: it holds no %d",
        ),
        (
            &[
                "--orbit",
                "12",
                "-o",
                "f%d.png",
                "--ids",
                "a%d.npy",
                "--depth",
                "a%02d.npy",
            ],
            "would both write",
        ),
        (
            &[
                "--views",
                "good.txt",
                "-o",
                "f%d.png",
                "--ids",
                "good%d.txt",
            ],
            "must end in .npy",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--stats", "s%d.json"],
            "one record covers every view",
        ),
        (
            &["--views", "good.txt", "--eye", "1,2,3", "-o", "f%d.png"],
            "--eye: --views good.txt gives every view's camera",
        ),
        (
            &["--orbit", "3", "--repeat", "2", "-o", "f%d.png"],
            "--repeat 2",
        ),
        (
            &["--orbit", "3", "--views", "good.txt", "-o", "f%d.png"],
            "cannot be used with",
        ),
        (&["--orbit", "0", "-o", "f%d.png"], "--orbit"),
        // with every image streamed and no file per view, nothing tells a view is done
        (
            &["--orbit", "2", "-o", "-", "--skip-existing"],
            "--skip-existing: with -o - and no --ids, --depth, --zdepth or --normals",
        ),
        (
            &[
                "--orbit",
                "2",
                "-o",
                "-",
                "--stats",
                "s.json",
                "--skip-existing",
            ],
            "--skip-existing: with -o - and no --ids, --depth, --zdepth or --normals",
        ),
        (
            &["--orbit", "2", "-o", "f%d.png", "-fov", "180"],
            "field of view",
        ),
        (
            &["--views", "k.txt", "-o", "f%d.png"],
            "k.txt:2:40: focal length fx = 0 pixels",
        ),
        (
            &["--views", "far.txt", "-o", "f%d.png", "-size", "64x48"],
            "far.txt:1:1: camera: principal point cx = 1000000",
        ),
        (
            &["--views", "scaled.txt", "-o", "f%d.png"],
            "scaled.txt:1:1: the world-to-camera matrix is not a rigid transform",
        ),
        (
            &["--views", "mirror.txt", "-o", "f%d.png"],
            "mirror.txt:2:3: the world-to-camera matrix's 3x3 rotation has determinant -1",
        ),
        (
            &["--views", "row.txt", "-o", "f%d.png"],
            "row.txt:1:1: the world-to-camera matrix's last row must be 0 0 0 1",
        ),
        // --save-views: never over a file the run reads or writes, only with --orbit
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", scene],
            "the name must end in .txt",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", "f2.png"],
            "--save-views f2.png: written as a views file (text); the name must end in .txt",
        ),
        (
            &[
                "--orbit",
                "3",
                "-o",
                "f%d.png",
                "--stats",
                "s.json",
                "--save-views",
                "s.json",
            ],
            "--save-views s.json: written as a views file (text); the name must end in .txt",
        ),
        (
            &[
                "--views",
                "good.txt",
                "-o",
                "f%d.png",
                "--save-views",
                "v.txt",
            ],
            "--save-views v.txt: writes the cameras of --orbit N",
        ),
        (
            &["-o", "f.png", "--save-views", "v.txt"],
            "--save-views v.txt: writes the cameras of --orbit N",
        ),
        // a views file is text named .txt, as every other output's kind has its extensions;
        // an existing file is replaced only when it is a views file
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", "mesh.obj"],
            "--save-views mesh.obj: written as a views file (text); the name must end in .txt",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", "views.png"],
            "--save-views views.png: written as a views file (text); the name must end in .txt",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", "shape.txt"],
            "--save-views shape.txt: exists and is not a views file (shape.txt:1:1:",
        ),
    ];
    let before = dir.entries();
    for (extra, needle) in cases {
        let mut args = vec!["-i", scene];
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{args:?}: {}", stderr(&o));
        assert_eq!(dir.entries(), before, "{args:?} wrote something");
    }
    // a views file that cannot be read is an I/O error, as a scene's is
    let o = run(
        &dir.path,
        &["-i", scene, "--views", "missing.txt", "-o", "f%d.png"],
    );
    assert_eq!(o.status.code(), Some(1));
    assert!(
        stderr(&o).contains("missing.txt: cannot read views"),
        "{}",
        stderr(&o)
    );
    assert_eq!(dir.entries(), before);
    // an output pattern naming the views file itself
    dir.write("v0.npy", "camera eye 0 2 9 look 0 0 0 up 0 1 0\n");
    let o = run(
        &dir.path,
        &[
            "-i", scene, "--views", "v0.npy", "-o", "f%d.png", "--ids", "v%d.npy",
        ],
    );
    assert_eq!(o.status.code(), Some(2));
    assert!(stderr(&o).contains("is the views file"), "{}", stderr(&o));
}

/// A view whose eye puts a primitive outside the f32 range rule (scene 6's flat star seen from
/// 4e-16 off its plane, an edge pointing at the eye) is refused before any view renders,
/// naming the views file's line and the scene's; the orbit that crosses that plane does so
/// exactly (quarter turns are exact) and renders whole.
#[test]
fn a_view_out_of_range_is_refused_before_anything_renders() {
    let dir = TempDir::new("views-range");
    let scene = seed_scene(6);
    let scene = scene.to_str().unwrap();
    dir.write(
        "v.txt",
        "camera eye 0 0 7 look 0 0 0 up 0 1 0\ncamera eye 7 0 4.3e-16 look 0 0 0 up 0 1 0\n",
    );
    let o = run(
        &dir.path,
        &["-i", scene, "--views", "v.txt", "-o", "f%d.png"],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let e = stderr(&o);
    assert!(
        e.contains("v.txt:2:1: view 1:") && e.contains("scene6.sc:15:1:"),
        "{e}"
    );
    assert_eq!(dir.entries(), ["v.txt"]);
    let o = run(
        &dir.path,
        &["-i", scene, "--orbit", "12", "-o", "o%02d.png"],
    );
    assert_success(&o, "scene 6 orbit");
    // v.txt, and 12 images with their records
    assert_eq!(dir.entries().len(), 25);
}

/// `--save-views` replaces a views file (the one a run saved before, or one written by hand),
/// and nothing else: a mesh the scene does not read, an image, notes, an empty file keep their
/// bytes and the run writes nothing (exit 2).
#[test]
fn save_views_replaces_only_a_views_file() {
    let dir = TempDir::new("views-save-over");
    let scene = seed_scene(1);
    let scene = scene.to_str().unwrap();
    let save = |name: &str| {
        run(
            &dir.path,
            &[
                "-i",
                scene,
                "-size",
                "32x24",
                "--orbit",
                "3",
                "--ids",
                "i%d.npy",
                "--save-views",
                name,
            ],
        )
    };
    dir.write(
        "old.txt",
        "# by hand\ncamera eye 0 2 9 look 0 0 0 up 0 1 0\n",
    );
    assert_success(&save("old.txt"), "over a views file");
    let saved = fs::read_to_string(dir.join("old.txt")).unwrap();
    assert_eq!(
        saved.lines().filter(|l| l.starts_with("camera ")).count(),
        3
    );
    assert_success(&save("old.txt"), "over the views file it saved");
    assert_eq!(fs::read_to_string(dir.join("old.txt")).unwrap(), saved);
    let others: [(&str, &[u8]); 5] = [
        ("bunny.obj", b"v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n"),
        ("views.png", b"\x89PNG\r\n\x1a\n"),
        ("notes.txt", b"things to render tomorrow\n"),
        ("empty.txt", b""),
        (
            "latin1.txt",
            b"camera eye 0 2 9 look 0 0 0 up 0 1 0 # caf\xe9\n",
        ),
    ];
    for (name, bytes) in others {
        fs::write(dir.join(name), bytes).unwrap();
    }
    // nor a file the run reads, even when it is a views file too
    dir.write("both.txt", &fs::read_to_string(scene).unwrap());
    let o = run(
        &dir.path,
        &[
            "-i",
            "both.txt",
            "--orbit",
            "2",
            "--ids",
            "i%d.npy",
            "--save-views",
            "both.txt",
        ],
    );
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    assert!(
        stderr(&o).contains("is the input scene; refusing to overwrite it"),
        "{}",
        stderr(&o)
    );
    let before = dir.entries();
    for (name, bytes) in others {
        let o = save(name);
        assert_eq!(o.status.code(), Some(2), "{name}: {}", stderr(&o));
        assert!(
            stderr(&o).contains(&format!("--save-views {name}:")),
            "{}",
            stderr(&o)
        );
        assert!(fs::read(dir.join(name)).unwrap() == bytes, "{name} changed");
        assert_eq!(dir.entries(), before, "{name}: the run wrote something");
    }
}
