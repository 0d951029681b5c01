//! Many views leave out what they cannot see: whole clusters of 64 triangles
//! (`scene::range_clusters`) that no ray of the view reaches (off screen, behind the eye), and
//! clusters that face away from the eye or that the last view did not show, once the view's
//! own frame proves them hidden. A view's ids, depths and re-decided pixels stay those of a
//! render of every primitive (a one-view run with the same camera), bit for bit.
//!
//! Per view (`Views::render_marking`):
//!
//! 1. Each cluster's reach from the eye (`accel::clusters`): the pixels on which any kernel can
//!    accept one of its faces, and a distance `near` below every distance it can return there.
//!    A cluster on no pixel is left out. A cluster with a tightly bounded reach
//!    ([`TRIAL_G`]) that faces away from the eye (every face seen from behind its winding, as
//!    a closed surface's far side is; after a view where most such clusters failed their
//!    check, a surface wound inwards, those facing the eye: [`Facing`]), or that the last
//!    view showed none of from an eye near enough ([`PARALLAX`]), is left out *on trial*,
//!    when the trials are worth it ([`TRIALS_MIN`]). Every other cluster is *kept*; one with
//!    no bounded reach is *loose*.
//! 2. The kept clusters are rendered as usual (`Renderer`, the stores and tiles of those
//!    primitives alone): the frame `F`, and the pixels whose f32 hit `--precision auto`
//!    re-decided.
//! 3. Each cluster on trial is checked against `F`: it stays out when every pixel of its
//!    rectangle holds a hit nearer than its `near` that was not re-decided.
//!    Why that is exact: at such a pixel the cluster's faces can only return distances at or
//!    beyond `near`, so the nearest-hit rule (smaller `t`, ties to the lower id) keeps the f32
//!    winner, whose distance is the pixel's depth; whether that hit is trusted, measured or
//!    re-decided depends on the winner and the pixel alone, so `auto` does the same; and a
//!    re-decision at any other pixel meets none of the cluster's faces (its rays lie outside
//!    the rectangle, which holds every ray the f64 kernels accept too).
//! 4. The clusters that fail (the view turned them towards the eye, or a nearer surface does
//!    not cover them) are rendered in a second frame `G`, merged into `F` pixel by pixel:
//!    - where neither re-decided the pixel, the nearer of the two winners by the nearest-hit
//!      rule: over the primitives of both, the f32 winner is the nearer of the two, and it is
//!      trusted in the union as it was in its own frame;
//!    - where `F` re-decided a pixel that no failed cluster reaches, `F`'s value: the failed
//!      clusters cannot be hit there;
//!    - where `F` re-decided a pixel that a failed cluster's rectangle holds, `G` must hold
//!      every cluster a kernel may hit there (the failed ones, the loose ones, the kept ones
//!      whose rectangle holds it: `Plan::second`), and gives the pixel alone;
//!    - where `G` re-decided a pixel, `F`'s value if no failed cluster reaches it, or if `F`
//!      holds an f32 hit there nearer than every failed cluster's `near` (the union's winner is
//!      then `F`'s, trusted); otherwise a third render `H` of every cluster a kernel may hit at
//!      those pixels (`Plan::only_at`) gives them alone.
//!
//! Facing away and what the last view showed are guesses, and the check makes any guess safe:
//! a bad guess (an open surface's back, a mesh wound inconsistently) costs the second render,
//! never a wrong pixel. Views whose options take no tiles (other kernels, methods,
//! accelerations) render every primitive (through `Views`, not this module).
//!
//! Tests: `tests/views_cull.rs` holds every view of slow orbits, random jumps and dollies on
//! the seed scans and on subdivided spheres, with `auto` and `f32`, and of a scene built to
//! take the third render, to a renderer of its own: ids, depths and re-decided pixels.
//! `accel::clusters` holds the reach to the kernels.

