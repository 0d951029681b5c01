//! A render's result, [`Frame`]: per-pixel primitive ids and hit distances, and the ways to
//! write them out (an image shaded from them, the buffers as `.npy`), each by the one function
//! the command line uses too ([`shade`], [`crate::output`]).

use std::path::Path;

use crate::camera::Camera;
use crate::par::prelude::*;
use crate::scene::Scene;
use crate::shade::{ColorMode, Variation, shade};
use crate::{Result, output};

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

impl<D> Frame<D> {
    /// Writes the ids as a `height` x `width` NumPy array of little-endian i32 (`.npy`),
    /// atomically ([`output::write_npy_i32`]).
    pub fn write_ids(&self, path: &Path) -> Result<()> {
        output::write_npy_i32(path, self.width, self.height, &self.ids)
    }
}

impl Frame<f32> {
    /// The frame shaded to RGB, three bytes per pixel, row 0 at the top ([`shade`]: a colour per
    /// primitive by `mode`, or `shade`'s headlight on the surfaces, dimmed with distance by
    /// `variation`; `seed` varies the random colours). `scene` and `camera` are those the frame
    /// was rendered from: `shade` mode lights each hit by its normal ([`Frame::headlight`]).
    pub fn rgb(
        &self,
        scene: &Scene,
        camera: &Camera,
        mode: ColorMode,
        variation: Variation,
        seed: u64,
    ) -> Vec<u8> {
        let light = mode.needs_light().then(|| self.headlight(scene, camera));
        shade(
            &self.ids,
            &self.depth,
            light.as_deref(),
            self.width,
            mode,
            variation,
            seed,
        )
    }

    /// Writes the frame shaded as [`Frame::rgb`] to a PNG or BMP image, by `path`'s extension
    /// (`.png` or `.bmp`, any case; another is a usage error), atomically
    /// ([`output::write_image`]).
    pub fn write_image(
        &self,
        path: &Path,
        (scene, camera): (&Scene, &Camera),
        mode: ColorMode,
        variation: Variation,
        seed: u64,
    ) -> Result<()> {
        output::image_format(path)?; // before the work of shading
        let rgb = self.rgb(scene, camera, mode, variation, seed);
        output::write_image(path, self.width, self.height, &rgb)
    }

    /// Writes the depths as a `height` x `width` NumPy array of little-endian f32 (`.npy`; +inf
    /// for background), atomically ([`output::write_npy_f32`]).
    pub fn write_depth(&self, path: &Path) -> Result<()> {
        output::write_npy_f32(path, self.width, self.height, &self.depth)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Options, Renderer};
    use std::fs;

    /// What the frame writes is what the command line's functions give for its buffers, byte
    /// for byte; a wrong extension fails before anything is written.
    #[test]
    fn a_frame_writes_what_the_output_functions_write() {
        let text = "camera eye 0 2 8 look 0 1 0 up 0 1 0\nsphere 0 1 0 1\ntriangle -3 0 0  3 0 0  0 3 -2\n";
        let scene = crate::parse_scene(text, Path::new("inline.sc")).unwrap();
        let camera = Camera::for_scene(&scene, 33, 17, None).unwrap();
        let frame = Renderer::new(&scene, &camera, &Options::default())
            .unwrap()
            .render();
        let dir = std::env::temp_dir().join(format!("lanecast-frame-{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let (png, ids, depth) = (dir.join("a.png"), dir.join("ids.npy"), dir.join("d.npy"));
        frame
            .write_image(
                &png,
                (&scene, &camera),
                ColorMode::Ordered,
                Variation::Log,
                0,
            )
            .unwrap();
        frame.write_ids(&ids).unwrap();
        frame.write_depth(&depth).unwrap();
        assert_eq!(fs::read(&ids).unwrap(), output::npy_i32(33, 17, &frame.ids));
        assert_eq!(
            fs::read(&depth).unwrap(),
            output::npy_f32(33, 17, &frame.depth)
        );
        let rgb = shade(
            &frame.ids,
            &frame.depth,
            None,
            33,
            ColorMode::Ordered,
            Variation::Log,
            0,
        );
        assert_eq!(
            frame.rgb(&scene, &camera, ColorMode::Ordered, Variation::Log, 0),
            rgb
        );
        let back = image::open(&png).unwrap().to_rgb8();
        assert_eq!((back.width(), back.height()), (33, 17));
        assert_eq!(back.into_raw(), rgb);
        let jpg = frame.write_image(
            &dir.join("a.jpg"),
            (&scene, &camera),
            ColorMode::Random,
            Variation::Linear,
            1,
        );
        assert!(matches!(jpg, Err(crate::Error::Usage(_))));
        let mut names: Vec<_> = fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        names.sort();
        assert_eq!(names, ["a.png", "d.npy", "ids.npy"]);
        fs::remove_dir_all(&dir).unwrap();
    }
}
