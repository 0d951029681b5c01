//! The f32 range check: whether the f32 kernels can represent every primitive of a scene seen
//! from an eye (within `limits::MAX_EYE_DISTANCE`, spheres above `limits::MIN_RADIUS`, every
//! polygon edge subtending `limits::MIN_EDGE_ANGLE`, the eye not so near a polygon's plane that
//! the distance underflows f32), the first offender named by its line. Run on every scene
//! loaded and, relative to each view's eye, on every view (`range_clusters.rs` settles most of
//! a view's primitives a cluster at a time).

use super::validate::VERTEX_NAMES;
use super::{Scene, Shape};
use crate::error::Error;
use crate::limits::{MAX_EYE_DISTANCE, MIN_EDGE_ANGLE, MIN_RADIUS};
use glam::DVec3;
use std::path::Path;

/// Scene-level check that the f32 kernels can represent every primitive seen from this eye.
///
/// The kernels compute eye-relative constants in f64 and round them to f32 (`soa`, `kernel`),
/// so a scene is fine at any absolute position (coordinates of 3e38 with the eye nearby
/// render), but each primitive must lie within `limits::MAX_EYE_DISTANCE` of the eye, a sphere
/// radius must be at least `limits::MIN_RADIUS`, and the eye may not be so close to a polygon's
/// plane (but off it) that the distance underflows f32, and every polygon edge must subtend at
/// least `limits::MIN_EDGE_ANGLE` from the eye. The first offending primitive is named
/// by its line. Polygons with an area that underflows f32 are fine: their edge planes are
/// normalised in f64 before rounding.
pub fn f32_range(scene: &Scene) -> Result<(), Error> {
    f32_range_from(scene, scene.camera.eye)
}

/// [`f32_range`] for a camera at `eye` rather than the scene's own (a view of the scene).
pub fn f32_range_from(scene: &Scene, eye: DVec3) -> Result<(), Error> {
    outcome(scene, first_offender(scene, eye))
}

/// [`f32_range`] of a scene parsed from `text` in memory (the browser's scenes, Rust callers'
/// strings): an error's column comes from that text, not from reading the file again.
pub(crate) fn f32_range_text(scene: &Scene, text: &[u8]) -> Result<(), Error> {
    outcome_in(scene, first_offender(scene, scene.camera.eye), Some(text))
}

/// The first primitive [`shape_f32`] refuses seen from `eye`, and why.
fn first_offender(scene: &Scene, eye: DVec3) -> Option<(usize, String)> {
    // Checked on all threads; `find_first` keeps "the first offending primitive" exact.
    use crate::par::prelude::*;
    scene
        .shapes
        .par_chunks(0..scene.shapes.len(), 1 << 12)
        .find_map_first(|(at, shapes)| {
            (shapes.enumerate())
                .find_map(|(j, shape)| shape_f32(&shape, eye).err().map(|m| (at + j, m)))
        })
}

/// The check's outcome when `first` is the first offending primitive and its message, if any:
/// the error names it by its line (or, in a mesh rendered alone, by its face number).
pub(crate) fn outcome(scene: &Scene, first: Option<(usize, String)>) -> Result<(), Error> {
    outcome_in(scene, first, None)
}

/// [`outcome`], the columns read from `text` (the scene's bytes) when given.
fn outcome_in(
    scene: &Scene,
    first: Option<(usize, String)>,
    text: Option<&[u8]>,
) -> Result<(), Error> {
    match first {
        // line 0: a mesh rendered alone, whose shapes are its faces
        Some((i, msg)) if scene.shapes.line(i) == 0 => Err(Error::InputFile {
            file: scene.source.clone(),
            msg: format!("face {}: {msg}", i + 1),
        }),
        Some((i, msg)) => {
            let line = scene.shapes.line(i);
            // a radius too small is the radius's fault (its column, as the parser names a
            // radius of 0); a primitive too far, the statement's
            let token = match scene.shapes.get(i) {
                Shape::Sphere { radius, .. } if radius < MIN_RADIUS => 4,
                _ => 0,
            };
            let col = token_col(&scene.source, text, line, token);
            Err(Error::input(&scene.source, line, col, msg))
        }
        None => Ok(()),
    }
}

