//! Colour from per-pixel hit buffers: a base colour per primitive, dimmed with distance.
//!
//! Inputs are the renderer's buffers, row 0 at the top: `ids` (primitive id per pixel, -1 for
//! background) and `depth` (hit distance `t`, `+inf` for background). The output is RGB, three
//! bytes per pixel. Background pixels are black (0, 0, 0).
//!
//! Base colour, by [`ColorMode`]:
//! - `random` (default): a vivid colour per primitive id, hashed from the id and the seed
//!   (splitmix64), so it is the same on every run and changes with `--seed`.
//! - `ordered`: [`PALETTE`] (violet, blue, green, yellow, orange, red), cycling after six,
//!   given to primitives in order of first appearance scanning rows from the top-left pixel.
//! - `shade`: [`SHADE_GREY`] for every primitive, lit by a headlight (below).
//!
//! Brightness, by [`Variation`], with `tmin` and `tmax` the smallest and largest finite hit
//! distance in the image and `B_MIN = 0.2`:
//! - `linear`: `b = 1 - (1 - B_MIN) * (t - tmin) / (tmax - tmin)`
//! - `log`:    `b = 1 - (1 - B_MIN) * ln(t / tmin) / ln(tmax / tmin)`
//!
//! with `b = 1` when `tmax == tmin` (and, for `log`, when `tmin <= 0`). Each channel is
//! `round(colour * b)`, so the nearest hit shows its full colour and the farthest `B_MIN` of it.
//!
//! `shade` multiplies `b` by a headlight, a light at the eye: `l = L_MIN + (1 - L_MIN) |n . d|`,
//! with `n` the hit's unit normal and `d` its unit ray (`Frame::headlight` gives `|n . d|`, f64
//! rounded to f32: the light is exact to a part in 1e7, far below the 1/255 of a byte) and
//! `L_MIN` = [`L_MIN`], so that a surface seen edge-on stays visible against the black
//! background. Grey rather than each primitive's `random` colour: rendered both ways, the
//! armadillo's 52,000 triangles tinted read as confetti that hides the shading, grey shows its
//! shape; on the seed scenes' few spheres and polygons the shading alone tells one surface from
//! the next. README's mesh pictures use it; `-cm random` keeps a colour per primitive.

use std::collections::HashMap;

use crate::Frame;
use crate::camera::Camera;
use crate::par::prelude::*;
use crate::scene::Scene;

/// The `ordered` palette, in assignment order: violet, blue, green, yellow, orange, red.
pub const PALETTE: [[u8; 3]; 6] = [
    [148, 0, 211], // violet
    [0, 0, 255],   // blue
    [0, 200, 0],   // green
    [255, 255, 0], // yellow
    [255, 140, 0], // orange
    [255, 0, 0],   // red
];

/// Brightness of the farthest hit, as a fraction of its colour, so it stays visible.
pub const B_MIN: f64 = 0.2;

/// The colour of every primitive in `shade` mode, before the headlight and the dimming.
pub const SHADE_GREY: [u8; 3] = [235, 235, 235];

/// The headlight of a surface seen edge-on in `shade` mode (`|n . d| = 0`), as a fraction of
/// face-on.
pub const L_MIN: f64 = 0.15;

/// How each primitive gets its base colour.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ColorMode {
    /// `random`: a vivid colour hashed from the id and the seed (the default).
    Random,
    /// `ordered`: [`PALETTE`] in order of first appearance, scanning from the top-left pixel.
    Ordered,
    /// `shade`: [`SHADE_GREY`] lit by a headlight at the eye, `|n . d|` (module comment): the
    /// shape of a surface rather than its primitives. Needs each pixel's `|n . d|`
    /// ([`Frame::headlight`](crate::Frame::headlight)).
    Shade,
}

impl ColorMode {
    /// Every mode, in the order the command line lists them.
    pub const ALL: [ColorMode; 3] = [ColorMode::Random, ColorMode::Ordered, ColorMode::Shade];

    /// The mode named `s` on the command line (`random`, `ordered`, `shade`), or `None`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "random" => Some(ColorMode::Random),
            "ordered" => Some(ColorMode::Ordered),
            "shade" => Some(ColorMode::Shade),
            _ => None,
        }
    }

    /// The command-line name of the mode, as [`ColorMode::parse`] accepts it.
    pub fn name(&self) -> &'static str {
        match self {
            ColorMode::Random => "random",
            ColorMode::Ordered => "ordered",
            ColorMode::Shade => "shade",
        }
    }

    /// Whether the mode lights surfaces by their normals, so that [`shade`] needs each pixel's
    /// `|n . d|`.
    pub fn needs_light(&self) -> bool {
        *self == ColorMode::Shade
    }
}

