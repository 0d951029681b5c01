//! `lanecast compare`: the packet kernel against the f64 scalar oracle, pixel by pixel.
//!
//! Each id mismatch is classified, by re-evaluating both candidates in f64 on the oracle's ray:
//! - tie: both candidates are hit and their f64 distances agree within [`TIE_REL`] (relative):
//!   which one is "nearest" is decided by rounding, not by the scene;
//! - edge: the ray passes within [`EDGE_BAND`] radians of either candidate's boundary (a polygon
//!   edge or a sphere's silhouette), so f32 rounding of the ray or the primitive can flip it;
//! - unexcused: anything else. The command fails when these exceed `--max-mismatch-ppm`.
//!
//! Depth differences are measured where both kernels hit the same primitive.

use crate::accel::Accel;
use crate::camera::Camera;
use crate::precision::Precision;
use crate::real::V3;
use crate::render::{Frame, PacketScene, prepare_f64, render_packet, render_scalar_counting};
use crate::scene::{Scene, Shape};
use crate::shade::{ColorMode, Variation, shade};
use crate::soa::{Stored, Visit, visit};
use crate::words::count;
use glam::DVec3;

/// Two hits closer than this relative distance are a genuine tie. The packet kernel's distances
/// err by ~5u_f32 = 3e-7 relative (kernel comments); 1e-5 leaves a wide margin.
pub const TIE_REL: f64 = 1e-5;

/// Half-width, in radians, of the band around a primitive's boundary inside which f32 may
/// legitimately disagree with f64: ~3u_f32 of ray direction error plus the polygons' 8u edge
/// tolerance plus ~4u of sphere silhouette error, doubled: 32u_f32 = 1.9e-6 rad.
pub const EDGE_BAND: f64 = 32.0 * crate::real::U32;

/// The outcome of one comparison.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// Pixels compared (width x height).
    pub pixels: usize,
    /// Pixels whose primitive id differs from the oracle's (ties + edges + unexcused).
    pub mismatches: usize,
    /// Mismatches that are ties: both candidates hit within [`TIE_REL`].
    pub ties: usize,
    /// Mismatches within [`EDGE_BAND`] of either candidate's boundary.
    pub edges: usize,
    /// Mismatches that are neither ties nor in the edge band.
    pub unexcused: usize,
    /// Pixels where both kernels hit the same primitive.
    pub same_hits: usize,
    /// Largest relative depth error |t_f32 - t_f64| / t_f64 over the same-hit pixels (0 if none).
    pub depth_rel_max: f64,
    /// 99th percentile (nearest rank) of the same relative depth errors (0 if none).
    pub depth_rel_p99: f64,
    /// Per pixel: 0 agree, [`TIE`], [`EDGE`] or [`UNEXCUSED`].
    pub class: Vec<u8>,
    /// Pixels `--precision auto` decided again in f64 (row-major, ascending; empty for the
    /// other precisions).
    pub redecided: Vec<usize>,
}

impl Report {
    /// Unexcused mismatches in parts per million of the pixels, the figure
    /// `--max-mismatch-ppm` limits.
    pub fn unexcused_ppm(&self) -> f64 {
        self.unexcused as f64 * 1e6 / self.pixels.max(1) as f64
    }
}

/// f64 distance to `shape` along `d` from `eye`, with its boundary moved outward by `slack`
/// radians (inward when negative): its family's
/// [`Family::hit_with_slack`](crate::experimental::kernel::Family::hit_with_slack).
pub fn hit_with_slack(shape: &Shape, eye: DVec3, d: V3<f64>, slack: f64) -> Option<f64> {
    struct Slack(DVec3, V3<f64>, f64);
    impl Visit<Option<f64>> for Slack {
        fn visit<F: Stored>(self, g: F::Geometry) -> Option<f64> {
            F::hit_with_slack(&g, self.0, self.1, self.2)
        }
    }
    visit(*shape, Slack(eye, d, slack))
}

/// Classifies one mismatch: 1 tie, 2 edge, 3 unexcused.
fn classify(scene: &Scene, eye: DVec3, d: V3<f64>, a: i32, b: i32) -> u8 {
    classify_within(scene, eye, d, a, b, EDGE_BAND)
}

