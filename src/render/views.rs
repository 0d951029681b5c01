//! Many views of one scene: [`Views`] holds a loaded scene and the render options, and renders
//! any number of cameras (a turntable, a camera path, a dataset of poses) one after another,
//! each view written into the buffers of the view before (its frame, its stores' columns, its
//! tiles' lists), so that after the first view most of a view's memory is already in use.
//!
//! Every view is rendered exactly as a one-camera [`Renderer`] for the same camera and options
//! renders it: ids and depths are bit-identical to `lanecast -i SCENE` with that camera, at any
//! thread count (tests/views_cli/). What depends on the camera (the eye-relative primitive
//! constants, the tiles' bins) is built per view; what does not (the scene, its validation, the
//! range check's cluster bounds) is done once. A view leaves out the clusters of triangles it
//! proves it cannot see (`render::cull`).

use super::cull::{self, Plan};
use super::renderer::Spare;
use super::{Frame, Options, Renderer};
use crate::accel::Accel;
use crate::camera::Camera;
use crate::error::Result;
use crate::scene::Scene;
use crate::scene::range_clusters::RangeClusters;
use crate::soa::IdSet;
use std::sync::{Mutex, OnceLock};

/// A scene prepared for rendering from many cameras. Borrows the scene: `--precision auto`
/// re-decides hits from its shapes. Between views it keeps the last view's buffers (its frame,
/// stores, tiles' lists and working buffers, `auto`'s per-primitive arrays), emptied, for the
/// next view to fill: about as much memory as one view's setup uses, held until the `Views`
/// is dropped (docs/performance.md, "Many views", gives the figures).
pub struct Views<'s> {
    scene: &'s Scene,
    options: Options,
    /// The f32 range check's cluster bounds (`scene::range_clusters`), built by the first view
    /// whose eye is not the scene's or that culls (`render::cull`).
    range: OnceLock<RangeClusters>,
    /// The buffers the next view fills: the last frame handed back ([`Views::recycle`]) and
    /// those of the last renderer handed back ([`Views::give_back`]).
    spare: Mutex<Spare>,
    /// What the culling keeps between views: the ids the last view showed and its eye, the
    /// side of faces it guesses hidden (`cull::Facing`), the frame of the last second render,
    /// and spare id sets.
    cull: Mutex<CullState>,
    /// `--accel world`: the scene prepared once, by the first view.
    world: OnceLock<std::sync::Arc<crate::world::World>>,
}

#[derive(Default)]
struct CullState {
    /// The ids the last view showed, and its eye.
    last: Option<(IdSet, glam::DVec3)>,
    facing: cull::Facing,
    touch: Option<Frame<f32>>,
    sets: [IdSet; 2],
}