/// How brightness falls off with hit distance.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Variation {
    /// `linear`: brightness falls linearly from 1 at `tmin` to [`B_MIN`] at `tmax`.
    Linear,
    /// `log`: brightness falls with ln(t / tmin), from 1 at `tmin` to [`B_MIN`] at `tmax`.
    Log,
}

impl Variation {
    /// The variation named `s` on the command line (`linear`, `log`), or `None`.
    pub fn parse(s: &str) -> Option<Self> {
        match s {
            "linear" => Some(Variation::Linear),
            "log" => Some(Variation::Log),
            _ => None,
        }
    }

    /// The command-line name of the variation, as [`Variation::parse`] accepts it.
    pub fn name(&self) -> &'static str {
        match self {
            Variation::Linear => "linear",
            Variation::Log => "log",
        }
    }
}

/// Shades a `width`-wide image from its hit buffers; returns `3 * ids.len()` RGB bytes
/// ([`Frame::rgb`](crate::Frame::rgb) shades a frame). `light` is each pixel's `|n . d|`
/// ([`Frame::headlight`](crate::Frame::headlight)), which `shade` mode needs and the palette
/// modes ignore.
///
/// Panics if `ids` and `depth` (or a `light` given) differ in length, if `ids.len()` is not a
/// multiple of `width`, or if `mode` is `shade` and `light` is `None` (programming errors: the
/// renderer allocates the buffers together, and the callers compute the light for the mode).
pub fn shade(
    ids: &[i32],
    depth: &[f32],
    light: Option<&[f32]>,
    width: u32,
    mode: ColorMode,
    variation: Variation,
    seed: u64,
) -> Vec<u8> {
    assert_eq!(
        ids.len(),
        depth.len(),
        "id and depth buffers differ in length"
    );
    let light = match (mode, light) {
        (ColorMode::Shade, None) => panic!("shade mode needs each pixel's |n . d|"),
        (ColorMode::Shade, Some(l)) => {
            assert_eq!(l.len(), ids.len(), "id and light buffers differ in length");
            Some(l)
        }
        _ => None,
    };
    let width = width as usize;
    let mut rgb = vec![0u8; ids.len() * 3];
    if ids.is_empty() {
        return rgb;
    }
    assert!(
        width > 0 && ids.len().is_multiple_of(width),
        "buffer length is not a whole number of rows"
    );

    let bright = Brightness::new(ids, depth, variation);
    // Ordered colours depend on scan position, so they are fixed here, sequentially, before
    // any parallel work; the per-pixel pass below only looks them up.
    let ordered = match mode {
        ColorMode::Ordered => Some(first_appearance(ids)),
        ColorMode::Random | ColorMode::Shade => None,
    };
    let base = |id: i32| match (&ordered, mode) {
        (Some(order), _) => PALETTE[order[&id] as usize % PALETTE.len()],
        (None, ColorMode::Shade) => SHADE_GREY,
        (None, _) => random_color(id, seed),
    };

    rgb.par_chunks_mut(width * 3)
        .zip(ids.par_chunks(width))
        .zip(depth.par_chunks(width))
        .enumerate()
        .for_each(|(row, ((out, ids), depth))| {
            let lights = light.map(|l| &l[row * width..(row + 1) * width]);
            // Neighbouring pixels mostly share a primitive: look its colour up once per run.
            let mut last: Option<(i32, [u8; 3])> = None;
            for (x, ((px, &id), &t)) in out.chunks_exact_mut(3).zip(ids).zip(depth).enumerate() {
                if id < 0 {
                    continue; // background stays black
                }
                let colour = match last {
                    Some((lid, c)) if lid == id => c,
                    _ => {
                        let c = base(id);
                        last = Some((id, c));
                        c
                    }
                };
                let mut b = bright.at(t);
                if let Some(l) = lights {
                    b *= headlight(l[x]);
                }
                for (o, &c) in px.iter_mut().zip(&colour) {
                    *o = (f64::from(c) * b).round() as u8;
                }
            }
        });
    rgb
}

