//! Accelerations agree with testing every primitive, byte for byte, through random cameras:
//! the repository's meshes and seed scenes at several scales, seen from 1 to 1e4 times their
//! size, with fields of view from 0.01 to 179 degrees, eyes inside and outside the meshes and up
//! vectors near the view direction. Every precision (`f32`, `auto`, `f64`) and both scalar
//! kernels render each camera with `--accel none`, `tiles` and `bvh`; ids and depths must be
//! equal bit for bit. The cases the random search found are kept below as named tests.

mod common;

use common::{Rng, bounds};
use glam::DVec3;
use lanecast::Accel;
use lanecast::Camera;
use lanecast::scene::{CameraSpec, Scene, Shape, Shapes};
use lanecast::{Kernel, Options, Precision, Renderer};
use std::path::Path;

/// What renders a case: each is checked through every acceleration against `none`.
#[derive(Debug, Clone, Copy)]
enum Kind {
    F32,
    Auto,
    F64,
    ScalarF32,
    ScalarF64,
}

const ALL: [Kind; 5] = [
    Kind::F32,
    Kind::Auto,
    Kind::F64,
    Kind::ScalarF32,
    Kind::ScalarF64,
];

impl Kind {
    fn options(self, accel: Accel) -> Options {
        let (kernel, precision) = match self {
            Kind::F32 => (Kernel::Packet, Precision::F32),
            Kind::Auto => (Kernel::Packet, Precision::Auto),
            Kind::F64 => (Kernel::Packet, Precision::F64),
            Kind::ScalarF32 => (Kernel::Scalar, Precision::F32),
            Kind::ScalarF64 => (Kernel::Scalar, Precision::F64),
        };
        Options {
            precision,
            accel,
            kernel,
        }
    }
}

/// A scene of the repository, parsed.
fn repo_scene(name: &str) -> Scene {
    let p = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("scenes")
        .join(name);
    lanecast::scene::load_scene(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()))
}

/// `scene`'s shapes scaled by `s` about the origin (every shape loose).
fn scaled(scene: &Scene, s: f64) -> Scene {
    let mut shapes = Shapes::new();
    for (i, shape) in scene.shapes.iter().enumerate() {
        let moved = match shape {
            Shape::Sphere { center, radius } => Shape::Sphere {
                center: center * s,
                radius: radius * s,
            },
            Shape::Triangle(v) => Shape::Triangle(v.map(|p| p * s)),
            Shape::Quad(v) => Shape::Quad(v.map(|p| p * s)),
        };
        shapes.push(moved, scene.shapes.line(i));
    }
    Scene {
        source: scene.source.clone(),
        camera: scene.camera,
        camera_at: scene.camera_at,
        shapes,
        warnings: Vec::new(),
    }
}

/// A random camera for a scene of centre `c` and size `size`, with its fov: mostly telephoto
/// views of a detail from 1 to 1e4 sizes away; some from inside the scene's box looking any
/// way; fields of view log-uniform from 0.01 to 179 degrees (narrow ones more often); an up
/// vector near the view direction one time in four.
fn random_camera(rng: &mut Rng, c: DVec3, size: f64) -> CameraSpec {
    let (eye, look) = if rng.unit() < 0.8 {
        let look = rng.in_box(c, size * 0.3);
        let eye = look + rng.direction() * size * 10f64.powf(rng.range(0.0, 4.0));
        (eye, look)
    } else {
        let eye = rng.in_box(c, size * 0.25);
        (eye, eye + rng.direction() * size)
    };
    let dir = (look - eye).normalize();
    let up = if rng.unit() < 0.25 {
        // within 1e-8 to 1e-2 radians of the view direction
        dir + dir.any_orthonormal_vector() * 10f64.powf(rng.range(-8.0, -2.0))
    } else {
        rng.direction()
    };
    let fov = if rng.unit() < 0.6 {
        10f64.powf(rng.range(-2.0, 0.7))
    } else {
        10f64.powf(rng.range(-2.0, 179f64.log10()))
    };
    CameraSpec {
        eye,
        look,
        up,
        lens: Some(lanecast::Lens::Fov(fov)),
    }
}

/// `scene` seen by `spec`, when lanecast accepts that camera for it (else `None`).
fn with_camera(scene: &Scene, spec: CameraSpec) -> Option<Scene> {
    lanecast::experimental::scene::validate::camera(&spec).ok()?;
    let mut s = scene.clone();
    s.camera = spec;
    lanecast::experimental::scene::range::f32_range(&s).ok()?;
    Some(s)
}

