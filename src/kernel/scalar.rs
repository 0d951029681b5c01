//! The scalar driver: one ray at a time against every primitive, in f64 (the oracle) or f32 (the
//! baseline the packet kernel's speedup is measured against). Plain loops, no acceleration.

use crate::kernel::Hit;
use crate::kernel::polygon::polygon_x1;
use crate::kernel::sphere::sphere_x1;
use crate::real::{Real, V3};
use crate::soa::Prepared;

/// Nearest hit along unit direction `d` from the eye.
#[inline]
pub fn trace_x1<T: Real>(p: &Prepared<T>, d: V3<T>) -> Hit<T> {
    let mut hit = Hit::NONE;
    for (k, &id) in p.spheres.k.iter().zip(&p.spheres.id) {
        if let Some(t) = sphere_x1(k, d) {
            hit.update(t, id);
        }
    }
    for (k, &id) in p.triangles.k.iter().zip(&p.triangles.id) {
        if let Some(t) = polygon_x1(k, d) {
            hit.update(t, id);
        }
    }
    for (k, &id) in p.quads.k.iter().zip(&p.quads.id) {
        if let Some(t) = polygon_x1(k, d) {
            hit.update(t, id);
        }
    }
    hit
}
