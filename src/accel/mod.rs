//! Acceleration: what keeps the packet kernel's cost growing slowly with primitive count.
//!
//! - `none`: every packet tests every primitive (the brute-force loops of `kernel::packet`).
//! - `tiles`: object-order casting (`tiles.rs`): each primitive binned into the 8x8-pixel
//!   screen tiles its conservative rectangle covers, each packet testing its tile's list
//!   nearest first and leaving it once no entry can win.
//! - `bvh`: a bounding volume hierarchy over eye-relative boxes (`build.rs`), traversed by each
//!   8-ray packet, a node entered when any lane's ray enters its box before that lane's nearest
//!   hit so far (`bvh.rs`).
//!
//! All three feed the same kernels and the same (t, id) minimum. `tiles` and `bvh` leave a
//! primitive out of a ray's tests only where no kernel (f32 or f64) can accept that ray on it
//! at a distance that could still win, by a written bound on the kernels' error (`reach.rs`),
//! derived for any camera and scene `scene::validate` accepts (to first order in u, with a
//! slack of at least 1.4 times on the leading terms). So ids and depths are bit-identical
//! between them, for every kernel and precision, and `--precision auto` re-decides the same
//! pixels (tests/accel.rs; tests/accel_random.rs over random cameras).
//!
//! `auto` picks `tiles` from [`AUTO_MIN`] primitives on, `none` below. Measured
//! (docs/performance.md, "Acceleration", `scripts/accel_table.py`, 1 thread): with one
//! primitive (scene7) any structure is overhead; from two on, `tiles` renders every measured
//! scene faster than `bvh`, the 3.3M-triangle armadillo included, and its setup is parallel.
//! The BVH stays for `--accel bvh` and as a second culled path the tests hold to `none`.

pub(crate) mod build;
pub(crate) mod bvh;
pub(crate) mod clusters;
pub(crate) mod footprint;
pub(crate) mod reach;
pub(crate) mod tiles;

pub(crate) use bvh::Bvh;
pub(crate) use tiles::Tiles;

/// Tile width in pixels: two packets of 4x2. Measured against 16 and 32 (docs/performance.md,
/// "Acceleration"): the same on the seed scenes, 15-35% faster at 65,536 primitives.
pub const TILE_W: usize = 8;
/// Tile height in pixels: the renderer's strip height, so a strip is one row of tiles.
pub const TILE_H: usize = 8;

/// From this many primitives on, `auto` bins the primitives into tiles.
pub const AUTO_MIN: usize = 2;

/// Which acceleration the packet kernel uses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accel {
    /// `auto`: `Tiles` from [`AUTO_MIN`] primitives on, `None` below ([`Accel::resolve`]).
    Auto,
    /// `none`: every packet tests every primitive.
    None,
    /// `bvh`: a bounding volume hierarchy over eye-relative boxes, traversed per packet.
    Bvh,
    /// `tiles`: primitives binned into 8x8-pixel screen tiles, tested nearest first.
    Tiles,
    /// `world`: the scene prepared once for any camera ([`crate::world::World`]), each view
    /// rendered in object order; a view's bits are its own (not `tiles`' bit for bit), held to
    /// the f64 oracle.
    World,
}

impl Accel {
    /// The concrete choice for a scene of `primitives` primitives.
    pub fn resolve(self, primitives: usize) -> Accel {
        match self {
            Accel::Auto if primitives >= AUTO_MIN => Accel::Tiles,
            Accel::Auto => Accel::None,
            other => other,
        }
    }

    /// The `--accel` name of the choice.
    pub fn name(self) -> &'static str {
        match self {
            Accel::Auto => "auto",
            Accel::None => "none",
            Accel::Bvh => "bvh",
            Accel::Tiles => "tiles",
            Accel::World => "world",
        }
    }
}
