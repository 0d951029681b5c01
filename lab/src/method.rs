//! The lab's intersection methods, each a point on the chart: a triangle/quad method and a
//! sphere method ([`crate::methods`], lanecast's own kernels) in a precision, and
//! [`Method::prepare`] builds its driver. lanecast's precisions (`f64x4`: `--precision f64`,
//! `auto`: `--precision auto`) render through lanecast's own renderer, with its acceleration
//! and threads; the others run a brute-force driver ([`kits`](crate::kits)): every ray against
//! every primitive, on the calling thread. Those exist to be compared (by this lab's table and
//! chart, and `lab-render`), not to be fast.

use crate::kits::{Kernels, Kit, Mt, Naive, Oracle, Plane, Product, Watertight, WorldF32};
use lanecast::experimental::render::wide64::Kit64;
use lanecast::scene::Scene;
use lanecast::{Accel, Camera, Frame, Options, Precision, Renderer};

/// One method as a point on the chart: a triangle/quad method, a sphere method, a precision.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Method {
    /// The default: edge planes + stable sphere, f32, eye-relative f64 setup.
    Default,
    /// Möller–Trumbore triangles (+ stable spheres).
    Mt,
    /// Woop–Benthin–Wald watertight triangles (+ stable spheres).
    Watertight,
    /// The seed's plane + determinants (+ stable spheres).
    Plane,
    /// Textbook sphere quadratic (+ edge-plane polygons).
    Naive,
    /// The default methods with the classic f32 world-space setup.
    WorldF32,
    /// The default methods in f64x4 packets.
    F64x4,
    /// The default methods in f32x8 packets, with each hit whose f32 distance cannot be trusted
    /// to 1e-5 decided again in f64 (`--precision auto`, lanecast's default;
    /// `lanecast::experimental::render::redecide`).
    Auto,
}

impl Method {
    /// Every method, the default first.
    pub const ALL: [Method; 8] = [
        Method::Default,
        Method::Mt,
        Method::Watertight,
        Method::Plane,
        Method::Naive,
        Method::WorldF32,
        Method::F64x4,
        Method::Auto,
    ];

