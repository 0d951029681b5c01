//! The engine's inner layers, opened as they are for the accuracy lab (`lab/`), the benches,
//! the examples, the tests and the fuzz targets: **no stability promise**. Anything here may
//! change or go in any release; a caller that renders images needs only the crate root.
//!
//! Each module here is the crate's own module of that name, re-exported whole (`kernel` is
//! the crate's `kernel`, and so on): the kernels one primitive family at a time, in f32x8 and
//! f64x4 lanes ([`kernel`]), the primitives prepared as records and SoA columns
//! ([`soa`]), the acceleration ([`accel`]), the ray tables ([`camera`]), rendering's parts
//! ([`render`]: one kernel set up and timed alone, f64x4 packets, `--precision auto`), the
//! scene reader's stages ([`scene`]), shading's constants ([`shade`]) and the scalar type the
//! generic kernels are written over ([`real`]).

/// Acceleration: [`Accel`](crate::Accel) and the size from which `auto` bins into tiles.
pub mod accel {
    pub use crate::accel::*;
}

/// The pinhole camera's parts: the basis and the per-column and per-row ray tables.
pub mod camera {
    pub use crate::camera::*;
}

/// Intersection kernels: one file per primitive family, 1-lane and 8-lane forms side by side,
/// their f64x4 form (`wide64`) and the loops that drive them.
pub mod kernel {
    pub use crate::kernel::*;
}

/// `Real`: the two precisions (f32, f64) the scalar kernels are written over, and 3-vectors.
pub mod real {
    pub use crate::real::*;
}

/// Rendering's parts: one kernel's setup ([`Setup`](render::Setup)), the packet renderer
/// alone, f64x4 packets (`wide64`), `--precision auto` (`redecide`).
pub mod render {
    pub use crate::render::*;
}

/// The scene reader's stages, each alone: parsing without the f32 range check, the OBJ
/// reader, the validation rules and their tolerances.
pub mod scene {
    /// The OBJ reader behind `mesh PATH`.
    pub mod mesh {
        pub use crate::scene::mesh::*;
    }
    /// Scene text and files to a [`Scene`](crate::Scene), without the f32 range check that
    /// [`crate::load_scene`] adds.
    pub mod parse {
        pub use crate::scene::parse::*;
    }
    /// The geometric rules of the format and their tolerances.
    pub mod validate {
        pub use crate::scene::validate::*;
    }
    /// The f32 range check: every primitive representable by the f32 kernels from an eye.
    pub mod range {
        pub use crate::scene::range::*;
    }
    /// The f32 range check of many views, settled a cluster of triangles at a time.
    pub mod range_clusters {
        pub use crate::scene::range_clusters::*;
    }
}

/// Shading's constants: the `ordered` palette and the farthest hit's brightness.
pub mod shade {
    pub use crate::shade::*;
}

/// Primitives prepared for the kernels: constant records and SoA columns.
pub mod soa {
    pub use crate::soa::*;
}
