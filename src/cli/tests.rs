//! The command line's parsing and flag rules, on argument lists (no binary run).

use super::*;

fn args(s: &str) -> Vec<OsString> {
    std::iter::once("lanecast")
        .chain(s.split_whitespace())
        .map(OsString::from)
        .collect()
}

fn render(s: &str) -> RenderSettings {
    match parse(args(s)).unwrap() {
        Command::Render(r) => r,
        other => panic!("{other:?}"),
    }
}

#[test]
fn original_invocations_parse() {
    let r = render("-i scene1.sc");
    assert_eq!(r.output, Some(PathBuf::from("scene1.png")));
    assert_eq!((r.view.width, r.view.height), (640, 480));
    assert_eq!(r.color_mode, ColorMode::Random);
    assert_eq!(r.variation, Variation::Linear);
    assert_eq!(
        render("-i scene1.sc -o out.bmp").output,
        Some(PathBuf::from("out.bmp"))
    );
    let r = render("-i scene1.sc -size 800x600");
    assert_eq!((r.view.width, r.view.height), (800, 600));
    assert_eq!(render("-i scene1.sc -fov 80").view.fov, Some(80.0));
    assert_eq!(
        render("-i scene1.sc -cm ordered").color_mode,
        ColorMode::Ordered
    );
    assert_eq!(render("-i scene1.sc -cv log").variation, Variation::Log);
    assert!(render("-i scene1.sc -time").time);
}

#[test]
fn long_forms_parse_the_same() {
    let a = render("-i s.sc -o o.png -size 320x200 -fov 45 -cm ordered -cv log -time");
    let b = render(
        "--input s.sc --output o.png --size 320x200 --fov 45 --color-mode ordered \
         --color-variation log --time",
    );
    // the same settings; only -fov's spelling, kept for messages, is the one typed
    assert_eq!(a.view.fov_typed.as_deref(), Some("-fov 45"));
    assert_eq!(b.view.fov_typed.as_deref(), Some("--fov 45"));
    let b = RenderSettings {
        view: ViewSettings {
            fov_typed: a.view.fov_typed.clone(),
            ..b.view
        },
        ..b
    };
    assert_eq!(a, b);
}

#[test]
fn bad_sizes_are_usage_errors() {
    for s in [
        "0x10",
        "10x0",
        "10",
        "axb",
        "100000x10",
        "65536x65536",
        "-5x10",
    ] {
        let e = parse(args(&format!("-i s.sc -size {s}"))).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{s}");
        assert!(e.to_string().contains("size"), "{s}: {e}");
    }
}

#[test]
fn bad_fov_and_threads_are_usage_errors() {
    for a in [
        "-fov 0",
        "-fov 180",
        "-fov -3",
        "--threads 0",
        "--threads 1025",
        "--kernel gpu",
        "-cm rainbow",
    ] {
        let e = parse(args(&format!("-i s.sc {a}"))).unwrap_err();
        assert_eq!(e.exit_code(), 2, "{a}: {e}");
    }
    assert!(parse(args("-o x.png")).is_err(), "-i is required");
}

#[test]
fn help_is_info_and_lists_examples() {
    match parse(args("-h")).unwrap() {
        Command::Info(t) => assert!(t.contains("Examples:") && t.contains("--color-mode")),
        other => panic!("{other:?}"),
    }
}

/// The usage error of `s`, checking exit code 2.
fn refused(s: &str) -> String {
    let e = parse(args(s)).unwrap_err();
    assert_eq!(e.exit_code(), 2, "{s}: {e}");
    e.to_string()
}

#[test]
fn combinations_that_cannot_apply_name_the_typed_flags() {
    for (s, words) in [
        (
            "-i s.sc --kernel scalar --precision f32",
            &["--precision f32", "--kernel scalar"][..],
        ),
        (
            "-i s.sc --precision f64 --kernel scalar-f32",
            &["--precision f64", "--kernel scalar-f32"],
        ),
        ("-i s.sc -cm ordered --seed 2", &["--seed 2", "-cm ordered"]),
    ] {
        let msg = refused(s);
        for w in words {
            assert!(msg.contains(w), "{s}: {msg}");
        }
    }
}

