//! `lanecast compare`: the packet kernel against the f64 scalar oracle, pixel by pixel.
//!
//! Each id mismatch is classified, by re-evaluating both candidates in f64 on the oracle's ray:
//! - tie: the oracle's kernels hit both candidates and their f64 distances agree within the
//!   sum of the two hits' depth bounds ([`tie_rel`]): which one is "nearest" is decided by
//!   rounding, not by the scene;
//! - edge: the ray passes within the view's id band (`Camera::id_band`, an eighth of the
//!   smallest pixel's angle) of either candidate's true boundary (a polygon's edge arcs, a
//!   sphere's silhouette), so rounding of the ray or the primitive can flip it;
//! - unexcused: anything else. The command fails when these exceed `--max-mismatch-ppm`.
//!
//! Both excuses scale with the view: a telephoto camera's band is as many pixels wide as a
//! wide-angle one's, and a tie at 1e4 units is a depth difference within the kernels' error
//! there, not 1e-5 of the distance. A mismatch far from every boundary and every true tie (a
//! false hit streaking out of a sliver's corner, say) is unexcused.
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

/// The accuracy lab's tie tolerance for its methods (`lanecast-lab`): two hits closer than this
/// relative distance. `compare` itself uses the kernels' depth bounds ([`tie_rel`]).
pub const TIE_REL: f64 = 1e-5;

/// The accuracy lab's edge band for its methods, in radians: ~3u_f32 of ray direction error
/// plus the polygons' 8u edge tolerance plus ~4u of sphere silhouette error, doubled:
/// 32u_f32 = 1.9e-6 rad. `compare` itself uses the view's id band (`Camera::id_band`).
pub const EDGE_BAND: f64 = 32.0 * crate::real::U32;

/// The relative depth error, against the oracle, that a hit at distance `t` on a primitive may
/// carry in lanecast's f32 engines: for a polygon at plane distance `p`, the per-eye kernel's
/// first-order bound `u (5.5 + (4 + a/u) t / p)` (`render::redecide`'s bounds; `a` the
/// camera's `direction_error`) or the world engine's trusted error (`world::T_TIGHT`),
/// whichever is larger; for any other primitive, and wherever that passes it, the 1e-5 depth
/// guarantee. Two hits whose f64 distances differ by less than the sum of their bounds are a
/// tie.
pub fn tie_rel(plane_distance: Option<f64>, t: f64, a: f64) -> f64 {
    let u = crate::real::U32;
    let tolerance = crate::render::redecide::TOLERANCE;
    match plane_distance {
        Some(p) if p > 0.0 => (u * (5.5 + (4.0 + a / u) * t / p))
            .max(crate::world::T_TIGHT)
            .min(tolerance),
        _ => tolerance,
    }
}

/// The outcome of one comparison.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Report {
    /// Pixels compared (width x height).
    pub pixels: usize,
    /// Pixels whose primitive id differs from the oracle's (ties + edges + unexcused).
    pub mismatches: usize,
    /// Mismatches that are ties: both candidates hit within their depth bounds ([`tie_rel`]).
    pub ties: usize,
    /// Mismatches within the id band of either candidate's boundary.
    pub edges: usize,
    /// The id band the edges were judged with, in radians (`Camera::id_band`).
    pub band: f64,
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

/// Whether `d` from `eye` passes within `band` radians of `shape`'s true boundary: its
/// family's [`Family::near_boundary`](crate::experimental::kernel::Family::near_boundary).
pub fn near_boundary(shape: &Shape, eye: DVec3, d: V3<f64>, band: f64) -> bool {
    struct Near(DVec3, V3<f64>, f64);
    impl Visit<bool> for Near {
        fn visit<F: Stored>(self, g: F::Geometry) -> bool {
            F::near_boundary(&g, self.0, self.1, self.2)
        }
    }
    visit(*shape, Near(eye, d, band))
}

/// The plane distance of a flat `shape` seen from `eye` (`None` for a curved one).
fn plane_distance(shape: &Shape, eye: DVec3) -> Option<f64> {
    struct Flat(DVec3);
    impl Visit<Option<f64>> for Flat {
        fn visit<F: Stored>(self, g: F::Geometry) -> Option<f64> {
            F::plane(&g, self.0).map(|(_, p)| p)
        }
    }
    visit(*shape, Flat(eye))
}

