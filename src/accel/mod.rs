//! Acceleration: what keeps the packet kernel's cost growing slowly with primitive count.
//!
//! - `none`: every packet tests every primitive (the brute-force loops of `kernel::packet`).
//! - `bvh`: a bounding volume hierarchy over eye-relative boxes (`build.rs`), traversed by each
//!   8-ray packet, a node entered when any lane's ray enters its box before that lane's nearest
//!   hit so far (`bvh.rs`). Leaves are contiguous ranges of the SoA stores, tested with the same
//!   8-lane kernels as `none`, so ids agree with `none` except at genuine ties.
//!
//! `auto` picks `bvh` from [`AUTO_BVH_MIN`] primitives on. Measured (README "Acceleration",
//! render phase, 1 thread, best of 10 at 1920x1080): with one primitive (scene7) the box test is
//! pure overhead (8.4 ms without, 9.1 ms with); from a handful on, the boxes cull the rays that
//! miss everything: 4 primitives 9.3 -> 6.3 ms, scene1 (10) 18.8 -> 11.3 ms, scene2 (64) 42.6 ->
//! 13.2 ms.

pub(crate) mod build;
pub(crate) mod bvh;

pub(crate) use bvh::Bvh;

/// From this many primitives on, `auto` builds a BVH.
pub const AUTO_BVH_MIN: usize = 2;

/// Which acceleration the packet kernel uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accel {
    Auto,
    None,
    Bvh,
}

impl Accel {
    /// The concrete choice for a scene of `primitives` primitives.
    pub fn resolve(self, primitives: usize) -> Accel {
        match self {
            Accel::Auto if primitives >= AUTO_BVH_MIN => Accel::Bvh,
            Accel::Auto => Accel::None,
            other => other,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            Accel::Auto => "auto",
            Accel::None => "none",
            Accel::Bvh => "bvh",
        }
    }
}