use super::{Frame, Options, Renderer};
use crate::accel::clusters::{ClusterScreen, Reach, Slab};
use crate::camera::Camera;
use crate::par::prelude::*;
use crate::scene::Scene;
use crate::scene::range_clusters::RangeClusters;
use crate::soa::IdSet;
use glam::DVec3;

mod check;
mod merge;

use check::{Check, TileDepths};
pub(crate) use merge::{Pixel, merge, merged_redone};

/// Only clusters whose box is widened by at most this fraction of their distance
/// (`accel::clusters`: `g`) are left out on trial. The others, the silhouette's (an eye
/// nearly in some face's plane), have a `near` far before their faces and would fail.
const TRIAL_G: f64 = 1e-4;

/// A view leaves clusters out on trial only when they hold at least this fraction of the
/// scene's primitives, and the clusters with no bounded reach at most [`LOOSE_MAX`]: a cluster
/// that fails its check is rendered a second time (with every cluster with no bounded reach,
/// where `auto` re-decided a pixel it covers), and trials of a few clusters cost more than
/// they save. Measured on orbits of the seed armadillo subdivided twice and three times
/// (docs/performance.md, "Many views").
const TRIALS_MIN: f64 = 0.25;
/// See [`TRIALS_MIN`].
const LOOSE_MAX: f64 = 0.4;

/// What the last view showed is a guess at a cluster's view only from an eye at most this
/// fraction of the cluster's distance from the last view's eye (about 14 degrees of
/// parallax): from farther, the surfaces that hid it from the last view no longer line up.
const PARALLAX: f64 = 0.25;

/// A cluster left out on trial: its index, pixel rectangle and `near`.
type Trial = (u32, [u16; 4], f32);

/// Which side of their faces marks clusters a view guesses hidden ([`Plan::new`]): those
/// seen from behind (the far side of a closed surface wound outwards, as meshes usually are),
/// then, where most of those fail their check (a surface wound inwards), those seen from the
/// front, then neither ([`Facing::after`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub(crate) enum Facing {
    #[default]
    Away,
    Towards,
    Neither,
}

impl Facing {
    /// Whether a cluster seen from the side `front` (`Gap::front`) is guessed hidden.
    fn guesses(self, front: Option<bool>) -> bool {
        match self {
            Facing::Away => front == Some(false),
            Facing::Towards => front == Some(true),
            Facing::Neither => false,
        }
    }

    /// The guess for the next view, after `failed` of the `tried` clusters this one left out
    /// on trial for their side failed their check: the next guess once more than half of at
    /// least [`FACING_MIN`] failed.
    pub(crate) fn after(self, (tried, failed): (usize, usize)) -> Facing {
        if tried < FACING_MIN || 2 * failed <= tried {
            return self;
        }
        match self {
            Facing::Away => Facing::Towards,
            _ => Facing::Neither,
        }
    }
}

/// The fewest clusters on trial for their side from which [`Facing::after`] judges.
const FACING_MIN: usize = 16;

/// What one view does with one cluster (module comment, step 1).
enum Verdict {
    /// On no pixel: left out for sure.
    Nowhere,
    /// Rendered: its reach is not bounded.
    Loose,
    /// Rendered: its faces can be hit on the pixels of this rectangle alone.
    Kept([u16; 4]),
    /// Left out on trial, with the box its faces' accepted rays meet, and whether the side it
    /// is seen from is a reason.
    Trial(Trial, Slab, bool),
}

/// Which clusters one view leaves out.
pub(crate) struct Plan {
    /// The ids of every cluster left out (on no pixel, or on trial).
    pub(crate) left_out: IdSet,
    /// The clusters left out on trial, and the boxes their faces' accepted rays meet.
    trials: Vec<Trial>,
    slabs: Vec<Slab>,
    /// The clusters rendered with a bounded reach, and their rectangles.
    kept: Vec<(u32, [u16; 4])>,
    /// The clusters rendered whose reach is not bounded.
    loose: Vec<u32>,
    /// The clusters on trial for the side they are seen from, whatever the last view showed
    /// (ascending).
    by_side: Vec<u32>,
}

