//! Binned SAH build of a BVH2 over a scene's triangles, in world space, once per scene.
//!
//! Method: top-down, each node's triangles binned by centroid into [`BINS`] equal bins along
//! each axis of the centroid bounds (Wald, "On fast construction of SAH-based bounding volume
//! hierarchies", 2007; tinybvh's `Build`); the split of least `area(L) n(L) + area(R) n(R)` is
//! taken down to [`MAX_LEAF`] triangles, which make a leaf (more only where the centroids
//! coincide, halved by position until they fit). Nodes of more than [`PAR_MIN`]
//! triangles bin in parallel and build their two children in parallel (`rayon::join`), each
//! into its own node list, spliced after; below that one thread builds a subtree in place.
//!
//! Bounds: each triangle's box is its f64 vertices' box rounded outward to f32 ([`down`],
//! [`up`]), so a node's f32 box holds the exact triangle and its f32-rounded vertices alike
//! (Ize, "Robust BVH ray traversal", 2013: conservative bounds; the slab test's own rounding is
//! covered in `traverse`).

use super::triangle::Tri;
use glam::{DVec3, Vec3};
use lanecast::scene::{Scene, Shape};
use rayon::prelude::*;

/// Centroid bins per axis.
pub const BINS: usize = 16;
/// Most triangles in a leaf, unless every centroid is the same point.
pub const MAX_LEAF: usize = 4;
/// Nodes with more triangles than this bin and split in parallel.
pub const PAR_MIN: usize = 1 << 16;

/// One node: its box, and either two children at `first` and `first + 1` (`count == 0`) or
/// `count` triangles from `first` in [`Bvh::tris`].
#[derive(Debug, Clone, Copy, Default)]
#[repr(C)]
pub struct Node {
    pub lo: [f32; 3],
    pub first: u32,
    pub hi: [f32; 3],
    /// Triangles in a leaf; 0 for an inner node, whose split axis is `axis`.
    pub count: u16,
    pub axis: u16,
}

/// The hierarchy: node 0 is the root; leaves index `tris`, stored in leaf order.
#[derive(Debug, Clone)]
pub struct Bvh {
    pub nodes: Vec<Node>,
    pub tris: Vec<Tri>,
}

/// Largest f32 at or below `x`.
pub fn down(x: f64) -> f32 {
    let f = x as f32;
    if f as f64 > x { f.next_down() } else { f }
}

/// Smallest f32 at or above `x`.
pub fn up(x: f64) -> f32 {
    let f = x as f32;
    if (f as f64) < x { f.next_up() } else { f }
}

#[derive(Clone, Copy)]
struct Aabb {
    lo: Vec3,
    hi: Vec3,
}

impl Aabb {
    const EMPTY: Aabb = Aabb {
        lo: Vec3::splat(f32::INFINITY),
        hi: Vec3::splat(f32::NEG_INFINITY),
    };
    fn grow(&mut self, b: &Aabb) {
        self.lo = self.lo.min(b.lo);
        self.hi = self.hi.max(b.hi);
    }
    fn grow_point(&mut self, p: Vec3) {
        self.lo = self.lo.min(p);
        self.hi = self.hi.max(p);
    }
    /// Half the surface area (0 when empty).
    fn area(&self) -> f32 {
        let e = (self.hi - self.lo).max(Vec3::ZERO);
        e.x * e.y + e.y * e.z + e.z * e.x
    }
}

/// The per-triangle inputs of the build: box and centroid.
struct Prims {
    boxes: Vec<Aabb>,
    centroids: Vec<Vec3>,
}

#[derive(Clone, Copy)]
struct Bins {
    boxes: [[Aabb; BINS]; 3],
    counts: [[u32; BINS]; 3],
    bounds: Aabb,
}

impl Bins {
    fn new() -> Bins {
        Bins {
            boxes: [[Aabb::EMPTY; BINS]; 3],
            counts: [[0; BINS]; 3],
            bounds: Aabb::EMPTY,
        }
    }
    fn merge(mut self, o: Bins) -> Bins {
        for a in 0..3 {
            for b in 0..BINS {
                self.boxes[a][b].grow(&o.boxes[a][b]);
                self.counts[a][b] += o.counts[a][b];
            }
        }
        self.bounds.grow(&o.bounds);
        self
    }
}

