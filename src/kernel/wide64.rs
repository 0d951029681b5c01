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
use crate::kernel::HitLanes;
use crate::kernel::polygon::{PolyK, polygon_lanes};
use crate::kernel::sphere::{SphereK, sphere_lanes};
use wide::f64x4;

/// [`crate::kernel::polygon::polygon_x8`] in four f64 lanes: the one generic form.
#[inline(always)]
pub fn polygon_x4d<const N: usize>(k: &PolyK<f64, N>, d: &[f64x4; 3]) -> Option<(f64x4, f64x4)> {
    polygon_lanes(k, d)
}

/// [`crate::kernel::sphere::sphere_x8`] in four f64 lanes: the one generic form.
#[inline(always)]
pub fn sphere_x4d(s: &SphereK<f64>, d: &[f64x4; 3]) -> Option<(f64x4, f64x4)> {
    sphere_lanes(s, d)
}

/// The nearest hits of four rays, ids as f64 (exact); the rule of `kernel::Hit8`.
pub type Hit4d = HitLanes<f64x4>;

/// Four unit directions, lane by lane the operations of `RayTables::<f64>::dir_x1`.
#[inline(always)]
pub fn dir_x4d(tables: &RayTables<f64>, sx: f64x4, sy: f64x4) -> [f64x4; 3] {
    let (f, r, u) = (tables.f, tables.r, tables.u);
    let c = |i: usize| f64x4::splat(f[i]) + sx * f64x4::splat(r[i]) + sy * f64x4::splat(u[i]);
    let d = [c(0), c(1), c(2)];
    let len = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
    [d[0] / len, d[1] / len, d[2] / len]
}
