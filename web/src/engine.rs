//! Which engine renders the page's frames: the per-eye path (`--accel auto`: tiles from two
//! primitives on, rebuilt for every camera) or the world engine (`--accel world`: the scene
//! prepared once, each view costing what it sees). Chosen from the scene and the image size
//! alone, never from how many frames have been or will be rendered, so that a frame is the
//! same bits whether it is the first or the thousandth (a view depends only on scene, camera,
//! size and precision).

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
/// Measured in the page's module (node, one thread, the render alone, medians; the same loaded
/// 2-core Intel Xeon, ratios within one run; docs/performance.md, "Browser"):
/// - Orbiting at the scene's own distance, the per-eye path costs less a pixel and the world
///   engine less a primitive. At 1280x720, per-eye against world: the bunny (3,674 triangles)
///   40 against 67 ms, the twice-subdivided teapot (15,872) 83 against 142, the armadillo
///   (52,000) 165 against 127, the 832k armadillo 1084 against 334. Orbit costs alone meet near
///   one primitive for 32 pixels.
/// - Close up (the eye at a tenth of the scene's distance, as the page's zoom allows), the world
///   engine boxes the polygons reaching behind the eye plane from their visible part: on the
///   command line (2 threads, 1280x720) the armadillo takes 0.08 s by it against 0.05 s by the
///   per-eye path (docs/performance.md, "`--accel world` against Embree").
///
/// So the world engine is chosen only where its orbit gain is large (3x at 0.9 primitives a
/// pixel, the 832k armadillo at 1280x720) and not where it is within the noise (1.1-1.3x at
/// 0.06, the armadillo): from one primitive for 4 pixels. The rule reads the primitive and pixel
/// counts alone, never the number of frames, so a frame's bits do not depend on the frames
/// before it.
pub const PIXELS_PER_WORLD: u64 = 4;

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
    fn the_choice_turns_at_one_primitive_for_4_pixels() {
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