/// The bin (of `nb`) of centroid coordinate `c` on an axis from `lo` with `scale` bins per
/// unit.
#[inline]
fn bin_of(c: f32, lo: f32, scale: f32, nb: usize) -> usize {
    (((c - lo) * scale) as usize).min(nb - 1)
}

/// Bins used for a node of `n` triangles: [`BINS`], 8 below 256 triangles (the sweep's fixed
/// cost dominates small nodes).
fn bins_for(n: usize) -> usize {
    if n < 256 { 8 } else { BINS }
}

impl Bvh {
    /// Builds the hierarchy of `scene`'s triangles on the current rayon pool. Fails, naming the
    /// first one, on a sphere or a quad (the spike traces triangles only).
    pub fn build(scene: &Scene) -> Result<Bvh, String> {
        let n = scene.shapes.len();
        if n == 0 {
            return Err(format!("{}: no primitives", scene.source.display()));
        }
        if n > u32::MAX as usize / 2 {
            return Err(format!("{}: too many triangles", scene.source.display()));
        }
        let mut verts: Vec<[DVec3; 3]> = Vec::with_capacity(n);
        for (id, s) in scene.shapes.iter().enumerate() {
            match s {
                Shape::Triangle(v) => verts.push(v),
                _ => {
                    return Err(format!(
                        "{}:{}: primitive {id} is not a triangle; the BVH spike traces \
                         triangles only",
                        scene.source.display(),
                        scene.shapes.line(id)
                    ));
                }
            }
        }
        let (boxes, centroids): (Vec<Aabb>, Vec<Vec3>) = verts
            .par_iter()
            .map(|v| {
                let lo = v[0].min(v[1]).min(v[2]);
                let hi = v[0].max(v[1]).max(v[2]);
                let b = Aabb {
                    lo: Vec3::new(down(lo.x), down(lo.y), down(lo.z)),
                    hi: Vec3::new(up(hi.x), up(hi.y), up(hi.z)),
                };
                (b, (b.lo + b.hi) * 0.5)
            })
            .unzip();
        let prims = Prims { boxes, centroids };
        let mut items: Vec<u32> = (0..n as u32).collect();
        let nodes = build_par(&prims, &mut items, 0);
        let tris = items
            .par_iter()
            .map(|&i| Tri::new(verts[i as usize].map(|p| p.as_vec3()), i as i32))
            .collect();
        Ok(Bvh { nodes, tris })
    }

    /// Bytes held: nodes and triangles.
    pub fn bytes(&self) -> usize {
        self.nodes.len() * size_of::<Node>() + self.tris.len() * size_of::<Tri>()
    }

    /// Leaves and the deepest leaf's depth.
    pub fn shape(&self) -> (usize, usize) {
        let (mut leaves, mut deepest) = (0, 0);
        let mut stack = vec![(0usize, 0usize)];
        while let Some((i, d)) = stack.pop() {
            let node = &self.nodes[i];
            if node.count > 0 {
                leaves += 1;
                deepest = deepest.max(d);
            } else {
                stack.push((node.first as usize, d + 1));
                stack.push((node.first as usize + 1, d + 1));
            }
        }
        (leaves, deepest)
    }
}

/// Bins `items` (their boxes and centroid bounds too), in parallel above [`PAR_MIN`].
fn bin(prims: &Prims, items: &[u32], cb: &Aabb, nb: usize) -> Bins {
    let scale = (cb.hi - cb.lo).map(|e| if e > 0.0 { nb as f32 / e } else { 0.0 });
    let run = |chunk: &[u32]| {
        let mut bins = Bins::new();
        for &i in chunk {
            let (b, c) = (&prims.boxes[i as usize], prims.centroids[i as usize]);
            for a in 0..3 {
                let k = bin_of(c[a], cb.lo[a], scale[a], nb);
                bins.boxes[a][k].grow(b);
                bins.counts[a][k] += 1;
            }
            bins.bounds.grow(b);
        }
        bins
    };
    if items.len() > PAR_MIN {
        items
            .par_chunks(PAR_MIN / 4)
            .map(run)
            .reduce(Bins::new, Bins::merge)
    } else {
        run(items)
    }
}

