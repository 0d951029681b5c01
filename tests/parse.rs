//! Integration tests of the scene parser through the library API: `parse_scene`, `load_scene`.

use glam::DVec3;
use lanecast::Error;
use lanecast::limits::{MAX_LINE_BYTES, MAX_SCENE_BYTES};
use lanecast::scene::{Scene, Shape, load_scene, parse_scene};
use std::path::{Path, PathBuf};

const CAM: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0\n";

fn parse(text: &str) -> lanecast::Result<Scene> {
    parse_scene(text, Path::new("scene.sc"))
}

fn ok(text: &str) -> Scene {
    parse(text).unwrap_or_else(|e| panic!("rejected {text:?}: {e}"))
}

/// Asserts `text` is rejected with a message starting with `at` (e.g. "scene.sc:3:7:") and
/// containing every one of `words`; returns the message.
fn rejected(text: &str, at: &str, words: &[&str]) -> String {
    let e = match parse(text) {
        Ok(_) => panic!("accepted {text:?}"),
        Err(e) => e,
    };
    assert_eq!(e.exit_code(), 2, "{e}");
    let msg = e.to_string();
    assert!(msg.starts_with(at), "{msg:?} does not start with {at:?}");
    for w in words {
        assert!(msg.contains(w), "{msg:?} does not contain {w:?}");
    }
    msg
}

fn d(x: f64, y: f64, z: f64) -> DVec3 {
    DVec3::new(x, y, z)
}

fn sphere(center: DVec3, radius: f64) -> Shape {
    Shape::Sphere { center, radius }
}

/// `rejected` for a `body` after a camera line: errors in `body` start on line 2.
fn rejected_body(body: &str, at: &str, words: &[&str]) {
    rejected(&with_cam(body), at, words);
}

/// A scene with the camera first and `body` after: errors in `body` start on line 2.
fn with_cam(body: &str) -> String {
    format!("{CAM}{body}")
}

#[test]
fn parses_every_statement() {
    let s = ok("camera eye 1 2 3 look -4 5.5 6 up 0 0 1 fov 45\n\
                sphere 1 -2 3.25 0.5\n\
                triangle 0 0 0  1 0 0  0 1 0\n\
                quad 0 0 1  2 0 1  2 3 1  0 3 1\n");
    assert_eq!(s.source, PathBuf::from("scene.sc"));
    assert_eq!(s.camera.eye, d(1., 2., 3.));
    assert_eq!(s.camera.look, d(-4., 5.5, 6.));
    assert_eq!(s.camera.up, d(0., 0., 1.));
    assert_eq!(s.camera.fov_deg(), Some(45.0));
    assert_eq!(
        s.shapes.iter().collect::<Vec<_>>(),
        vec![
            sphere(d(1., -2., 3.25), 0.5),
            Shape::Triangle([d(0., 0., 0.), d(1., 0., 0.), d(0., 1., 0.)]),
            Shape::Quad([d(0., 0., 1.), d(2., 0., 1.), d(2., 3., 1.), d(0., 3., 1.)]),
        ]
    );
    assert_eq!(s.shapes.lines().collect::<Vec<_>>(), vec![2, 3, 4]);
    assert_eq!(s.counts(), [1, 1, 1]);
    assert_eq!(ok(CAM).camera.fov_deg(), None);
}

#[test]
fn ids_follow_file_order_across_types() {
    let s = ok("# header\n\
                quad 0 0 0 1 0 0 1 1 0 0 1 0\n\
                sphere 0 0 0 1\n\
                \n\
                camera eye 0 0 5 look 0 0 0 up 0 1 0\n\
                triangle 0 0 0 1 0 0 0 1 0\n\
                sphere 9 9 9 2\n");
    assert_eq!(s.shapes.lines().collect::<Vec<_>>(), vec![2, 3, 6, 7]);
    assert!(matches!(s.shapes.get(0), Shape::Quad(_)));
    assert!(matches!(s.shapes.get(1), Shape::Sphere { radius: 1.0, .. }));
    assert!(matches!(s.shapes.get(2), Shape::Triangle(_)));
    assert!(matches!(s.shapes.get(3), Shape::Sphere { radius: 2.0, .. }));
}

