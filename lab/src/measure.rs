//! What the lab measures, per method and scene, against the f64 scalar oracle.
//!
//! Each pixel where the method's id differs from the oracle's is classified by re-evaluating
//! both candidates in f64 on the oracle's ray (the rules of `compare`):
//! - tie: both candidates are hit (boundaries widened by `compare::EDGE_BAND`) and their f64
//!   distances agree within `compare::TIE_REL` (1e-5 relative): which is nearest is decided by
//!   rounding, not by the scene (coplanar overlaps);
//! - edge: the ray passes within `EDGE_BAND` (1.9e-6 rad) of either candidate's boundary;
//! - unexcused: anything else.
//!
//! Independently of that class, a pixel may be
//! - a hole: the oracle hits a primitive of a closed surface (`# lab: closed` in the scene) and
//!   the method hits nothing, or something farther (it sees through the surface), while every
//!   ray within 4 `EDGE_BAND` of this one hits the surface too (not its silhouette): a leak
//!   through an edge or a vertex;
//! - a false hit: the method reports a primitive that the f64 ray does not meet at all, not
//!   even with the boundary widened by `EDGE_BAND` (behind the eye, t <= 0, or elsewhere).
//!
//! Depth error: |t - t_oracle| / t_oracle where both hit the same primitive: median, 99th
//! percentile, max. Throughput: primary rays per second on one thread, best of repeated
//! renders (at least 2, about 0.3 s in all), setup excluded.

use crate::kits::Oracle;
use crate::method::{Method, MethodRender};
use crate::scenes::LabFrame;
use crate::scenes::LabScene;
use glam::DVec3;
use lanecast::compare::{EDGE_BAND, TIE_REL, hit_with_slack};
use lanecast::experimental::real::V3;
use lanecast::scene::Shape;
use std::time::Instant;

/// Class of a pixel (low two bits) and flags.
pub use lanecast::compare::{EDGE, TIE, UNEXCUSED};
pub const HOLE: u8 = 4;
pub const FALSE_HIT: u8 = 8;

/// One method's measures on one scene.
#[derive(Debug, Clone)]
pub struct Row {
    pub method: Method,
    pub pixels: usize,
    pub mismatches: usize,
    pub ties: usize,
    pub edges: usize,
    pub unexcused: usize,
    pub holes: usize,
    pub false_hits: usize,
    /// Pixels counted by the chart: unexcused, hole or false hit.
    pub errors: usize,
    pub same_hits: usize,
    pub depth_med: f64,
    pub depth_p99: f64,
    pub depth_max: f64,
    pub rays_per_s: f64,
    /// Pixels the method decided again in f64 (`auto`; 0 for the others).
    pub redecided: usize,
    /// Per pixel: class | flags.
    pub class: Vec<u8>,
}

impl Row {
    pub fn ppm(&self, n: usize) -> f64 {
        n as f64 * 1e6 / self.pixels.max(1) as f64
    }
}

/// Every method on one scene, and the oracle's frame and speed.
#[derive(Debug, Clone)]
pub struct SceneResult {
    pub name: String,
    pub stress: bool,
    pub oracle: LabFrame,
    pub oracle_rays_per_s: f64,
    pub rows: Vec<Row>,
}

/// Renders with `r` repeatedly on one thread (a one-thread pool: `f64x4` would otherwise
/// spread over every core): the first frame and the best rays/s.
pub fn time_render(r: &dyn MethodRender) -> (LabFrame, f64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a one-thread pool");
    pool.install(|| time_render_here(r))
}

fn time_render_here(r: &dyn MethodRender) -> (LabFrame, f64) {
    let start = Instant::now();
    let frame = r.render();
    let mut best = start.elapsed().as_secs_f64();
    let mut total = best;
    let mut runs = 1;
    while runs < 2 || (total < 0.3 && runs < 20) {
        let t = Instant::now();
        std::hint::black_box(r.render());
        let e = t.elapsed().as_secs_f64();
        best = best.min(e);
        total += e;
        runs += 1;
    }
    let rays = f64::from(frame.width) * f64::from(frame.height);
    (frame, rays / best.max(1e-9))
}

