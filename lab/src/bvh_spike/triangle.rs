//! The triangle test for rays that share one origin `o` (a pinhole camera's eye): edge planes
//! through the eye, set up once per triangle and tile, then tested 8 rays at a time.
//!
//! Formula: with `a_i = v_i - o` and `e_i = v_{i+1} - v_i`, edge `i` spans the plane through
//! the eye with normal `m_i = a_i x a_{i+1} = a_i x e_i`. A ray `d` passes inside the
//! triangle's cone when `w_i = d . m_i` are all >= 0 or all <= 0 (either facing: triangles are
//! two-sided). Its distance is `t = (n . a_0) / (n . d)` with the plane's normal
//! `n = (v_1 - v_0) x (v_2 - v_0)`. A hit needs `t > 0` (the opposite cone passes the signs
//! too) and `n . d != 0`. `a_i x e_i`, not `a_i x a_{i+1}`: the long, nearly parallel `a_i`
//! and `a_{i+1}` of a small far triangle cancel in the cross product (a first try lost about
//! 1e-4 of the normal's direction, 20% of a pixel at 1080p on the 3.3M armadillo), where `e_i`
//! is short and exact to a rounding; for the same reason `t` uses `n`, not `m_0 + m_1 + m_2`. This is the shared-origin form of the Plücker edge test
//! (Benthin et al.; the object-order engine's edge functions in 3D), not Möller-Trumbore.
//!
//! No gaps along shared edges: each edge's normal is computed from its two endpoints in one
//! canonical order (the lexicographically smaller vertex first) and negated (exactly) for the
//! triangle that runs the edge the other way, so two triangles sharing an edge compute bit-for-bit
//! opposite `w` for every ray, and a ray on the edge (`w = 0`) passes both; a ray is never
//! between them. `vertex_fan_has_no_gaps` (below) checks this on closed meshes.
//!
//! Precision: f32 throughout, no fused multiply-add (wide's `*` and `+`). `a_i` and `e_i` are
//! rounded once (relative error u = 2^-24, on top of the vertices' rounding to f32), the cross
//! product's components err by about `2u |a_i| |e_i|`, so an edge plane turns by a few u
//! unless the edge points at the eye: near an edge, a ray within about `4u |a_i|` may go to
//! the neighbour (the f64 oracle's "edge band" is 32u). `t` has a relative error of a few u
//! when the ray is not grazing. The spike does not re-decide such
//! rays in f64.

use glam::Vec3;
use wide::f32x8;

/// A triangle as the tile test reads it: its f32 vertices, the scene id, and which of its
/// edges run in their canonical direction ([`EdgeSetup`]).
#[derive(Debug, Clone, Copy)]
#[repr(C)]
pub struct Tri {
    pub v: [Vec3; 3],
    pub id: i32,
    /// Bit `i`: edge `v_i -> v_{i+1}` starts at the lexicographically smaller vertex.
    pub canon: u32,
}

impl Tri {
    /// The triangle of f32 vertices `v` with scene id `id`.
    pub fn new(v: [Vec3; 3], id: i32) -> Tri {
        let canon = (0..3).fold(0, |bits, i| {
            bits | (before(v[i], v[(i + 1) % 3]) as u32) << i
        });
        Tri { v, id, canon }
    }
}

/// A triangle set up for one origin: the three edge normals, oriented for this triangle, the
/// plane's normal and the numerator of `t`.
#[derive(Debug, Clone, Copy)]
pub struct EdgeSetup {
    pub m: [Vec3; 3],
    pub n: Vec3,
    pub num: f32,
    pub id: i32,
}

/// The canonical order of two vertices: lexicographic on (x, y, z).
#[inline]
pub fn before(a: Vec3, b: Vec3) -> bool {
    (a.x, a.y, a.z) < (b.x, b.y, b.z)
}