#[test]
fn bom_crlf_comments_tabs_and_blank_lines() {
    let text = "\u{feff}# a scene\r\n\
                \r\n\
                \t  \r\n\
                sphere\t1 2\t 3  4   # trailing comment\r\n\
                camera eye 0 0 5 look 0 0 0 up 0 1 0#glued comment\r\n\
                   # indented comment\n\
                sphere 0 0 0 1#x";
    let s = ok(text);
    assert_eq!(
        s.shapes.iter().collect::<Vec<_>>(),
        vec![sphere(d(1., 2., 3.), 4.), sphere(d(0., 0., 0.), 1.),]
    );
    assert_eq!(s.shapes.lines().collect::<Vec<_>>(), vec![4, 7]);
    // Columns count characters after the BOM; tabs count as one.
    rejected("\u{feff}Camera eye", "scene.sc:1:1:", &["unknown keyword"]);
    rejected("\u{feff}\tsphere\t0 0 x 1\r\n", "scene.sc:1:13:", &["'x'"]);
    rejected("# é ü\n  ça 1\n", "scene.sc:2:3:", &["'ça'"]);
}

#[test]
fn camera_anywhere_and_zero_primitives() {
    let last =
        ok("sphere 0 0 0 1\ntriangle 0 0 0 1 0 0 0 1 0\ncamera eye 0 0 5 look 0 0 0 up 0 1 0");
    assert_eq!(last.shapes.len(), 2);
    assert_eq!(last.camera.eye, d(0., 0., 5.));
    let only = ok(CAM);
    assert!(only.shapes.is_empty() && only.shapes.lines().next().is_none());
}

#[test]
fn unknown_keywords() {
    let body = with_cam("sphere 0 0 0 1\nSphere 0 0 0 1\n");
    rejected(
        &body,
        "scene.sc:3:1:",
        &["unknown keyword 'Sphere'", "camera, sphere, triangle, quad"],
    );
    rejected_body("  box 1 2 3", "scene.sc:2:3:", &["unknown keyword 'box'"]);
    rejected_body("1 2 3", "scene.sc:2:1:", &["unknown keyword '1'"]);
    rejected(
        "CAMERA eye 0 0 5 look 0 0 0 up 0 1 0",
        "scene.sc:1:1:",
        &["'CAMERA'"],
    );
}

#[test]
fn wrong_number_counts() {
    rejected_body(
        "sphere 0 0 0",
        "scene.sc:2:1: ",
        &["too few", "expects 4", "got 3"],
    );
    rejected_body(
        "sphere 0 0 0 1 2",
        "scene.sc:2:16:",
        &["too many", "expects 4", "got 5"],
    );
    rejected_body("sphere", "scene.sc:2:1: ", &["expects 4", "got 0"]);
    let tri = "triangle 0 0 0 1 0 0 0 1 0 7";
    rejected(
        &with_cam(tri),
        "scene.sc:2:28:",
        &["too many", "expects 9", "got 10"],
    );
    rejected_body(
        "triangle 0 0 0 1 0 0 0 1",
        "scene.sc:2:1: ",
        &["expects 9", "got 8"],
    );
    let quad = "quad 0 0 0 1 0 0 1 1 0 0 1";
    rejected(
        &with_cam(quad),
        "scene.sc:2:1: ",
        &["too few", "expects 12", "got 11"],
    );
    rejected_body(
        "quad 0 0 0 1 0 0 1 1 0 0 1 0 0 0",
        "scene.sc:2:",
        &["expects 12", "got 14"],
    );
}

#[test]
fn accepted_numbers() {
    let s = ok(&with_cam(
        "sphere .5 5. +1 1E3\nsphere 1e-400 -0 -2.5e+1 1e-3\nsphere 007 -.25 1e2 1",
    ));
    assert_eq!(s.shapes.get(0), sphere(d(0.5, 5., 1.), 1000.));
    assert_eq!(s.shapes.get(1), sphere(d(0., 0., -25.), 1e-3));
    assert_eq!(s.shapes.get(2), sphere(d(7., -0.25, 100.), 1.));
}

