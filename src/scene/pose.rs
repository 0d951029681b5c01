//! A camera's pose as rigs and datasets give it: a 4x4 world-to-camera matrix `[R t; 0 0 0 1]`,
//! row-major, in OpenCV's axes (x right, y down, z forward): a world point `X` is at
//! `R X + t` in the camera's frame. Its eye, look and up (the scene format's pose):
//! ```text
//! eye = -R^T t;  look = eye + R[2] (row z: forward);  up = -R[1] (row y points down)
//! ```
//! `camera::Camera` then builds its frame from these (forward `R[2]`, right
//! `normalize(R[2] x -R[1])`, up their cross product), so a matrix within [`RIGID_TOL`] of a
//! rotation gives that frame; `R[0]` is checked, not used. `Camera::world_to_camera` is the
//! inverse map.

use super::CameraSpec;
use glam::DVec3;

/// How far a world-to-camera matrix's 3x3 block may be from a rotation: every entry of
/// `R R^T - I` within this (absolute). Matrices written with 5 or 6 significant digits (as
/// datasets ship them) are rotations to about 1e-5; a matrix that scales by 1e-4 or shears
/// by 1e-4 rad is refused.
pub const RIGID_TOL: f64 = 1e-4;

/// The pose of a world-to-camera matrix `m` (module comment), or why it is not a rigid
/// transform: a non-finite entry, a last row other than exactly `0 0 0 1`, a 3x3 block that
/// is not orthonormal within [`RIGID_TOL`], or a reflection (determinant below 0).
pub fn from_world_to_camera(m: &[[f64; 4]; 4]) -> Result<CameraSpec, String> {
    if !m.iter().flatten().all(|x| x.is_finite()) {
        return Err("the world-to-camera matrix must be finite".into());
    }
    if m[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(format!(
            "the world-to-camera matrix's last row must be 0 0 0 1, got {} {} {} {}",
            m[3][0], m[3][1], m[3][2], m[3][3]
        ));
    }
    let row = |i: usize| DVec3::new(m[i][0], m[i][1], m[i][2]);
    let (x, y, z) = (row(0), row(1), row(2));
    let off = [
        x.dot(x) - 1.0,
        y.dot(y) - 1.0,
        z.dot(z) - 1.0,
        x.dot(y),
        y.dot(z),
        x.dot(z),
    ];
    let worst = off.iter().fold(0.0f64, |a, o| a.max(o.abs()));
    let rigid = worst <= RIGID_TOL;
    if !rigid {
        return Err(format!(
            "the world-to-camera matrix is not a rigid transform: its 3x3 rotation is off \
             orthonormal by {worst:.3e} (entries of R R^T - I; the tolerance is {RIGID_TOL:e})"
        ));
    }
    if x.cross(y).dot(z) <= 0.0 {
        return Err(
            "the world-to-camera matrix's 3x3 rotation has determinant -1 (a reflection); \
             OpenCV's axes are right-handed: x right, y down, z forward"
                .into(),
        );
    }
    let t = DVec3::new(m[0][3], m[1][3], m[2][3]);
    let eye = -(x * t.x + y * t.y + z * t.z);
    let look = eye + z;
    // the view direction is `look - eye`: where the eye is so far from the origin that f64
    // cannot hold `eye + z` apart from it, the translation is what is wrong
    let lost = ((look - eye) - z).abs().max_element();
    if lost.is_nan() || lost > RIGID_TOL {
        return Err(format!(
            "the world-to-camera matrix's translation ({:?} {:?} {:?}) puts the eye {:.3e} from the \
             origin: too far for f64 to hold its view direction (R's row z) within {RIGID_TOL:e} \
             (it is off by {lost:.1e}); bring the world's origin nearer the cameras",
            t.x,
            t.y,
            t.z,
            eye.length()
        ));
    }
    Ok(CameraSpec {
        eye,
        look,
        up: -y,
        lens: None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;

    /// A translation too large for the view direction to survive `eye + z` is named as such,
    /// not as an eye on its look point.
    #[test]
    fn a_translation_too_far_is_named() {
        let m = |t: f64| {
            [
                [1.0, 0.0, 0.0, 0.0],
                [0.0, -1.0, 0.0, 0.0],
                [0.0, 0.0, -1.0, t],
                [0.0, 0.0, 0.0, 1.0],
            ]
        };
        let e = from_world_to_camera(&m(1e17)).unwrap_err();
        assert!(e.contains("translation (0.0 0.0 1e17)"), "{e}");
        assert!(e.contains("puts the eye 1.000e17 from the origin"), "{e}");
        assert!(!e.contains("same point"), "{e}");
        let spec = from_world_to_camera(&m(1e6)).unwrap();
        assert_eq!(spec.look - spec.eye, DVec3::new(0.0, 0.0, -1.0));
    }

    /// A random rotation's matrix (rows x, y, z) and translation give back the eye, forward and
    /// down it was built from; `camera::Camera::world_to_camera` of that pose is the matrix.
    #[test]
    fn a_rotation_and_translation_give_their_pose_back() {
        let mut rng = Rng(5);
        for _ in 0..500 {
            let (z, up) = (rng.direction(), rng.direction());
            let Some(x) = z.cross(-up).try_normalize() else {
                continue;
            };
            let y = z.cross(x);
            let eye = rng.point(1e3);
            let t = -DVec3::new(x.dot(eye), y.dot(eye), z.dot(eye));
            let m = [
                [x.x, x.y, x.z, t.x],
                [y.x, y.y, y.z, t.y],
                [z.x, z.y, z.z, t.z],
                [0.0, 0.0, 0.0, 1.0],
            ];
            let spec = from_world_to_camera(&m).unwrap();
            assert!((spec.eye - eye).length() < 1e-12 * 1e3);
            let cam = crate::Camera::look_at(&spec, 64, 48).unwrap();
            let back = cam.world_to_camera();
            for i in 0..4 {
                for j in 0..4 {
                    let tol = if j == 3 { 1e-9 } else { 1e-12 };
                    assert!(
                        (back[i][j] - m[i][j]).abs() < tol,
                        "{i},{j}: {back:?} {m:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn matrices_that_are_not_rigid_are_refused() {
        let id = [
            [1.0, 0.0, 0.0, 0.0],
            [0.0, 1.0, 0.0, 0.0],
            [0.0, 0.0, 1.0, 0.0],
            [0.0, 0.0, 0.0, 1.0],
        ];
        assert_eq!(from_world_to_camera(&id).unwrap().eye, DVec3::ZERO);
        let with = |i: usize, j: usize, v: f64| {
            let mut m = id;
            m[i][j] = v;
            from_world_to_camera(&m)
        };
        // an entry 1 + d puts 2d (and d^2) into R R^T - I
        assert!(with(0, 0, 1.0 + 0.4 * RIGID_TOL).is_ok());
        assert!(with(0, 0, 1.0 + 0.6 * RIGID_TOL).is_err());
        for (i, j, v, says) in [
            (0, 0, 1.0 + 3.0 * RIGID_TOL, "not a rigid transform"),
            (1, 0, 0.01, "not a rigid transform"),
            (2, 2, 2.0, "not a rigid transform"),
            (0, 0, -1.0, "determinant -1"),
            (3, 0, 0.5, "last row must be 0 0 0 1"),
            (3, 3, 2.0, "last row must be 0 0 0 1"),
            (1, 3, f64::NAN, "finite"),
        ] {
            let e = with(i, j, v).unwrap_err();
            assert!(e.contains(says), "{i},{j} = {v}: {e}");
        }
    }
}
