//! Geometric rules for scene statements and the tolerances they use.
//!
//! Each check returns a human-readable message; `parse.rs` wraps it with file, line and column.
//! Every shape tolerance is relative to the shape's own size, never absolute, so a scene scaled
//! by 1e-12 or 1e12 is accepted or rejected exactly as the original: before measuring, a
//! shape's vertices are translated to its first vertex and divided by their largest coordinate
//! difference, so all measures work on numbers of order 1.
//!
//! Separately, a shape whose own size does not fit f64 arithmetic (twice its area overflows to
//! infinity or underflows below the smallest normal f64, e.g. coordinates around 1e200 or
//! 1e-200) is rejected, so that no NaN or infinity reaches the renderer.

use super::{CameraSpec, Intrinsics, Lens};
use glam::DVec3;

/// A triangle (or a corner of a quad) is degenerate when `|AB x AC| <= DEGENERATE_TOL * L^2`,
/// `L` its longest edge. `|AB x AC| / L^2` is about the sine of the smallest angle (exactly it
/// for an isosceles sliver), so this rejects angles below ~1e-12 rad. Rounding the decimal
/// inputs to f64 leaves ~1e-16 relative error, so points that are collinear as written (e.g.
/// 0.1/0.2/0.3 steps) measure ~1e-16 and are rejected, while a thin but real triangle with a
/// 1e-9 rad angle measures 1e-9 and is accepted: four orders of margin on either side.
pub const DEGENERATE_TOL: f64 = 1e-12;

/// A quad is planar when the vertex off the plane of the other three (the plane of its
/// best-shaped corner triangle) lies within `PLANAR_TOL * D` of it, `D` the quad's diameter
/// (its longest edge or diagonal). Coordinates written with 9-10 significant digits put a
/// planar quad's vertices ~1e-9 of its size off the plane: accepted, three orders inside. A
/// vertex 1e-4 of the size off the plane is a real twist the renderer's two-triangle split
/// would show: rejected, two orders outside.
pub const PLANAR_TOL: f64 = 1e-6;

/// The camera's `up` may not be parallel to the view direction `look - eye`: the sine of the
/// angle between them, `|normalize(look - eye) x normalize(up)|`, must be at least this. Below
/// it the camera's sideways axis (their normalised cross product) is mostly rounding noise;
/// 1e-9 rad is far below any deliberate tilt.
pub const CAMERA_PARALLEL_TOL: f64 = 1e-9;

pub(super) const VERTEX_NAMES: [&str; 4] = ["A", "B", "C", "D"];

/// Is `x` (a squared length, or twice an area squared) usable in f64 arithmetic: finite and at
/// least the smallest normal f64?
fn in_f64_range(x: f64) -> bool {
    x.is_finite() && x >= f64::MIN_POSITIVE
}

/// The vertices translated to the first one and divided by their largest coordinate
/// difference `s` (returned too), or `None` when a difference overflows f64.
fn normalized<const N: usize>(v: &[DVec3; N]) -> Option<([DVec3; N], f64)> {
    for i in 0..N {
        for j in i + 1..N {
            if !(v[j] - v[i]).is_finite() {
                return None;
            }
        }
    }
    let rel = v.map(|p| p - v[0]);
    let s = rel
        .iter()
        .fold(0.0_f64, |m, r| m.max(r.abs().max_element()));
    Some((rel.map(|r| r / s), s))
}

/// The first pair of identical vertices, by name.
fn repeated(v: &[DVec3]) -> Option<(&'static str, &'static str)> {
    for i in 0..v.len() {
        for j in i + 1..v.len() {
            if v[i] == v[j] {
                return Some((VERTEX_NAMES[i], VERTEX_NAMES[j]));
            }
        }
    }
    None
}