/// The first difference between `none` and another acceleration for any of `kinds` on `scene`
/// at `w` x `h`, described; `None` when every frame is equal bit for bit.
fn first_difference(scene: &Scene, (w, h): (u32, u32), kinds: &[Kind]) -> Option<String> {
    let fov = scene.camera.fov_deg().expect("a random camera has its fov");
    let camera = Camera::new(&scene.camera, fov, w, h);
    for &kind in kinds {
        let render = |accel| {
            let r = Renderer::new(scene, &camera, &kind.options(accel)).expect("valid options");
            assert_eq!(r.accel(), accel);
            r.render_marking(None)
        };
        let (none, redone) = render(Accel::None);
        for accel in [Accel::Tiles, Accel::Bvh] {
            let (other, other_redone) = render(accel);
            if redone != other_redone {
                return Some(format!(
                    "{kind:?} {}: {} pixels decided again in f64, against {} with none",
                    accel.name(),
                    other_redone.len(),
                    redone.len()
                ));
            }
            let differ = (0..none.ids.len())
                .filter(|&i| {
                    (none.ids[i], none.depth[i].to_bits())
                        != (other.ids[i], other.depth[i].to_bits())
                })
                .collect::<Vec<_>>();
            if let Some(&i) = differ.first() {
                return Some(format!(
                    "{kind:?} {}: {} pixels differ, first ({}, {}): none {} at {}, {} at {}",
                    accel.name(),
                    differ.len(),
                    i % w as usize,
                    i / w as usize,
                    none.ids[i],
                    none.depth[i],
                    other.ids[i],
                    other.depth[i]
                ));
            }
        }
    }
    None
}

/// The scenes the random cameras look at: the meshes (the armadillo only where `big`), the seed
/// scenes, each at scales 1e-3, 1 and 1e3.
fn scenes(big: bool) -> Vec<(String, Scene)> {
    let mut names = vec![
        "bunny.sc",
        "teapot.sc",
        "scene1.sc",
        "scene2.sc",
        "scene3.sc",
        "scene4.sc",
    ];
    if big {
        names.extend(["armadillo.sc", "scene5.sc", "scene6.sc", "scene7.sc"]);
        let stress = std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/stress"));
        let mut more: Vec<String> = stress
            .expect("scenes/stress")
            .map(|e| {
                e.expect("an entry")
                    .file_name()
                    .to_string_lossy()
                    .into_owned()
            })
            .filter(|name| name.ends_with(".sc"))
            .map(|name| format!("stress/{name}"))
            .collect();
        more.sort();
        names.extend(more.into_iter().map(|n| &*n.leak()));
    }
    let mut out = Vec::new();
    for name in names {
        let scene = repo_scene(name);
        for s in [1e-3, 1.0, 1e3] {
            out.push((format!("{name} x{s}"), scaled(&scene, s)));
        }
    }
    out
}

/// Renders `cameras` random cameras spread over `scenes` (seeded by `seed`) at `size` with
/// `kinds`; returns the cases that differ, each as a line to paste into a regression test.
fn survey(
    scenes: &[(String, Scene)],
    seed: u64,
    cameras: usize,
    size: (u32, u32),
    kinds: &[Kind],
) -> (usize, Vec<String>) {
    let mut rng = Rng::new(seed);
    let (mut tried, mut failed) = (0, Vec::new());
    // (a camera lanecast refuses for its scene is drawn again, for the next scene)
    for attempt in 0..cameras * 20 {
        if tried == cameras {
            break;
        }
        let (name, scene) = &scenes[attempt % scenes.len()];
        let (c, size_of) = bounds(scene);
        let Some(case) = with_camera(scene, random_camera(&mut rng, c, size_of)) else {
            continue;
        };
        tried += 1;
        if let Some(why) = first_difference(&case, size, kinds) {
            let k = case.camera;
            failed.push(format!(
                "{name}: eye {:?} look {:?} up {:?} fov {:?}: {why}",
                k.eye.to_array(),
                k.look.to_array(),
                k.up.to_array(),
                k.fov_deg().unwrap_or(f64::NAN)
            ));
        }
    }
    (tried, failed)
}