/// The normal of the plane through `o` and edge `p -> q`, `(p - o) x (q - p)`, computed as for
/// the edge's canonical direction (`canon`: `p -> q` is it) and negated when `p -> q` runs the
/// other way. Operands picked by selects, not a branch: the direction is a coin toss per edge.
#[inline(always)]
fn edge(canon: bool, p: Vec3, q: Vec3, ap: Vec3, aq: Vec3) -> Vec3 {
    let m = glam::BVec3::splat(canon);
    let (start, end) = (Vec3::select(m, p, q), Vec3::select(m, q, p));
    let n = Vec3::select(m, ap, aq).cross(end - start);
    Vec3::select(m, n, -n)
}

impl EdgeSetup {
    /// `tri` seen from `o`.
    #[inline(always)]
    pub fn new(tri: &Tri, o: Vec3) -> EdgeSetup {
        let [v0, v1, v2] = tri.v;
        let a = [v0 - o, v1 - o, v2 - o];
        let c = |i: u32| tri.canon >> i & 1 == 1;
        let m = [
            edge(c(0), v0, v1, a[0], a[1]),
            edge(c(1), v1, v2, a[1], a[2]),
            edge(c(2), v2, v0, a[2], a[0]),
        ];
        let n = (v1 - v0).cross(v2 - v0);
        EdgeSetup {
            m,
            n,
            num: n.dot(a[0]),
            id: tri.id,
        }
    }

    /// One ray: `t` where it hits, or `None`.
    pub fn hit_x1(&self, d: Vec3) -> Option<f32> {
        // each product and sum rounded in the order the 8-lane form uses
        let w = self.m.map(|m| d.x * m.x + d.y * m.y + d.z * m.z);
        let inside = (w[0] >= 0.0 && w[1] >= 0.0 && w[2] >= 0.0)
            || (w[0] <= 0.0 && w[1] <= 0.0 && w[2] <= 0.0);
        let n = self.n;
        let den = d.x * n.x + d.y * n.y + d.z * n.z;
        let t = self.num / den;
        (inside && den != 0.0 && t > 0.0).then_some(t)
    }

