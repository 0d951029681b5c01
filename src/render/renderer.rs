//! The entry point: [`Options`] (precision, acceleration, kernel) and a scene seen by a camera
//! make a prepared [`Renderer`] (the setup phase), whose [`Renderer::render`] gives a
//! [`Frame`] of ids and depths.

use super::redecide::Redecide;
use super::wide64::Kit64;
use super::{Frame, Kernel, PacketScene, Plain, Setup, f32_depth, packet_blocks, strip_count};
use crate::accel::Accel;
use crate::kernel::packet::{BLOCK_H, BLOCK_W};
use crate::precision::Precision;
use crate::soa::IdSet;
use crate::world::{self, World};
use std::sync::atomic::AtomicUsize;
use std::sync::{Arc, Mutex};

/// How to render: in which precision, with which acceleration, by which kernel.
/// `Options::default()` is what the command line does with no flags: `--precision auto` (f32x8
/// packets, each hit f32 cannot be trusted with decided again in f64), automatic acceleration.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Options {
    /// The precision (`--precision`).
    pub precision: Precision,
    /// The acceleration (`--accel`): every kernel and precision takes any but `world`, which
    /// has its own kernels and takes the packet kernel only.
    pub accel: Accel,
    /// The kernel: packets (the default), or one ray at a time (`--kernel scalar`, the oracle
    /// in f64; `scalar-f32` with [`Precision::F32`]).
    pub kernel: Kernel,
}

impl Options {
    /// Fails when the options contradict each other: `--accel world` with the scalar kernel.
    pub fn check(&self) -> crate::Result<()> {
        if self.accel == Accel::World && self.kernel != Kernel::Packet {
            return Err(crate::Error::usage(
                "--accel world has its own setup and kernels: it takes the packet kernel, and \
                 --precision chooses how they decide"
                    .to_string(),
            ));
        }
        Ok(())
    }
}

impl Default for Options {
    fn default() -> Options {
        Options {
            precision: Precision::Auto,
            accel: Accel::Auto,
            kernel: Kernel::Packet,
        }
    }
}

/// A scene prepared for one camera and one set of [`Options`]: every per-primitive constant
/// and acceleration structure is built, so [`Renderer::render`] only traces rays. With
/// [`Precision::Auto`] it borrows the scene, whose shapes the f64 re-decisions read.
pub struct Renderer<'s> {
    width: usize,
    height: usize,
    job: Job<'s>,
    /// A frame handed back by [`Renderer::recycle`], whose buffers the next packet render
    /// fills.
    spare: Mutex<Option<Frame<f32>>>,
}

enum Job<'s> {
    Setup(Box<Setup>, Option<Box<Redecide<'s>>>),
    /// f64x4 packets (`--precision f64`; `--precision auto` for a view the f32 kernels do not
    /// resolve, `kernel::f32_resolves`, when the flag is set: every pixel then counts as
    /// decided again in f64).
    Wide64(Box<Kit64>, bool),
    /// `--accel world`: the prepared scene (shared by every view), the camera, the precision
    /// and the view's working buffers.
    World(
        Arc<World>,
        Box<crate::camera::Camera>,
        world::Precision,
        Mutex<world::Scratch>,
    ),
}

/// What a finished renderer leaves for the next one of the same scene to fill rather than
/// allocate ([`Renderer::into_spare`], [`Renderer::with_spare`]): its last recycled frame and
/// the packet kernel's buffers (stores and tiles) and `--precision auto`'s.
#[derive(Debug, Default)]
pub(crate) struct Spare {
    pub(crate) frame: Option<Frame<f32>>,
    pub(crate) scene: PacketScene,
    pub(crate) redecide: super::redecide::Spare,
    /// Whether the renderer built from this keeps its working buffers for the next view
    /// (`Views`), at the cost of holding them while it lives.
    pub(crate) keep: bool,
}

