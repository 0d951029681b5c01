//! [`TriangleK::triangle`]'s constants for four triangles at once, in the lanes of `f64x4`: the
//! setup of every view computes them for every triangle of the scene, and four lanes share the
//! square roots and divisions.
//!
//! The same formula as [`PolyK::new`] (`kernel::polygon`: eye-relative vertices, the plane
//! normal `(B - A) x (C - A)` oriented away from the eye, edge-plane normals `r_i x r_j`
//! normalised, the plane distance the mean of the vertices' along the normal), written with
//! the same operations in the same order as glam's `length`, `cross`, `dot` and `x * (1 / |x|)`
//! and no fused multiply-add: each lane's IEEE results, square roots and divisions included,
//! are the scalar form's, so the constants are bit-identical and a lane is `None` exactly when
//! the scalar form's is (`the_four_lanes_are_the_scalar_constants_bit_for_bit`, over random
//! triangles at every scale, edge-on, with collapsed edges, NaN and infinite vertices).
//! Precision and failure cases are [`PolyK::new`]'s.

use super::{EDGE_ON_SINE, PolyK, TriangleK};
use crate::limits::MIN_EDGE_ANGLE;
use glam::DVec3;
use wide::f64x4;

/// Four 3-vectors, one per lane.
#[derive(Clone, Copy)]
struct V4 {
    x: f64x4,
    y: f64x4,
    z: f64x4,
}

impl V4 {
    fn of(v: [DVec3; 4]) -> V4 {
        V4 {
            x: f64x4::new(v.map(|p| p.x)),
            y: f64x4::new(v.map(|p| p.y)),
            z: f64x4::new(v.map(|p| p.z)),
        }
    }

    fn sub(self, o: V4) -> V4 {
        V4 {
            x: self.x - o.x,
            y: self.y - o.y,
            z: self.z - o.z,
        }
    }

    fn scale(self, k: f64x4) -> V4 {
        V4 {
            x: self.x * k,
            y: self.y * k,
            z: self.z * k,
        }
    }

    /// glam's `cross`, term for term.
    fn cross(self, r: V4) -> V4 {
        V4 {
            x: self.y * r.z - r.y * self.z,
            y: self.z * r.x - r.z * self.x,
            z: self.x * r.y - r.x * self.y,
        }
    }

    /// glam's `dot`.
    fn dot(self, r: V4) -> f64x4 {
        (self.x * r.x) + (self.y * r.y) + (self.z * r.z)
    }

    fn length(self) -> f64x4 {
        self.dot(self).sqrt()
    }

    /// The four lanes as vectors.
    fn lanes(&self) -> [[f64; 3]; 4] {
        let (x, y, z) = (self.x.to_array(), self.y.to_array(), self.z.to_array());
        std::array::from_fn(|k| [x[k], y[k], z[k]])
    }
}

