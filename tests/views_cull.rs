//! Many views leave out the clusters of triangles they prove they cannot see (`render::cull`):
//! every view must still be a render of every primitive, bit for bit. Camera paths that turn
//! slowly (where the last view's guess is good), jump at random (where it is bad), and dolly
//! from far off into the scene, on the seed scans and on a scene of subdivided spheres with
//! quads and spheres among them, with `--precision auto` and `f32`: each view's ids, depths and
//! re-decided pixels equal a renderer of its own. The paths must leave primitives out and
//! take second renders, or the test would not test the culling (the raw scans' clusters are
//! mostly unbounded, so their views leave out only what is off screen: the spheres' views take
//! the trials). A scene built for it takes the third render, which those paths never need.

mod common;

use common::{Rng, bounds, icosphere};
use glam::DVec3;
use lanecast::scene::cameras::orbit;
use lanecast::scene::{CameraSpec, Scene, Shape, Shapes};
use lanecast::{Camera, Options, Precision, Renderer, Views, load_scene};
use std::path::Path;

/// Three subdivided spheres of triangles (runs of 64 neighbouring faces), one behind the
/// other, a floor of quads and two sphere primitives.
fn spheres_scene() -> Scene {
    let mut shapes = Shapes::new();
    let balls = [
        (DVec3::new(0.0, 1.0, 0.0), 1.0),
        (DVec3::new(0.4, 1.2, -3.0), 1.5),
        (DVec3::new(-2.5, 0.8, -1.0), 0.8),
    ];
    for (centre, r) in balls {
        for t in icosphere(centre, r, 4) {
            shapes.push(Shape::Triangle(t), 2);
        }
    }
    for i in -2..2 {
        let (x0, x1) = (i as f64 * 3.0, i as f64 * 3.0 + 3.0);
        let quad =
            [(x0, 6.0), (x1, 6.0), (x1, -6.0), (x0, -6.0)].map(|(x, z)| DVec3::new(x, -0.2, z));
        shapes.push(Shape::Quad(quad), 3);
    }
    for (c, r) in [
        (DVec3::new(2.0, 0.5, 1.0), 0.5),
        (DVec3::new(-1.0, 2.5, -5.0), 0.7),
    ] {
        shapes.push(
            Shape::Sphere {
                center: c,
                radius: r,
            },
            4,
        );
    }
    let mut scene = lanecast::parse_scene(
        "camera eye 0 2 7 look 0 1 -1 up 0 1 0 fov 50\n",
        Path::new("balls.sc"),
    )
    .unwrap();
    scene.shapes = shapes;
    scene
}

/// Cameras: a slow orbit, random jumps from inside the scene to four radii off, and a dolly
/// from far off to the centre.
fn paths(scene: &Scene, rng: &mut Rng) -> Vec<Vec<CameraSpec>> {
    let (centre, diagonal) = bounds(scene);
    let radius = diagonal / 2.0;
    let slow = orbit(&scene.camera, 48).into_iter().take(10).collect();
    let jumps = (0..8)
        .map(|_| CameraSpec {
            eye: centre + rng.direction() * radius * rng.range(0.2, 4.0),
            look: centre + rng.direction() * radius * rng.range(0.0, 0.5),
            up: rng.direction(),
            lens: Some(lanecast::Lens::Fov(rng.range(10.0, 100.0))),
        })
        .collect();
    let from = centre + rng.direction() * radius * 3.0;
    let dolly = (0..8)
        .map(|k| CameraSpec {
            eye: from + (centre - from) * (k as f64 / 8.0),
            look: centre,
            up: DVec3::Y,
            lens: Some(lanecast::Lens::Fov(60.0)),
        })
        .collect();
    vec![slow, jumps, dolly]
}

/// The image size of every view.
const SIZE: (u32, u32) = (320, 240);

#[test]
fn views_that_leave_clusters_out_render_every_primitive_bit_for_bit() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut scenes = vec![spheres_scene()];
    for name in ["bunny.sc", "armadillo.sc", "teapot.sc"] {
        scenes.push(load_scene(&root.join("scenes").join(name)).expect(name));
    }
    let mut rng = Rng::new(0x0CC1_0DED);
    let (mut views_done, mut culled, mut second, mut third) = (0, 0, 0, 0);
    for scene in &scenes {
        for path in paths(scene, &mut rng) {
            for precision in [Precision::Auto, Precision::F32] {
                let options = Options {
                    precision,
                    ..Options::default()
                };
                let views = Views::new(scene, &options).unwrap();
                for (k, spec) in path.iter().enumerate() {
                    let Ok(camera) = Camera::look_at(spec, SIZE.0, SIZE.1) else {
                        continue;
                    };
                    if views.check(&camera).is_err() {
                        continue;
                    }
                    let what = format!("{} {precision:?} view {k}", scene.source.display());
                    let got = views.render_marking(&camera).unwrap();
                    let alone = Renderer::new(scene, &camera, &options).unwrap();
                    let (want, redone) = alone.render_marking(None);
                    let pixel =
                        |f: &lanecast::Frame<f32>, p: usize| (f.ids[p], f.depth[p].to_bits());
                    if let Some(p) =
                        (0..want.ids.len()).find(|&p| pixel(&got.frame, p) != pixel(&want, p))
                    {
                        panic!(
                            "{what}: pixel {p}: (id, depth bits) {:?}, alone {:?}",
                            pixel(&got.frame, p),
                            pixel(&want, p)
                        );
                    }
                    assert_eq!(got.redecided, redone, "{what}: re-decided pixels");
                    views_done += 1;
                    culled += usize::from(got.left_out > 0);
                    second += usize::from(got.renders >= 2);
                    third += usize::from(got.renders >= 3);
                    views.recycle(got.frame);
                }
            }
        }
    }
    eprintln!(
        "{views_done} views: {culled} left primitives out, {second} rendered twice, {third} three times"
    );
    assert!(
        views_done > 150 && culled > views_done / 4 && second > 20,
        "{views_done} views: {culled} left primitives out, {second} rendered twice"
    );
}

