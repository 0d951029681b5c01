//! The default methods in double precision packets: the edge-plane polygon test
//! (`kernel::polygon`) and the stable sphere (`kernel::sphere`) in `wide::f64x4` lanes, two
//! f64x4 halves per 8-ray packet. Same formulas, same operation order, no fused multiply-add,
//! and the constants are the f64 ones the oracle uses, so each lane equals
//! `polygon_x1::<f64>` / `sphere_x1::<f64>` bit for bit: this is the f64 oracle vectorised.
//!
//! Precision: that of the f64 oracle (u = 2^-53; edge tolerance 8u = 8.9e-16 rad). Serves the
//! scenes f32 cannot represent (a radius-1e4 ground seen from 1.5 above, 1e-3 triangles 1e4
//! away, 1e-5 rad grazing angles). Known to fail: only where f64 itself does (sizes below
//! ~1e-16 of the distance). Costs: half the lanes per instruction and twice the bytes per
//! constant of the f32 kernels. Proven by `tests/stability.rs` (`f64_packets_match_the_oracle`,
//! `x8_equals_x1_*`).

use crate::camera::RayTables;
use crate::kernel::edge_eps;
use crate::kernel::polygon::PolyK;
use crate::kernel::sphere::SphereK;
use wide::f64x4;

/// Lanes per f64 packet.
pub const LANES_F64: usize = 4;

/// [`crate::kernel::polygon::polygon_x8`] in four f64 lanes.
#[inline(always)]
pub fn polygon_x4d<const N: usize>(k: &PolyK<f64, N>, d: &[f64x4; 3]) -> Option<(f64x4, f64x4)> {
    // edge tests
    let eps = f64x4::splat(-edge_eps::<f64>());
    let side = |n: &[f64; 3]| {
        f64x4::splat(n[0]) * d[0] + f64x4::splat(n[1]) * d[1] + f64x4::splat(n[2]) * d[2]
    };
    let mut inside = side(&k.n[0]).simd_ge(eps);
    for n in &k.n[1..] {
        if !inside.any() {
            return None;
        }
        inside &= side(n).simd_ge(eps);
    }
    if !inside.any() {
        return None;
    }
    // plane distance
    Some((inside, f64x4::splat(k.p) / side(&k.nrm)))
}

/// [`crate::kernel::sphere::sphere_x8`] in four f64 lanes.
#[inline(always)]
pub fn sphere_x4d(s: &SphereK<f64>, d: &[f64x4; 3]) -> Option<(f64x4, f64x4)> {
    let oc = s.oc.map(f64x4::splat);
    let b = oc[0] * d[0] + oc[1] * d[1] + oc[2] * d[2];
    let l = [oc[0] - b * d[0], oc[1] - b * d[1], oc[2] - b * d[2]];
    let disc = f64x4::splat(s.r2) - (l[0] * l[0] + l[1] * l[1] + l[2] * l[2]);
    let meets = disc.simd_ge(f64x4::ZERO);
    if !meets.any() {
        return None;
    }
    let q = b + disc.sqrt();
    let t = if s.inside { q } else { f64x4::splat(s.c) / q };
    Some((meets, t))
}

/// The nearest hits of four rays, ids as f64 (exact); the rule of `kernel::Hit8`.
#[derive(Debug, Clone, Copy)]
pub struct Hit4d {
    pub t: f64x4,
    pub id: f64x4,
}

impl Hit4d {
    /// No hit yet in the `active` lanes; the others start at t = 0 and stay unchanged.
    #[inline(always)]
    pub fn new(active: f64x4) -> Hit4d {
        Hit4d {
            t: active.select(f64x4::splat(f64::INFINITY), f64x4::ZERO),
            id: f64x4::splat(-1.0),
        }
    }

    #[inline(always)]
    pub fn update(&mut self, mask: f64x4, t: f64x4, id: f64) {
        let id = f64x4::splat(id);
        let wins = t.simd_lt(self.t) | (t.simd_eq(self.t) & id.simd_lt(self.id));
        let take = mask & t.simd_gt(f64x4::ZERO) & wins;
        self.t = take.select(t, self.t);
        self.id = take.select(id, self.id);
    }
}

/// Four unit directions, lane by lane the operations of `RayTables::<f64>::dir_x1`.
#[inline(always)]
pub fn dir_x4d(tables: &RayTables<f64>, sx: f64x4, sy: f64x4) -> [f64x4; 3] {
    let (f, r, u) = (tables.f, tables.r, tables.u);
    let c = |i: usize| f64x4::splat(f[i]) + sx * f64x4::splat(r[i]) + sy * f64x4::splat(u[i]);
    let d = [c(0), c(1), c(2)];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    [d[0] / len, d[1] / len, d[2] / len]
}