/// The second render of a view (module comment, step 4): the primitives it leaves out, and
/// the pixels where it holds every primitive a kernel can accept (`F`'s re-decided pixels in
/// a failed cluster's rectangle), whose values it gives alone.
pub(crate) struct Second {
    pub(crate) left_out: IdSet,
    pub(crate) complete: Vec<usize>,
}

impl Plan {
    /// The plan for `camera`: clusters on no pixel, and, on trial, the clusters with a bounded
    /// reach seen from the side `facing` guesses or, where `last` (the ids the last view
    /// showed, and its eye) is given, that showed none of them from near enough.
    pub(crate) fn new(
        clusters: &RangeClusters,
        camera: &Camera,
        (last, facing): (Option<(&IdSet, DVec3)>, Facing),
        spare: IdSet,
    ) -> Plan {
        let screen = ClusterScreen::new(camera);
        let eye = camera.eye;
        let verdicts: Vec<Verdict> = (0..clusters.len())
            .into_par_iter()
            .map(|k| {
                let Some(gap) = clusters.gap(k, eye) else {
                    return Verdict::Loose;
                };
                let (rect, near, g, slab) = match screen.reach(&gap) {
                    Reach::Nowhere => return Verdict::Nowhere,
                    Reach::Unbounded => return Verdict::Loose,
                    Reach::Pixels(rect, near, g, slab) => (rect, near, g, slab),
                };
                // the guesses: the side it is seen from, and, seen from near the last view's
                // eye, showing none of its faces there
                let unseen = || {
                    last.is_some_and(|(s, last_eye)| {
                        last_eye.distance(eye) <= PARALLAX * gap.centre.distance(eye)
                            && !(clusters.cluster(k).iter()).any(|&id| s.contains(id as usize))
                    })
                };
                let side = facing.guesses(gap.front);
                if g <= TRIAL_G && (side || unseen()) {
                    Verdict::Trial((k as u32, rect, near), slab, side)
                } else {
                    Verdict::Kept(rect)
                }
            })
            .collect();
        let mut plan = Plan {
            left_out: IdSet::empty_in(clusters.ids_len(), spare),
            trials: Vec::new(),
            slabs: Vec::new(),
            kept: Vec::new(),
            loose: Vec::new(),
            by_side: Vec::new(),
        };
        // trials only where they may pay (module comment)
        let size = |class: fn(&Verdict) -> bool| {
            (verdicts.iter().enumerate())
                .filter(|(_, v)| class(v))
                .map(|(k, _)| clusters.cluster(k).len())
                .sum::<usize>()
        };
        let n = clusters.ids_len();
        let on_trial = size(|v| matches!(v, Verdict::Trial(..)));
        let loose = size(|v| matches!(v, Verdict::Loose));
        let trials =
            on_trial as f64 >= TRIALS_MIN * n as f64 && loose as f64 <= LOOSE_MAX * n as f64;
        for (k, verdict) in verdicts.into_iter().enumerate() {
            let k32 = k as u32;
            let verdict = match verdict {
                Verdict::Trial((_, rect, _), ..) if !trials => Verdict::Kept(rect),
                v => v,
            };
            let leave_out = match verdict {
                Verdict::Nowhere => true,
                Verdict::Loose => {
                    plan.loose.push(k32);
                    false
                }
                Verdict::Kept(rect) => {
                    plan.kept.push((k32, rect));
                    false
                }
                Verdict::Trial(trial, slab, by_side) => {
                    plan.trials.push(trial);
                    plan.slabs.push(slab);
                    if by_side {
                        plan.by_side.push(k32);
                    }
                    true
                }
            };
            if leave_out {
                for &id in clusters.cluster(k) {
                    plan.left_out.insert(id as usize);
                }
            }
        }
        plan
    }

