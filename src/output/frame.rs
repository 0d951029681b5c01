//! A [`Frame`]'s files: its image, shaded ([`Frame::rgb`]), and its buffers as `.npy`, each
//! written atomically by the one function of this module the command line uses too.

use std::path::Path;

use super::{image_format, write_image, write_npy_f32, write_npy_f32x3, write_npy_i32};
use crate::camera::Camera;
use crate::scene::Scene;
use crate::shade::{ColorMode, Variation};
use crate::{Frame, Result};

impl<D> Frame<D> {
    /// Writes the ids as a `height` x `width` NumPy array of little-endian i32 (`.npy`),
    /// atomically ([`write_npy_i32`]).
    pub fn write_ids(&self, path: &Path) -> Result<()> {
        write_npy_i32(path, self.width, self.height, &self.ids)
    }
}

impl Frame<f32> {
    /// Writes the frame shaded as [`Frame::rgb`] to a PNG or BMP image, by `path`'s extension
    /// (`.png` or `.bmp`, any case; another is a usage error), atomically
    /// ([`write_image`]).
    pub fn write_image(
        &self,
        path: &Path,
        (scene, camera): (&Scene, &Camera),
        mode: ColorMode,
        variation: Variation,
        seed: u64,
    ) -> Result<()> {
        image_format(path)?; // before the work of shading
        let rgb = self.rgb(scene, camera, mode, variation, seed);
        write_image(path, self.width, self.height, &rgb)
    }

    /// Writes the depths as a `height` x `width` NumPy array of little-endian f32 (`.npy`; +inf
    /// for background), atomically ([`write_npy_f32`]).
    pub fn write_depth(&self, path: &Path) -> Result<()> {
        write_npy_f32(path, self.width, self.height, &self.depth)
    }

    /// Writes the unit surface normals ([`Frame::normals`], of the scene and camera the frame
    /// was rendered with) as a `height` x `width` x 3 NumPy array of little-endian f32
    /// (`.npy`; 0, 0, 0 for background), atomically ([`write_npy_f32x3`]): the command line's
    /// `--normals` file.
    pub fn write_normals(&self, path: &Path, (scene, camera): (&Scene, &Camera)) -> Result<()> {
        let normals = self.normals(scene, camera);
        write_npy_f32x3(path, self.width, self.height, &normals)
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
        let normals = dir.join("n.npy");
        frame.write_normals(&normals, (&scene, &camera)).unwrap();
        assert_eq!(
            fs::read(&normals).unwrap(),
            crate::output::npy_f32x3(33, 17, &frame.normals(&scene, &camera))
        );
        assert_eq!(
            fs::read(&ids).unwrap(),
            crate::output::npy_i32(33, 17, &frame.ids)
        );
        assert_eq!(
            fs::read(&depth).unwrap(),
            crate::output::npy_f32(33, 17, &frame.depth)
        );
        let rgb = crate::shade::shade(
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
        assert_eq!(names, ["a.png", "d.npy", "ids.npy", "n.npy"]);
        fs::remove_dir_all(&dir).unwrap();
    }
}