/// The centroid bounds of `items`.
fn centroid_bounds(prims: &Prims, items: &[u32]) -> Aabb {
    let run = |chunk: &[u32]| {
        let mut b = Aabb::EMPTY;
        for &i in chunk {
            b.grow_point(prims.centroids[i as usize]);
        }
        b
    };
    if items.len() > PAR_MIN {
        items.par_chunks(PAR_MIN / 4).map(run).reduce(
            || Aabb::EMPTY,
            |mut a, b| {
                a.grow(&b);
                a
            },
        )
    } else {
        run(items)
    }
}

/// The node over `items` and, unless it is a leaf, where its triangles part: the items are
/// reordered so that the left child's come first, and the left count is returned.
fn split(prims: &Prims, items: &mut [u32]) -> (Aabb, Option<(usize, u16)>) {
    let n = items.len();
    if n <= MAX_LEAF {
        let mut bounds = Aabb::EMPTY;
        for &i in items.iter() {
            bounds.grow(&prims.boxes[i as usize]);
        }
        return (bounds, None);
    }
    let nb = bins_for(n);
    let cb = centroid_bounds(prims, items);
    let bins = bin(prims, items, &cb, nb);
    let bounds = bins.bounds;
    let mut best = (f32::INFINITY, 0usize, 0usize); // cost, axis, bins on the left
    for a in 0..3 {
        if cb.hi[a] <= cb.lo[a] {
            continue;
        }
        // right-to-left sweep: area and count of bins k.. on the right
        let mut right = [(0.0f32, 0u32); BINS];
        let (mut b, mut c) = (Aabb::EMPTY, 0u32);
        for k in (1..nb).rev() {
            b.grow(&bins.boxes[a][k]);
            c += bins.counts[a][k];
            right[k] = (b.area(), c);
        }
        let (mut b, mut c) = (Aabb::EMPTY, 0u32);
        for (k, &(r_area, r_count)) in right.iter().enumerate().take(nb).skip(1) {
            b.grow(&bins.boxes[a][k - 1]);
            c += bins.counts[a][k - 1];
            if c == 0 || r_count == 0 {
                continue;
            }
            let cost = 1.0 + (b.area() * c as f32 + r_area * r_count as f32) / bounds.area();
            if cost < best.0 {
                best = (cost, a, k);
            }
        }
    }
    if best.0.is_infinite() {
        // every centroid the same point: a leaf, or halves by position when too many
        if n <= MAX_LEAF {
            return (bounds, None);
        }
        return (bounds, Some((n / 2, 0)));
    }
    let (a, k) = (best.1, best.2);
    let scale = nb as f32 / (cb.hi[a] - cb.lo[a]);
    // partition: bins < k to the left
    let (mut i, mut j) = (0, n);
    while i < j {
        if bin_of(prims.centroids[items[i] as usize][a], cb.lo[a], scale, nb) < k {
            i += 1;
        } else {
            j -= 1;
            items.swap(i, j);
        }
    }
    (bounds, Some((i, a as u16)))
}

fn aabb_node(b: &Aabb, first: u32, count: u16, axis: u16) -> Node {
    Node {
        lo: b.lo.to_array(),
        first,
        hi: b.hi.to_array(),
        count,
        axis,
    }
}

/// The subtree over `items` (which start at `base` in the whole item list) as its own node
/// list, root first, children in pairs.
fn build_par(prims: &Prims, items: &mut [u32], base: usize) -> Vec<Node> {
    if items.len() <= PAR_MIN {
        let mut nodes = vec![Node::default()];
        build_seq(prims, items, base, &mut nodes, 0);
        return nodes;
    }
    let (bounds, cut) = split(prims, items);
    let Some((at, axis)) = cut else {
        return vec![aabb_node(&bounds, base as u32, items.len() as u16, 0)];
    };
    let (l, r) = items.split_at_mut(at);
    let (ln, rn) = rayon::join(
        || build_par(prims, l, base),
        || build_par(prims, r, base + at),
    );
    // [root, left root, right root, left's rest, right's rest]
    let mut nodes = Vec::with_capacity(1 + ln.len() + rn.len());
    nodes.push(aabb_node(&bounds, 1, 0, axis));
    let shift_l = |i: u32| if i == 0 { 1 } else { i + 2 };
    let shift_r = |i: u32| if i == 0 { 2 } else { i + 1 + ln.len() as u32 };
    let fix = |mut n: Node, f: &dyn Fn(u32) -> u32| {
        if n.count == 0 {
            n.first = f(n.first);
        }
        n
    };
    nodes.push(fix(ln[0], &shift_l));
    nodes.push(fix(rn[0], &shift_r));
    nodes.extend(ln[1..].iter().map(|&n| fix(n, &shift_l)));
    nodes.extend(rn[1..].iter().map(|&n| fix(n, &shift_r)));
    nodes
}

