//! Many views of one scene: [`Views`] holds a loaded scene and the render options, and renders
//! any number of cameras (a turntable, a camera path, a dataset of poses) one after another,
//! each view written into the buffers of the view before (its frame, its stores' columns, its
//! tiles' lists), so that after the first view most of a view's memory is already in use.
//!
//! Every view is rendered exactly as a one-camera [`Renderer`] for the same camera and options
//! renders it: ids and depths are bit-identical to `lanecast -i SCENE` with that camera, at any
//! thread count (tests/views.rs). What depends on the camera (the eye-relative primitive
//! constants, the tiles' bins) is built per view; what does not (the scene, its validation, the
//! range check's cluster bounds) is done once.

use super::renderer::Spare;
use super::{Frame, Options, Renderer};
use crate::camera::Camera;
use crate::error::Result;
use crate::scene::Scene;
use crate::scene::range_clusters::RangeClusters;
use std::sync::{Mutex, OnceLock};

/// A scene prepared for rendering from many cameras. Borrows the scene: `--precision auto`
/// re-decides hits from its shapes. Between views it keeps the last view's buffers (its frame,
/// stores, tiles' lists and working buffers, `auto`'s per-primitive arrays), emptied, for the
/// next view to fill: about as much memory as one view's setup uses, held until the `Views`
/// is dropped (docs/performance.md, "Many views", gives the figures).
pub struct Views<'s> {
    scene: &'s Scene,
    options: Options,
    /// The f32 range check's cluster bounds, built by the first view whose eye is not the
    /// scene's (`scene::range_clusters`).
    range: OnceLock<RangeClusters>,
    /// The buffers the next view fills: the last frame handed back ([`Views::recycle`]) and
    /// those of the last renderer handed back ([`Views::give_back`]).
    spare: Mutex<Spare>,
}

impl<'s> Views<'s> {
    /// Prepares `scene` for views rendered with `options`. Fails when the options contradict
    /// each other, as [`Renderer::new`] does.
    pub fn new(scene: &'s Scene, options: &Options) -> Result<Views<'s>> {
        options.check()?;
        Ok(Views {
            scene,
            options: *options,
            range: OnceLock::new(),
            spare: Mutex::new(Spare::default()),
        })
    }

    /// The scene the views show.
    pub fn scene(&self) -> &'s Scene {
        self.scene
    }

    /// The options every view is rendered with.
    pub fn options(&self) -> &Options {
        &self.options
    }

    /// Checks that the f32 kernels can represent every primitive seen from `camera`'s eye
    /// (`scene::range::f32_range`, relative to this eye): the error names the first
    /// primitive that cannot be. [`Views::render`] checks this too. The first eye other than
    /// the scene's builds bounds on clusters of primitives, built once, that settle most
    /// clusters of each later view at a time (`scene::range_clusters`); the outcome is the
    /// per-primitive check's.
    pub fn check(&self, camera: &Camera) -> Result<()> {
        if camera.eye == self.scene.camera.eye {
            return Ok(()); // checked when the scene was loaded
        }
        let range = self.range.get_or_init(|| RangeClusters::new(self.scene));
        range.check(self.scene, camera.eye)
    }

    /// Renders the view from `camera` (its own size) on the current rayon pool: the same ids
    /// and depths as `Renderer::new(scene, camera, options)?.render()`.
    pub fn render(&self, camera: &Camera) -> Result<Frame<f32>> {
        self.check(camera)?;
        let renderer = self.renderer(camera)?;
        let frame = renderer.render();
        self.give_back(renderer);
        Ok(frame)
    }