/// The column of token `token` (0: the first) on `line` of the scene file `source`, where
/// an error about a primitive points: as the parser does, a number's own column, or the first
/// token's for the primitive as a whole (`statement::Ctx::whole`). The scene keeps lines, not
/// columns, so the line is read again: an error's cost only. 0 (no column) where the file
/// cannot be read again (standard input).
fn token_col(source: &Path, text: Option<&[u8]>, line: usize, token: usize) -> usize {
    let read;
    let bytes: &[u8] = match text {
        Some(t) => t,
        None if source == Path::new(super::STDIN_NAME) => return 0,
        None => match std::fs::read(source) {
            Ok(b) => {
                read = b;
                &read
            }
            Err(_) => return 0,
        },
    };
    let body = bytes.strip_prefix("\u{feff}".as_bytes()).unwrap_or(bytes);
    let Some(r) = super::chunks::lines(body).nth(line.saturating_sub(1)) else {
        return 0;
    };
    let text = String::from_utf8_lossy(&body[r]);
    let content = text.find('#').map_or(&*text, |k| &text[..k]);
    let mut toks = Vec::new();
    super::statement::tokenize(content, &mut toks);
    toks.get(token)
        .or(toks.first())
        .map_or(0, |t| text[..t.off].chars().count() + 1)
}

/// `|v|` without the overflow of squaring: scaled by its largest component first, so that a
/// vector of 1e300 has length 1e300, not infinity (for messages; the rules use `length`).
fn distance(v: DVec3) -> f64 {
    let m = v.abs().max_element();
    if m == 0.0 || !m.is_finite() {
        return m;
    }
    (v / m).length() * m
}

/// A distance for a message, `1.000e300`: finite and true, or "more than" f64's largest
/// number where even the scaled length overflows (points at opposite ends of f64's range).
fn distance_text(d: f64) -> String {
    if d.is_finite() {
        format!("{d:.3e}")
    } else {
        format!("more than {:.3e}", f64::MAX)
    }
}

/// [`f32_range`]'s rules for one shape.
pub(crate) fn shape_f32(shape: &Shape, eye: DVec3) -> Result<(), String> {
    // NaN (never expected: inputs are finite) counts as too far.
    let far = |d: f64| d.is_nan() || d > MAX_EYE_DISTANCE;
    match shape {
        Shape::Sphere { center, radius } => {
            if *radius < MIN_RADIUS {
                return Err(format!(
                    "sphere radius {radius:e} is below the smallest supported radius \
                     {MIN_RADIUS:e} (its square underflows f32)"
                ));
            }
            let d = (*center - eye).length() + radius;
            if far(d) {
                return Err(format!(
                    "sphere reaches {} from the camera eye; the limit is \
                     {MAX_EYE_DISTANCE:e} (f32 arithmetic would overflow)",
                    distance_text(distance(*center - eye) + radius)
                ));
            }
            Ok(())
        }
        Shape::Triangle(v) => polygon_f32(v, eye, "triangle"),
        Shape::Quad(v) => polygon_f32(v, eye, "quad"),
    }
}

fn polygon_f32<const N: usize>(v: &[DVec3; N], eye: DVec3, kw: &str) -> Result<(), String> {
    let rel = v.map(|p| p - eye);
    if surely_in_range(v, &rel) {
        return Ok(());
    }
    polygon_f32_exact(v, &rel, kw)
}

