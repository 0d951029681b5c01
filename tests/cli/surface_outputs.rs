//! `--zdepth` and `--normals` (the library's `Frame::z_depth` and `Frame::normals` written as
//! `.npy`) against the f64 geometry of each pixel's primitive, through every `--accel`; their
//! refusals; and `-cm shade`'s image: a sphere face-on is brightest at its centre, grey, with
//! the background black where the ids say background. The palette modes' images are still
//! README's pictures of the seed scenes, byte for byte.

use super::*;
use glam::DVec3;
use lanecast::Camera;
use lanecast::scene::Shape;

const U: f64 = f32::EPSILON as f64 / 2.0;

/// The header dict and the little-endian 4-byte values of a `.npy` file.
fn npy(path: &Path) -> (String, Vec<[u8; 4]>) {
    let bytes = fs::read(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00", "{}", path.display());
    let len = u16::from_le_bytes([bytes[8], bytes[9]]) as usize;
    let dict = String::from_utf8(bytes[10..10 + len].to_vec()).unwrap();
    let values = bytes[10 + len..]
        .chunks_exact(4)
        .map(|c| c.try_into().unwrap())
        .collect();
    (dict, values)
}

/// The f32 values of a `.npy` file of `<f4` with the shape `shape` (as Python writes it).
fn f32s(path: &Path, shape: &str) -> Vec<f32> {
    let (dict, values) = npy(path);
    assert!(dict.contains("'descr': '<f4'"), "{dict}");
    assert!(dict.contains(&format!("'shape': {shape}")), "{dict}");
    values.into_iter().map(f32::from_le_bytes).collect()
}

fn i32s(path: &Path) -> Vec<i32> {
    let (dict, values) = npy(path);
    assert!(dict.contains("'descr': '<i4'"), "{dict}");
    values.into_iter().map(i32::from_le_bytes).collect()
}

/// The exact distance along unit ray `d` from `eye` to the sphere (`c`, `r`): the near root,
/// the far one with the eye inside.
fn sphere_t(eye: DVec3, d: DVec3, c: DVec3, r: f64) -> Option<f64> {
    let oc = c - eye;
    let b = oc.dot(d);
    let h2 = r * r - (oc - d * b).length_squared();
    (h2 >= 0.0).then(|| {
        let h = h2.sqrt();
        if b - h > 0.0 { b - h } else { b + h }
    })
}

/// The f64 geometry of primitive `shape` along ray `d`: its unit normal turned to face the eye
/// and the exact distance to its surface (`None` where the f64 ray misses a sphere at its
/// silhouette).
fn exact(shape: Shape, eye: DVec3, d: DVec3) -> (Option<f64>, DVec3, Option<f64>) {
    let plane = |n: DVec3, a: DVec3| {
        let n = n.normalize();
        let n = if n.dot(a - eye) > 0.0 { -n } else { n };
        (Some(n.dot(a - eye) / n.dot(d)), n, None)
    };
    match shape {
        Shape::Triangle([a, b, c]) => plane((b - a).cross(c - a), a),
        Shape::Quad([a, b, c, dd]) => plane((c - a).cross(dd - b), a),
        Shape::Sphere { center, radius } => {
            let Some(t) = sphere_t(eye, d, center, radius) else {
                return (None, DVec3::ZERO, Some(radius));
            };
            let n = (eye + d * t - center).normalize();
            let inside = (eye - center).length() < radius;
            (Some(t), if inside { -n } else { n }, Some(radius))
        }
    }
}

/// Over random scenes of spheres, triangles and quads (one camera in four inside a sphere),
/// with every `--accel`: background pixels hold z-depth +inf and normal 0; a hit's z-depth is
/// the exact f64 distance to its primitive times the ray's cosine with the forward axis,
/// within the depth's 1e-5 relative, and its normal is unit, faces the camera (`n . d <= 0`)
/// and is the primitive's f64 normal: a polygon's to 1e-6, a sphere's within its stated
/// `48u t / (r cos)` (docs/precision.md).
#[test]
fn normals_and_zdepth_files_hold_each_primitive_f64_geometry_with_every_accel() {
    let (w, h) = (56usize, 40usize);
    let size = format!("{w}x{h}");
    let mut rng = Rng::new(0x2D3E_0A11);
    let mut checked = [0usize; 3];
    for case in 0..8 {
        let dir = TempDir::new(&format!("surface-out-{case}"));
        let mut shapes = random_spheres(&mut rng, 4);
        shapes.extend(random_triangles(&mut rng, 4));
        shapes.extend(random_quads(&mut rng, 4));
        let mut cam = random_camera(&mut rng);
        if case % 4 == 3
            && let Shape::Sphere { center, radius } = shapes[0]
        {
            cam.eye = center + rng.direction() * radius * 0.5;
        }
        fs::write(dir.join("s.sc"), scene_text(&cam, &shapes)).unwrap();
        let scene = lanecast::load_scene(&dir.join("s.sc")).unwrap();
        let camera = Camera::for_scene(&scene, w as u32, h as u32, None).unwrap();
        let tables = camera.tables::<f64>(1, 1);
        for accel in ["auto", "none", "tiles", "bvh", "world"] {
            let what = format!("case {case} --accel {accel}");
            ok(
                &dir,
                &[
                    "-i",
                    "s.sc",
                    "-size",
                    &size,
                    "--accel",
                    accel,
                    "-o",
                    "a.png",
                    "--ids",
                    "i.npy",
                    "--depth",
                    "d.npy",
                    "--zdepth",
                    "z.npy",
                    "--normals",
                    "n.npy",
                ],
            );
            let ids = i32s(&dir.join("i.npy"));
            let depth = f32s(&dir.join("d.npy"), &format!("({h}, {w})"));
            let z = f32s(&dir.join("z.npy"), &format!("({h}, {w})"));
            let n = f32s(&dir.join("n.npy"), &format!("({h}, {w}, 3)"));
            assert_eq!((ids.len(), z.len(), n.len()), (w * h, w * h, 3 * w * h));
            for (i, &id) in ids.iter().enumerate() {
                let ni = DVec3::new(n[3 * i].into(), n[3 * i + 1].into(), n[3 * i + 2].into());
                if id < 0 {
                    assert_eq!((z[i], ni), (f32::INFINITY, DVec3::ZERO), "{what} pixel {i}");
                    continue;
                }
                let d = DVec3::from_array(tables.dir_x1(i % w, i / w));
                let t = f64::from(depth[i]);
                assert!(
                    (ni.length() - 1.0).abs() < 1e-6,
                    "{what} pixel {i}: |n| {ni}"
                );
                assert!(ni.dot(d) <= 1e-6, "{what} pixel {i}: {ni} faces away");
                let shape = scene.shapes.get(id as usize);
                let (t64, n64, radius) = exact(shape, camera.eye, d);
                let Some(t64) = t64 else {
                    continue; // a silhouette pixel the f64 ray just misses
                };
                let z64 = t64 * d.dot(camera.f);
                assert!(
                    (f64::from(z[i]) - z64).abs() <= (1e-5 + 2.0 * U) * z64,
                    "{what} pixel {i}: z {} against the exact {z64}",
                    z[i]
                );
                let angle = ni.cross(n64).length();
                let (bound, kind) = match radius {
                    // the f32 depth's error moves the hit along the ray, turning the normal
                    Some(r) => (48.0 * U * t / (r * n64.dot(d).abs()) + 1e-6, 0),
                    None => (
                        1e-6,
                        if matches!(shape, Shape::Triangle(_)) {
                            1
                        } else {
                            2
                        },
                    ),
                };
                assert!(
                    ni.dot(n64) > 0.0 && angle <= bound,
                    "{what} pixel {i}: {ni} is {angle:e} rad from the exact {n64} (bound {bound:e})"
                );
                checked[kind] += 1;
            }
        }
    }
    assert!(checked.iter().all(|&k| k > 500), "{checked:?}");
}

/// A scene of one sphere straight ahead.
const BALL: &str = "camera eye 0 0 5 look 0 0 0 up 0 1 0 fov 40\nsphere 0 0 0 1\n";

/// Bad names for the new outputs are refused before anything is written: a name not ending in
/// `.npy`, the same file as another output (however spelled), `-` (standard output is the
/// image's only), a plain name with several views, two patterns naming the same files; and
/// `--seed` with `-cm shade`. A valid `-o -` with `--normals` streams the image and writes the
/// file.
#[test]
fn bad_normals_and_zdepth_names_are_refused_with_nothing_written() {
    let dir = TempDir::new("surface-refused");
    fs::write(dir.join("b.sc"), BALL).unwrap();
    fs::create_dir(dir.join("sub")).unwrap();
    let cases: &[(&[&str], &str)] = &[
        (
            &["--normals", "n.txt"],
            "--normals n.txt: written as NumPy data",
        ),
        (
            &["--zdepth", "z.png"],
            "--zdepth z.png: written as NumPy data",
        ),
        (&["--normals", "-"], "--normals -: written as NumPy data"),
        (
            &["-o", "-", "--zdepth", "-"],
            "--zdepth -: written as NumPy data",
        ),
        (
            &["--depth", "d.npy", "--zdepth", "sub/../d.npy"],
            "name the same file",
        ),
        (
            &["--normals", "x.npy", "--zdepth", "./x.npy"],
            "name the same file",
        ),
        (
            &["-o", "f%d.png", "--orbit", "2", "--normals", "n.npy"],
            "--normals n.npy: it holds no %d",
        ),
        (
            &[
                "-o",
                "f%d.png",
                "--orbit",
                "2",
                "--zdepth",
                "z%d.npy",
                "--normals",
                "z%d.npy",
            ],
            "would both write",
        ),
        (&["-cm", "shade", "--seed", "3"], "--seed 3: -cm shade"),
    ];
    for (extra, needle) in cases {
        let mut args = vec!["-i", "b.sc", "-size", "16x12", "-o", "a.png"];
        if extra.contains(&"-o") {
            args.truncate(4);
        }
        args.extend_from_slice(extra);
        let o = run(&dir.path, &args);
        let what = args.join(" ");
        assert_eq!(o.status.code(), Some(2), "{what}: {}", stderr(&o));
        assert!(stderr(&o).contains(needle), "{what}: {}", stderr(&o));
        assert!(o.stdout.is_empty(), "{what}");
        assert_eq!(dir.entries(), ["b.sc", "sub"], "{what}");
    }
    // the image to standard output, the normals to their file
    let o = ok(
        &dir,
        &[
            "-i",
            "b.sc",
            "-size",
            "16x12",
            "-o",
            "-",
            "--normals",
            "n.npy",
        ],
    );
    assert_eq!(&o.stdout[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(f32s(&dir.join("n.npy"), "(12, 16, 3)").len(), 16 * 12 * 3);
    // with -o -, a .npy output is a file per view for --skip-existing to find
    ok(
        &dir,
        &[
            "-i",
            "b.sc",
            "-size",
            "16x12",
            "--orbit",
            "2",
            "-o",
            "-",
            "--skip-existing",
            "--zdepth",
            "z%d.npy",
        ],
    );
    // each view's file with its record, which --skip-existing reads
    assert_eq!(
        dir.entries(),
        [
            ".z0.npy.lanecast-view",
            ".z1.npy.lanecast-view",
            "b.sc",
            "n.npy",
            "sub",
            "z0.npy",
            "z1.npy"
        ]
    );
}

/// Many views number the new outputs with the others; `--skip-existing` renders again exactly
/// the views whose z-depth or normals file is not whole (cut short, or the other shape), and
/// the files it rewrites come back byte for byte.
#[test]
fn numbered_normals_and_zdepth_resume_with_skip_existing() {
    let dir = TempDir::new("surface-views");
    dir.copy_in(&seed_scene(5), "s.sc");
    let args = [
        "-i",
        "s.sc",
        "--orbit",
        "4",
        "-size",
        "40x30",
        "-o",
        "f%d.png",
        "--zdepth",
        "z%02d.npy",
        "--normals",
        "n%d.npy",
        "--stats",
        "s.json",
    ];
    ok(&dir, &args);
    let names = |k: usize| {
        [
            format!("f{k}.png"),
            format!("z{k:02}.npy"),
            format!("n{k}.npy"),
        ]
    };
    let before: Vec<Vec<Vec<u8>>> = (0..4)
        .map(|k| {
            names(k)
                .iter()
                .map(|n| fs::read(dir.join(n)).unwrap())
                .collect()
        })
        .collect();
    for k in 0..4 {
        let z = f32s(&dir.join(&names(k)[1]), "(30, 40)");
        let n = f32s(&dir.join(&names(k)[2]), "(30, 40, 3)");
        assert!(z.iter().any(|v| v.is_finite()), "view {k} sees the scene");
        assert!(n.iter().any(|&v| v != 0.0), "view {k}");
    }
    assert_ne!(before[0][2], before[1][2], "views 0 and 1 are other poses");
    // view 1: normals cut short; view 3: a z-depth of the normals' shape (the file is whole
    // but not this output's)
    let n1 = &before[1][2];
    fs::write(dir.join("n1.npy"), &n1[..n1.len() - 1]).unwrap();
    fs::write(dir.join("z03.npy"), &before[3][2]).unwrap();
    let mut again = args.to_vec();
    again.push("--skip-existing");
    ok(&dir, &again);
    let stats: serde_json::Value =
        serde_json::from_slice(&fs::read(dir.join("s.json")).unwrap()).unwrap();
    assert_eq!(stats["views_summary"]["rendered"], 2);
    assert_eq!(stats["views_summary"]["skipped"], 2);
    assert_eq!(stats["views"][1]["outputs"]["normals"], "n1.npy");
    assert_eq!(stats["views"][3]["outputs"]["zdepth"], "z03.npy");
    // the run's outputs are the patterns; each view's, its own names
    assert_eq!(stats["outputs"]["normals"], "n%d.npy");
    assert_eq!(stats["outputs"]["zdepth"], "z%02d.npy");
    assert_eq!(stats["outputs"]["image"], "f%d.png");
    assert_eq!(stats["outputs"]["stats"], "s.json");
    for (k, files) in before.iter().enumerate() {
        for (name, bytes) in names(k).iter().zip(files) {
            assert!(fs::read(dir.join(name)).unwrap() == *bytes, "{name}");
        }
    }
}

/// `-cm shade` on a sphere face-on: every hit pixel grey, the brightest at the centre and the
/// brightness falling towards the rim along the middle row; black exactly where the ids say
/// background; with the light `0.15 + 0.85 |n . d|` times the dimming (`-cv linear`), the
/// centre at full grey and the rim at no less than the edge-on light of the farthest hit.
#[test]
fn shade_lights_a_sphere_brightest_face_on_and_leaves_the_background_black() {
    let dir = TempDir::new("surface-shade");
    fs::write(dir.join("b.sc"), BALL).unwrap();
    let s = 65u32;
    ok(
        &dir,
        &[
            "-i", "b.sc", "-size", "65x65", "-cm", "shade", "-o", "a.png", "--ids", "i.npy",
        ],
    );
    let img = image_of(&dir.join("a.png"), s, s);
    let ids = i32s(&dir.join("i.npy"));
    let grey = |x: u32, y: u32| {
        let p = img.get_pixel(x, y).0;
        assert!(p[0] == p[1] && p[1] == p[2], "({x}, {y}): {p:?}");
        p[0]
    };
    let mut hits = 0;
    for y in 0..s {
        for x in 0..s {
            let g = grey(x, y);
            if ids[(y * s + x) as usize] < 0 {
                assert_eq!(g, 0, "({x}, {y}) background");
            } else {
                assert!(
                    g >= (235.0 * 0.2 * 0.15f64).floor() as u8,
                    "({x}, {y}): {g}"
                );
                assert!(g <= grey(32, 32), "({x}, {y}) brighter than the centre");
                hits += 1;
            }
        }
    }
    assert!(hits > 500, "{hits}");
    assert_eq!(grey(32, 32), 235, "the nearest point, face-on: full grey");
    let row: Vec<u8> = (32..s).map(|x| grey(x, 32)).collect();
    let lit: Vec<u8> = row.iter().copied().take_while(|&g| g > 0).collect();
    assert!(lit.len() > 10, "{row:?}");
    assert!(lit.windows(2).all(|p| p[1] <= p[0]), "{row:?}");
    assert!(lit.last().unwrap() < &100, "the rim, near edge-on: {row:?}");
}

/// The palette modes are as they were: README's pictures of the seed scenes (`-cm ordered`,
/// docs/scenes/) come out byte for byte, and `-cm random` ignores everything `shade` adds
/// (its image with `--normals` asked for is the same).
#[test]
fn palette_modes_still_draw_readmes_seed_pictures() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = TempDir::new("surface-palette");
    for n in [1, 4, 7] {
        dir.copy_in(&seed_scene(n), "s.sc");
        ok(&dir, &["-i", "s.sc", "-cm", "ordered", "-o", "a.png"]);
        let want = image_of(&root.join(format!("docs/scenes/scene{n}.png")), 640, 480);
        assert!(image_of(&dir.join("a.png"), 640, 480) == want, "scene{n}");
    }
    ok(&dir, &["-i", "s.sc", "-size", "96x64", "-o", "r.png"]);
    ok(
        &dir,
        &[
            "-i",
            "s.sc",
            "-size",
            "96x64",
            "-o",
            "q.png",
            "--normals",
            "n.npy",
        ],
    );
    assert_eq!(
        fs::read(dir.join("r.png")).unwrap(),
        fs::read(dir.join("q.png")).unwrap()
    );
}

/// README's mesh pictures are `-cm shade` renders of their scenes, as the command beside them
/// says (`lanecast -i scenes/NAME.sc -o docs/scenes/NAME.png -cm shade`), pixel for pixel.
#[test]
fn readmes_mesh_pictures_are_shade_renders() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let dir = TempDir::new("surface-pictures");
    for name in ["bunny", "teapot"] {
        let scene = root.join(format!("scenes/{name}.sc"));
        ok(
            &dir,
            &["-i", scene.to_str().unwrap(), "-o", "a.png", "-cm", "shade"],
        );
        let want = image_of(&root.join(format!("docs/scenes/{name}.png")), 640, 480);
        let got = image_of(&dir.join("a.png"), 640, 480);
        assert!(got == want, "{name}");
        assert!(
            got.pixels().all(|p| p[0] == p[1] && p[1] == p[2]),
            "{name}: grey"
        );
    }
}