/// The property: random cameras on the seed scenes and meshes at three scales, every precision
/// and both scalar kernels, `tiles` and `bvh` equal to `none` bit for bit.
#[test]
fn random_cameras_render_alike_through_every_acceleration() {
    let scenes = scenes(false);
    let (tried, failed) = survey(&scenes, 0x000A_CCE1_2024, 150, (40, 24), &ALL);
    assert_eq!(tried, 150);
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// The same property over thousands of cameras and every repository scene, for the f32 and
/// auto precisions (run by hand: `cargo test --release --test accel_random -- --ignored`).
#[test]
#[ignore]
fn thousands_of_random_cameras_render_alike() {
    let scenes = scenes(true);
    let cameras = std::env::var("CAMERAS").map_or(3000, |v| v.parse().expect("a count"));
    let (tried, failed) = survey(
        &scenes,
        0x05EE_D0FA_CCE1,
        cameras,
        (64, 48),
        &[Kind::F32, Kind::Auto],
    );
    eprintln!("{tried} cameras, {} differ", failed.len());
    assert!(failed.is_empty(), "{}", failed.join("\n"));
}

/// A camera as literal floats: eye, look, up and fov (degrees).
type Shot = ([f64; 3], [f64; 3], [f64; 3], f64);

/// One camera the random search found rendering differently through an acceleration before
/// the tiles and the BVH were sized by the kernels' written error bound (`accel::reach`):
/// the repository scene `name` scaled by `scale`, seen from `eye` towards `look` with `up` and
/// `fov` degrees, at `size`; `kinds` must render alike through every acceleration.
fn regression(
    name: &str,
    scale: f64,
    (eye, look, up, fov): Shot,
    size: (u32, u32),
    kinds: &[Kind],
) {
    let spec = CameraSpec {
        eye: DVec3::from(eye),
        look: DVec3::from(look),
        up: DVec3::from(up),
        lens: Some(lanecast::Lens::Fov(fov)),
    };
    let scene = with_camera(&scaled(&repo_scene(name), scale), spec)
        .unwrap_or_else(|| panic!("{name}: lanecast refuses the camera"));
    if let Some(why) = first_difference(&scene, size, kinds) {
        panic!("{name} x{scale}: {why}");
    }
}

/// The bunny from 1,468 units away through half a degree: the f32 kernel accepts rays on
/// slivers of its silhouette (seen nearly edge-on) in a strip across the image, which the
/// tiles' rectangles left out (8 pixels differed) and the BVH's boxes too.
#[test]
fn bunny_from_1468_units_at_half_a_degree() {
    let camera = (
        [1468.2884, -14.6069, 306.1969],
        [1.3537, 3.2223, 0.9267],
        [0.0, 1.0, 0.0],
        0.5,
    );
    regression("bunny.sc", 1.0, camera, (200, 150), &ALL);
}

/// Found by `random_cameras_render_alike_through_every_acceleration` (its first seed).
#[test]
fn bunny_at_a_thousandth_through_0_03_degrees() {
    let camera = (
        [
            -3.6065819397247876,
            -0.4159140140486566,
            -1.6190556905313422,
        ],
        [
            0.0014193085801342286,
            0.008453993700061703,
            -0.0003941116938987713,
        ],
        [0.9071795896043352, 0.1067013166058743, 0.40698896943271207],
        0.03105095154502538,
    );
    regression("bunny.sc", 1e-3, camera, (40, 24), &ALL);
}

/// Found by `random_cameras_render_alike_through_every_acceleration`: 65 pixels differed,
/// nearer hits found by `none` on slivers the tiles had binned elsewhere.
#[test]
fn teapot_from_450_000_units_through_0_014_degrees() {
    let camera = (
        [40819.20953504175, 272967.1796382369, -351049.6692705674],
        [-13.177051626610094, 12.480427089699717, -2.1372985181141324],
        [
            -0.07378915668255974,
            -0.8293573240730658,
            -0.5538245113413094,
        ],
        0.013700338182058866,
    );
    regression("teapot.sc", 1.0, camera, (40, 24), &ALL);
}

/// Found by `random_cameras_render_alike_through_every_acceleration`.
#[test]
fn teapot_at_a_thousandth_through_0_05_degrees() {
    let camera = (
        [177.18087238599185, -36.266891773506586, -127.74905507349847],
        [
            0.01124733058764112,
            -0.011608045777919447,
            -0.007182572977592772,
        ],
        [0.6126971386292455, 0.575476032244135, 0.5416913813492722],
        0.054441351436267285,
    );
    regression("teapot.sc", 1e-3, camera, (40, 24), &ALL);
}

/// Found by `random_cameras_render_alike_through_every_acceleration`: 47 pixels differed.
#[test]
fn bunny_at_a_thousandth_through_0_024_degrees() {
    let camera = (
        [32.50005022107668, 25.372886809814805, -11.376511751167662],
        [
            0.00421964532088435,
            0.009180337926295391,
            0.0002092397019122943,
        ],
        [0.6022166993055615, 0.6736544203369863, 0.42839790970306313],
        0.023888060957934432,
    );
    regression("bunny.sc", 1e-3, camera, (40, 24), &ALL);
}

/// Found by `random_cameras_render_alike_through_every_acceleration`: the bunny a thousand
/// times larger, from 1.1e7 units away.
#[test]
fn bunny_thousandfold_from_1e7_units() {
    let camera = (
        [1537464.718976286, -9840782.859475926, 4351434.891028973],
        [-4254.462220392574, 3632.373856007836, -4338.179466945195],
        [0.7711740179332222, 0.4002559272293237, 0.49506143738179087],
        0.035437794212506875,
    );
    regression("bunny.sc", 1e3, camera, (40, 24), &ALL);
}

/// Found by `thousands_of_random_cameras_render_alike` (147 of its 3,000 cameras differed):
/// the first case on each scene, and the two where the BVH differed (a grid's slivers, and
/// the grazing plane from 8e6 units away). 64 x 48 pixels, f32 and auto, as found.
#[test]
fn surveyed_cameras_render_alike() {
    #[rustfmt::skip]
    let cases: [(&str, f64, Shot); 13] = [
        ("armadillo.sc", 1.0, ([387.9155127273475, 41846.178127757405, 1384.7979785197158], [-57.94101008284909, 18.855750524260433, -68.52475487465448], [-0.2714213501792939, 0.8918455904864907, -0.36185894129709123], 0.33796712044906746)),
        ("bunny.sc", 1.0, ([-17.900318129590534, -486.8149028887647, 48.8108857087308], [0.7651753834830659, 0.6556653543922177, -3.236568825988202], [0.8088972827297674, -0.4660829934792611, -0.3584017706175709], 0.34421788848321777)),
        ("scene1.sc", 1.0, ([62816.32361950494, -14076.092908581444, -104451.94042323466], [0.8713064078574284, 0.652980982919606, -4.361271579321199], [-0.9294961534696216, 0.3643940163502976, -0.057042979701948035], 0.011330323997846316)),
        ("scene4.sc", 1e-3, ([2.9535414184441944, -13.403832515908809, 36.95837686664376], [0.0020306654344303724, 0.0014161943651020662, 0.001608891491328097], [-0.07489188378519836, 0.3382313575021445, -0.9380801778523064], 0.010450288308872634)),
        ("scene6.sc", 1e-3, ([-26.17074181348576, 27.07113866965646, -0.20276136233969877], [-0.001981310351430199, -5.1609843759892454e-5, -0.00200125679384744], [-0.9007682552612704, -0.22018982476629978, 0.3743434137031839], 0.014282070740893459)),
        ("stress/behind.sc", 1e-3, ([-62.50955567559843, 3.2160623721466273, 18.27088454589753], [0.0007320354146623134, -0.0034060008609774787, 0.0039761067165898605], [0.17353712891791526, -0.5070057746629112, 0.8442926088420933], 0.012457157199711405)),
        ("stress/fan.sc", 1e-3, ([-15.780703523771606, 67.39174514546909, -47.74348740108008], [0.0009865607777138946, -0.0038875995444208797, -0.008291359120798428], [0.18769386010568423, -0.801533859959119, 0.5677274754306058], 0.09464248631338223)),
        ("stress/grazing.sc", 1e3, ([-14066195217.715584, 9225382774.705786, 44858614872.56677], [-5612421.48588088, -1290222.4615910284, -10220831.669995628], [-0.2824414598890851, 0.7737119587548337, 0.5670949008900371], 0.02923058633797757)),
        ("stress/grazing.sc", 1.0, ([-4885251.029316717, 4306040.453866345, 4918712.667386494], [-1618.8421242917598, 5653.544416638846, -4343.7598039727], [-0.698291842372658, 0.2476340027486818, 0.6716144009463054], 3.83880232941444)),
        ("stress/grid.sc", 1e-3, ([267.92739410639314, -274.1577339149896, 196.11019843613428], [0.005521840728655494, -0.017035415834005516, -0.04086493889002485], [-0.6222238225419184, 0.6366368973779827, -0.4555556787407551], 0.06527568192365762)),
        ("stress/icosphere.sc", 1e-3, ([60.003619190525825, 13.594999358172522, -31.607485809351815], [-0.001408104874632873, 0.0032104081213198766, -0.0082532856422393], [0.8464114524552604, -0.1949429497309213, 0.49556523233857314], 0.04629448859493093)),
        ("stress/tiny_far.sc", 1.0, ([202.62800867895834, -147.92301183452614, -10425.868826455244], [0.11895513840911623, 0.13394965670865366, -9999.847222015014], [0.7979017586232742, -0.5206606696514153, 0.3037519558192604], 0.03975871057528235)),
        ("teapot.sc", 1.0, ([207765.99057021906, -230937.3697756938, -187541.06360888085], [25.838775077913382, -17.223546756463, -21.130222105546984], [0.2584324107008582, -0.7460439852031585, -0.6137027466465604], 0.024415708752400116)),
    ];
    for (name, scale, camera) in cases {
        regression(name, scale, camera, (64, 48), &[Kind::F32, Kind::Auto]);
    }
}