/// Measures `frame` (a method's render) against `oracle` on scene `s`.
pub fn measure(s: &LabScene, method: Method, oracle: &LabFrame, frame: &LabFrame) -> Row {
    let (w, h) = (oracle.width as usize, oracle.height as usize);
    let eye = s.camera.eye;
    let t64 = s.camera.tables::<f64>(1, 1);
    let shapes = &s.scene.shapes;
    let shape = |id: i32| (id >= 0).then(|| shapes.get(id as usize));
    let closed_ids: Vec<usize> = (0..shapes.len()).filter(|&i| s.closed[i]).collect();
    // every ray within `delta` of d hits the closed surface: d is not on its silhouette
    let interior = |d: V3<f64>| {
        let d = DVec3::from_array(d);
        let delta = 4.0 * EDGE_BAND;
        (0..8).all(|k| {
            let a = k as f64 * std::f64::consts::FRAC_PI_4;
            let p = (d + (s.camera.r * a.cos() + s.camera.u * a.sin()) * delta).normalize();
            closed_ids
                .iter()
                .any(|&i| hit_with_slack(&shapes.get(i), eye, p.to_array(), 0.0).is_some())
        })
    };
    let mut row = Row {
        method,
        pixels: w * h,
        mismatches: 0,
        ties: 0,
        edges: 0,
        unexcused: 0,
        holes: 0,
        false_hits: 0,
        errors: 0,
        same_hits: 0,
        depth_med: 0.0,
        depth_p99: 0.0,
        depth_max: 0.0,
        rays_per_s: 0.0,
        redecided: 0,
        class: vec![0; w * h],
    };
    let mut rel = Vec::new();
    for i in 0..w * h {
        let (a, b) = (oracle.ids[i], frame.ids[i]);
        let (ta, tb) = (oracle.depth[i], frame.depth[i]);
        if a == b {
            if a >= 0 {
                rel.push((tb - ta).abs() / ta);
            }
            continue;
        }
        let d = t64.dir_x1(i % w, i / w);
        let (sa, sb) = (shape(a), shape(b));
        let (sa, sb) = (sa.as_ref(), sb.as_ref());
        let wide_a = sa.and_then(|x| hit_with_slack(x, eye, d, EDGE_BAND));
        let wide_b = sb.and_then(|x| hit_with_slack(x, eye, d, EDGE_BAND));
        let near_edge = |x: Option<&Shape>| {
            x.is_some_and(|x| {
                hit_with_slack(x, eye, d, EDGE_BAND).is_some()
                    != hit_with_slack(x, eye, d, -EDGE_BAND).is_some()
            })
        };
        let mut c = match (wide_a, wide_b) {
            (Some(x), Some(y)) if (x - y).abs() <= TIE_REL * x.max(y) => TIE,
            _ if near_edge(sa) || near_edge(sb) => EDGE,
            _ => UNEXCUSED,
        };
        if sb.is_some() && wide_b.is_none() {
            c |= FALSE_HIT;
        }
        let sees_through = b < 0 || tb > ta * (1.0 + 1e-3);
        if a >= 0 && s.closed[a as usize] && sees_through && interior(d) {
            c |= HOLE;
        }
        row.mismatches += 1;
        match c & 3 {
            TIE => row.ties += 1,
            EDGE => row.edges += 1,
            _ => row.unexcused += 1,
        }
        row.holes += (c & HOLE != 0) as usize;
        row.false_hits += (c & FALSE_HIT != 0) as usize;
        row.errors += (c & 3 == UNEXCUSED || c & (HOLE | FALSE_HIT) != 0) as usize;
        row.class[i] = c;
    }
    row.same_hits = rel.len();
    rel.sort_by(f64::total_cmp);
    let q = |p: usize| {
        rel.get((rel.len() * p).div_ceil(100).saturating_sub(1))
            .copied()
            .unwrap_or(0.0)
    };
    row.depth_med = q(50);
    row.depth_p99 = q(99);
    row.depth_max = rel.last().copied().unwrap_or(0.0);
    row
}

/// The oracle and every method in `methods` on one scene.
pub fn run_scene(s: &LabScene, methods: &[Method]) -> SceneResult {
    let oracle = Oracle::new(&s.scene, &s.camera);
    let (oracle_frame, oracle_rays_per_s) = time_render(&oracle);
    let rows = methods
        .iter()
        .map(|&m| {
            let prepared = m.prepare(&s.scene, &s.camera);
            let (frame, rays_per_s) = time_render(prepared.as_ref());
            let mut row = measure(s, m, &oracle_frame, &frame);
            row.rays_per_s = rays_per_s;
            row.redecided = prepared.render_marking().1.len();
            row
        })
        .collect();
    SceneResult {
        name: s.name.clone(),
        stress: s.stress,
        oracle: oracle_frame,
        oracle_rays_per_s,
        rows,
    }
}

/// The oracle's frame of a scene (f64 scalar, one thread).
pub fn oracle_frame(s: &LabScene) -> LabFrame {
    Oracle::new(&s.scene, &s.camera).render()
}

/// One method's frame of a scene, rendered once, untimed.
pub fn method_frame(s: &LabScene, m: Method) -> LabFrame {
    m.prepare(&s.scene, &s.camera).render()
}

/// [`measure`] of one untimed render (for tests).
pub fn accuracy(s: &LabScene, m: Method, oracle: &LabFrame) -> Row {
    measure(s, m, oracle, &method_frame(s, m))
}
