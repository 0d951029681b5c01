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
            "is the input scene; refusing to overwrite it",
        ),
        (
            &["--orbit", "3", "-o", "f%d.png", "--save-views", "f2.png"],
            "--save-views f2.png: the run also writes f2.png",
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
            "--save-views s.json: the run also writes s.json",
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
    assert_eq!(dir.entries().len(), 13);
}