/// `--method` is the lab's (`lab-render`), not the product's: refused, for render and compare
/// alike, saying where it went.
#[test]
fn method_is_not_a_product_flag() {
    for s in ["-i s.sc --method mt", "compare -i s.sc --method f64x4"] {
        let msg = refused(s);
        assert!(msg.starts_with("--method: "), "{s}: {msg}");
        assert!(msg.contains("lab-render"), "{s}: {msg}");
    }
}

#[test]
fn consistent_combinations_resolve() {
    use crate::Precision;
    use crate::accel::Accel;
    let r = render("-i s.sc --kernel scalar --precision f64 --accel tiles");
    assert_eq!(
        (r.kernel, r.view.precision),
        (KernelArg::Scalar, Precision::F64)
    );
    assert_eq!(r.view.accel, Accel::Tiles);
    // every kernel and precision takes every acceleration and every thread
    for s in [
        "-i s.sc --kernel scalar --accel bvh --threads 2",
        "-i s.sc --kernel scalar-f32 --accel bvh",
        "-i s.sc --precision f64 --accel tiles --threads 2",
        "-i s.sc --precision f32 --accel bvh",
    ] {
        assert!(parse(args(s)).is_ok(), "{s}");
    }
    // a scalar kernel's precision is its own, typed or not
    let r = render("-i s.sc --kernel scalar-f32 --precision f32");
    assert_eq!(r.view.precision, Precision::F32);
    assert_eq!(
        render("-i s.sc --kernel scalar").view.precision,
        Precision::F64
    );
    assert_eq!(
        render("-i s.sc --kernel scalar-f32").view.precision,
        Precision::F32
    );
    assert_eq!(render("-i s.sc").view.precision, Precision::Auto);
    assert_eq!(
        render("-i s.sc --precision f64").view.precision,
        Precision::F64
    );
    assert_eq!(render("-i s.sc --seed 5 -cm random").seed, 5);
    assert_eq!(render("-i s.sc --threads 4").view.threads, Some(4));
}

#[test]
fn messages_spell_single_dash_options_as_typed() {
    assert!(refused("-i s.sc -size 0x1").starts_with("-size 0x1:"));
    assert!(refused("-i s.sc --size 0x1").starts_with("--size 0x1:"));
    assert!(refused("-i s.sc -cm rainbow").contains("'-cm <MODE>'"));
    assert!(refused("-i s.sc --color-mode=ordered --seed 1").contains("--color-mode"));
}

#[test]
fn compare_subcommand() {
    match parse(args(
        "compare -i s.sc -size 64x48 -o d.png --max-mismatch-ppm 5",
    ))
    .unwrap()
    {
        Command::Compare(c) => {
            assert_eq!((c.view.width, c.view.height), (64, 48));
            assert_eq!(c.output, Some(PathBuf::from("d.png")));
            assert_eq!(c.max_mismatch_ppm, 5.0);
        }
        other => panic!("{other:?}"),
    }
}

/// The message of the usage error `s` gives.
fn usage_message(s: &str) -> String {
    match parse(args(s)) {
        Err(Error::Usage(m)) => m,
        other => panic!("{s}: expected a usage error, got {other:?}"),
    }
}

/// Every long flag of the command line and of `compare`, as clap's `Command` defines them,
/// typed with one dash, is refused with a message naming it as typed and its two-dash form,
/// whatever comes before or after it (never read as `-i ds`, a subcommand, or a short flag).
#[test]
fn every_long_flag_with_one_dash_is_named_with_its_two_dash_form() {
    let mut top = Cli::command();
    top.build();
    let compare = top.find_subcommand("compare").unwrap().clone();
    let mut walked = 0;
    for (prefix, cmd) in [("", &top), ("compare ", &compare)] {
        for arg in cmd.get_arguments() {
            let Some(long) = arg.get_long() else { continue };
            if SINGLE_DASH.iter().any(|(short, _)| short[1..] == *long) {
                continue; // -size, -fov, -time: the original's, which work
            }
            for line in [
                format!("{prefix}-i s.sc -{long} x"),
                format!("{prefix}-{long} x -i s.sc"),
                format!("{prefix}-{long}=x -i s.sc"),
            ] {
                let m = usage_message(&line);
                assert!(m.starts_with(&format!("-{long}")), "{line}: {m}");
                assert!(m.contains(&format!("--{long}")), "{line}: {m}");
            }
            walked += 1;
        }
    }
    assert!(walked > 30, "only {walked} long flags");
}

