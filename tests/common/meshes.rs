//! Meshes whose edges are shared: cubes, icospheres, fans and grids, and cameras and bounds
//! to view them by.

use super::*;

/// The 12 triangles of the axis-aligned cube `centre +- h`, outward winding.
pub fn cube(centre: DVec3, h: f64) -> Vec<[DVec3; 3]> {
    let p = |x: f64, y: f64, z: f64| centre + DVec3::new(x, y, z) * h;
    let corners: [DVec3; 8] = std::array::from_fn(|i| {
        let s = |bit: usize| if i >> bit & 1 == 1 { 1.0 } else { -1.0 };
        p(s(0), s(1), s(2))
    });
    // faces as corner indices in perimeter order
    let faces = [
        [0, 2, 3, 1], // z-
        [4, 5, 7, 6], // z+
        [0, 1, 5, 4], // y-
        [2, 6, 7, 3], // y+
        [0, 4, 6, 2], // x-
        [1, 3, 7, 5], // x+
    ];
    let mut out = Vec::new();
    for f in faces {
        let [a, b, c, d] = f.map(|i| corners[i]);
        out.push([a, b, c]);
        out.push([a, c, d]);
    }
    out
}

/// An icosahedron of radius `r` around `centre`, each face split into four `subdiv` times, new
/// vertices pushed out to the sphere. Shared edges use the same vertex values on both sides.
pub fn icosphere(centre: DVec3, r: f64, subdiv: usize) -> Vec<[DVec3; 3]> {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut verts: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut faces: Vec<[usize; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..subdiv {
        let mut mid = std::collections::HashMap::new();
        let mut midpoint = |a: usize, b: usize, verts: &mut Vec<DVec3>| {
            *mid.entry((a.min(b), a.max(b))).or_insert_with(|| {
                verts.push(((verts[a] + verts[b]) / 2.0).normalize());
                verts.len() - 1
            })
        };
        let mut next = Vec::new();
        for [a, b, c] in faces {
            let ab = midpoint(a, b, &mut verts);
            let bc = midpoint(b, c, &mut verts);
            let ca = midpoint(c, a, &mut verts);
            next.extend([[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        faces = next;
    }
    faces
        .iter()
        .map(|f| f.map(|i| centre + verts[i] * r))
        .collect()
}

/// A fan of `k` triangles around `hub`, rim vertices `rim` (closed loop), all sharing the hub.
pub fn fan(hub: DVec3, rim: &[DVec3]) -> Vec<[DVec3; 3]> {
    (0..rim.len())
        .map(|i| [hub, rim[i], rim[(i + 1) % rim.len()]])
        .collect()
}

/// An `n` x `n` grid of unit squares in the plane z = `z`, corners at integer x and y from
/// -n/2 to n/2 (n even), as quads.
pub fn grid_quads(n: i32, z: f64) -> Vec<Shape> {
    let mut out = Vec::new();
    for i in -n / 2..n / 2 {
        for j in -n / 2..n / 2 {
            let p = |x: i32, y: i32| DVec3::new(x as f64, y as f64, z);
            out.push(Shape::Quad([
                p(i, j),
                p(i + 1, j),
                p(i + 1, j + 1),
                p(i, j + 1),
            ]));
        }
    }
    out
}

/// The same grid with each square split along a diagonal (alternating direction) into two
/// triangles.
pub fn grid_triangles(n: i32, z: f64) -> Vec<Shape> {
    let mut out = Vec::new();
    for s in grid_quads(n, z) {
        let Shape::Quad([a, b, c, d]) = s else {
            unreachable!()
        };
        if ((a.x + a.y) as i64).rem_euclid(2) == 0 {
            out.push(Shape::Triangle([a, b, c]));
            out.push(Shape::Triangle([a, c, d]));
        } else {
            out.push(Shape::Triangle([a, b, d]));
            out.push(Shape::Triangle([b, c, d]));
        }
    }
    out
}

pub fn triangles(tris: &[[DVec3; 3]]) -> Vec<Shape> {
    tris.iter().map(|&v| Shape::Triangle(v)).collect()
}

/// A head-on camera for the plane z = `plane_z`: eye (0, 0, `plane_z + dist`) looking down -z,
/// with an odd `size` x `size` image whose pixel centres land on the plane `step` apart, the
/// centre pixel on (0, 0): for column x = (W - 1)/2 + j, sx = (2(x + 0.5)/W - 1) half_w =
/// 2 j half_w / W, so half_w = W step / (2 dist) puts column j's ray through x = j step
/// (likewise rows, since half_h = half_w H / W). With `step` = 1/2^k and integer vertices,
/// every 2^k-th pixel ray passes through a vertex, and whole rows and columns of rays run
/// along the edges.
pub fn head_on(plane_z: f64, dist: f64, size: u32, step: f64) -> CameraSpec {
    assert!(size % 2 == 1);
    let half_w = size as f64 * step / (2.0 * dist);
    let fov = 2.0 * half_w.atan().to_degrees();
    spec(
        DVec3::new(0.0, 0.0, plane_z + dist),
        DVec3::new(0.0, 0.0, plane_z),
        DVec3::Y,
        fov,
    )
}

/// The centre and the diagonal of `scene`'s bounding box.
pub fn bounds(scene: &Scene) -> (DVec3, f64) {
    let (mut lo, mut hi) = (DVec3::INFINITY, DVec3::NEG_INFINITY);
    let mut grow = |p: DVec3| (lo, hi) = (lo.min(p), hi.max(p));
    for shape in scene.shapes.iter() {
        match shape {
            Shape::Sphere { center, radius } => {
                grow(center - DVec3::splat(radius));
                grow(center + DVec3::splat(radius));
            }
            Shape::Triangle(v) => v.iter().for_each(|&p| grow(p)),
            Shape::Quad(v) => v.iter().for_each(|&p| grow(p)),
        }
    }
    ((lo + hi) / 2.0, (hi - lo).length())
}