/// One view rendered by [`Views::render_marking`]: its frame, the pixels whose f32 hit was
/// decided again in f64, and what it took.
#[derive(Debug)]
pub struct Rendered {
    /// The view's ids and depths.
    pub frame: Frame<f32>,
    /// The pixels `--precision auto` decided again in f64 (row-major indices, ascending).
    pub redecided: Vec<usize>,
    /// Seconds of setup (stores, tiles; the culling's plan and checks) and of render (0 in a
    /// browser, which has no clock).
    pub setup_s: f64,
    /// Seconds of rendering (and merging a second render in, where one was needed).
    pub render_s: f64,
    /// The acceleration used.
    pub accel: Accel,
    /// Whether f32 hits that cannot be trusted were decided again in f64.
    pub redecides: bool,
    /// Primitives the view left out (clusters off screen, and clusters proven hidden).
    pub left_out: usize,
    /// Renders the view took: 1; 2 when clusters left out on trial were not hidden and were
    /// rendered in a second frame merged in; 3 when a third render gave the few re-decided
    /// pixels neither frame holds (`render::cull`, step 4).
    pub renders: usize,
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
            cull: Mutex::new(CullState::default()),
            world: OnceLock::new(),
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
        Ok(self.render_marking(camera)?.frame)
    }

    /// [`Views::render`] without the range check (call [`Views::check`] first), also giving
    /// the pixels re-decided in f64 and what the view took. With the tiles and the packet
    /// kernel's default method, the view leaves out the clusters of triangles it proves it
    /// cannot see (`render::cull`); the ids and depths are a render of every primitive's, bit
    /// for bit. Views render one at a time: each reads what the one before showed.
    pub fn render_marking(&self, camera: &Camera) -> Result<Rendered> {
        if self.options.accel == Accel::World {
            let clock = cull::Clock::start();
            let renderer = self.renderer(camera)?;
            let setup_s = clock.secs();
            let clock = cull::Clock::start();
            let (frame, redecided) = renderer.render_marking(None);
            let done = Rendered {
                frame,
                redecided,
                setup_s,
                render_s: clock.secs(),
                accel: Accel::World,
                redecides: renderer.redecides(),
                left_out: 0,
                renders: 1,
            };
            self.give_back(renderer);
            return Ok(done);
        }
        let mut guard = self.cull.lock().unwrap_or_else(|e| e.into_inner());
        let state = &mut *guard;
        let culls = cull::applies(&self.options, self.scene);
        // each view shows what the next may leave out; the first guesses from the faces alone
        // (the plan counts in the view's setup, as do the clusters' bounds when this view
        // builds them)
        let clock = cull::Clock::start();
        let plan = culls.then(|| {
            let clusters = self.range.get_or_init(|| RangeClusters::new(self.scene));
            let set = std::mem::take(&mut state.sets[0]);
            let last = state.last.as_ref().map(|(s, eye)| (s, *eye));
            Plan::new(clusters, camera, (last, state.facing), set)
        });
        let spare = self.take_spare();
        let left_out = plan.as_ref().map(|p| &p.left_out);
        let planned = clock.secs();
        let (renderer, frame, redone, [setup, render]) =
            cull::render_without(self.scene, camera, &self.options, spare, left_out)?;
        let mut done = Rendered {
            frame,
            redecided: redone,
            setup_s: planned + setup,
            render_s: render,
            accel: renderer.accel(),
            redecides: renderer.redecides(),
            left_out: plan.as_ref().map_or(0, |p| p.left_out.len()),
            renders: 1,
        };
        self.give_back(renderer);
        if let Some(plan) = plan {
            done = self.settle(state, camera, plan, done)?;
        }
        if culls {
            let clock = cull::Clock::start();
            let spare = state.last.take().map(|(s, _)| s).unwrap_or_default();
            let n = self.scene.shapes.len();
            state.last = Some((cull::shown(&done.frame, n, spare), camera.eye));
            done.setup_s += clock.secs();
        }
        Ok(done)
    }

    /// Steps 3 and 4 of `render::cull`: the clusters on trial checked against the view's
    /// frame, those that fail rendered in a second frame and merged in, and the pixels that
    /// neither frame holds (re-decided ones) rendered alone with every cluster that may be
    /// hit there.
    fn settle(
        &self,
        state: &mut CullState,
        camera: &Camera,
        plan: Plan,
        mut done: Rendered,
    ) -> Result<Rendered> {
        let clusters = self.range.get().expect("built by the plan");
        let clock = cull::Clock::start();
        let failed = if plan.on_trial() {
            plan.failed(&done.frame, &done.redecided, camera)
        } else {
            Vec::new()
        };
        state.facing = state.facing.after(plan.side_failures(&failed));
        done.setup_s += clock.secs();
        if !failed.is_empty() {
            let f_redone = std::mem::take(&mut done.redecided);
            let width = camera.width as usize;
            let clock = cull::Clock::start();
            let spare = std::mem::take(&mut state.sets[1]);
            let second = plan.second(clusters, &failed, (&f_redone, width), spare);
            done.setup_s += clock.secs();
            let (g, g_redone) = self.touch_up(state, camera, &second.left_out, &mut done)?;
            done.renders = 2;
            let clock = cull::Clock::start();
            let (mut known, mut h_redone) = (Vec::new(), Vec::new());
            let merge = |frame: &mut Frame<f32>, known: &[cull::Pixel]| {
                cull::merge(frame, &f_redone, (&g, &g_redone), &second, &failed, known)
            };
            let mut merged = merge(&mut done.frame, &known);
            done.render_s += clock.secs();
            if let Err(unsettled) = &merged {
                // the pixels neither frame holds: rendered with every cluster that may be hit there
                let set = plan.only_at(clusters, (unsettled, width), IdSet::default());
                let (h, redone) = self.touch_up(state, camera, &set, &mut done)?;
                h_redone = redone;
                done.renders = 3;
                known.extend(unsettled.iter().map(|&p| (p, (h.ids[p], h.depth[p]))));
                state.touch = Some(h);
                merged = merge(&mut done.frame, &known);
            }
            done.redecided =
                cull::merged_redone(&f_redone, [&g_redone, &h_redone], &second, &known);
            state.touch = Some(g);
            state.sets[1] = second.left_out;
            // (the second merge takes every unsettled pixel from `known`: it cannot fail)
            merged.expect("every unsettled pixel has its value");
            let back: usize = (failed.iter())
                .map(|&(k, ..)| clusters.cluster(k as usize).len())
                .sum();
            done.left_out -= back;
        }
        state.sets[0] = plan.left_out;
        Ok(done)
    }

    /// Renders `camera` without the primitives of `left_out` (a second or third render, into
    /// the frame kept for those), adding its times to `done`: the frame and its re-decided
    /// pixels.
    fn touch_up(
        &self,
        state: &mut CullState,
        camera: &Camera,
        left_out: &IdSet,
        done: &mut Rendered,
    ) -> Result<(Frame<f32>, Vec<usize>)> {
        let touch = Spare {
            frame: state.touch.take(),
            ..Spare::default()
        };
        let (renderer, frame, redone, [s, r]) =
            cull::render_without(self.scene, camera, &self.options, touch, Some(left_out))?;
        drop(renderer);
        done.setup_s += s;
        done.render_s += r;
        Ok((frame, redone))
    }

    /// The prepared one-camera renderer for `camera` (the per-view setup), for a caller that
    /// wants its counters or progress ([`Renderer::render_marking`]); hand it back with
    /// [`Views::give_back`] once done. The eye's range is not checked here: call
    /// [`Views::check`] first.
    pub fn renderer(&self, camera: &Camera) -> Result<Renderer<'s>> {
        if self.options.accel == Accel::World {
            let world = self
                .world
                .get_or_init(|| std::sync::Arc::new(crate::world::World::new(self.scene)));
            return Ok(Renderer::of_world(
                world.clone(),
                camera,
                &self.options,
                self.take_spare(),
            ));
        }
        Renderer::with_spare(self.scene, camera, &self.options, self.take_spare(), None)
    }

    /// The buffers the next view fills, kept for the view after.
    fn take_spare(&self) -> Spare {
        Spare {
            keep: true,
            ..std::mem::take(&mut *self.spare())
        }
    }

    /// Hands a renderer back once its frame is rendered: the next view's stores and tiles are
    /// written into its buffers rather than fresh memory.
    pub fn give_back(&self, renderer: Renderer<'s>) {
        let mut left = renderer.into_spare();
        // a view that left primitives out holds only what it used: the next view's columns
        // grow where they need to, without copying (the memory is not held between views)
        left.scene.packed.shrink_to_fit();
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
        for precision in [crate::Precision::Auto, crate::Precision::F32] {
            let options = Options {
                precision,
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
                lens: Some(crate::scene::Lens::Fov(20.0 + 10.0 * k as f64)),
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
            lens: None,
        };
        let e = Camera::look_at(&on_look, 8, 8).unwrap_err().to_string();
        assert!(e.contains("same point"), "{e}");
        let parallel = CameraSpec {
            up: DVec3::Y,
            look: DVec3::new(0.0, 9.0, 0.0),
            eye: DVec3::ZERO,
            lens: None,
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