/// The class ([`TIE`], [`EDGE`] or [`UNEXCUSED`]) of a mismatch between ids `a` and `b` (-1:
/// background) on the f64 ray `d` from `eye`, with an edge band of `band` radians: what
/// `compare` does with [`EDGE_BAND`], and the `--precision auto` tests with 1e-6.
pub fn classify_within(scene: &Scene, eye: DVec3, d: V3<f64>, a: i32, b: i32, band: f64) -> u8 {
    let shape = |id: i32| (id >= 0).then(|| scene.shapes.get(id as usize));
    let (sa, sb) = (shape(a), shape(b));
    if let (Some(sa), Some(sb)) = (&sa, &sb) {
        let ta = hit_with_slack(sa, eye, d, band);
        let tb = hit_with_slack(sb, eye, d, band);
        if let (Some(ta), Some(tb)) = (ta, tb)
            && (ta - tb).abs() <= TIE_REL * ta.max(tb)
        {
            return TIE;
        }
    }
    let near_edge = |s: Option<&Shape>| {
        s.is_some_and(|s| {
            hit_with_slack(s, eye, d, band).is_some() != hit_with_slack(s, eye, d, -band).is_some()
        })
    };
    if near_edge(sa.as_ref()) || near_edge(sb.as_ref()) {
        EDGE
    } else {
        UNEXCUSED
    }
}

/// Renders `scene` with both kernels (in the current rayon pool) and compares them, the packet
/// kernel with automatic acceleration.
pub fn compare(scene: &Scene, camera: &Camera) -> (Report, Frame<f64>) {
    compare_with(scene, camera, Accel::Auto)
}

/// [`compare`] with the packet kernel's acceleration chosen by the caller.
pub fn compare_with(scene: &Scene, camera: &Camera, accel: Accel) -> (Report, Frame<f64>) {
    if accel == Accel::World {
        let options = crate::Options {
            accel,
            precision: Precision::F32,
            ..crate::Options::default()
        };
        let frame = crate::Renderer::new(scene, camera, &options)
            .expect("the packet kernel takes every acceleration")
            .render();
        return compare_frame(scene, camera, &frame);
    }
    let (w, h) = (camera.width as usize, camera.height as usize);
    let packet = render_packet(
        &PacketScene::new(scene, camera, accel),
        &camera.tables(4, 2),
        w,
        h,
    );
    compare_frame(scene, camera, &packet)
}

/// [`compare`] of the packets in `precision` (`lanecast compare --precision`) with
/// acceleration `accel`: f32 ([`compare_with`]), `auto` ([`compare_auto`]) or f64 (f64x4
/// lanes, or the world engine in f64 with `--accel world`).
pub fn compare_precision(
    scene: &Scene,
    camera: &Camera,
    precision: Precision,
    accel: Accel,
) -> (Report, Frame<f64>) {
    match precision {
        Precision::F32 => compare_with(scene, camera, accel),
        Precision::Auto => compare_auto(scene, camera, accel),
        Precision::F64 => {
            let options = crate::Options {
                accel,
                precision,
                ..crate::Options::default()
            };
            let frame = crate::Renderer::new(scene, camera, &options)
                .expect("the packet kernel takes every acceleration")
                .render();
            compare_frame(scene, camera, &frame)
        }
    }
}

/// [`compare`] of `--precision auto` with acceleration `accel`; the report lists the pixels
/// re-decided in f64 ([`Report::redecided`]).
pub fn compare_auto(scene: &Scene, camera: &Camera, accel: Accel) -> (Report, Frame<f64>) {
    let (frame, redecided) =
        crate::render::Renderer::auto(scene, camera, accel).render_marking(None);
    let (mut report, oracle) = compare_frame(scene, camera, &frame);
    report.redecided = redecided;
    (report, oracle)
}

/// The f64 scalar oracle's frame of `scene` seen by `camera` (`--kernel scalar`, depths kept
/// in f64), in the current rayon pool. It traces through the tiles when `auto` would use them:
/// bit-identical to testing every primitive (tests/accel.rs), and seconds instead of minutes
/// on large meshes.
pub fn oracle(scene: &Scene, camera: &Camera) -> Frame<f64> {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let (prepared, structure) = prepare_f64(Accel::Auto, scene, camera);
    render_scalar_counting(&prepared, &camera.tables(1, 1), &structure, w, h, None)
}

