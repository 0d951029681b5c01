//! The f32 setup's written bounds (`setup.rs`) held to exact f64 geometry over random polygons
//! and eyes: sizes from 1e-3 to 1e3, up to 1e4 from the origin, eyes from 1 to 1e4 times the
//! size away, any orientation, grazing views included. For every tight polygon, at random
//! rays through it and near its edges: the f32 distance is within `e_t` of the exact one, and
//! every edge test agrees with the exact side wherever the ray is farther than `e_edge` from
//! the edge's plane. (Measured: dividing both bounds by 30 fails at once.)

use super::setup::{self, Basis, Class};
use crate::kernel::Triangle;
use crate::real::U32;
use crate::test_rng::Rng;
use glam::DVec3;

fn f32v(v: DVec3) -> [f32; 3] {
    [v.x as f32, v.y as f32, v.z as f32]
}

#[test]
fn tight_polygons_keep_their_written_bounds() {
    let mut rng = Rng(0x5eed_1234_abcd_0001);
    let (mut tight, mut checked_t, mut checked_e) = (0, 0, 0);
    for case in 0..20_000 {
        let size = rng.log(-3.0, 3.0);
        let centre = rng.point(1e4);
        let v = [0, 1, 2].map(|_| centre + rng.point(size));
        let eye = centre + rng.direction() * size * rng.log(0.0, 4.0);
        // an orthonormal basis looking at the polygon, rounded to f32 as a view's is
        let f = (centre - eye).normalize();
        let r = f.cross(rng.direction()).normalize();
        let u = r.cross(f);
        let basis = Basis {
            f: f32v(f),
            r: f32v(r),
            u: f32v(u),
            lmax: 2f64.sqrt(),
        };
        let a = v.map(|p| f32v(p - eye));
        let g = setup::shape::<Triangle, 3>(&v);
        let k = setup::polygon::<Triangle, 3>(a, g, &basis);
        if k.class != Class::Tight {
            continue;
        }
        tight += 1;
        let e_t = (1.0 - k.lower as f64) / 2.0;
        let e_edge = k.eps as f64 / basis.lmax;
        let nrm = (v[1] - v[0]).cross(v[2] - v[0]).normalize();
        for _ in 0..8 {
            // a point of the polygon's plane near it, and the ray to it in screen terms
            let (b1, b2) = (rng.range(-0.2, 1.2), rng.range(-0.2, 1.2));
            let target = v[0] + (v[1] - v[0]) * b1 + (v[2] - v[0]) * b2 * (1.0 - b1.min(1.0));
            let d = (target - eye).normalize();
            let z = d.dot(f);
            if z <= 0.3 {
                continue;
            }
            let (sx, sy) = ((d.dot(r) / z) as f32, (d.dot(u) / z) as f32);
            if sx.abs() > 1.0 || sy.abs() > 1.0 {
                continue;
            }
            // the exact ray of these (rounded) screen coordinates, in the f64 basis
            let dv = f + r * sx as f64 + u * sy as f64;
            let d = dv.normalize();
            let len = dv.length();
            // each edge: the exact signed sine of the ray's angle to the edge plane (inside >= 0)
            let mut inside_exact = true;
            for i in 0..3 {
                let (p, q) = (v[i] - eye, v[(i + 1) % 3] - eye);
                let n = p.cross(q).normalize();
                let n = if n.dot(v[(i + 2) % 3] - eye) < 0.0 {
                    -n
                } else {
                    n
                };
                let exact = d.dot(n);
                let e = (k.e[i][0] + sy * k.e[i][2]) + sx * k.e[i][1];
                let passes = e >= -k.eps;
                if exact > e_edge {
                    assert!(
                        passes,
                        "case {case} edge {i}: exact {exact:e} inside, f32 {e:e}"
                    );
                    checked_e += 1;
                } else if exact < -(e_edge + k.eps as f64) {
                    assert!(
                        !passes,
                        "case {case} edge {i}: exact {exact:e} outside, f32 {e:e}"
                    );
                    checked_e += 1;
                }
                inside_exact &= exact > e_edge;
            }
            if inside_exact {
                let t64 = (v[0] - eye).dot(nrm) / d.dot(nrm);
                let den = (k.den[0] + sy * k.den[2]) + sx * k.den[1];
                let t32 = (k.p / den) as f64 * len;
                let rel = (t32 - t64).abs() / t64;
                assert!(
                    rel <= e_t,
                    "case {case}: t {t32} against {t64}, {rel:e} past the bound {e_t:e} ({} u)",
                    e_t / U32
                );
                checked_t += 1;
            }
        }
    }
    assert!(
        tight > 5_000 && checked_t > 10_000 && checked_e > 50_000,
        "too few cases: {tight} tight polygons, {checked_t} distances, {checked_e} edge tests"
    );
}