#[test]
fn rejected_numbers() {
    let bad = [
        "inf", "-inf", "nan", "NaN", "infinity", "0x10", "1.2.3", "--1", "1e", "1e+", ".", "+",
        "e5", "1_0", "1,5", "½",
    ];
    for b in bad {
        let text = with_cam(&format!("sphere 0 {b} 0 1"));
        rejected(
            &text,
            "scene.sc:2:10:",
            &[&format!("'{b}'"), "not a number"],
        );
    }
    let text = with_cam("sphere 0 0 0 1e400");
    rejected(&text, "scene.sc:2:14:", &["'1e400'", "out of range"]);
    rejected_body(
        "sphere 0 -1e309 0 1",
        "scene.sc:2:10:",
        &["'-1e309'", "out of range"],
    );
    rejected(
        "camera eye 0 0 5 look 0 0 nan up 0 1 0",
        "scene.sc:1:27:",
        &["'nan'"],
    );
}

#[test]
fn sphere_radius() {
    rejected_body("sphere 0 0 0 0", "scene.sc:2:14:", &["radius", "positive"]);
    rejected_body(
        "sphere 1 2 3 -1.5",
        "scene.sc:2:14:",
        &["radius", "positive"],
    );
    rejected_body("sphere 0 0 0 1e-400", "scene.sc:2:14:", &["radius"]);
    rejected_body(
        "sphere 0 0 0 1e200",
        "scene.sc:2:14:",
        &["radius", "too large"],
    );
}

#[test]
fn camera_count() {
    let e = parse("sphere 0 0 0 1\n").unwrap_err();
    assert!(matches!(e, Error::InputFile { .. }), "{e:?}");
    assert_eq!(e.exit_code(), 2);
    assert!(e.to_string().starts_with("scene.sc: no camera line"), "{e}");
    assert!(
        parse("")
            .unwrap_err()
            .to_string()
            .contains("no camera line")
    );
    assert!(
        parse("# only a comment\n\n")
            .unwrap_err()
            .to_string()
            .contains("no camera line")
    );
    let two = format!("sphere 0 0 0 1\n{CAM}sphere 0 0 0 1\n  {CAM}");
    rejected(&two, "scene.sc:4:3:", &["second camera", "line 2"]);
}

#[test]
fn camera_geometry() {
    let e = "camera eye 1 2 3 look 1 2 3 up 0 1 0";
    rejected(e, "scene.sc:1:", &["eye", "look", "same point"]);
    for up in ["0 0 1", "0 0 -3", "0 0 1e-3", "1e-12 0 1"] {
        let text = format!("camera eye 0 0 5 look 0 0 0 up {up}");
        rejected(&text, "scene.sc:1:", &["up", "parallel"]);
    }
    rejected(
        "camera eye 0 0 5 look 0 0 0 up 0 0 0",
        "scene.sc:1:",
        &["up", "zero length"],
    );
    assert_eq!(
        ok("camera eye 0 0 5 look 0 0 0 up 1e-6 0 1").camera.up,
        d(1e-6, 0., 1.)
    );
    let big = "camera eye -1e200 0 0 look 1e200 0 0 up 0 1 0";
    rejected(big, "scene.sc:1:", &["eye", "look", "f64"]);
}

#[test]
fn camera_fov() {
    for fov in ["0", "-10", "180", "180.0001", "1e3"] {
        let text = format!("\ncamera eye 0 0 5 look 0 0 0 up 0 1 0 fov {fov}");
        rejected(&text, "scene.sc:2:42:", &["field of view", "(0, 180)"]);
    }
    for fov in ["1e-3", "90", "179.999"] {
        let s = ok(&format!("camera eye 0 0 5 look 0 0 0 up 0 1 0 fov {fov}"));
        assert_eq!(s.camera.fov_deg(), Some(fov.parse().unwrap()));
    }
}

