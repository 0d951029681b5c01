//! The camera's orthonormal frame: the first line of the camera formula (`camera.rs`), on its
//! own below both the scene, whose validation asks whether a camera line has a frame, and the
//! camera, which builds its rays on it.
//!
//! ```text
//! f = normalize(look - eye); r = normalize(cross(f, up)); u = cross(r, f)
//! ```
//! In f64 (glam's `DVec3`). `u` is a unit vector to within a few units of 2^-53, since `r` and
//! `f` are unit vectors at right angles.

use glam::DVec3;

/// The orthonormal camera frame (forward, right, up), or `None` when `look == eye` or `up` is
/// parallel to the view direction (the cross product has no usable length).
pub fn basis(eye: DVec3, look: DVec3, up: DVec3) -> Option<[DVec3; 3]> {
    let f = (look - eye).try_normalize()?;
    let r = f.cross(up).try_normalize()?;
    let u = r.cross(f);
    Some([f, r, u])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn basis_is_right_handed_and_orthonormal() {
        let [f, r, u] = basis(
            DVec3::new(1.0, 2.0, 3.0),
            DVec3::new(-4.0, 0.5, 2.0),
            DVec3::Y,
        )
        .unwrap();
        for v in [f, r, u] {
            assert!((v.length() - 1.0).abs() < 1e-15);
        }
        assert!(f.dot(r).abs() < 1e-15 && f.dot(u).abs() < 1e-15 && r.dot(u).abs() < 1e-15);
        assert!(
            (r.cross(u) - (-f)).length() < 1e-15,
            "r x u = -f: camera looks down -z of (r,u)"
        );
    }

    #[test]
    fn degenerate_bases_are_refused() {
        assert!(basis(DVec3::ONE, DVec3::ONE, DVec3::Y).is_none());
        assert!(basis(DVec3::ZERO, DVec3::Y, DVec3::Y).is_none());
    }
}