    /// The method's `--method` name (`lab-render`, the lab bench; also its label in reports).
    pub fn name(self) -> &'static str {
        match self {
            Method::Default => "eplane+stable",
            Method::Mt => "mt",
            Method::Watertight => "watertight",
            Method::Plane => "plane",
            Method::Naive => "naive",
            Method::WorldF32 => "world-f32",
            Method::F64x4 => "f64x4",
            Method::Auto => "auto",
        }
    }

    /// A one-line description: the triangle/quad and sphere methods, lanes and setup.
    pub fn describe(self) -> &'static str {
        match self {
            Method::Default => {
                "default: edge planes (triangles, quads) + stable sphere, f32x8, eye-relative f64 setup"
            }
            Method::Mt => {
                "Möller–Trumbore triangles, quads as 2 triangles (+ stable spheres), f32x8"
            }
            Method::Watertight => {
                "Woop–Benthin–Wald watertight triangles, quads as 2 triangles (+ stable spheres), f32x8"
            }
            Method::Plane => {
                "plane hit + edge determinants, quads as 2 triangles (+ stable spheres), f32x8"
            }
            Method::Naive => "textbook quadratic spheres (+ edge-plane polygons), f32x8",
            Method::WorldF32 => {
                "default methods, constants computed in f32 from f32 world coordinates"
            }
            Method::F64x4 => "default methods in f64x4 lanes, two per 4x2 packet",
            Method::Auto => {
                "default methods in f32x8, hits f32 cannot hold to 1e-5 re-decided in f64 (--precision auto)"
            }
        }
    }

    /// Whether the method runs in a brute-force driver ([`Method::prepare`]): every ray
    /// against every primitive, no acceleration, on the calling thread. lanecast's precisions
    /// (`f64x4`, `auto`) take an acceleration and every thread of the pool.
    pub fn is_brute_force(self) -> bool {
        !matches!(self, Method::Default | Method::F64x4 | Method::Auto)
    }

    /// The precision the method computes in: `f64` for [`Method::F64x4`], `auto` for
    /// [`Method::Auto`], else `f32`.
    pub fn precision(self) -> &'static str {
        match self {
            Method::F64x4 => "f64",
            Method::Auto => "auto",
            _ => "f32",
        }
    }

    /// The method whose [`Method::name`] is `s`, or `None`.
    pub fn parse(s: &str) -> Option<Method> {
        Method::ALL.into_iter().find(|m| m.name() == s)
    }

    /// Prepares the method for a scene: constants and ray tables (the setup phase), without
    /// acceleration.
    pub fn prepare<'s>(self, scene: &'s Scene, camera: &Camera) -> Box<dyn MethodRender + 's> {
        self.prepare_with(scene, camera, Accel::None)
    }

    /// [`Method::prepare`] with acceleration `accel`, which only the methods that are not
    /// [`Method::is_brute_force`] use (the others test every primitive whatever it says).
    pub fn prepare_with<'s>(
        self,
        scene: &'s Scene,
        camera: &Camera,
        accel: Accel,
    ) -> Box<dyn MethodRender + 's> {
        match self {
            Method::Default => Box::new(Kit::<Product>::new(scene, camera)),
            Method::Mt => Box::new(Kit::<Mt>::new(scene, camera)),
            Method::Watertight => Box::new(Kit::<Watertight>::new(scene, camera)),
            Method::Plane => Box::new(Kit::<Plane>::new(scene, camera)),
            Method::Naive => Box::new(Kit::<Naive>::new(scene, camera)),
            Method::WorldF32 => Box::new(Kit::<WorldF32>::new(scene, camera)),
            Method::F64x4 => Box::new(Kit64::with_accel(scene, camera, accel)),
            Method::Auto => {
                let options = Options {
                    precision: Precision::Auto,
                    accel,
                    ..Options::default()
                };
                Box::new(Renderer::new(scene, camera, &options).expect("auto takes any accel"))
            }
        }
    }
}

/// A prepared method: renders the whole image.
pub trait MethodRender: Send + Sync {
    /// Renders the whole image, depth in f64: on the calling thread unless
    /// [`MethodRender::is_parallel`].
    fn render(&self) -> Frame<f64>;

    /// The acceleration in use (`none` for the brute-force drivers).
    fn accel(&self) -> Accel {
        Accel::None
    }

    /// Whether [`MethodRender::render`] spreads over the current rayon pool's threads.
    fn is_parallel(&self) -> bool {
        false
    }

    /// [`MethodRender::render`], also returning the pixels whose hit was decided again in f64
    /// (row-major indices, ascending; empty but for [`Method::Auto`]).
    fn render_marking(&self) -> (Frame<f64>, Vec<usize>) {
        (self.render(), Vec::new())
    }
}

impl MethodRender for Renderer<'_> {
    fn render(&self) -> Frame<f64> {
        MethodRender::render_marking(self).0
    }

    fn accel(&self) -> Accel {
        Renderer::accel(self)
    }

    fn is_parallel(&self) -> bool {
        true
    }

    fn render_marking(&self) -> (Frame<f64>, Vec<usize>) {
        let (f, marks) = Renderer::render_marking(self, None);
        let depth = f.depth.iter().map(|&d| d as f64).collect();
        (
            Frame {
                width: f.width,
                height: f.height,
                ids: f.ids,
                depth,
            },
            marks,
        )
    }
}

impl<M: Kernels> MethodRender for Kit<M> {
    fn render(&self) -> Frame<f64> {
        self.render_x8()
    }
}

impl MethodRender for Kit64 {
    fn render(&self) -> Frame<f64> {
        Kit64::render(self)
    }

    fn accel(&self) -> Accel {
        Kit64::accel(self)
    }

    fn is_parallel(&self) -> bool {
        true
    }
}

impl MethodRender for Oracle {
    fn render(&self) -> Frame<f64> {
        Oracle::render(self)
    }
}