impl<'s> Renderer<'s> {
    /// Prepares `scene` seen by `camera` (the setup phase). Fails when the options contradict
    /// each other ([`Options::check`]).
    pub fn new(
        scene: &'s crate::scene::Scene,
        camera: &crate::camera::Camera,
        options: &Options,
    ) -> crate::Result<Renderer<'s>> {
        Renderer::with_spare(scene, camera, options, Spare::default(), None)
    }

    /// [`Renderer::new`], filling `spare`'s buffers (another renderer's of the same scene,
    /// [`Renderer::into_spare`]) rather than new ones: the same renderer, the same frames.
    pub(crate) fn with_spare(
        scene: &'s crate::scene::Scene,
        camera: &crate::camera::Camera,
        options: &Options,
        spare: Spare,
        left_out: Option<&IdSet>,
    ) -> crate::Result<Renderer<'s>> {
        options.check()?;
        if options.accel == Accel::World {
            let world = Arc::new(World::new(scene));
            return Ok(Renderer::of_world(world, camera, options, spare));
        }
        let job = match (options.kernel, options.precision) {
            (Kernel::Packet, Precision::Auto) => {
                return Ok(Renderer::auto_in(
                    scene,
                    camera,
                    options.accel,
                    spare,
                    left_out,
                ));
            }
            (Kernel::Packet, Precision::F64) => Job::Wide64(
                Box::new(Kit64::with_accel(scene, camera, options.accel)),
                false,
            ),
            (kernel, precision) => Job::Setup(
                Box::new(Setup::with_accel_in(
                    Plain::of(kernel, precision).expect("a plain kernel"),
                    options.accel,
                    scene,
                    camera,
                    spare.scene,
                    spare.keep,
                    left_out,
                )),
                None,
            ),
        };
        Ok(Renderer {
            width: camera.width as usize,
            height: camera.height as usize,
            job,
            spare: Mutex::new(spare.frame),
        })
    }

    /// A renderer of `camera`'s view of a prepared [`World`] (`--accel world`), in the
    /// precision `options` give.
    pub(crate) fn of_world(
        world: Arc<World>,
        camera: &crate::camera::Camera,
        options: &Options,
        spare: Spare,
    ) -> Renderer<'s> {
        let precision = options.precision;
        Renderer {
            width: camera.width as usize,
            height: camera.height as usize,
            job: Job::World(world, Box::new(*camera), precision, Mutex::default()),
            spare: Mutex::new(spare.frame),
        }
    }

    /// The buffers this renderer leaves for the next ([`Renderer::with_spare`]).
    pub(crate) fn into_spare(self) -> Spare {
        let frame = self.spare.into_inner().unwrap_or_else(|e| e.into_inner());
        let (scene, redecide) = match self.job {
            Job::Setup(setup, redo) => (
                match *setup {
                    Setup::Packet(p, _) => *p,
                    _ => PacketScene::default(),
                },
                redo.map(|r| r.into_spare()).unwrap_or_default(),
            ),
            Job::Wide64(..) | Job::World(..) => Default::default(),
        };
        Spare {
            frame,
            scene,
            redecide,
            keep: false,
        }
    }

    /// The packet kernel with the f32 hits that cannot be trusted decided again in f64
    /// ([`Precision::Auto`], `--precision auto`).
    pub(crate) fn auto(
        scene: &'s crate::scene::Scene,
        camera: &crate::camera::Camera,
        accel: Accel,
    ) -> Renderer<'s> {
        if accel == Accel::World {
            let world = Arc::new(World::new(scene));
            return Renderer::of_world(world, camera, &Options::default(), Spare::default());
        }
        Renderer::auto_in(scene, camera, accel, Spare::default(), None)
    }

    /// [`Renderer::auto`], written into `spare`'s buffers ([`PacketScene::new_in`],
    /// [`Redecide::new_in`], the frame).
    fn auto_in(
        scene: &'s crate::scene::Scene,
        camera: &crate::camera::Camera,
        accel: Accel,
        spare: Spare,
        left_out: Option<&IdSet>,
    ) -> Renderer<'s> {
        if !crate::kernel::f32_resolves(camera) {
            // a telephoto view: the f32 kernels' edge band is a sizeable part of a pixel
            return Renderer {
                width: camera.width as usize,
                height: camera.height as usize,
                job: Job::Wide64(Box::new(Kit64::with_accel(scene, camera, accel)), true),
                spare: Mutex::new(spare.frame),
            };
        }
        let mut p = PacketScene::new_in(scene, camera, accel, spare.scene, spare.keep, left_out);
        let mut redecide = Redecide::new_in(scene, camera, &p.packed, spare.redecide);
        if let Some(tiles) = &mut p.tiles {
            redecide.attach_to(tiles, &p.packed, camera);
        }
        let tables = camera.tables(BLOCK_W as u32, BLOCK_H as u32);
        Renderer {
            width: camera.width as usize,
            height: camera.height as usize,
            job: Job::Setup(
                Box::new(Setup::Packet(Box::new(p), tables)),
                Some(Box::new(redecide)),
            ),
            spare: Mutex::new(spare.frame),
        }
    }

    /// The acceleration in use.
    pub fn accel(&self) -> Accel {
        match &self.job {
            Job::Setup(s, _) => s.accel(),
            Job::Wide64(k, _) => k.accel(),
            Job::World(..) => Accel::World,
        }
    }

    /// Whether f32 hits that cannot be trusted are decided again in f64 (`--precision auto`
    /// with the packet kernel).
    pub fn redecides(&self) -> bool {
        matches!(self.job, Job::Setup(_, Some(_)) | Job::Wide64(_, true))
            || matches!(self.job, Job::World(_, _, world::Precision::Auto, _))
    }

    /// What `--precision auto` did on the tile path in this renderer's last frame
    /// ([`crate::render::redecide::Work`]; all zero through the BVH or without acceleration);
    /// `None` for other precisions. Counts of the frame rendered last, whichever thread
    /// rendered it: two frames rendered at once on one renderer mix their counts.
    pub fn auto_work(&self) -> Option<crate::render::redecide::Work> {
        match &self.job {
            Job::Setup(_, Some(r)) => Some(r.work()),
            _ => None,
        }
    }

    /// Renders the frame in the current rayon pool. Depth is reported in f32 by every kernel
    /// (f64 distances rounded once).
    pub fn render(&self) -> Frame<f32> {
        self.render_counting(None)
    }

    /// Hands a frame back once its caller is done with it: the next render with the packet
    /// kernel fills its buffers rather than new ones, when it has this renderer's size
    /// ([`Frame::reuse`]). For a caller that renders frame after frame (`--repeat`, benches).
    pub fn recycle(&self, frame: Frame<f32>) {
        *self.spare.lock().unwrap_or_else(|e| e.into_inner()) = Some(frame);
    }

    /// How many units of work [`Renderer::render_counting`] counts (strips of rows).
    pub fn work_units(&self) -> usize {
        strip_count(self.height)
    }

    /// [`Renderer::render`], adding 1 to `progress` per finished strip of rows (f64 packets and
    /// `--accel world` count nothing).
    pub fn render_counting(&self, progress: Option<&AtomicUsize>) -> Frame<f32> {
        self.render_marking(progress).0
    }

    /// [`Renderer::render_counting`], also returning the pixels whose f32 hit was decided again
    /// in f64 (row-major indices, ascending; empty unless [`Renderer::redecides`]).
    pub fn render_marking(&self, progress: Option<&AtomicUsize>) -> (Frame<f32>, Vec<usize>) {
        let (w, h) = (self.width, self.height);
        let spare = || self.spare.lock().unwrap_or_else(|e| e.into_inner()).take();
        match &self.job {
            Job::Setup(s, redo) => match s.as_ref() {
                Setup::Packet(p, t) => {
                    let redo = redo.as_deref();
                    packet_blocks::<BLOCK_W>(p, t, (w, h), progress, redo, spare())
                }
                other => (other.render_counting(w, h, progress), Vec::new()),
            },
            Job::Wide64(k, false) => (f32_depth(k.render()), Vec::new()),
            Job::Wide64(k, true) => (f32_depth(k.render()), (0..w * h).collect()),
            Job::World(world, camera, precision, scratch) => {
                let mut scratch = scratch.lock().unwrap_or_else(|e| e.into_inner());
                world.render_marking(camera, *precision, &mut scratch, spare())
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// `--accel world` takes every precision with the packet kernel, and refuses the scalar
    /// kernel.
    #[test]
    fn world_takes_the_precisions_and_refuses_the_scalar_kernel() {
        let with = |kernel, precision| {
            Options {
                precision,
                accel: Accel::World,
                kernel,
            }
            .check()
        };
        for p in Precision::ALL {
            assert!(with(Kernel::Packet, p).is_ok(), "{p:?}");
            assert!(with(Kernel::Scalar, p).is_err(), "{p:?}");
        }
    }
    use crate::camera::Camera;
    use std::path::Path;

    /// A frame handed back is filled as a new one would be: dirtied, recycled and rendered into,
    /// it gives the fresh frame's ids and depths in its own buffers, with `f32` and `auto`; a
    /// frame of another size is not used.
    #[test]
    fn a_recycled_frame_renders_as_a_new_one() {
        let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("scenes/scene2.sc");
        let scene = crate::scene::load_scene(&path).expect("scene 2");
        let camera = Camera::for_scene(&scene, 96, 64, None).expect("a camera");
        for precision in [Precision::F32, Precision::Auto] {
            let options = Options {
                precision,
                ..Options::default()
            };
            let r = Renderer::new(&scene, &camera, &options).expect("a renderer");
            let fresh = r.render();
            let mut dirty = fresh.clone();
            dirty.ids.iter_mut().for_each(|id| *id = 7);
            dirty.depth.iter_mut().for_each(|t| *t = 1.0);
            let buffer = dirty.ids.as_ptr();
            r.recycle(dirty);
            let again = r.render();
            assert_eq!(again, fresh, "{precision:?}");
            assert_eq!(
                again.ids.as_ptr(),
                buffer,
                "{precision:?}: the buffers reused"
            );
            r.recycle(Frame::new(10, 10, 0.0));
            assert_eq!(r.render(), fresh, "{precision:?}: another size");
        }
    }
}
