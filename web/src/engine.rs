//! Which engine renders the page's frames: the per-eye path (`--accel auto`: tiles from two
//! primitives on, rebuilt for every camera) or the world engine (`--accel world`: the scene
//! prepared once, each view costing what it sees). Chosen from the scene and the image size
//! alone, never from how many frames have been or will be rendered, so that a frame is the
//! same bits whether it is the first or the thousandth (issue contract: a view depends only on
//! scene, camera, size and precision).

use lanecast::Scene;

/// An engine the page renders with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Engine {
    /// The per-eye path: the command line's default (`--accel auto`).
    Tiles,
    /// The world engine: `--accel world`.
    World,
}

impl Engine {
    /// The `--accel` value that gives this engine's bits on the command line.
    pub fn accel(self) -> &'static str {
        match self {
            Engine::Tiles => "auto",
            Engine::World => "world",
        }
    }
}

/// The world engine renders a frame with at least one primitive for every `PIXELS_PER_WORLD`
/// pixels; fewer primitives go the per-eye path.
///
/// Measured in the page's module (node, one thread, web/bench.mjs's orbit, render alone):
/// the per-eye path costs less a pixel, the world engine less a primitive. At 1280x720 the
/// per-eye path renders the bunny (3,674 triangles) in 0.6x the world engine's time and a
/// twice-subdivided teapot (15,872) in 0.6x, the world engine the armadillo (52,000) in 0.87x
/// and the 832k armadillo in 0.27x; at 640x360 the world engine already wins on the
/// armadillo. The two costs meet near one primitive for 32 pixels (about 29k primitives at
/// 1280x720, 7k at 640x360). docs/performance.md ("Browser") has the page's figures.
pub const PIXELS_PER_WORLD: u64 = 32;

/// The engine for `scene` at `width` x `height`: from the scene's primitive count and the
/// pixel count alone.
pub fn choose(scene: &Scene, width: u32, height: u32) -> Engine {
    let pixels = u64::from(width) * u64::from(height);
    if scene.shapes.len() as u64 * PIXELS_PER_WORLD >= pixels {
        Engine::World
    } else {
        Engine::Tiles
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scene(n: usize) -> Scene {
        let mut text = String::from("camera eye 0 0 10 look 0 0 0 up 0 1 0\n");
        for k in 0..n {
            text += &format!("sphere {} 0 0 0.1\n", k as f64 * 0.01);
        }
        lanecast::parse_scene(&text, std::path::Path::new("n.sc")).unwrap()
    }

    /// The choice turns at one primitive for `PIXELS_PER_WORLD` pixels, at any size, and
    /// depends on nothing else.
    #[test]
    fn the_choice_turns_at_one_primitive_for_32_pixels() {
        for (w, h) in [(64u32, 32u32), (97, 61), (320, 10)] {
            let at = (u64::from(w) * u64::from(h)).div_ceil(PIXELS_PER_WORLD) as usize;
            assert_eq!(choose(&scene(at), w, h), Engine::World, "{w}x{h}, {at}");
            assert_eq!(
                choose(&scene(at - 1), w, h),
                Engine::Tiles,
                "{w}x{h}, {}",
                at - 1
            );
        }
        assert_eq!(choose(&scene(1), 1, 1), Engine::World);
        assert_eq!(choose(&scene(1), 1280, 720), Engine::Tiles);
    }
}