#[test]
fn camera_syntax() {
    const C: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0";
    let cases: [(&str, &str, &[&str]); 13] = [
        ("camera", "1:1: ", &["missing 'eye'"]),
        (
            "camera look 0 0 0 eye 0 0 5 up 0 1 0",
            "1:8:",
            &["expected 'eye'", "'look'"],
        ),
        (
            "camera eye 0 0 5 up 0 1 0 look 0 0 0",
            "1:18:",
            &["expected 'look'", "'up'"],
        ),
        (
            "camera eye 0 0 5 Look 0 0 0 up 0 1 0",
            "1:18:",
            &["expected 'look'", "'Look'"],
        ),
        (
            "camera eye 0 0 look 0 0 0 up 0 1 0",
            "1:16:",
            &["'eye' expects 3", "got 2"],
        ),
        (
            "camera eye 0 0 5 1 look 0 0 0 up 0 1 0",
            "1:18:",
            &["'eye' expects 3", "got 4"],
        ),
        (
            "camera eye 0 0 5 look 0 0 0 up 0 1",
            "1:1: ",
            &["'up' expects 3", "got 2"],
        ),
        (&format!("{C} 2 3"), "1:38:", &["'up' expects 3", "got 5"]),
        (&format!("{C} fov"), "1:1: ", &["'fov' expects 1", "got 0"]),
        (
            &format!("{C} fov 60 70"),
            "1:45:",
            &["'fov' expects 1", "got 2"],
        ),
        (&format!("{C} zoom 2"), "1:38:", &["unexpected 'zoom'"]),
        (
            &format!("{C} fov 60 fov 70"),
            "1:45:",
            &["unexpected 'fov'"],
        ),
        (&format!("{C} fov x"), "1:42:", &["'x'", "not a number"]),
    ];
    for (text, at, words) in cases {
        rejected(text, &format!("scene.sc:{at}"), words);
    }
}

#[test]
fn line_length_limit() {
    let longest = format!("{CAM}#{}\n", "x".repeat(MAX_LINE_BYTES - 1));
    ok(&longest);
    let crlf = format!("{CAM}#{}\r\n", "x".repeat(MAX_LINE_BYTES - 1));
    ok(&crlf);
    let too_long = format!("{CAM}\n#{}\n", "x".repeat(MAX_LINE_BYTES));
    rejected(&too_long, "scene.sc:3:1: ", &["line is", "limit"]);
}

/// Formats vertices to 9 significant digits, as a scene file would hold them.
fn statement(kw: &str, v: &[DVec3]) -> String {
    let nums: Vec<String> = v
        .iter()
        .flat_map(|p| p.to_array())
        .map(|x| format!("{x:.8e}"))
        .collect();
    format!("{kw} {}", nums.join(" "))
}

/// The geometric rules are scale-free, so the same shape at every scale must get the same
/// verdict. The eye moves with the scale (5 shape-sizes away), so that the f32 range rules that
/// `parse_scene` applies too (a primitive must subtend at least 1e-12 rad from the eye) see the
/// same view at every scale.
fn check_shape(kw: &str, v: &[DVec3], expect: Result<(), &str>) {
    let size = v.iter().map(|p| p.abs().max_element()).fold(0.0, f64::max);
    for scale in [1.0, 1e6, 1e-6, 1e12, 1e-12] {
        let v: Vec<DVec3> = v.iter().map(|p| *p * scale).collect();
        let cam = format!(
            "camera eye 0 0 {:e} look 0 0 0 up 0 1 0\n",
            5.0 * size * scale
        );
        let text = format!("{cam}{}\n", statement(kw, &v));
        match expect {
            Ok(()) => assert_eq!(ok(&text).shapes.len(), 1),
            Err(word) => drop(rejected(&text, "scene.sc:2:1: ", &[kw, word])),
        }
    }
}

#[test]
fn triangle_tolerances() {
    let tri = |a, b, c| [a, b, c];
    check_shape(
        "triangle",
        &tri(d(0., 0., 0.), d(1., 0., 0.), d(0.5, 1e-9, 0.)),
        Ok(()),
    );
    check_shape(
        "triangle",
        &tri(d(0., 0., 0.), d(1e-12, 0., 0.), d(0., 1e-12, 0.)),
        Ok(()),
    );
    let steps = tri(d(0.1, 0.2, 0.3), d(0.2, 0.4, 0.6), d(0.3, 0.6, 0.9));
    check_shape("triangle", &steps, Err("collinear"));
    let diag = tri(d(0., 0., 0.), d(0.1, 0.1, 0.1), d(0.3, 0.3, 0.3));
    check_shape("triangle", &diag, Err("collinear"));
    check_shape(
        "triangle",
        &tri(d(1., 2., 3.), d(1., 2., 3.), d(0., 0., 1.)),
        Err("same point"),
    );
    // Written as decimals directly too, not only through formatting.
    rejected_body(
        "triangle 0.1 0.2 0.3 0.2 0.4 0.6 0.3 0.6 0.9",
        "scene.sc:2:1: ",
        &["collinear"],
    );
    let huge = "triangle 0 0 0 1e200 0 0 0 1e200 0";
    rejected_body(huge, "scene.sc:2:1: ", &["too large"]);
}