/// A triangle with positive area: no repeated vertices, not collinear within
/// `DEGENERATE_TOL`, and a size that f64 arithmetic can handle.
pub fn triangle(v: &[DVec3; 3]) -> Result<(), String> {
    if let Some((a, b)) = repeated(v) {
        return Err(format!(
            "degenerate triangle: vertices {a} and {b} are the same point"
        ));
    }
    let Some((p, s)) = normalized(v) else {
        return Err("triangle too large: its coordinates overflow f64 arithmetic".into());
    };
    let longest_sq = [p[1], p[2], p[2] - p[1]]
        .iter()
        .fold(0.0_f64, |m, e| m.max(e.length_squared()));
    let area2 = p[1].cross(p[2]).length();
    if area2 <= DEGENERATE_TOL * longest_sq {
        return Err("degenerate triangle: its vertices are collinear (zero area)".into());
    }
    let raw = (v[1] - v[0]).cross(v[2] - v[0]).length_squared();
    if !in_f64_range(raw) {
        let what = if raw.is_finite() {
            "small: its area underflows"
        } else {
            "large: its area overflows"
        };
        return Err(format!("triangle too {what} f64 arithmetic (scale {s:e})"));
    }
    Ok(())
}

/// A planar convex quad, vertices in perimeter order: no repeated vertices, the fourth vertex
/// within `PLANAR_TOL` of the plane of the other three, and every corner turning the same way
/// around the quad's normal, none of them straight (three consecutive vertices collinear
/// within `DEGENERATE_TOL`).
pub fn quad(v: &[DVec3; 4]) -> Result<(), String> {
    if let Some((a, b)) = repeated(v) {
        return Err(format!(
            "degenerate quad: vertices {a} and {b} are the same point"
        ));
    }
    let Some((p, s)) = normalized(v) else {
        return Err("quad too large: its coordinates overflow f64 arithmetic".into());
    };
    let mut diam_sq = 0.0_f64;
    for i in 0..4 {
        for j in i + 1..4 {
            diam_sq = diam_sq.max((p[j] - p[i]).length_squared());
        }
    }
    // corner[i] = (P[i] - P[i-1]) x (P[i+1] - P[i]): twice the area of triangle (i-1, i, i+1),
    // pointing along the quad's normal where the perimeter turns left.
    let corner: [DVec3; 4] =
        std::array::from_fn(|i| (p[i] - p[(i + 3) % 4]).cross(p[(i + 1) % 4] - p[i]));
    let k = (0..4)
        .max_by(|&a, &b| {
            corner[a]
                .length_squared()
                .total_cmp(&corner[b].length_squared())
        })
        .unwrap_or(0);
    let n_len = corner[k].length();
    if n_len <= DEGENERATE_TOL * diam_sq {
        return Err("degenerate quad: its vertices are collinear (zero area)".into());
    }
    let normal = corner[k] / n_len;
    let diam = diam_sq.sqrt();
    let off = normal.dot(p[(k + 2) % 4] - p[k]).abs() / diam;
    if off > PLANAR_TOL {
        return Err(format!(
            "quad is not planar: vertex {} is {off:.1e} of the quad's size off the plane of \
             the other three (tolerance {PLANAR_TOL:e})",
            VERTEX_NAMES[(k + 2) % 4]
        ));
    }
    let turn = corner.map(|c| c.dot(normal));
    let flat_tol = DEGENERATE_TOL * diam_sq;
    if let Some(i) = (0..4).find(|&i| turn[i].abs() <= flat_tol) {
        let name = |j: usize| VERTEX_NAMES[j % 4];
        return Err(format!(
            "degenerate quad: vertices {}, {}, {} are collinear",
            name(i + 3),
            name(i),
            name(i + 1)
        ));
    }
    let reflex: Vec<usize> = (0..4).filter(|&i| turn[i] < 0.0).collect();
    match reflex.as_slice() {
        [] => {}
        [i] => {
            return Err(format!(
                "quad is not convex: the corner at vertex {} turns inwards",
                VERTEX_NAMES[*i]
            ));
        }
        _ => {
            return Err(
                "quad is not convex: its edges cross (a bow-tie); list the vertices \
                        in perimeter order"
                    .into(),
            );
        }
    }
    let raw = (corner[k] * s * s).length_squared();
    if !in_f64_range(raw) {
        let what = if raw.is_finite() {
            "small: its area underflows"
        } else {
            "large: its area overflows"
        };
        return Err(format!("quad too {what} f64 arithmetic (scale {s:e})"));
    }
    Ok(())
}