    /// Of the clusters on trial for their side, how many there were and how many of them are
    /// among `failed` (as [`Plan::failed`] gives them, ascending): what [`Facing::after`]
    /// judges by. (All of them, not only those the last view's guess left out too: those alone
    /// are few on an orbit, and lie at the silhouette, where most fail whatever the winding.)
    pub(crate) fn side_failures(&self, failed: &[Trial]) -> (usize, usize) {
        let failed_by_side = (self.by_side.iter())
            .filter(|&&k| failed.binary_search_by_key(&k, |t| t.0).is_ok())
            .count();
        (self.by_side.len(), failed_by_side)
    }

    /// Whether anything is left out on trial.
    pub(crate) fn on_trial(&self) -> bool {
        !self.trials.is_empty()
    }

    /// The clusters on trial that `frame` (its re-decided pixels `redone`, ascending; the
    /// view of `camera`) does not prove hidden (module comment, step 3).
    pub(crate) fn failed(
        &self,
        frame: &Frame<f32>,
        redone: &[usize],
        camera: &Camera,
    ) -> Vec<Trial> {
        let farthest = TileDepths::new(frame, redone);
        let rays = camera.tables::<f64>(1, 1);
        let check = Check {
            frame,
            redone,
            rays: &rays,
        };
        (self.trials.par_iter().zip(&self.slabs))
            .filter(|(t, slab)| !farthest.hides(&check, t.1, t.2, slab))
            .map(|(t, _)| *t)
            .collect()
    }

    /// The second render for the clusters `failed`, after the first frame's re-decided
    /// pixels `redone` (width `width`): the failed clusters and, where a failed one's
    /// rectangle holds a re-decided pixel, every cluster that may be hit there (the loose
    /// ones, the kept ones whose rectangle holds it).
    pub(crate) fn second(
        &self,
        clusters: &RangeClusters,
        failed: &[Trial],
        (redone, width): (&[usize], usize),
        spare: IdSet,
    ) -> Second {
        let complete: Vec<usize> = (redone.iter().copied())
            .filter(|&p| failed.iter().any(|&(_, rect, _)| inside(p, width, rect)))
            .collect();
        let kept = (self.kept.iter())
            .filter(|&&(_, rect)| complete.iter().any(|&p| inside(p, width, rect)))
            .map(|&(k, _)| k);
        // (the loose clusters only where some pixel needs them all)
        let loose = if complete.is_empty() {
            &[][..]
        } else {
            &self.loose[..]
        };
        let rendered = (failed.iter().map(|&(k, ..)| k))
            .chain(loose.iter().copied())
            .chain(kept);
        let left_out = all_but(clusters, rendered, spare);
        Second { left_out, complete }
    }

    /// The ids left out of a render that gives `pixels` (width `width`) their values alone:
    /// every cluster but those that may be hit there (the loose ones, and those kept or on
    /// trial whose rectangle holds one).
    pub(crate) fn only_at(
        &self,
        clusters: &RangeClusters,
        (pixels, width): (&[usize], usize),
        spare: IdSet,
    ) -> IdSet {
        let holds = |rect| pixels.iter().any(|&p| inside(p, width, rect));
        let rendered = (self.trials.iter().filter(|t| holds(t.1)).map(|t| t.0))
            .chain(self.kept.iter().filter(|k| holds(k.1)).map(|k| k.0))
            .chain(self.loose.iter().copied());
        all_but(clusters, rendered, spare)
    }
}

/// Every id but those of the clusters `rendered`, in `spare`'s buffer: what a render of those
/// clusters alone leaves out.
fn all_but(clusters: &RangeClusters, rendered: impl Iterator<Item = u32>, spare: IdSet) -> IdSet {
    let mut left_out = IdSet::full_in(clusters.ids_len(), spare);
    for k in rendered {
        for &id in clusters.cluster(k as usize) {
            left_out.remove(id as usize);
        }
    }
    left_out
}