/// Builds the subtree over `items` into `nodes[at]` and pairs appended to `nodes`.
fn build_seq(prims: &Prims, items: &mut [u32], base: usize, nodes: &mut Vec<Node>, at: usize) {
    let (bounds, cut) = split(prims, items);
    let Some((mid, axis)) = cut else {
        nodes[at] = aabb_node(&bounds, base as u32, items.len() as u16, 0);
        return;
    };
    let first = nodes.len();
    nodes[at] = aabb_node(&bounds, first as u32, 0, axis);
    nodes.push(Node::default());
    nodes.push(Node::default());
    let (l, r) = items.split_at_mut(mid);
    build_seq(prims, l, base, nodes, first);
    build_seq(prims, r, base + mid, nodes, first + 1);
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every triangle in exactly one leaf, inside every box on its path, ids a permutation.
    fn check(bvh: &Bvh, verts: &[[DVec3; 3]]) {
        let mut seen = vec![false; verts.len()];
        let mut stack = vec![(0usize, Vec::<usize>::new())];
        while let Some((i, path)) = stack.pop() {
            let node = bvh.nodes[i];
            let mut path = path;
            path.push(i);
            if node.count > 0 {
                for t in &bvh.tris[node.first as usize..][..node.count as usize] {
                    assert!(!seen[t.id as usize]);
                    seen[t.id as usize] = true;
                    for &p in &path {
                        let b = bvh.nodes[p];
                        for v in verts[t.id as usize] {
                            for a in 0..3 {
                                assert!(b.lo[a] as f64 <= v[a] && v[a] <= b.hi[a] as f64);
                            }
                        }
                    }
                }
            } else {
                stack.push((node.first as usize, path.clone()));
                stack.push((node.first as usize + 1, path));
            }
        }
        assert!(seen.iter().all(|&s| s));
    }

    #[test]
    fn every_triangle_in_one_leaf_inside_its_boxes() {
        use lanecast::scene::scene_from_arrays;
        let mut rng = 0x9e3779b97f4a7c15u64;
        let mut next = || {
            rng ^= rng << 13;
            rng ^= rng >> 7;
            rng ^= rng << 17;
            (rng >> 11) as f64 / (1u64 << 53) as f64
        };
        // small and parallel-sized meshes, some with coincident triangles
        for n in [1usize, 3, 5, 17, 1000, PAR_MIN * 2 + 7] {
            let mut vertices = Vec::new();
            let mut faces = Vec::new();
            for k in 0..n {
                let scale = 10f64.powf(next() * 6.0 - 3.0);
                let c = DVec3::new(next(), next(), next()) * 100.0 - 50.0;
                let c = if k % 7 == 3 { DVec3::ZERO } else { c };
                let b = vertices.len() as i64;
                for _ in 0..3 {
                    vertices.push((c + DVec3::new(next(), next(), next()) * scale).to_array());
                }
                faces.push([b, b + 1, b + 2]);
            }
            let path = std::path::Path::new("random");
            let scene = scene_from_arrays(path, None, &vertices, &faces, &[], &[]).unwrap();
            let bvh = Bvh::build(&scene).unwrap();
            let verts: Vec<_> = faces
                .iter()
                .map(|f| f.map(|i| DVec3::from(vertices[i as usize])))
                .collect();
            check(&bvh, &verts);
        }
    }

    #[test]
    fn spheres_are_refused_naming_the_line() {
        let scene = lanecast::parse_scene(
            "camera eye 0 0 5 look 0 0 0 up 0 1 0\ntriangle 0 0 0 1 0 0 0 1 0\nsphere 0 0 0 1\n",
            std::path::Path::new("s.sc"),
        )
        .unwrap();
        let e = Bvh::build(&scene).unwrap_err();
        assert!(e.contains("s.sc:3") && e.contains("triangles only"), "{e}");
    }
}