/// Compares a render of `scene` (ids, depths) with the f64 oracle's.
pub fn compare_frame(scene: &Scene, camera: &Camera, packet: &Frame<f32>) -> (Report, Frame<f64>) {
    let (w, h) = (camera.width as usize, camera.height as usize);
    let t64 = camera.tables::<f64>(1, 1);
    let oracle = oracle(scene, camera);
    let mut r = Report {
        pixels: w * h,
        class: vec![0; w * h],
        ..Report::default()
    };
    let mut rel = Vec::new();
    for i in 0..w * h {
        let (a, b) = (oracle.ids[i], packet.ids[i]);
        if a == b {
            if a >= 0 {
                let (t64, t32) = (oracle.depth[i], packet.depth[i] as f64);
                rel.push((t32 - t64).abs() / t64);
            }
            continue;
        }
        let c = classify(scene, camera.eye, t64.dir_x1(i % w, i / w), a, b);
        r.class[i] = c;
        r.mismatches += 1;
        match c {
            TIE => r.ties += 1,
            EDGE => r.edges += 1,
            _ => r.unexcused += 1,
        }
    }
    r.same_hits = rel.len();
    rel.sort_by(f64::total_cmp);
    r.depth_rel_max = rel.last().copied().unwrap_or(0.0);
    r.depth_rel_p99 = rel
        .get((rel.len() * 99).div_ceil(100).saturating_sub(1))
        .copied()
        .unwrap_or(0.0);
    (r, oracle)
}

/// Mismatch class of [`Report::class`]: a tie (both hit, distances within [`TIE_REL`]).
pub const TIE: u8 = 1;
/// Mismatch class of [`Report::class`]: the ray is within [`EDGE_BAND`] of a boundary.
pub const EDGE: u8 = 2;
/// Mismatch class of [`Report::class`]: neither a tie nor in the edge band.
pub const UNEXCUSED: u8 = 3;

/// Marking colour of a mismatch class: tie yellow, edge band cyan, unexcused red.
pub fn class_colour(c: u8) -> Option<[u8; 3]> {
    match c {
        TIE => Some([255, 255, 0]),
        EDGE => Some([0, 255, 255]),
        UNEXCUSED => Some([255, 0, 0]),
        _ => None,
    }
}

/// Unexcused pixels listed by `compare`, at most (README, "Command line").
pub const LIST_UNEXCUSED: usize = 20;
/// Half-width in pixels of the square outline drawn around each unexcused pixel in the diff
/// picture, so that a single pixel is seen in the image at full size.
pub const OUTLINE_HALF: usize = 4;

impl Report {
    /// The report as `lanecast compare` prints it below its header (the scene, what was
    /// compared), a line each: the pixels of the `width` x `height` image, the mismatches by
    /// class (with `allowed`, the unexcused ppm the caller accepts, when given), the first
    /// [`LIST_UNEXCUSED`] unexcused pixels, the pixels re-decided in f64 (when `redecided`),
    /// and the depth error over same-id hits. The lab's `lab-render` prints the same lines.
    pub fn lines(
        &self,
        width: u32,
        height: u32,
        allowed: Option<f64>,
        redecided: bool,
    ) -> Vec<String> {
        let ppm = |n: usize| n as f64 * 1e6 / self.pixels.max(1) as f64;
        let mut out = vec![
            format!("pixels      {} ({width}x{height})", self.pixels),
            format!(
                "mismatches  {} ({:.1} ppm)",
                self.mismatches,
                ppm(self.mismatches)
            ),
            format!(
                "  ties      {} (f64 distances within {TIE_REL:e} relative)",
                self.ties
            ),
            format!(
                "  edge band {} (ray within {EDGE_BAND:.2e} rad of a boundary)",
                self.edges
            ),
            match allowed {
                Some(a) => format!(
                    "  unexcused {} ({:.1} ppm; allowed {a} ppm)",
                    self.unexcused,
                    self.unexcused_ppm()
                ),
                None => format!(
                    "  unexcused {} ({:.1} ppm)",
                    self.unexcused,
                    self.unexcused_ppm()
                ),
            },
        ];
        if self.unexcused > 0 {
            let first: Vec<String> = (self.unexcused_pixels(width))
                .take(LIST_UNEXCUSED)
                .map(|(x, y)| format!("({x}, {y})"))
                .collect();
            let shown = if self.unexcused > LIST_UNEXCUSED {
                format!("first {LIST_UNEXCUSED}")
            } else {
                "all".to_string()
            };
            out.push(format!(
                "  unexcused at (x, y), {shown}: {}",
                first.join(" ")
            ));
        }
        if redecided {
            out.push(format!(
                "re-decided  {} in f64 ({:.4}%)",
                count(self.redecided.len(), "pixel", "pixels"),
                self.redecided.len() as f64 * 100.0 / self.pixels.max(1) as f64
            ));
        }
        out.push(format!(
            "depth rel   max {:.3e}, p99 {:.3e} over {}",
            self.depth_rel_max,
            self.depth_rel_p99,
            count(self.same_hits, "same-id hit", "same-id hits")
        ));
        out
    }

