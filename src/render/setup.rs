//! The setup phase of the plain kernels ([`Setup`]): for the packet kernel its SoA stores
//! and acceleration ([`PacketScene`]), for the scalar kernels f64 constant records and the
//! structure they trace through ([`prepare_f64`], [`Structure`]); and rendering from it.

use super::{Frame, PacketScene, f32_depth, render_packet_blocks, render_scalar_counting};
use crate::accel::{Accel, Bvh, Tiles};
use crate::camera::RayTables;
use crate::kernel::packet::{BLOCK_H, BLOCK_W};
use crate::precision::Precision;
use crate::soa::{IdSet, Packed, Prepared};
use std::sync::atomic::AtomicUsize;

/// The acceleration structure the scalar kernels and the f64x4 packets trace through, built
/// over f64 constant records ([`prepare_f64`]). The same structures as the packet kernel's, and
/// as conservative for the f64 kernels (see `Tiles::trace_x1`, `accel::bvh::trace_bvh_x1`).
#[derive(Debug, Clone)]
pub enum Structure {
    /// Every ray tests every primitive.
    None,
    /// Screen tiles, nearest first.
    Tiles(Box<Tiles>),
    /// The BVH; the records are in its leaf order.
    Bvh(Box<Bvh>),
}

impl Structure {
    /// The acceleration this is.
    pub fn accel(&self) -> Accel {
        match self {
            Structure::None => Accel::None,
            Structure::Tiles(_) => Accel::Tiles,
            Structure::Bvh(_) => Accel::Bvh,
        }
    }
}

/// The f64 constant records of `scene` seen by `camera` and the structure `accel` resolves to
/// (as for the packet kernel: `auto` picks tiles from `accel::AUTO_MIN` primitives). With the
/// BVH the records come back in its leaf order.
pub fn prepare_f64(
    accel: Accel,
    scene: &crate::scene::Scene,
    camera: &crate::camera::Camera,
) -> (Prepared<f64>, Structure) {
    let p = Prepared::new(scene, camera.eye);
    match accel.resolve(scene.shapes.len()) {
        Accel::Tiles => {
            let (tiles, order) = Tiles::new(scene, &Packed::new(&p), camera);
            let mut p = p;
            p.permute(&order);
            (p, Structure::Tiles(Box::new(tiles)))
        }
        Accel::Bvh => {
            let (bvh, reordered) = Bvh::new(&p, scene, camera);
            (reordered, Structure::Bvh(Box::new(bvh)))
        }
        _ => (p, Structure::None),
    }
}

/// Which kernel renders (`--kernel`); [`Precision`] says in what.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Kernel {
    /// 4x2-pixel packets: f32x8 lanes (`auto` re-deciding the untrusted hits in f64), or f64x4
    /// lanes with [`Precision::F64`].
    #[default]
    Packet,
    /// One ray at a time: in f32 with [`Precision::F32`], else in f64 (the oracle; `auto` has
    /// nothing to re-decide there).
    Scalar,
}

/// A kernel in one precision with nothing re-decided: what [`Setup`] prepares and times alone
/// (f32 packets, and the scalar kernel in f32 and in f64). `--precision auto` and f64 packets
/// are [`super::Renderer`]'s.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Plain {
    /// 8-lane f32 packets.
    Packet,
    /// One ray at a time in f32.
    ScalarF32,
    /// One ray at a time in f64: the oracle.
    ScalarF64,
}

impl Plain {
    /// The plain kernel of `kernel` in `precision`: `None` for the packets in `auto` or f64.
    pub fn of(kernel: Kernel, precision: Precision) -> Option<Plain> {
        match (kernel, precision) {
            (Kernel::Packet, Precision::F32) => Some(Plain::Packet),
            (Kernel::Packet, _) => None,
            (Kernel::Scalar, Precision::F32) => Some(Plain::ScalarF32),
            (Kernel::Scalar, _) => Some(Plain::ScalarF64),
        }
    }
}

/// Everything a kernel needs before its first ray: the setup phase.
pub enum Setup {
    /// [`Plain::Packet`]: the SoA stores (and acceleration), f32 ray tables padded to blocks.
    Packet(Box<PacketScene>, RayTables<f32>),
    /// [`Plain::ScalarF32`]: f32 constant records, f32 ray tables and the acceleration.
    ScalarF32(Prepared<f32>, RayTables<f32>, Structure),
    /// [`Plain::ScalarF64`]: f64 constant records, f64 ray tables and the acceleration (the
    /// oracle).
    ScalarF64(Prepared<f64>, RayTables<f64>, Structure),
}

impl Setup {
    /// The setup of `kernel` for `scene` seen by `camera`, with automatic acceleration.
    pub fn new(
        kernel: Plain,
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
    ) -> Setup {
        Setup::with_accel(kernel, Accel::Auto, scene, camera)
    }

    /// As [`Setup::new`], with the acceleration chosen by the caller (every kernel takes every
    /// acceleration).
    pub fn with_accel(
        kernel: Plain,
        accel: Accel,
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
    ) -> Setup {
        Setup::with_accel_in(
            kernel,
            accel,
            scene,
            camera,
            PacketScene::default(),
            false,
            None,
        )
    }

    /// [`Setup::with_accel`], the packet kernel's buffers written into `spare`'s
    /// ([`PacketScene::new_in`]); the scalar kernels drop it.
    pub fn with_accel_in(
        kernel: Plain,
        accel: Accel,
        scene: &crate::scene::Scene,
        camera: &crate::camera::Camera,
        spare: PacketScene,
        keep: bool,
        left_out: Option<&IdSet>,
    ) -> Setup {
        match kernel {
            Plain::Packet => Setup::Packet(
                Box::new(PacketScene::new_in(
                    scene, camera, accel, spare, keep, left_out,
                )),
                camera.tables(BLOCK_W as u32, BLOCK_H as u32),
            ),
            Plain::ScalarF32 => {
                let (p, structure) = prepare_f64(accel, scene, camera);
                Setup::ScalarF32(p.cast(), camera.tables(1, 1), structure)
            }
            Plain::ScalarF64 => {
                let (p, structure) = prepare_f64(accel, scene, camera);
                Setup::ScalarF64(p, camera.tables(1, 1), structure)
            }
        }
    }

    /// The acceleration in use.
    pub fn accel(&self) -> Accel {
        match self {
            Setup::Packet(p, _) => p.accel(),
            Setup::ScalarF32(_, _, s) => s.accel(),
            Setup::ScalarF64(_, _, s) => s.accel(),
        }
    }

    /// Renders a `width` x `height` frame (the camera's size). Depth is reported in f32 by every
    /// kernel (the oracle's f64 distances rounded once).
    pub fn render(&self, width: usize, height: usize) -> Frame<f32> {
        self.render_counting(width, height, None)
    }

    /// [`Setup::render`], counting finished strips (of [`super::strip_count`]) in `progress`.
    pub fn render_counting(
        &self,
        width: usize,
        height: usize,
        progress: Option<&AtomicUsize>,
    ) -> Frame<f32> {
        match self {
            Setup::Packet(p, t) => render_packet_blocks::<BLOCK_W>(p, t, width, height, progress),
            Setup::ScalarF32(p, t, s) => render_scalar_counting(p, t, s, width, height, progress),
            Setup::ScalarF64(p, t, s) => {
                f32_depth(render_scalar_counting(p, t, s, width, height, progress))
            }
        }
    }
}