/// Classifies one mismatch on the oracle's ray `d` of `camera`: [`TIE`], [`EDGE`] (within
/// the view's id band, `Camera::id_band`) or [`UNEXCUSED`].
pub fn classify(scene: &Scene, camera: &Camera, d: V3<f64>, a: i32, b: i32) -> u8 {
    classify_within(scene, camera, d, a, b, camera.id_band())
}

/// The class ([`TIE`], [`EDGE`] or [`UNEXCUSED`]) of a mismatch between ids `a` and `b` (-1:
/// background) on the f64 ray `d` of `camera`, with an edge band of `band` radians: what
/// `compare` does with the view's id band, and tests with other bands. A tie needs both
/// candidates hit by the oracle's kernels, with distances within their depth bounds of each
/// other ([`tie_rel`]); an edge needs the ray within `band` of either's true boundary
/// ([`near_boundary`]). It derives the camera's ray error (`Camera::direction_error`) on each
/// call; [`compare_frame`] derives it once a frame.
pub fn classify_within(
    scene: &Scene,
    camera: &Camera,
    d: V3<f64>,
    a: i32,
    b: i32,
    band: f64,
) -> u8 {
    let view = Judged {
        eye: camera.eye,
        angle: camera.direction_error(),
        band,
    };
    view.class(scene, d, a, b)
}

/// What classifying a mismatch needs of the view, derived once: the eye, the angle between a
/// pixel's f32 and f64 rays (`Camera::direction_error`) and the edge band.
struct Judged {
    eye: DVec3,
    angle: f64,
    band: f64,
}

impl Judged {
    /// [`classify_within`] with the view's values.
    fn class(&self, scene: &Scene, d: V3<f64>, a: i32, b: i32) -> u8 {
        let (eye, band) = (self.eye, self.band);
        let shape = |id: i32| (id >= 0).then(|| scene.shapes.get(id as usize));
        let (sa, sb) = (shape(a), shape(b));
        if let (Some(sa), Some(sb)) = (&sa, &sb) {
            let ta = hit_with_slack(sa, eye, d, 0.0);
            let tb = hit_with_slack(sb, eye, d, 0.0);
            if let (Some(ta), Some(tb)) = (ta, tb) {
                let bound = |s: &Shape, t: f64| tie_rel(plane_distance(s, eye), t, self.angle) * t;
                if (ta - tb).abs() <= bound(sa, ta) + bound(sb, tb) {
                    return TIE;
                }
            }
        }
        let near = |s: Option<&Shape>| s.is_some_and(|s| near_boundary(s, eye, d, band));
        if near(sa.as_ref()) || near(sb.as_ref()) {
            EDGE
        } else {
            UNEXCUSED
        }
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
    let judged = Judged {
        eye: camera.eye,
        angle: camera.direction_error(),
        band: camera.id_band(),
    };
    let oracle = oracle(scene, camera);
    let mut r = Report {
        pixels: w * h,
        band: camera.id_band(),
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
        let c = judged.class(scene, t64.dir_x1(i % w, i / w), a, b);
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

/// Above this many excused pixels (ties and edge band), `compare` says how many in a line of
/// its own.
pub const EXCUSED_NOTE: usize = 16;

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
                "  ties      {} (both hit, f64 distances within the kernels' depth bounds)",
                self.ties
            ),
            format!(
                "  edge band {} (ray within {:.2e} rad, 1/{} pixel, of a boundary)",
                self.edges,
                self.band,
                1.0 / crate::camera::ID_BAND_PIXELS,
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
        let excused = self.ties + self.edges;
        if excused > EXCUSED_NOTE {
            out.push(format!(
                "  note      {} excused ({:.1} ppm): each is at a tie or within the band of a \
                 boundary; see them with -o DIFF.png (ties yellow, edge band cyan)",
                count(excused, "pixel", "pixels"),
                ppm(excused)
            ));
        }
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