/// The headlight factor `L_MIN + (1 - L_MIN) |n . d|` in `[L_MIN, 1]`, for `cos = |n . d|`
/// (clamped to `[0, 1]`; a NaN, which no hit gives, lights as edge-on).
fn headlight(cos: f32) -> f64 {
    let cos = if cos.is_nan() {
        0.0
    } else {
        f64::from(cos).clamp(0.0, 1.0)
    };
    L_MIN + (1.0 - L_MIN) * cos
}

/// Maps each visible primitive id to its rank of first appearance in reading order.
fn first_appearance(ids: &[i32]) -> HashMap<i32, u32> {
    let mut order = HashMap::new();
    let mut last = -1;
    for &id in ids {
        // Skip runs of the same id so the hash map is touched once per run, not per pixel.
        if id >= 0 && id != last {
            let next = order.len() as u32;
            order.entry(id).or_insert(next);
        }
        last = id;
    }
    order
}

/// Depth range of the image and the fall-off to apply within it.
struct Brightness {
    tmin: f64,
    tmax: f64,
    variation: Variation,
}

impl Brightness {
    fn new(ids: &[i32], depth: &[f32], variation: Variation) -> Self {
        // min and max are exact, so the parallel reduction gives the same range on any thread
        // count.
        let (tmin, tmax) = ids
            .par_iter()
            .zip(depth.par_iter())
            .filter(|(id, t)| **id >= 0 && t.is_finite())
            .map(|(_, &t)| (t, t))
            .reduce(
                || (f32::INFINITY, f32::NEG_INFINITY),
                |a, b| (a.0.min(b.0), a.1.max(b.1)),
            );
        Brightness {
            tmin: f64::from(tmin),
            tmax: f64::from(tmax),
            variation,
        }
    }

    /// Brightness factor in `[B_MIN, 1]` for a hit at distance `t`.
    fn at(&self, t: f32) -> f64 {
        let (tmin, tmax) = (self.tmin, self.tmax);
        // Also covers "no finite hit at all" (tmin = +inf, tmax = -inf).
        if tmin >= tmax {
            return 1.0;
        }
        if !t.is_finite() {
            return B_MIN; // a hit without a usable distance: treat it as the farthest
        }
        let t = f64::from(t);
        let frac = match self.variation {
            Variation::Linear => (t - tmin) / (tmax - tmin),
            Variation::Log if tmin <= 0.0 => return 1.0,
            Variation::Log => (t / tmin).ln() / (tmax / tmin).ln(),
        };
        (1.0 - (1.0 - B_MIN) * frac).clamp(B_MIN, 1.0)
    }
}