/// A sphere radius: positive, and with a square that f64 arithmetic can handle.
pub fn sphere_radius(r: f64) -> Result<(), String> {
    if r.is_nan() || r <= 0.0 {
        return Err(format!("sphere radius must be positive, got {r}"));
    }
    if !in_f64_range(r * r) {
        let what = if r > 1.0 { "large" } else { "small" };
        return Err(format!(
            "sphere radius {r:e} too {what}: its square is out of f64 range"
        ));
    }
    Ok(())
}

/// A field of view in degrees: strictly between 0 and 180.
pub fn fov(deg: f64) -> Result<(), String> {
    if deg > 0.0 && deg < 180.0 {
        Ok(())
    } else {
        Err(format!("field of view {deg} degrees is outside (0, 180)"))
    }
}

/// Pinhole intrinsics as a `camera ... K FX FY CX CY` line gives them: focal lengths positive
/// and finite, principal point finite. What depends on the image size (`limits::check_lens`)
/// is checked when the camera is made for one.
pub fn intrinsics(k: &Intrinsics) -> Result<(), String> {
    for (name, f) in [("fx", k.fx), ("fy", k.fy)] {
        if !(f > 0.0 && f.is_finite()) {
            return Err(format!(
                "focal length {name} = {f} pixels: it must be positive and finite"
            ));
        }
    }
    for (name, c) in [("cx", k.cx), ("cy", k.cy)] {
        if !c.is_finite() {
            return Err(format!("principal point {name} = {c}: it must be finite"));
        }
    }
    Ok(())
}