/// The rectangle `[x0, x1] x [y0, y1]` at depth `z`, in `nx` x `ny` cells of two triangles, as
/// scene lines: wound towards +z (`(B - A) x (C - A)` along +z), or away from it.
fn sheet_lines(
    ([x0, x1], [y0, y1], z): ([f64; 2], [f64; 2], f64),
    (nx, ny): (usize, usize),
    towards: bool,
) -> String {
    let at = |i: usize, j: usize| {
        let (u, v) = (i as f64 / nx as f64, j as f64 / ny as f64);
        format!("{} {} {z}", x0 + (x1 - x0) * u, y0 + (y1 - y0) * v)
    };
    let mut text = String::new();
    for i in 0..nx {
        for j in 0..ny {
            let (a, b, c, d) = (at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1));
            let (t1, t2) = if towards {
                ([&a, &b, &c], [&a, &c, &d])
            } else {
                ([&a, &c, &b], [&a, &d, &c])
            };
            for t in [t1, t2] {
                text += &format!("triangle {}  {}  {}\n", t[0], t[1], t[2]);
            }
        }
    }
    text
}

/// The third render of `render::cull`'s step 4, which the paths above never take. The ground
/// of `scenes/stress/ground.sc` (a sphere of radius 1e4, whose hits near the horizon `auto`
/// re-decides), a wall facing the eye across the horizon, and nearer, wound away from the eye,
/// clusters of two strips each, one above the horizon and one below (64 faces: one cluster),
/// with the horizon and the wall seen between them. The strips face away, so the first view
/// leaves them out on trial; nothing hides them, so they fail and take the second render; the
/// first frame re-decided horizon pixels in their rectangles, so the second render holds the
/// ground too, and re-decides the horizon behind the wall, where the first frame's hit (the
/// wall) is not nearer than the strips can be: neither frame holds those pixels, and a third
/// render gives them (in the views after the first). Every view equals a renderer of its own:
/// ids, depths, re-decided pixels.
#[test]
fn a_third_render_gives_the_pixels_neither_frame_holds() {
    let mut text = String::from("camera eye 0 1.5 0 look 0 0 -20 up 0 1 0 fov 60\n");
    for c in 0..4 {
        let x = [-4.0 + 2.0 * c as f64, -2.0 + 2.0 * c as f64];
        text += &sheet_lines((x, [1.6, 1.8], -10.0), (16, 1), false);
        text += &sheet_lines((x, [0.4, 0.6], -10.0), (16, 1), false);
    }
    text += &sheet_lines(([-2.0, 2.0], [0.0, 4.0], -30.0), (8, 8), true);
    text += "sphere 0 -10000 0 10000\n";
    let scene = lanecast::parse_scene(&text, Path::new("third.sc")).unwrap();
    let options = Options {
        precision: Precision::Auto,
        ..Options::default()
    };
    let views = Views::new(&scene, &options).unwrap();
    let mut renders = Vec::new();
    for k in 0..4 {
        let spec = CameraSpec {
            eye: scene.camera.eye + DVec3::new(0.02 * k as f64, 0.0, 0.0),
            ..scene.camera
        };
        let camera = Camera::look_at(&spec, SIZE.0, SIZE.1).unwrap();
        views.check(&camera).unwrap();
        let got = views.render_marking(&camera).unwrap();
        let (want, redone) = Renderer::new(&scene, &camera, &options)
            .unwrap()
            .render_marking(None);
        assert_eq!(got.frame.ids, want.ids, "view {k}");
        let bits = |d: &[f32]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        assert_eq!(bits(&got.frame.depth), bits(&want.depth), "view {k}");
        assert_eq!(got.redecided, redone, "view {k}: re-decided pixels");
        renders.push((got.renders, got.left_out, redone.len()));
        views.recycle(got.frame);
    }
    // (3 of the 4 views take the third render; checked to fail when the third render's
    // values are not put in)
    assert!(
        renders.iter().filter(|r| r.0 == 3).count() >= 2,
        "renders, left out, re-decided: {renders:?}"
    );
}