/// A cheap test that accepts only polygons [`polygon_f32_exact`] accepts: no square root or
/// division, each of its three rules checked with a margin far larger than the rounding of
/// either computation. It runs on every polygon for every eye (the load, and each view of a
/// many-view run), so most polygons skip the exact test's ten square roots; anything it
/// cannot settle goes to the exact test, so the outcome (and the first polygon named) is the
/// exact test's alone.
///
/// With `u = 2^-53`, `|x|_1 >= |x|` the 1-norm, `r_k` the eye-relative vertices and `c` the
/// plane's normal `(B - A) x (C - A)` as the exact test computes it:
/// - distance: `|r_k|^2 <= (MAX_EYE_DISTANCE / 2)^2`, so `|r_k|`, rounded, is within the limit.
/// - plane: the exact test's `p = |sum r_k . c/|c|| / N`. A dot product errs by at most
///   `3u |r|_1 |c|_1` (normalising `c` first adds `2u |r| |c|` per term), so if
///   `|sum r_k . c| >= 2 MIN_POSITIVE_F32 N |c|_1 + 16u |c|_1 sum |r_k|_1`, then the exact `p`
///   is at least `MIN_POSITIVE_F32` and, above all, not 0: the exact test goes on to the edges
///   and passes the plane rule.
/// - edges: the exact sine is `|a/|a| x b/|b||`; its rounding, and that of `|a x b|` below, are
///   at most `8u |a| |b|` absolute in `|a x b|` (each component of a cross product errs by
///   `2u` times its terms' size; normalising adds `3u`). So `|a x b|^2 >= (2 MIN_EDGE_ANGLE +
///   16u)^2 |a|^2 |b|^2` leaves the exact sine above `MIN_EDGE_ANGLE`.
///
/// Where a quantity under- or overflows, or is NaN, a comparison fails (the strict `> 0`
/// guards reject zeros), and the exact test decides. Tested against the exact test over random
/// polygons and eyes at every scale the limits allow, the near-plane and near-collinear cases
/// included (`the_quick_range_test_accepts_only_what_the_exact_one_does`).
#[inline]
fn surely_in_range<const N: usize>(v: &[DVec3; N], rel: &[DVec3; N]) -> bool {
    use crate::real::U64 as U;
    const FAR2: f64 = (MAX_EYE_DISTANCE / 2.0) * (MAX_EYE_DISTANCE / 2.0);
    const SIN: f64 = 2.0 * MIN_EDGE_ANGLE + 16.0 * U;
    let one = |x: DVec3| x.x.abs() + x.y.abs() + x.z.abs();
    let c = (v[1] - v[0]).cross(v[2] - v[0]);
    let c1 = one(c);
    let mut dots = 0.0;
    let mut size = 0.0;
    let mut len2 = [0.0; N];
    for k in 0..N {
        len2[k] = rel[k].length_squared();
        if !(len2[k] > 0.0 && len2[k] <= FAR2) {
            return false;
        }
        dots += rel[k].dot(c);
        size += one(rel[k]);
    }
    let plane = 2.0 * f64::from(f32::MIN_POSITIVE) * N as f64 * c1 + 16.0 * U * c1 * size;
    if !(c1 > 0.0 && dots.abs() >= plane && plane > 0.0) {
        return false;
    }
    (0..N).all(|i| {
        let j = (i + 1) % N;
        let cross2 = rel[i].cross(rel[j]).length_squared();
        let bound = SIN * SIN * len2[i] * len2[j];
        cross2 > 0.0 && bound > 0.0 && cross2 >= bound
    })
}