/// [`TriangleK::triangle`] of each of `tris` seen from `eye`, bit for bit.
pub fn triangles_x4(tris: &[[DVec3; 3]; 4], eye: DVec3) -> [Option<TriangleK<f64>>; 4] {
    let vert = |k: usize| V4::of(tris.map(|t| t[k]));
    let v = [vert(0), vert(1), vert(2)];
    let e = V4::of([eye; 4]);
    let rel = v.map(|p| p.sub(e));
    let len = rel.map(V4::length);
    let raw = v[1].sub(v[0]).cross(v[2].sub(v[0]));
    let raw_len = raw.length();
    let facing = rel[0].dot(raw);
    // lanes as bits: a comparison's lanes, and the scalar form's refusals negated (a NaN
    // compares false, as there)
    let bits = |m: f64x4| m.to_bitmask();
    let inf = f64x4::splat(f64::INFINITY);
    let finite = |x: f64x4| bits(x.abs().simd_lt(inf));
    let edge_on = facing
        .abs()
        .simd_le(f64x4::splat(EDGE_ON_SINE) * len[0] * raw_len);
    let mut ok = finite(facing) & !bits(edge_on);
    // (signum of a finite non-zero `facing`; other lanes are refused)
    let s = facing
        .simd_lt(f64x4::ZERO)
        .select(f64x4::splat(-1.0), f64x4::ONE);
    let nrm = raw.scale(f64x4::ONE / raw_len).scale(s);
    let p = (rel[0].dot(nrm) + rel[1].dot(nrm) + rel[2].dot(nrm)) / f64x4::splat(3.0);
    let mut n = [nrm; 3];
    for i in 0..3 {
        let j = (i + 1) % 3;
        let c = rel[i].cross(rel[j]);
        let c_len = c.length();
        ok &= !bits(c_len.simd_lt(f64x4::splat(MIN_EDGE_ANGLE) * len[i] * len[j]));
        let rcp = f64x4::ONE / c_len;
        ok &= finite(rcp) & bits(rcp.simd_gt(f64x4::ZERO));
        n[i] = c.scale(rcp).scale(s);
    }
    ok &= bits(p.simd_gt(f64x4::ZERO)) & finite(p) & finite(nrm.x) & finite(nrm.y) & finite(nrm.z);
    let (p, n, nrm) = (p.to_array(), n.map(|e| e.lanes()), nrm.lanes());
    // a lane whose vertex A lies near the eye's horizon of its plane takes the scalar form,
    // which asks for the polygon's nearest point (rare: an eye near a triangle's plane)
    let near_plane = bits(edge_on) & finite(facing);
    std::array::from_fn(|k| {
        if near_plane >> k & 1 == 1 {
            return TriangleK::triangle(&tris[k], eye);
        }
        (ok >> k & 1 == 1).then(|| PolyK {
            n: n.map(|e| e[k]),
            nrm: nrm[k],
            p: p[k],
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Random triangles at scales 1e-12 to 1e15 around eyes up to 1e15 away, edge-on ones
    /// (the eye in the plane), collapsed edges, repeated vertices, and NaN or infinite
    /// coordinates: every lane is the scalar constants, bit for bit, or `None` with them.
    #[test]
    fn the_four_lanes_are_the_scalar_constants_bit_for_bit() {
        let mut rng = crate::test_rng::Rng(0x2545_F491_4F6C_DD1D);
        let mut unit = || rng.unit();
        let point = |scale: f64, u: &mut dyn FnMut() -> f64| {
            DVec3::new(u() - 0.5, u() - 0.5, u() - 0.5) * scale
        };
        let bits = |k: &Option<TriangleK<f64>>| {
            k.map(|k| {
                let mut b: Vec<u64> = k.n.iter().flatten().map(|x| x.to_bits()).collect();
                b.extend(k.nrm.map(f64::to_bits));
                b.push(k.p.to_bits());
                b
            })
        };
        let (mut some, mut none) = (0, 0);
        for case in 0..20_000 {
            let scale = 10f64.powf(unit() * 27.0 - 12.0);
            let eye = point(10f64.powf(unit() * 15.0), &mut unit);
            let tris: [[DVec3; 3]; 4] = std::array::from_fn(|_| {
                let a = point(scale, &mut unit);
                let mut t = [a, a + point(scale, &mut unit), a + point(scale, &mut unit)];
                match (unit() * 10.0) as u32 {
                    // the eye in the triangle's plane: edge-on
                    0 => t[2] = eye + (t[0] - eye) * 2.0 - (t[1] - eye),
                    1 => t[1] = t[0],
                    2 => t[2] = t[0] + (t[1] - t[0]) * 1e-13,
                    3 => t[1].y = f64::NAN,
                    4 => t[2].x = f64::INFINITY,
                    _ => {}
                }
                t
            });
            let lanes = triangles_x4(&tris, eye);
            for (k, t) in tris.iter().enumerate() {
                let scalar = TriangleK::triangle(t, eye);
                assert_eq!(
                    bits(&lanes[k]),
                    bits(&scalar),
                    "case {case} lane {k}: {t:?}"
                );
                if scalar.is_some() {
                    some += 1
                } else {
                    none += 1
                }
            }
        }
        // (about 34,000 and 46,000: small triangles far from the eye subtend too little)
        assert!(some > 25_000 && none > 10_000, "{some} {none}");
    }
}