/// Misspelt one-dash flags, a scene without `-i`, render flags given to `compare`, and bad
/// values of `--orbit` and `--max-mismatch-ppm`: named as typed, with what was meant or why.
#[test]
fn misreadings_are_named_as_typed_with_what_was_meant() {
    for (line, want) in [
        (
            "-i s.sc -szie 800x600",
            "-szie: no such flag; did you mean -size?",
        ),
        ("-i s.sc -tim", "-tim: no such flag; did you mean -time?"),
        (
            "-i s.sc -ids x.npy",
            "-ids: long flags take two dashes: --ids",
        ),
        (
            "-ids x.npy -i s.sc",
            "-ids: long flags take two dashes: --ids",
        ),
        (
            "-i s.sc -output x.png",
            "-output: long flags take two dashes: --output",
        ),
        (
            "-i s.sc -orbit 4",
            "-orbit: long flags take two dashes: --orbit",
        ),
        (
            "good.sc",
            "good.sc: the scene is given with -i: lanecast -i good.sc",
        ),
        (
            "good.sc -o x.png",
            "good.sc: the scene is given with -i: lanecast -i good.sc",
        ),
        (
            "compare mesh.obj",
            "mesh.obj: the scene is given with -i: lanecast compare -i mesh.obj",
        ),
        (
            "compare -i s.sc --kernel scalar",
            "--kernel: applies to the render command (lanecast -i SCENE ...), not to compare: \
             compare always renders with both kernels",
        ),
        (
            "compare -i s.sc --seed 3",
            "--seed: applies to the render command",
        ),
        (
            "-i s.sc --max-mismatch-ppm 3",
            "--max-mismatch-ppm: applies to compare only",
        ),
        (
            "-i s.sc --orbit -3",
            "the number of views on the turntable must be at least 1",
        ),
        ("-i s.sc --orbit 0", "must be at least 1"),
        ("-i s.sc --orbit 1000001", "at most 1000000 views per run"),
        ("-i s.sc --orbit x", "must be a whole number"),
        (
            "compare -i s.sc --max-mismatch-ppm -1",
            "--max-mismatch-ppm -1: must be a number of parts per million, 0 or more",
        ),
    ] {
        let m = usage_message(line);
        assert!(m.contains(want), "{line}: {m}");
    }
    // -3 is named as typed with --orbit
    let m = usage_message("-i s.sc --orbit -3");
    assert!(m.contains("'-3'") && m.contains("--orbit"), "{m}");
    // values that start with a dash are values, not flags
    assert_eq!(
        render("-i s.sc --eye -1,2,3").view.camera.eye.unwrap().x,
        -1.0
    );
    assert_eq!(render("-i s.sc -o -").output, Some(PathBuf::from("-")));
    assert_eq!(render("-is.sc").view.input, PathBuf::from("s.sc"));
}

/// A many-view run writes the outputs it names: no image when only buffers are named (and no
/// `-o`), images by default when nothing is; one view keeps its image beside the input.
#[test]
fn many_views_naming_only_buffers_write_no_image() {
    let r = render("-i s.sc --orbit 3 --ids i%d.npy");
    assert_eq!((r.output.as_deref(), r.image_file()), (None, None));
    assert!(!r.writes_image());
    let r = render("-i s.sc --views v.txt --normals n%d.npy --depth d%d.npy");
    assert_eq!(r.output, None);
    let r = render("-i s.sc --orbit 3");
    assert_eq!(r.image_file(), Some(Path::new("s_%05d.png")));
    let r = render("-i s.sc --orbit 3 --ids i%d.npy -o f%d.png");
    assert_eq!(r.image_file(), Some(Path::new("f%d.png")));
    let r = render("-i s.sc --orbit 3 --ids i%d.npy -o -");
    assert_eq!((r.image_file(), r.writes_image()), (None, true));
    // one view: the image beside the input, whatever else is named
    let r = render("-i s.sc --ids i.npy");
    assert_eq!(r.image_file(), Some(Path::new("s.png")));
    let m = usage_message("-i s.sc --orbit 3 --ids i%d.npy --format bmp");
    assert!(
        m.contains("--format bmp") && m.contains("writes no image"),
        "{m}"
    );
}