    /// The prepared one-camera renderer for `camera` (the per-view setup), for a caller that
    /// wants its counters or progress ([`Renderer::render_marking`]); hand it back with
    /// [`Views::give_back`] once done. The eye's range is not checked here: call
    /// [`Views::check`] first.
    pub fn renderer(&self, camera: &Camera) -> Result<Renderer<'s>> {
        let spare = Spare {
            keep: true,
            ..std::mem::take(&mut *self.spare())
        };
        Renderer::with_spare(self.scene, camera, &self.options, spare)
    }

    /// Hands a renderer back once its frame is rendered: the next view's stores and tiles are
    /// written into its buffers rather than fresh memory.
    pub fn give_back(&self, renderer: Renderer<'s>) {
        let left = renderer.into_spare();
        let mut spare = self.spare();
        spare.scene = left.scene;
        spare.redecide = left.redecide;
        if spare.frame.is_none() {
            spare.frame = left.frame;
        }
    }

    /// Hands a frame back once its caller is done with it: the next view fills its buffers
    /// when it has the same size.
    pub fn recycle(&self, frame: Frame<f32>) {
        self.spare().frame = Some(frame);
    }

    fn spare(&self) -> std::sync::MutexGuard<'_, Spare> {
        self.spare.lock().unwrap_or_else(|e| e.into_inner())
    }
}

impl std::fmt::Debug for Views<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Views")
            .field("scene", &self.scene.source)
            .field("options", &self.options)
            .finish()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::{CameraSpec, parse_scene};
    use glam::DVec3;
    use std::path::Path;

    const TEXT: &str = "camera eye 0 2 8 look 0 1 0 up 0 1 0 fov 60\n\
                        sphere 0 1 0 1\n\
                        triangle -3 0 -2  3 0 -2  0 3 -2\n\
                        quad -4 0 -4  4 0 -4  4 0 4  -4 0 4\n";

    /// Views of changing eyes, fields of view and sizes, each rendered into the buffers of the
    /// one before (with `--precision auto` and `f32`), give a fresh renderer's ids and depths.
    #[test]
    fn every_view_renders_as_a_renderer_of_its_own() {
        for method in [crate::Method::Auto, crate::Method::Default] {
            let options = Options {
                method,
                ..Options::default()
            };
            views_render_alone(&options);
        }
    }

    fn views_render_alone(options: &Options) {
        let scene = parse_scene(TEXT, Path::new("v.sc")).unwrap();
        let options = *options;
        let views = Views::new(&scene, &options).unwrap();
        for k in 0..12 {
            let a = k as f64 * 0.5;
            let spec = CameraSpec {
                eye: DVec3::new(8.0 * a.sin(), 2.0 + k as f64 * 0.3, 8.0 * a.cos()),
                look: DVec3::new(0.0, 1.0, 0.0),
                up: DVec3::Y,
                fov_deg: Some(20.0 + 10.0 * k as f64),
            };
            let camera = Camera::look_at(&spec, 37 + k, 23 + 2 * k).unwrap();
            let frame = views.render(&camera).unwrap();
            let alone = Renderer::new(&scene, &camera, &options).unwrap().render();
            assert_eq!(frame.ids, alone.ids, "view {k}");
            let bits = |d: &[f32]| d.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&frame.depth), bits(&alone.depth), "view {k}");
            assert!(frame.ids.iter().any(|&i| i >= 0), "view {k} sees the scene");
            views.recycle(frame);
            // the stores are kept for the next view
            assert!(
                views.spare().scene.packed.triangles.id.capacity() > 0,
                "view {k}"
            );
        }
    }

    #[test]
    fn a_bad_camera_is_refused_by_name() {
        let scene = parse_scene(TEXT, Path::new("v.sc")).unwrap();
        let on_look = CameraSpec {
            eye: DVec3::ONE,
            look: DVec3::ONE,
            up: DVec3::Y,
            fov_deg: None,
        };
        let e = Camera::look_at(&on_look, 8, 8).unwrap_err().to_string();
        assert!(e.contains("same point"), "{e}");
        let parallel = CameraSpec {
            up: DVec3::Y,
            look: DVec3::new(0.0, 9.0, 0.0),
            eye: DVec3::ZERO,
            fov_deg: None,
        };
        let e = Camera::look_at(&parallel, 8, 8).unwrap_err().to_string();
        assert!(e.contains("parallel"), "{e}");
        let far = CameraSpec {
            eye: DVec3::new(0.0, 0.0, 2e18),
            ..scene.camera
        };
        let camera = Camera::look_at(&far, 8, 8).unwrap();
        let views = Views::new(&scene, &Options::default()).unwrap();
        let e = views.render(&camera).unwrap_err().to_string();
        assert!(e.contains("v.sc:2"), "{e}");
    }
}