/// A camera: eye and look distinct, up non-zero and not parallel to the view direction (within
/// `CAMERA_PARALLEL_TOL`), the lens (if given) valid: a fov in (0, 180), or [`intrinsics`].
pub fn camera(c: &CameraSpec) -> Result<(), String> {
    let dir = c.look - c.eye;
    if dir == DVec3::ZERO {
        return Err("camera eye and look are the same point: there is no view direction".into());
    }
    if !dir.is_finite() || !in_f64_range(dir.length_squared()) {
        return Err(
            "camera eye and look are too far apart or too close together for f64 \
                    arithmetic"
                .into(),
        );
    }
    if c.up == DVec3::ZERO {
        return Err("camera up vector has zero length".into());
    }
    if !in_f64_range(c.up.length_squared()) {
        return Err("camera up vector is too long or too short for f64 arithmetic".into());
    }
    let sin = dir.normalize().cross(c.up.normalize()).length();
    // The second test asks the camera's own basis (one formula, in basis.rs) whether it can
    // be built; the tolerance makes the first one stricter.
    if sin < CAMERA_PARALLEL_TOL || crate::basis::basis(c.eye, c.look, c.up).is_none() {
        return Err("camera up vector is parallel to the view direction (look - eye)".into());
    }
    match c.lens {
        Some(Lens::Fov(deg)) => fov(deg)?,
        Some(Lens::Pinhole(k)) => intrinsics(&k)?,
        None => {}
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const SCALES: [f64; 5] = [1e-12, 1e-6, 1.0, 1e6, 1e12];

    fn d(x: f64, y: f64, z: f64) -> DVec3 {
        DVec3::new(x, y, z)
    }

    fn scaled<const N: usize>(v: [DVec3; N], s: f64) -> [DVec3; N] {
        v.map(|p| p * s)
    }

    /// Rounds each coordinate to 9 significant digits, like a scene file written with `{:.8e}`.
    fn rounded<const N: usize>(v: [DVec3; N]) -> [DVec3; N] {
        let r = |x: f64| format!("{x:.8e}").parse::<f64>().unwrap();
        v.map(|p| d(r(p.x), r(p.y), r(p.z)))
    }

    /// A convex quad in a tilted plane, its vertices not a parallelogram, and the plane normal.
    fn tilted_quad() -> ([DVec3; 4], DVec3) {
        let u = d(1.0, 0.3, -0.7).normalize();
        let w = u.cross(d(0.2, 1.0, 0.4)).normalize();
        let v = w.cross(u);
        let o = d(0.37, -1.2, 2.9);
        let q = [(0.0, 0.0), (2.0, 0.1), (1.7, 1.9), (0.2, 1.3)].map(|(x, y)| o + u * x + v * y);
        (q, w)
    }

    #[test]
    fn triangle_examples_at_every_scale() {
        for s in SCALES {
            let ok = |v: [DVec3; 3]| triangle(&scaled(v, s));
            assert!(
                ok([d(0., 0., 0.), d(1., 0., 0.), d(0., 1., 0.)]).is_ok(),
                "scale {s}"
            );
            // Thin but real: angles of ~2e-9 rad at A and B.
            assert!(
                ok([d(0., 0., 0.), d(1., 0., 0.), d(0.5, 1e-9, 0.)]).is_ok(),
                "scale {s}"
            );
            // A 1e-12 sized triangle, scaled again.
            assert!(
                ok([d(0., 0., 0.), d(1e-12, 0., 0.), d(0., 1e-12, 0.)]).is_ok(),
                "scale {s}"
            );
            let collinear = [d(0.1, 0.2, 0.3), d(0.2, 0.4, 0.6), d(0.3, 0.6, 0.9)];
            let e = ok(collinear).unwrap_err();
            assert!(e.contains("collinear"), "scale {s}: {e}");
            let e = ok([d(0., 0., 0.), d(0.1, 0.1, 0.1), d(0.3, 0.3, 0.3)]).unwrap_err();
            assert!(e.contains("collinear"), "{e}");
            let e = ok([d(1., 2., 3.), d(4., 5., 6.), d(1., 2., 3.)]).unwrap_err();
            assert!(e.contains("vertices A and C are the same"), "{e}");
        }
    }

    #[test]
    fn collinear_by_rounding_measures_far_below_the_tolerance() {
        let (a, b, c) = (d(0.1, 0.2, 0.3), d(0.2, 0.4, 0.6), d(0.3, 0.6, 0.9));
        let (ab, ac) = (b - a, c - a);
        let measure = ab.cross(ac).length() / ac.length_squared();
        assert!(
            measure > 0.0 && measure < DEGENERATE_TOL * 1e-3,
            "{measure}"
        );
    }

    #[test]
    fn triangle_out_of_f64_range() {
        let big = [d(0., 0., 0.), d(1e200, 0., 0.), d(0., 1e200, 0.)];
        assert!(triangle(&big).unwrap_err().contains("too large"));
        let far = [d(-1e308, 0., 0.), d(1e308, 0., 0.), d(0., 1., 0.)];
        assert!(triangle(&far).unwrap_err().contains("too large"));
        let tiny = [d(0., 0., 0.), d(1e-200, 0., 0.), d(0., 1e-200, 0.)];
        assert!(triangle(&tiny).unwrap_err().contains("too small"));
    }

    #[test]
    fn quad_examples_at_every_scale() {
        let (q, normal) = tilted_quad();
        let size = 2.0;
        for s in SCALES {
            let ok = |v: [DVec3; 4]| quad(&rounded(scaled(v, s)));
            assert!(ok(q).is_ok(), "scale {s}: {:?}", ok(q));
            let mut twisted = q;
            twisted[3] += normal * 1e-4 * size;
            assert!(ok(twisted).unwrap_err().contains("not planar"), "scale {s}");
            let mut twisted = q;
            twisted[1] -= normal * 1e-4 * size;
            assert!(ok(twisted).unwrap_err().contains("not planar"), "scale {s}");
            let square = [d(0., 0., 0.), d(1., 0., 0.), d(1., 1., 0.), d(0., 1., 0.)];
            assert!(ok(square).is_ok());
            let dart = [d(0., 0., 0.), d(1., 0.3, 0.), d(2., 0., 0.), d(1., 2., 0.)];
            assert!(
                ok(dart).unwrap_err().contains("vertex B turns inwards"),
                "{:?}",
                ok(dart)
            );
            let bow_tie = [d(0., 0., 0.), d(1., 0., 0.), d(0., 1., 0.), d(1., 1., 0.)];
            assert!(ok(bow_tie).unwrap_err().contains("bow-tie"));
            let straight = [d(0., 0., 0.), d(0.5, 0., 0.), d(1., 0., 0.), d(0., 1., 0.)];
            assert!(ok(straight).unwrap_err().contains("A, B, C are collinear"));
            let line = [d(0., 0., 0.), d(1., 0., 0.), d(2., 0., 0.), d(3., 0., 0.)];
            assert!(ok(line).unwrap_err().contains("zero area"));
            let repeated = [d(0., 0., 0.), d(1., 0., 0.), d(1., 0., 0.), d(0., 1., 0.)];
            assert!(ok(repeated).unwrap_err().contains("B and C are the same"));
        }
    }

    #[test]
    fn thin_quad_twist_is_measured_against_its_size() {
        // A 1 x 0.001 strip with one corner 1e-4 off the plane: a volume-based measure would
        // see only 1e-7, this one sees the distance itself.
        let strip = [
            d(0., 0., 0.),
            d(1., 0., 0.),
            d(1., 1e-3, 1e-4),
            d(0., 1e-3, 0.),
        ];
        assert!(quad(&strip).unwrap_err().contains("not planar"));
        let flat = [
            d(0., 0., 0.),
            d(1., 0., 0.),
            d(1., 1e-3, 0.),
            d(0., 1e-3, 0.),
        ];
        assert!(quad(&flat).is_ok());
    }

    #[test]
    fn quad_out_of_f64_range() {
        let big = [
            d(0., 0., 0.),
            d(1e200, 0., 0.),
            d(1e200, 1e200, 0.),
            d(0., 1e200, 0.),
        ];
        assert!(quad(&big).unwrap_err().contains("too large"));
    }

    #[test]
    fn sphere_radius_rules() {
        assert!(sphere_radius(1.0).is_ok());
        assert!(sphere_radius(1e-12).is_ok());
        assert!(sphere_radius(1e12).is_ok());
        for r in [0.0, -0.0, -1.0, f64::NAN] {
            assert!(
                sphere_radius(r)
                    .unwrap_err()
                    .contains("radius must be positive"),
                "{r}"
            );
        }
        assert!(sphere_radius(1e200).unwrap_err().contains("too large"));
        assert!(sphere_radius(1e-200).unwrap_err().contains("too small"));
    }

    #[test]
    fn fov_rules() {
        for ok in [1e-3, 1.0, 60.0, 179.999] {
            assert!(fov(ok).is_ok(), "{ok}");
        }
        for bad in [0.0, -1.0, 180.0, 360.0, f64::NAN, f64::INFINITY] {
            assert!(fov(bad).unwrap_err().contains("outside (0, 180)"), "{bad}");
        }
    }

    #[test]
    fn camera_rules() {
        let cam = |eye: DVec3, look: DVec3, up: DVec3, fov_deg: Option<f64>| CameraSpec {
            eye,
            look,
            up,
            lens: fov_deg.map(Lens::Fov),
        };
        let (z, y) = (d(0., 0., 0.), d(0., 1., 0.));
        assert!(camera(&cam(d(0., 0., 5.), z, y, None)).is_ok());
        assert!(camera(&cam(d(0., 0., 5.), z, d(0., 1., 1.), Some(90.0))).is_ok());
        let e = camera(&cam(d(1., 2., 3.), d(1., 2., 3.), y, None)).unwrap_err();
        assert!(e.contains("same point"), "{e}");
        for up in [d(0., 0., -2.), d(0., 0., 1e-3), d(1e-12, 0., 1.)] {
            let e = camera(&cam(d(0., 0., 5.), z, up, None)).unwrap_err();
            assert!(e.contains("parallel"), "{up}: {e}");
        }
        assert!(camera(&cam(d(0., 0., 5.), z, d(1e-6, 0., 1.), None)).is_ok());
        let e = camera(&cam(d(0., 0., 5.), z, z, None)).unwrap_err();
        assert!(e.contains("zero length"), "{e}");
        let e = camera(&cam(d(0., 0., 5.), z, y, Some(180.0))).unwrap_err();
        assert!(e.contains("field of view"), "{e}");
        let e = camera(&cam(d(-1e200, 0., 0.), d(1e200, 0., 0.), y, None)).unwrap_err();
        assert!(e.contains("f64"), "{e}");
    }
}