/// Whether pixel `p` (row-major, `width` wide) lies in `rect`.
fn inside(p: usize, width: usize, [x0, y0, x1, y1]: [u16; 4]) -> bool {
    let (x, y) = (p % width, p / width);
    (x0 as usize..=x1 as usize).contains(&x) && (y0 as usize..=y1 as usize).contains(&y)
}

/// The ids a frame shows, in `spare`'s buffer: a view's guess at the next one's.
pub(crate) fn shown(frame: &Frame<f32>, primitives: usize, spare: IdSet) -> IdSet {
    let mut set = IdSet::empty_in(primitives, spare);
    for &id in &frame.ids {
        if id >= 0 {
            set.insert(id as usize);
        }
    }
    set
}

/// Whether a renderer for `options` takes the tiles with f32 packets (`f32` or `auto`): the
/// renders whose frames the check of step 3 reasons about.
pub(crate) fn applies(options: &Options, scene: &Scene) -> bool {
    use super::Kernel;
    use crate::accel::Accel;
    use crate::precision::Precision;
    options.kernel == Kernel::Packet
        && matches!(options.precision, Precision::F32 | Precision::Auto)
        && options.accel.resolve(scene.shapes.len()) == Accel::Tiles
}

/// A render's renderer (to hand its buffers back), its frame and re-decided pixels, and its
/// seconds of setup and render.
pub(crate) type Rendering<'s> = (Renderer<'s>, Frame<f32>, Vec<usize>, [f64; 2]);

/// Renders `camera` with the primitives of `left_out` left out, into `spare`'s buffers: the
/// renderer (to hand its buffers back), the frame and its re-decided pixels, and the seconds
/// of setup and render.
pub(crate) fn render_without<'s>(
    scene: &'s Scene,
    camera: &Camera,
    options: &Options,
    spare: super::renderer::Spare,
    left_out: Option<&IdSet>,
) -> crate::Result<Rendering<'s>> {
    let clock = Clock::start();
    let renderer = Renderer::with_spare(scene, camera, options, spare, left_out)?;
    let setup = clock.secs();
    let clock = Clock::start();
    let (frame, redone) = renderer.render_marking(None);
    Ok((renderer, frame, redone, [setup, clock.secs()]))
}

/// A stopwatch for a view's phases, reading 0 where the platform has no clock (WebAssembly in
/// a browser, where `std::time::Instant` panics).
pub(crate) struct Clock {
    #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
    start: std::time::Instant,
}

impl Clock {
    /// Started now.
    pub(crate) fn start() -> Clock {
        Clock {
            #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
            start: std::time::Instant::now(),
        }
    }

    /// Seconds since the start (0 without a clock).
    pub(crate) fn secs(&self) -> f64 {
        #[cfg(not(all(target_arch = "wasm32", target_os = "unknown")))]
        return self.start.elapsed().as_secs_f64();
        #[cfg(all(target_arch = "wasm32", target_os = "unknown"))]
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The side guessed: seen from behind, then, once more than half of at least
    /// `FACING_MIN` such clusters fail, from the front, then neither; never for a cluster of
    /// mixed windings.
    #[test]
    fn the_side_guessed_turns_when_most_of_its_clusters_fail() {
        use Facing::*;
        assert!(Away.guesses(Some(false)) && !Away.guesses(Some(true)) && !Away.guesses(None));
        assert!(Towards.guesses(Some(true)) && !Towards.guesses(Some(false)));
        assert!(!Neither.guesses(Some(true)) && !Neither.guesses(Some(false)));
        assert_eq!(Away.after((FACING_MIN, FACING_MIN / 2)), Away);
        assert_eq!(Away.after((FACING_MIN, FACING_MIN / 2 + 1)), Towards);
        assert_eq!(Away.after((FACING_MIN - 1, FACING_MIN - 1)), Away);
        assert_eq!(Towards.after((100, 51)), Neither);
        assert_eq!(Towards.after((100, 50)), Towards);
        assert_eq!(Neither.after((100, 100)), Neither);
    }
}