    /// Eight rays: `t` in the lanes that hit, else +inf.
    #[inline(always)]
    pub fn hit_x8(&self, d: &[f32x8; 3]) -> f32x8 {
        // edge tests
        let w = self.m.map(|m| {
            d[0] * f32x8::splat(m.x) + d[1] * f32x8::splat(m.y) + d[2] * f32x8::splat(m.z)
        });
        let zero = f32x8::ZERO;
        let pos = w[0].simd_ge(zero) & w[1].simd_ge(zero) & w[2].simd_ge(zero);
        let neg = w[0].simd_le(zero) & w[1].simd_le(zero) & w[2].simd_le(zero);
        let inside = pos | neg;
        if inside.to_bitmask() == 0 {
            return f32x8::splat(f32::INFINITY);
        }
        // depth test
        let n = self.n;
        let den = d[0] * f32x8::splat(n.x) + d[1] * f32x8::splat(n.y) + d[2] * f32x8::splat(n.z);
        let t = f32x8::splat(self.num) / den;
        let valid = inside & den.simd_ne(zero) & t.simd_gt(zero);
        valid.select(t, f32x8::splat(f32::INFINITY))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Rng(u64);
    impl Rng {
        fn f(&mut self) -> f32 {
            self.0 ^= self.0 << 13;
            self.0 ^= self.0 >> 7;
            self.0 ^= self.0 << 17;
            (self.0 >> 40) as f32 / (1u64 << 24) as f32
        }
        fn v(&mut self) -> Vec3 {
            Vec3::new(self.f(), self.f(), self.f()) * 2.0 - 1.0
        }
    }

    /// The 8-lane form equals the 1-lane form lane by lane, over random triangles and rays
    /// from random origins (hits, misses, edge-on rays and rays through vertices included).
    #[test]
    fn x8_equals_x1_lane_by_lane() {
        let mut r = Rng(0x2545f4914f6cdd1d);
        for k in 0..20_000 {
            let scale = 10f32.powf(r.f() * 4.0 - 2.0);
            let v = [r.v() * scale, r.v() * scale, r.v() * scale];
            let o = r.v() * 10.0;
            let tri = Tri::new(v, 7);
            let s = EdgeSetup::new(&tri, o);
            let dirs: [Vec3; 8] = std::array::from_fn(|l| match (k + l) % 4 {
                0 => (v[l % 3] - o).normalize(),
                1 => ((v[0] + v[1]) * 0.5 - o).normalize(),
                _ => ((v[0] + v[1] + v[2]) / 3.0 + r.v() * scale * 0.5 - o).normalize(),
            });
            let d8 = [0, 1, 2].map(|a| f32x8::from(dirs.map(|d| d[a])));
            let t8 = s.hit_x8(&d8).to_array();
            for l in 0..8 {
                let t1 = s.hit_x1(dirs[l]).unwrap_or(f32::INFINITY);
                assert_eq!(t1.to_bits(), t8[l].to_bits(), "case {k} lane {l}");
            }
        }
    }

    /// Rays from random eyes outside a closed mesh (a jittered octahedron subdivided, so
    /// every edge is shared by two triangles), aimed at random points inside it, must hit a
    /// triangle on the way in and on the way out: none passes between neighbours. A third of
    /// the rays aim just inside a vertex, a third just inside an edge's midpoint (1e-3 of the
    /// radius; the mesh is star-shaped about its centre), so they cross the surface next to
    /// edges and vertices.
    #[test]
    fn vertex_fan_has_no_gaps() {
        let mut r = Rng(0x9e3779b97f4a7c15);
        for round in 0..40 {
            let (verts, faces) = closed_mesh(&mut r, 3);
            let tris: Vec<Tri> = faces
                .iter()
                .enumerate()
                .map(|(i, f)| Tri::new(f.map(|k| verts[k]), i as i32))
                .collect();
            let far = 3.0 + 1000.0 * r.f() * r.f();
            let o = r.v().normalize() * far;
            let setups: Vec<EdgeSetup> = tris.iter().map(|t| EdgeSetup::new(t, o)).collect();
            for k in 0..400 {
                let target = match k % 3 {
                    0 => verts[k % verts.len()] * (1.0 - 1e-3),
                    1 => {
                        let f = faces[k % faces.len()];
                        (verts[f[0]] + verts[f[1]]) * (0.5 - 5e-4)
                    }
                    _ => r.v() * 0.4,
                };
                let d = (target - o).normalize();
                let hits = setups.iter().filter_map(|s| s.hit_x1(d)).count();
                assert!(
                    hits >= 2,
                    "round {round} ray {k}: {hits} hits through a closed mesh"
                );
            }
        }
    }

    /// An octahedron subdivided `levels` times, vertices pushed out to a jittered sphere:
    /// closed, every edge in two faces, faces consistently oriented.
    fn closed_mesh(r: &mut Rng, levels: usize) -> (Vec<Vec3>, Vec<[usize; 3]>) {
        let mut verts = vec![Vec3::X, -Vec3::X, Vec3::Y, -Vec3::Y, Vec3::Z, -Vec3::Z];
        let mut faces = vec![
            [0, 2, 4],
            [2, 1, 4],
            [1, 3, 4],
            [3, 0, 4],
            [2, 0, 5],
            [1, 2, 5],
            [3, 1, 5],
            [0, 3, 5],
        ];
        for _ in 0..levels {
            let mut mid = std::collections::HashMap::new();
            let mut next = Vec::new();
            for f in &faces {
                let mut m = [0; 3];
                for e in 0..3 {
                    let key = (f[e].min(f[(e + 1) % 3]), f[e].max(f[(e + 1) % 3]));
                    m[e] = *mid.entry(key).or_insert_with(|| {
                        verts.push((verts[key.0] + verts[key.1]) * 0.5);
                        verts.len() - 1
                    });
                }
                next.push([f[0], m[0], m[2]]);
                next.push([f[1], m[1], m[0]]);
                next.push([f[2], m[2], m[1]]);
                next.push([m[0], m[1], m[2]]);
            }
            faces = next;
        }
        for v in &mut verts {
            *v = v.normalize() * (1.0 + 0.2 * r.f());
        }
        (verts, faces)
    }
}