/// splitmix64 finaliser: a well-mixed 64-bit hash of `x`.
fn splitmix64(x: u64) -> u64 {
    let mut z = x.wrapping_add(0x9E37_79B9_7F4A_7C15);
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// A vivid colour for primitive `id`: saturation in [0.6, 1], value in [0.8, 1], so the
/// brightest channel is at least 204 and no colour is near black (or grey). The hue walks the
/// golden-ratio sequence from a seeded start, `frac(start + id * 0.618...)`, so consecutive ids
/// (neighbouring faces of one object, usually) are always far apart in hue; an independent
/// hash per id put ids 1..3 of seed 0 within 6 degrees of each other.
fn random_color(id: i32, seed: u64) -> [u8; 3] {
    const GOLDEN: f64 = 0.618_033_988_749_894_9;
    let h = splitmix64(seed ^ (id as u32 as u64).wrapping_mul(0xD1B5_4A32_D192_ED03));
    let unit = |bits: u64| (bits & 0xFFFF) as f64 / 65535.0;
    let start = unit(splitmix64(seed));
    let hue = (start + id as f64 * GOLDEN).fract() * 6.0;
    let sat = 0.6 + 0.4 * unit(h >> 16);
    let val = 0.8 + 0.2 * unit(h >> 32);
    hsv_to_rgb(hue, sat, val)
}

/// HSV to 8-bit RGB, with `hue` in [0, 6] (sextants) and `sat`, `val` in [0, 1].
fn hsv_to_rgb(hue: f64, sat: f64, val: f64) -> [u8; 3] {
    let sextant = hue.floor();
    let f = hue - sextant;
    let p = val * (1.0 - sat);
    let q = val * (1.0 - sat * f);
    let r = val * (1.0 - sat * (1.0 - f));
    let (r, g, b) = match sextant as u32 % 6 {
        0 => (val, r, p),
        1 => (q, val, p),
        2 => (p, val, r),
        3 => (p, q, val),
        4 => (r, p, val),
        _ => (val, p, q),
    };
    let byte = |c: f64| (c * 255.0).round() as u8;
    [byte(r), byte(g), byte(b)]
}

impl Frame<f32> {
    /// The frame shaded to RGB, three bytes per pixel, row 0 at the top ([`shade()`]: a colour per
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
}

#[cfg(test)]
mod tests {
    use super::*;

    fn px(rgb: &[u8], i: usize) -> [u8; 3] {
        [rgb[3 * i], rgb[3 * i + 1], rgb[3 * i + 2]]
    }

    fn scaled(c: [u8; 3], b: f64) -> [u8; 3] {
        c.map(|v| (f64::from(v) * b).round() as u8)
    }

    #[test]
    fn names_round_trip() {
        for m in ColorMode::ALL {
            assert_eq!(ColorMode::parse(m.name()), Some(m));
        }
        for v in [Variation::Linear, Variation::Log] {
            assert_eq!(Variation::parse(v.name()), Some(v));
        }
        assert_eq!(ColorMode::parse("Random"), None);
        assert_eq!(Variation::parse("exp"), None);
    }

    #[test]
    fn palette_order_and_cycling() {
        // Seven primitives in reading order, all at the same depth (full brightness).
        let ids = [0, 1, 2, 3, 4, 5, 6];
        let depth = [1.0f32; 7];
        let rgb = shade(
            &ids,
            &depth,
            None,
            7,
            ColorMode::Ordered,
            Variation::Linear,
            0,
        );
        for i in 0..7 {
            assert_eq!(px(&rgb, i), PALETTE[i % 6], "pixel {i}");
        }
        assert_eq!(px(&rgb, 6), [148, 0, 211]); // the 7th is violet again
    }

    #[test]
    fn first_appearance_is_by_scan_position_not_id() {
        // 3x2 image: top row 42, -1, 7; bottom row 7, 3, 42. First seen: 42, 7, 3.
        let ids = [42, -1, 7, 7, 3, 42];
        let depth = [2.0, f32::INFINITY, 2.0, 2.0, 2.0, 2.0];
        let rgb = shade(
            &ids,
            &depth,
            None,
            3,
            ColorMode::Ordered,
            Variation::Linear,
            0,
        );
        assert_eq!(px(&rgb, 0), PALETTE[0]);
        assert_eq!(px(&rgb, 2), PALETTE[1]);
        assert_eq!(px(&rgb, 3), PALETTE[1]);
        assert_eq!(px(&rgb, 4), PALETTE[2]);
        assert_eq!(px(&rgb, 5), PALETTE[0]);
    }

    #[test]
    fn background_is_black() {
        let ids = [-1, 5, -1, -1];
        let depth = [f32::INFINITY, 3.0, f32::INFINITY, f32::INFINITY];
        for mode in [ColorMode::Random, ColorMode::Ordered] {
            let rgb = shade(&ids, &depth, None, 2, mode, Variation::Log, 9);
            for i in [0, 2, 3] {
                assert_eq!(px(&rgb, i), [0, 0, 0]);
            }
            assert_ne!(px(&rgb, 1), [0, 0, 0]);
        }
        let rgb = shade(
            &[-1; 4],
            &[f32::INFINITY; 4],
            None,
            2,
            ColorMode::Random,
            Variation::Linear,
            0,
        );
        assert!(rgb.iter().all(|&v| v == 0));
    }

    #[test]
    fn brightness_endpoints() {
        // One primitive seen at three distances: nearest full colour, farthest B_MIN of it.
        let ids = [0, 0, 0, -1];
        let depth = [1.0, 4.0, 10.0, f32::INFINITY];
        for variation in [Variation::Linear, Variation::Log] {
            let rgb = shade(&ids, &depth, None, 2, ColorMode::Ordered, variation, 0);
            assert_eq!(px(&rgb, 0), PALETTE[0]);
            assert_eq!(px(&rgb, 2), scaled(PALETTE[0], B_MIN));
            let mid = px(&rgb, 1);
            assert!(mid[0] < PALETTE[0][0] && mid[0] > scaled(PALETTE[0], B_MIN)[0]);
        }
        // Middle values follow the documented formulas.
        let lin = shade(
            &ids,
            &depth,
            None,
            2,
            ColorMode::Ordered,
            Variation::Linear,
            0,
        );
        assert_eq!(px(&lin, 1), scaled(PALETTE[0], 1.0 - 0.8 * 3.0 / 9.0));
        let log = shade(&ids, &depth, None, 2, ColorMode::Ordered, Variation::Log, 0);
        assert_eq!(
            px(&log, 1),
            scaled(PALETTE[0], 1.0 - 0.8 * 4f64.ln() / 10f64.ln())
        );
        // A single depth: everything at full brightness.
        let flat = shade(
            &[1, 2],
            &[5.0, 5.0],
            None,
            2,
            ColorMode::Ordered,
            Variation::Log,
            0,
        );
        assert_eq!(px(&flat, 1), PALETTE[1]);
    }

    #[test]
    fn random_is_deterministic_and_seed_sensitive() {
        let ids: Vec<i32> = (0..64).collect();
        let depth = vec![1.0f32; 64];
        let a = shade(
            &ids,
            &depth,
            None,
            8,
            ColorMode::Random,
            Variation::Linear,
            1,
        );
        let b = shade(
            &ids,
            &depth,
            None,
            8,
            ColorMode::Random,
            Variation::Linear,
            1,
        );
        let c = shade(
            &ids,
            &depth,
            None,
            8,
            ColorMode::Random,
            Variation::Linear,
            2,
        );
        assert_eq!(a, b);
        let differing = (0..64).filter(|&i| px(&a, i) != px(&c, i)).count();
        assert!(
            differing > 60,
            "only {differing} of 64 colours changed with the seed"
        );
        // A pixel's colour depends on its id only, not on its neighbours.
        let one = shade(
            &[17],
            &[1.0],
            None,
            1,
            ColorMode::Random,
            Variation::Linear,
            1,
        );
        assert_eq!(px(&one, 0), px(&a, 17));
    }

    /// `shade`: grey times the headlight `L_MIN + (1 - L_MIN) |n . d|` times the dimming, for
    /// random lights and depths; background black; the palette modes ignore a light given.
    #[test]
    fn shade_is_grey_times_the_headlight_times_the_dimming() {
        let mut rng = crate::test_rng::Rng(0x5AADE);
        for case in 0..200 {
            let n = 1 + rng.below(40) as usize;
            let ids: Vec<i32> = (0..n).map(|_| rng.below(5) as i32 - 1).collect();
            let depth: Vec<f32> = ids
                .iter()
                .map(|&id| {
                    if id < 0 {
                        f32::INFINITY
                    } else {
                        1.0 + 99.0 * rng.unit() as f32
                    }
                })
                .collect();
            let light: Vec<f32> = (0..n).map(|_| rng.unit() as f32).collect();
            for variation in [Variation::Linear, Variation::Log] {
                let rgb = shade(
                    &ids,
                    &depth,
                    Some(&light),
                    n as u32,
                    ColorMode::Shade,
                    variation,
                    7,
                );
                let bright = Brightness::new(&ids, &depth, variation);
                for i in 0..n {
                    let want = if ids[i] < 0 {
                        [0; 3]
                    } else {
                        let b = bright.at(depth[i]) * (L_MIN + (1.0 - L_MIN) * f64::from(light[i]));
                        scaled(SHADE_GREY, b)
                    };
                    assert_eq!(px(&rgb, i), want, "case {case} pixel {i}");
                }
                for mode in [ColorMode::Random, ColorMode::Ordered] {
                    assert_eq!(
                        shade(&ids, &depth, Some(&light), n as u32, mode, variation, 7),
                        shade(&ids, &depth, None, n as u32, mode, variation, 7),
                        "case {case}: {mode:?} ignores the light"
                    );
                }
            }
        }
        // face-on at the nearest distance: full grey; edge-on: L_MIN of it
        let rgb = shade(
            &[0, 0],
            &[2.0, 2.0],
            Some(&[1.0, 0.0]),
            2,
            ColorMode::Shade,
            Variation::Linear,
            0,
        );
        assert_eq!(px(&rgb, 0), SHADE_GREY);
        assert_eq!(px(&rgb, 1), scaled(SHADE_GREY, L_MIN));
    }

    #[test]
    #[should_panic(expected = "shade mode needs each pixel's |n . d|")]
    fn shade_without_the_light_is_a_programming_error() {
        shade(
            &[0],
            &[1.0],
            None,
            1,
            ColorMode::Shade,
            Variation::Linear,
            0,
        );
    }

    #[test]
    fn random_colours_are_never_near_black() {
        for id in 0..10_000 {
            let c = random_color(id, 0x5EED);
            assert!(c.iter().copied().max().unwrap() >= 200, "id {id}: {c:?}");
        }
    }
}
