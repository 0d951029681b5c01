//! A render's result, [`Frame`]: per-pixel primitive ids and hit distances, as plain data.
//! What is made of a frame lives with its subject, above the renderers: its surfaces
//! ([`Frame::z_depth`], [`Frame::normals`]: `surface.rs`), its colours ([`Frame::rgb`]:
//! `shade.rs`) and its files ([`Frame::write_image`], [`Frame::write_ids`],
//! [`Frame::write_depth`]: `output/frame.rs`).

use crate::par::prelude::*;

/// Per-pixel results, row 0 at the top: primitive id (-1 for background) and hit distance
/// along the unit ray (+inf for background). [`Renderer::render`](crate::Renderer::render)
/// gives a `Frame<f32>`.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame<D> {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Primitive id per pixel (-1: background), row-major, `width * height` entries.
    pub ids: Vec<i32>,
    /// Hit distance `t` per pixel (+inf: background), parallel to `ids`.
    pub depth: Vec<D>,
}

impl<D: Copy + Send + Sync> Frame<D> {
    /// A frame of background: id -1 and depth `background` everywhere. The buffers are filled
    /// by the current rayon pool's threads, each writing (and so first touching) its own part
    /// of the new allocation: no serial pass over the image before the render.
    pub fn new(width: u32, height: u32, background: D) -> Frame<D> {
        let n = width as usize * height as usize;
        let mut ids = Vec::with_capacity(n);
        ids.par_extend(crate::par::repeat_n(-1, n));
        let mut depth = Vec::with_capacity(n);
        depth.par_extend(crate::par::repeat_n(background, n));
        Frame {
            width,
            height,
            ids,
            depth,
        }
    }

    /// `spare` filled with background as [`Frame::new`] would give it, its buffers reused when
    /// it has the size asked for (else a new frame): a caller rendering frame after frame hands
    /// the last one back rather than freeing it. (Freed, a frame's buffers were handed back to
    /// the system at some sizes and faulted in again on every render: 2.4 against 4.9 ms on
    /// one thread for a 1280x720 frame, `Renderer::recycle`.)
    pub fn reuse(spare: Option<Frame<D>>, width: u32, height: u32, background: D) -> Frame<D> {
        match spare {
            Some(mut f) if f.width == width && f.height == height => {
                f.ids.par_iter_mut().for_each(|id| *id = -1);
                f.depth.par_iter_mut().for_each(|t| *t = background);
                f
            }
            _ => Frame::new(width, height, background),
        }
    }
}