    /// The (x, y) of the unexcused pixels in a `width`-wide image, row by row.
    pub fn unexcused_pixels(&self, width: u32) -> impl Iterator<Item = (u32, u32)> + '_ {
        let width = width as usize;
        (self.class.iter().enumerate())
            .filter(|&(_, &c)| c == UNEXCUSED)
            .map(move |(i, _)| ((i % width) as u32, (i / width) as u32))
    }
}

/// Colour of the pixels `--precision auto` re-decided in f64 that agree with the oracle
/// (a mismatch keeps its class colour): magenta.
pub const REDECIDED_COLOUR: [u8; 3] = [255, 0, 255];

/// `compare -o`'s picture: [`marked_render`] with every mismatch in its class colour, every
/// other re-decided pixel in [`REDECIDED_COLOUR`], and a red square outline [`OUTLINE_HALF`]
/// pixels out around each unexcused pixel (clipped at the border).
pub fn diff_picture(report: &Report, oracle: &Frame<f64>) -> Vec<u8> {
    let (w, h) = (oracle.width as usize, oracle.height as usize);
    let mut redecided = vec![false; w * h];
    for &i in &report.redecided {
        redecided[i] = true;
    }
    let mut rgb = marked_render(oracle, |i| {
        class_colour(report.class[i]).or(redecided[i].then_some(REDECIDED_COLOUR))
    });
    let red = class_colour(UNEXCUSED).expect("unexcused has a colour");
    for (x, y) in report.unexcused_pixels(oracle.width) {
        let (x, y) = (x as usize, y as usize);
        let (x0, y0) = (
            x.saturating_sub(OUTLINE_HALF),
            y.saturating_sub(OUTLINE_HALF),
        );
        let (x1, y1) = ((x + OUTLINE_HALF).min(w - 1), (y + OUTLINE_HALF).min(h - 1));
        for py in y0..=y1 {
            for px in x0..=x1 {
                let edge = px.abs_diff(x) == OUTLINE_HALF || py.abs_diff(y) == OUTLINE_HALF;
                if edge {
                    rgb[(py * w + px) * 3..][..3].copy_from_slice(&red);
                }
            }
        }
    }
    rgb
}

/// An error picture: the oracle's render (random colours) at a third of its brightness, with
/// `mark(pixel)` painted over the pixels it returns a colour for. `compare -o` and the lab's
/// error images both use it.
pub fn marked_render(oracle: &Frame<f64>, mark: impl Fn(usize) -> Option<[u8; 3]>) -> Vec<u8> {
    let depth: Vec<f32> = oracle.depth.iter().map(|&d| d as f32).collect();
    let mut rgb = shade(
        &oracle.ids,
        &depth,
        None,
        oracle.width,
        ColorMode::Random,
        Variation::Linear,
        0,
    );
    for (i, px) in rgb.chunks_mut(3).enumerate() {
        match mark(i) {
            Some(m) => px.copy_from_slice(&m),
            None => px.iter_mut().for_each(|v| *v /= 3),
        }
    }
    rgb
}