/// A convex, non-parallelogram quad in a tilted plane (size ~2), and the plane's unit normal.
fn tilted_quad() -> ([DVec3; 4], DVec3) {
    let u = d(1.0, 0.3, -0.7).normalize();
    let n = u.cross(d(0.2, 1.0, 0.4)).normalize();
    let v = n.cross(u);
    let o = d(0.37, -1.2, 2.9);
    let q = [(0.0, 0.0), (2.0, 0.1), (1.7, 1.9), (0.2, 1.3)].map(|(x, y)| o + u * x + v * y);
    (q, n)
}

#[test]
fn quad_tolerances() {
    let (q, n) = tilted_quad();
    // Planar up to the 9-digit rounding of its decimals.
    check_shape("quad", &q, Ok(()));
    let mut off = q;
    off[2] += n * 2e-4;
    check_shape("quad", &off, Err("not planar"));
    let concave = [d(0., 0., 0.), d(1., 0.3, 0.), d(2., 0., 0.), d(1., 2., 0.)];
    check_shape("quad", &concave, Err("not convex"));
    let bow_tie = [d(0., 0., 0.), d(1., 0., 1.), d(0., 1., 1.), d(1., 1., 2.)];
    check_shape("quad", &bow_tie, Err("bow-tie"));
    let straight = [d(0., 0., 0.), d(1., 0., 0.), d(2., 0., 0.), d(1., 1., 0.)];
    check_shape("quad", &straight, Err("collinear"));
    let repeated = [d(0., 0., 0.), d(1., 0., 0.), d(0., 1., 0.), d(0., 0., 0.)];
    check_shape("quad", &repeated, Err("same point"));
    let huge = "quad 0 0 0 1e200 0 0 1e200 1e200 0 0 1e200 0";
    rejected_body(huge, "scene.sc:2:1: ", &["too large"]);
}

fn temp_path(name: &str) -> PathBuf {
    std::env::temp_dir().join(format!("lanecast-parse-{}-{name}", std::process::id()))
}

#[test]
fn load_scene_reads_checks_utf8_and_size() {
    let good = temp_path("good.sc");
    std::fs::write(&good, format!("\u{feff}{CAM}sphere 0 0 0 1\r\n")).unwrap();
    let s = load_scene(&good);
    std::fs::remove_file(&good).unwrap();
    let s = s.unwrap();
    assert_eq!(s.source, good);
    assert_eq!(s.shapes.len(), 1);

    let bad = temp_path("bad-utf8.sc");
    std::fs::write(
        &bad,
        b"camera eye 0 0 5 look 0 0 0 up 0 1 0\n# ok\n# caf\xc3\xa9 \xff\n",
    )
    .unwrap();
    let e = load_scene(&bad);
    std::fs::remove_file(&bad).unwrap();
    let msg = e.unwrap_err().to_string();
    assert!(msg.starts_with(&format!("{}:3:8:", bad.display())), "{msg}");
    assert!(msg.contains("UTF-8"), "{msg}");

    let missing = temp_path("missing.sc");
    let e = load_scene(&missing).unwrap_err();
    assert!(
        matches!(
            e,
            Error::Io {
                action: "read scene",
                ..
            }
        ),
        "{e:?}"
    );
    assert_eq!(e.exit_code(), 1);

    // A sparse file one byte over the limit: rejected from its size, without reading it.
    let big = temp_path("big.sc");
    let f = std::fs::File::create(&big).unwrap();
    f.set_len(MAX_SCENE_BYTES + 1).unwrap();
    drop(f);
    let e = load_scene(&big);
    std::fs::remove_file(&big).unwrap();
    let e = e.unwrap_err();
    assert!(matches!(e, Error::InputFile { .. }), "{e:?}");
    let msg = e.to_string();
    assert!(
        msg.starts_with(&big.display().to_string()) && msg.contains("limit"),
        "{msg}"
    );
}
