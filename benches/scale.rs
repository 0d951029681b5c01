//! Scaling series and real meshes, per acceleration: render-phase throughput (rays) of the
//! packet kernel on one thread.
//!
//! Scaling scenes are made here, in the layout the Embree comparison uses
//! (`scripts/vs_embree.py`): camera at the origin looking down +z, fov 60, 1280x720; N random
//! spheres or triangles in the box x in [-8, 8], y in [-4.5, 4.5], z in [14, 34], sized so that
//! a ray crosses about two primitives along the whole box at every N (sphere radius
//! sqrt(2 V / (pi L N)), V the box volume, L its depth; triangles of vertices within
//! 2.07 times that radius of a centre). `none` (every packet tests every primitive) runs up to
//! N = 4096 only: beyond that a single frame takes minutes.
//!
//! `LANECAST_BENCH_QUICK=1`: N = 256 and 4096 only, and the bunny.

use criterion::{BenchmarkId, Criterion, Throughput, criterion_group, criterion_main};
use glam::DVec3;
use lanecast::Accel;
use lanecast::Camera;
use lanecast::DEFAULT_FOV;
use lanecast::experimental::render::{PacketScene, render_packet};
use lanecast::scene::{CameraSpec, Scene, Shape, load_scene};
use std::hint::black_box;
use std::path::Path;
use std::time::Duration;

const LO: DVec3 = DVec3::new(-8.0, -4.5, 14.0);
const HI: DVec3 = DVec3::new(8.0, 4.5, 34.0);

/// xorshift64*, seeded per scene.
struct Rng(u64);

impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn in_box(&mut self) -> DVec3 {
        LO + (HI - LO) * DVec3::new(self.unit(), self.unit(), self.unit())
    }
    fn in_ball(&mut self) -> DVec3 {
        loop {
            let p = DVec3::new(self.unit(), self.unit(), self.unit()) * 2.0 - 1.0;
            if p.length_squared() <= 1.0 {
                return p;
            }
        }
    }
}

fn radius(n: usize) -> f64 {
    let v = (HI - LO).x * (HI - LO).y * (HI - LO).z;
    (2.0 * v / (std::f64::consts::PI * (HI - LO).z * n as f64)).sqrt()
}

fn scaling_scene(kind: &str, n: usize) -> Scene {
    let mut rng = Rng(0x9E37_79B9 ^ (n as u64 * 1000 + (kind == "triangles") as u64));
    let r = radius(n);
    let s = r * (2.0 * std::f64::consts::PI / 0.3668f64).sqrt();
    let shapes = (0..n)
        .map(|_| match kind {
            "spheres" => Shape::Sphere {
                center: rng.in_box(),
                radius: r,
            },
            _ => loop {
                let c = rng.in_box();
                let v = [
                    c + rng.in_ball() * s,
                    c + rng.in_ball() * s,
                    c + rng.in_ball() * s,
                ];
                if (v[1] - v[0]).cross(v[2] - v[0]).length() * 0.5 >= 1e-3 * s * s {
                    break Shape::Triangle(v);
                }
            },
        })
        .collect::<Vec<_>>();
    Scene {
        camera_at: None,
        source: format!("{kind}_{n}").into(),
        camera: CameraSpec {
            eye: DVec3::ZERO,
            look: DVec3::Z,
            up: DVec3::Y,
            lens: Some(lanecast::Lens::Fov(60.0)),
        },
        shapes: shapes.into(),
        warnings: Vec::new(),
    }
}

fn bench_scene(
    c: &mut Criterion,
    group: &str,
    scene: &Scene,
    (w, h): (u32, u32),
    accels: &[Accel],
) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let camera = Camera::new(
        &scene.camera,
        scene.camera.fov_deg().unwrap_or(DEFAULT_FOV),
        w,
        h,
    );
    let tables = camera.tables::<f32>(4, 2);
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(w as u64 * h as u64));
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(300));
    g.measurement_time(Duration::from_secs(2));
    for &accel in accels {
        let ps = PacketScene::new(scene, &camera, accel);
        g.bench_function(BenchmarkId::new(accel.name(), "t1"), |b| {
            b.iter(|| {
                pool.install(|| black_box(render_packet(&ps, &tables, w as usize, h as usize)))
            })
        });
    }
    g.finish();
}

fn scaling(c: &mut Criterion) {
    let quick = std::env::var_os("LANECAST_BENCH_QUICK").is_some();
    let ns: &[usize] = if quick {
        &[256, 4096]
    } else {
        &[16, 256, 4096, 65536]
    };
    for kind in ["spheres", "triangles"] {
        for &n in ns {
            let accels: &[Accel] = if n <= 4096 {
                &[Accel::None, Accel::Tiles, Accel::Bvh]
            } else {
                &[Accel::Tiles, Accel::Bvh]
            };
            bench_scene(
                c,
                &format!("scale/{kind}_{n}/1280x720"),
                &scaling_scene(kind, n),
                (1280, 720),
                accels,
            );
        }
    }
}

fn meshes(c: &mut Criterion) {
    let quick = std::env::var_os("LANECAST_BENCH_QUICK").is_some();
    let names: &[&str] = if quick {
        &["bunny"]
    } else {
        &["bunny", "teapot", "armadillo"]
    };
    for name in names {
        let path = format!("{}/scenes/{name}.sc", env!("CARGO_MANIFEST_DIR"));
        let scene = load_scene(Path::new(&path)).expect("mesh scene loads");
        bench_scene(
            c,
            &format!("mesh/{name}/1920x1080"),
            &scene,
            (1920, 1080),
            &[Accel::Tiles, Accel::Bvh],
        );
    }
}

// No plots: criterion's plotters backend needs system fonts, which a clean machine lacks; the
// numbers (and scripts/bench_table.py) need only the JSON estimates.
criterion_group! {
    name = benches;
    config = Criterion::default().without_plots();
    targets = scaling, meshes
}
criterion_main!(benches);
