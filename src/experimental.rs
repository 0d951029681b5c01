//! The engine's inner parts that the accuracy lab (`lab/`), the benches, the examples, the
//! tests and the fuzz targets reach: **no stability promise**. Anything here may change or go
//! in any release; a caller that renders images needs only the crate root.
//!
//! A short, curated list: each module here names the items of the crate's module of that name
//! that those callers use (the kernels one primitive family at a time and their drivers, the
//! primitives' constant records and columns, the ray tables, one kernel set up and timed alone,
//! the f64x4 packets, the scene reader's stages), not the whole module. An item a new caller
//! needs is added here by name.

/// Acceleration: the size from which `auto` bins into tiles.
pub mod accel {
    pub use crate::accel::AUTO_MIN;
}

/// The pinhole camera's per-column and per-row ray tables ([`crate::Camera::tables`]) and the id band's width in pixels.
pub mod camera {
    pub use crate::camera::{ID_BAND_PIXELS, RayTables};
}

/// Intersection kernels: one primitive family at a time ([`Family`](kernel::Family)), 1-lane
/// and 8-lane forms side by side, their f64x4 form; the nearest-hit records.
pub mod kernel {
    pub use crate::kernel::{Family, Hit, Hit8, HitLanes, LANES, Quad, Sphere, Triangle, closer};
    /// The classes a family is bounded and drawn by.
    pub mod family {
        pub use crate::kernel::family::{Ball, Bounded, Class, Polygon};
    }

    /// The 8-ray packets' rays: a 4x2 pixel block's directions and live lanes.
    pub mod packet {
        pub use crate::kernel::packet::block_rays;
    }
    /// Triangles and quads: edge planes through the eye.
    pub mod polygon {
        pub use crate::kernel::polygon::{PolyK, QuadK, TriangleK, polygon_x1, polygon_x8};
    }
    /// The stable sphere.
    pub mod sphere {
        pub use crate::kernel::sphere::{SphereK, sphere_x1, sphere_x8};
    }
    /// The default kernels in f64x4 lanes (`--precision f64`).
    pub mod wide64 {
        pub use crate::kernel::wide64::{Hit4d, polygon_x4d, sphere_x4d};
    }
}

/// `Real`: the two precisions (f32, f64) the scalar kernels are written over, and 3-vectors.
pub mod real {
    pub use crate::real::{Real, V3, dot, v3};
}

/// Rendering's parts: one plain kernel's setup ([`Setup`](render::Setup), by
/// [`Plain`](render::Plain)), the packet renderer alone, f64x4 packets with their acceleration
/// (`wide64`), what `--precision auto` did (`redecide`).
pub mod render {
    pub use crate::render::{
        Frame, Options, PacketScene, Plain, Renderer, Setup, Structure, f32_depth, prepare_f64,
        render_packet, render_packet_blocks, strip_count,
    };

    /// `--precision auto`'s count of its work in a frame ([`crate::Renderer::auto_work`]).
    pub mod redecide {
        pub use crate::render::redecide::Work;
    }
    /// f64x4 packets (`--precision f64`) through an acceleration, on every thread.
    pub mod wide64 {
        pub use crate::render::wide64::Kit64;
    }
}

/// The scene reader's stages, each alone: parsing without the f32 range check, the OBJ and PLY
/// readers, the validation rules, the f32 range checks.
pub mod scene {
    /// The mesh readers behind `mesh PATH`.
    pub mod mesh {
        pub use crate::scene::mesh::{load_mesh, load_obj, load_ply, parse_obj, parse_ply};
    }
    /// Scene text and files to a [`Scene`](crate::Scene), without the f32 range check that
    /// [`crate::load_scene`] adds.
    pub mod parse {
        pub use crate::scene::parse::{load_scene, parse_scene};
    }
    /// The geometric rules of the format.
    pub mod validate {
        pub use crate::scene::validate::{camera, intrinsics, quad};
    }
    /// The f32 range check: every primitive representable by the f32 kernels from an eye.
    pub mod range {
        pub use crate::scene::range::{f32_range, f32_range_from};
    }
    /// The f32 range check of many views, settled a cluster of triangles at a time.
    pub mod range_clusters {
        pub use crate::scene::range_clusters::{CLUSTER, RangeClusters};
    }
}

/// Shading's constants: the `ordered` palette, `shade`'s grey and the farthest hit's brightness.
pub mod shade {
    pub use crate::shade::{B_MIN, PALETTE, SHADE_GREY};
}

/// Primitives prepared for the kernels: f64/f32 constant records and f32 SoA columns, and the
/// loops over them.
pub mod soa {
    pub use crate::soa::{Families, Packed, Prepared};

    /// The loops over a store: one ray against every primitive (the f64 oracle's loop).
    pub mod trace {
        pub use crate::soa::trace::trace_x1;
    }
}