/// The exact rules of [`polygon_f32`], in the order they are reported.
fn polygon_f32_exact<const N: usize>(
    v: &[DVec3; N],
    rel: &[DVec3; N],
    kw: &str,
) -> Result<(), String> {
    for (k, r) in rel.iter().enumerate() {
        let d = r.length();
        if d.is_nan() || d > MAX_EYE_DISTANCE {
            return Err(format!(
                "{kw} vertex {} is {} from the camera eye; the limit is \
                 {MAX_EYE_DISTANCE:e} (f32 arithmetic would overflow)",
                VERTEX_NAMES[k],
                distance_text(distance(*r))
            ));
        }
    }
    // Distance from the eye to the plane, as the kernels measure it (normal from f64 vertices).
    let normal = (v[1] - v[0]).cross(v[2] - v[0]).normalize_or_zero();
    let p = rel.iter().map(|r| r.dot(normal)).sum::<f64>().abs() / N as f64;
    if p == 0.0 {
        // Seen exactly edge-on: the kernels never draw it.
        return Ok(());
    }
    for i in 0..N {
        let (a, b) = (
            rel[i].normalize_or_zero(),
            rel[(i + 1) % N].normalize_or_zero(),
        );
        let sin = a.cross(b).length();
        if sin.is_nan() || sin < MIN_EDGE_ANGLE {
            return Err(format!(
                "{kw} edge {}-{} subtends {sin:.1e} rad seen from the camera eye: too small at \
                 this distance to resolve (at least {MIN_EDGE_ANGLE:e} rad); move the eye \
                 closer or drop the {kw}",
                VERTEX_NAMES[i],
                VERTEX_NAMES[(i + 1) % N]
            ));
        }
    }
    if p < f64::from(f32::MIN_POSITIVE) {
        return Err(format!(
            "the camera eye is {p:.3e} from the plane of this {kw}: off the plane but too close \
             to it for f32 arithmetic (move the eye into the plane or away from it)"
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A primitive too far away is refused with its true distance, never "inf", even where
    /// squaring the distance overflows f64.
    #[test]
    fn far_primitives_are_named_with_a_finite_distance() {
        let eye = DVec3::new(0.0, 0.0, 5.0);
        let sphere = Shape::Sphere {
            center: DVec3::new(1e300, 0.0, 0.0),
            radius: 1.0,
        };
        let e = shape_f32(&sphere, eye).unwrap_err();
        assert!(
            e.starts_with("sphere reaches 1.000e300 from the camera eye"),
            "{e}"
        );
        let far = DVec3::new(0.0, 3e200, 0.0);
        let tri = Shape::Triangle([far, far + DVec3::X * 1e199, far + DVec3::Z * 1e199]);
        let e = shape_f32(&tri, eye).unwrap_err();
        assert!(e.starts_with("triangle vertex A is 3.000e200 from"), "{e}");
        let ends = Shape::Sphere {
            center: DVec3::splat(-f64::MAX),
            radius: 1.0,
        };
        let e = shape_f32(&ends, DVec3::splat(f64::MAX)).unwrap_err();
        assert!(e.contains("reaches more than 1.798e308"), "{e}");
    }

    /// `surely_in_range` accepts only what the exact rules accept, over random triangles and
    /// quads and eyes at scales 1e-15 to 1e15, with eyes pushed near the polygon's plane (down
    /// to 1e-40 of its size) and near the line of an edge (where the edge subtends less than
    /// MIN_EDGE_ANGLE), and far away (near MAX_EYE_DISTANCE). It must also accept most
    /// ordinary polygons, or it would save nothing.
    #[test]
    fn the_quick_range_test_accepts_only_what_the_exact_one_does() {
        let mut rng = crate::test_rng::Rng(0x9E37_79B9_7F4A_7C15);
        let mut unit = move || rng.unit();
        let (mut quick, mut ordinary, mut refused) = (0, 0, 0);
        for case in 0..48_000 {
            // case 5: the scales where the rounding of a plane distance, u |r|, is about the
            // smallest f32 (1e-38), with the eye in the plane: the plane rule's margin decides
            let scale = match case % 6 {
                5 => 10f64.powf(unit() * 4.0 - 24.0),
                _ => 10f64.powf(unit() * 30.0 - 15.0),
            };
            let centre = DVec3::new(unit(), unit(), unit()) * 10f64.powf(unit() * 10.0) * scale;
            let mut p = || centre + (DVec3::new(unit(), unit(), unit()) * 2.0 - 1.0) * scale;
            let tri = [p(), p(), p()];
            let (a, b, c) = (tri[0], tri[1], tri[2]);
            let quad = [a, b, b + (c - a) * 0.5 + (c - b) * 0.5, a + (c - b)];
            let normal = (b - a).cross(c - a).normalize_or_zero();
            let eye = match case % 6 {
                // anywhere, from near to far
                0 => centre + DVec3::new(unit(), unit(), unit()) * scale * 10f64.powf(unit() * 8.0),
                // near the plane
                1 => a + (b - a) * unit() * 3.0 + normal * scale * 10f64.powf(-40.0 * unit()),
                // near the line of an edge, off the plane
                2 => {
                    let off = scale * 10f64.powf(-20.0 * unit());
                    a + (b - a) * (1.5 + unit() * 1e6) + normal * off
                }
                // far away
                3 => {
                    centre
                        + DVec3::new(unit(), 1.0, unit()) * MAX_EYE_DISTANCE * (0.4 + unit() * 0.2)
                }
                // in the plane, up to rounding
                5 => a + (b - a) * (unit() * 4.0 - 2.0) + (c - a) * (unit() * 4.0 - 2.0),
                // ordinary: a few sizes away, well off the plane
                _ => centre + (normal * 3.0 + DVec3::new(unit(), unit(), unit())) * scale,
            };
            let rel = tri.map(|v| v - eye);
            let exact = polygon_f32_exact(&tri, &rel, "triangle");
            if surely_in_range(&tri, &rel) {
                quick += 1;
                assert!(
                    exact.is_ok(),
                    "case {case}: {tri:?} from {eye:?}: {exact:?}"
                );
            }
            if case % 6 == 4 {
                ordinary += 1;
            }
            refused += exact.is_err() as usize;
            let rel = quad.map(|v| v - eye);
            if surely_in_range(&quad, &rel) {
                let exact = polygon_f32_exact(&quad, &rel, "quad");
                assert!(
                    exact.is_ok(),
                    "case {case}: {quad:?} from {eye:?}: {exact:?}"
                );
            }
        }
        // the exact rules refused some (the near-plane and near-line eyes), and the quick test
        // settled at least the ordinary cases
        assert!(refused > 1_000, "{refused}");
        assert!(quick >= ordinary, "{quick} of {ordinary}");
    }
}
