//! The scene's primitives in id order, kept in the form that costs least.
//!
//! Primitives written on their own lines (`sphere`, `triangle`, `quad`) are kept as [`Shape`]
//! values with their line. A mesh's triangles are kept indexed, as the OBJ file wrote them: its
//! f64 vertices once and three `u32` vertex indices per face ([`Mesh`]), all on the line of its
//! `mesh` statement. A closed scan has about half as many vertices as faces, so a mesh triangle
//! costs about 24 bytes here against 104 for a `Shape` (sized for the quad's four vertices) and
//! 8 for its line.
//!
//! Ids run over the runs in order: each run is a stretch of consecutive ids, either loose
//! shapes (consecutive in `loose`) or one mesh's faces. [`Shapes::get`] finds a run by binary
//! search (usually one or two runs), and [`Iter`] walks them without searching.

use super::Shape;
use crate::par::prelude::*;
use glam::DVec3;
use std::ops::Range;

/// A mesh's triangles, indexed: the faces in file order (fan-triangulated), each three indices
/// into `vertices`. Degenerate faces are kept, so the ids of the others do not shift.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Mesh {
    /// Every vertex of the mesh file, in file order (in a scene's [`Shapes`], in the order the
    /// faces first use them: [`Mesh::localize`]).
    pub vertices: Vec<DVec3>,
    /// Each face's three vertex indices (0-based, in range).
    pub faces: Vec<[u32; 3]>,
}

impl Mesh {
    /// Renumbers the vertices in the order the faces first use them (vertices no face uses
    /// keep their order, after the rest), the faces rewritten to match: every face keeps its
    /// three points, in its order. Faces read one after another then read vertices that lie
    /// together in memory, as each view's setup does twice per face (the f32 range check and
    /// the constants). A mesh already in that order is left as it is.
    pub fn localize(&mut self) {
        const NONE: u32 = u32::MAX;
        let mut map = vec![NONE; self.vertices.len()];
        let mut next = 0u32;
        for f in &self.faces {
            for &v in f {
                if map[v as usize] == NONE {
                    map[v as usize] = next;
                    next += 1;
                }
            }
        }
        if map.iter().enumerate().all(|(i, &m)| m == i as u32) {
            return;
        }
        for m in map.iter_mut().filter(|m| **m == NONE) {
            *m = next;
            next += 1;
        }
        let mut vertices = vec![DVec3::ZERO; self.vertices.len()];
        for (v, &m) in self.vertices.iter().zip(&map) {
            vertices[m as usize] = *v;
        }
        self.vertices = vertices;
        for f in &mut self.faces {
            *f = f.map(|v| map[v as usize]);
        }
    }

    /// Face `f`'s vertices.
    #[inline]
    pub fn triangle(&self, f: usize) -> [DVec3; 3] {
        self.faces[f].map(|v| self.vertices[v as usize])
    }

    /// How many faces.
    pub fn len(&self) -> usize {
        self.faces.len()
    }

    /// True when there are no faces.
    pub fn is_empty(&self) -> bool {
        self.faces.is_empty()
    }
}

/// Where a run's shapes are.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Src {
    /// Loose shapes from this index of `loose` on.
    Loose(usize),
    /// The faces of mesh `k`.
    Mesh(usize),
}

/// A stretch of consecutive ids starting at `first`.
#[derive(Debug, Clone, Copy, PartialEq)]
struct Run {
    first: usize,
    src: Src,
}

/// One piece of [`Shapes::assemble`]'s input, in id order.
pub(crate) enum Part {
    /// The next `n` loose shapes.
    Loose(usize),
    /// A mesh and the line of its `mesh` statement.
    Mesh(Mesh, usize),
}

/// One run of [`Shapes::parts`].
#[derive(Debug, Clone, Copy)]
pub enum PartRef<'a> {
    /// Consecutive loose shapes.
    Loose(&'a [Shape]),
    /// One mesh's faces.
    Mesh(&'a Mesh),
}

/// Every primitive of a scene, in id order (see the module comment).
#[derive(Clone, Default)]
pub struct Shapes {
    loose: Vec<Shape>,
    loose_lines: Vec<u32>,
    meshes: Vec<(Mesh, u32)>,
    runs: Vec<Run>,
    len: usize,
}

/// Lines are at most `MAX_SCENE_BYTES` (1 GiB) apart from the start, so they fit in 32 bits.
fn line32(line: usize) -> u32 {
    u32::try_from(line).expect("a line number of a scene under the size limit")
}

impl Shapes {
    /// An empty list.
    pub fn new() -> Shapes {
        Shapes::default()
    }

    /// Appends a loose shape written on `line` (0: no scene line, e.g. an OBJ rendered alone).
    pub fn push(&mut self, shape: Shape, line: usize) {
        self.extend_loose_run(self.loose.len());
        self.loose.push(shape);
        self.loose_lines.push(line32(line));
        self.len += 1;
    }

    /// Makes the next id continue a run of loose shapes, starting one at index `at` of
    /// `loose` unless the last run is loose already.
    fn extend_loose_run(&mut self, at: usize) {
        if !matches!(
            self.runs.last(),
            Some(Run {
                src: Src::Loose(_),
                ..
            })
        ) {
            self.runs.push(Run {
                first: self.len,
                src: Src::Loose(at),
            });
        }
    }

    /// Appends a mesh's faces, all on `line`, its vertices renumbered in the order the faces
    /// use them ([`Mesh::localize`]).
    pub fn push_mesh(&mut self, mut mesh: Mesh, line: usize) {
        if mesh.is_empty() {
            return;
        }
        mesh.localize();
        self.runs.push(Run {
            first: self.len,
            src: Src::Mesh(self.meshes.len()),
        });
        self.len += mesh.len();
        self.meshes.push((mesh, line32(line)));
    }

    /// The list made of `loose` (with their lines) and meshes, in the order `parts` gives.
    pub(crate) fn assemble(
        loose: Vec<Shape>,
        loose_lines: Vec<u32>,
        parts: impl IntoIterator<Item = Part>,
    ) -> Shapes {
        debug_assert_eq!(loose.len(), loose_lines.len());
        let mut s = Shapes {
            loose,
            loose_lines,
            ..Shapes::default()
        };
        let mut taken = 0;
        for part in parts {
            match part {
                Part::Loose(0) => {}
                Part::Loose(n) => {
                    s.extend_loose_run(taken);
                    taken += n;
                    s.len += n;
                }
                Part::Mesh(mesh, line) => s.push_mesh(mesh, line),
            }
        }
        assert_eq!(taken, s.loose.len(), "parts cover every loose shape");
        s
    }

    /// How many primitives.
    #[inline]
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when there are none.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// The index in `runs` of the run holding `id`.
    #[inline]
    fn run_of(&self, id: usize) -> usize {
        if self.runs.len() == 1 {
            0
        } else {
            self.runs.partition_point(|r| r.first <= id) - 1
        }
    }

    /// The id after run `r`'s last.
    #[inline]
    fn run_end(&self, r: usize) -> usize {
        self.runs.get(r + 1).map_or(self.len, |n| n.first)
    }

    #[inline]
    fn in_run(&self, r: usize, id: usize) -> Shape {
        let run = self.runs[r];
        match run.src {
            Src::Loose(at) => self.loose[at + id - run.first],
            Src::Mesh(k) => Shape::Triangle(self.meshes[k].0.triangle(id - run.first)),
        }
    }

    /// Where primitive `id`'s data lies in memory, as a start and a length in bytes: what
    /// [`Shapes::get`] reads first (a loose shape, or a mesh face's vertex indices). For cache
    /// hints; nothing reads through it. Panics when `id >= len()`.
    #[inline]
    pub fn address(&self, id: usize) -> (*const u8, usize) {
        assert!(id < self.len, "shape id {id} of {}", self.len);
        let run = self.runs[self.run_of(id)];
        match run.src {
            Src::Loose(at) => {
                let shape = &self.loose[at + id - run.first];
                ((shape as *const Shape).cast(), std::mem::size_of_val(shape))
            }
            Src::Mesh(k) => {
                let face = &self.meshes[k].0.faces[id - run.first];
                (face.as_ptr().cast(), std::mem::size_of_val(face))
            }
        }
    }

    /// Primitive `id`. Panics when `id >= len()`.
    #[inline]
    pub fn get(&self, id: usize) -> Shape {
        assert!(id < self.len, "shape id {id} of {}", self.len);
        self.in_run(self.run_of(id), id)
    }

    /// The 1-based scene line primitive `id` was written on (a mesh's faces: its `mesh` line),
    /// 0 when it has none (an OBJ file rendered alone).
    pub fn line(&self, id: usize) -> usize {
        assert!(id < self.len, "shape id {id} of {}", self.len);
        let run = self.runs[self.run_of(id)];
        match run.src {
            Src::Loose(at) => self.loose_lines[at + id - run.first] as usize,
            Src::Mesh(k) => self.meshes[k].1 as usize,
        }
    }

    /// Every primitive's line ([`Shapes::line`]), in id order.
    pub fn lines(&self) -> impl Iterator<Item = usize> + '_ {
        (self.runs.iter().enumerate()).flat_map(move |(r, run)| {
            let n = self.run_end(r) - run.first;
            (0..n).map(move |j| match run.src {
                Src::Loose(at) => self.loose_lines[at + j] as usize,
                Src::Mesh(k) => self.meshes[k].1 as usize,
            })
        })
    }

    /// Every primitive, in id order.
    pub fn iter(&self) -> Iter<'_> {
        self.range(0..self.len)
    }

    /// Primitives `ids`, in order.
    pub fn range(&self, ids: Range<usize>) -> Iter<'_> {
        assert!(ids.start <= ids.end && ids.end <= self.len);
        let run = if ids.is_empty() {
            0
        } else {
            self.run_of(ids.start)
        };
        Iter {
            shapes: self,
            id: ids.start,
            end: ids.end,
            run,
            run_end: if ids.is_empty() { 0 } else { self.run_end(run) },
        }
    }

    /// Primitives `ids` in consecutive pieces of `chunk` ids, in parallel: each piece's first
    /// id and its primitives.
    pub(crate) fn par_chunks(
        &self,
        ids: Range<usize>,
        chunk: usize,
    ) -> impl IndexedParallelIterator<Item = (usize, Iter<'_>)> + '_ {
        assert!(ids.end <= self.len);
        let chunk = chunk.max(1);
        (0..ids.len().div_ceil(chunk))
            .into_par_iter()
            .map(move |c| {
                let first = ids.start + c * chunk;
                (first, self.range(first..(first + chunk).min(ids.end)))
            })
    }

    /// The runs of consecutive ids in order: loose shapes, or one mesh's faces. Their lengths
    /// add up to `len()`.
    pub fn parts(&self) -> impl Iterator<Item = PartRef<'_>> {
        self.runs.iter().enumerate().map(|(r, run)| match run.src {
            Src::Loose(at) => PartRef::Loose(&self.loose[at..at + self.run_end(r) - run.first]),
            Src::Mesh(k) => PartRef::Mesh(&self.meshes[k].0),
        })
    }

    /// The loose shapes (those not from a mesh), in id order.
    pub fn loose(&self) -> &[Shape] {
        &self.loose
    }

    /// The meshes, each with its `mesh` line, in file order.
    pub fn meshes(&self) -> impl Iterator<Item = (&Mesh, usize)> {
        self.meshes.iter().map(|(m, l)| (m, *l as usize))
    }
}

impl PartialEq for Shapes {
    /// The same primitives on the same lines, however they are stored.
    fn eq(&self, other: &Shapes) -> bool {
        self.len == other.len && self.iter().eq(other.iter()) && self.lines().eq(other.lines())
    }
}

impl std::fmt::Debug for Shapes {
    /// The primitives and their lines, however they are stored (as [`PartialEq`] compares).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let lines: Vec<usize> = self.lines().collect();
        f.debug_struct("Shapes")
            .field("shapes", &self.iter().collect::<Vec<_>>())
            .field("lines", &lines)
            .finish()
    }
}

impl FromIterator<Shape> for Shapes {
    /// Loose shapes with no scene line (0), as a Rust caller builds a scene.
    fn from_iter<I: IntoIterator<Item = Shape>>(iter: I) -> Shapes {
        let mut s = Shapes::new();
        for shape in iter {
            s.push(shape, 0);
        }
        s
    }
}

impl From<Vec<Shape>> for Shapes {
    fn from(v: Vec<Shape>) -> Shapes {
        v.into_iter().collect()
    }
}

/// The primitives of a range of ids, in order ([`Shapes::iter`], [`Shapes::range`]).
#[derive(Debug, Clone)]
pub struct Iter<'a> {
    shapes: &'a Shapes,
    id: usize,
    end: usize,
    run: usize,
    run_end: usize,
}

impl Iterator for Iter<'_> {
    type Item = Shape;

    #[inline]
    fn next(&mut self) -> Option<Shape> {
        if self.id >= self.end {
            return None;
        }
        while self.id >= self.run_end {
            self.run += 1;
            self.run_end = self.shapes.run_end(self.run);
        }
        let s = self.shapes.in_run(self.run, self.id);
        self.id += 1;
        Some(s)
    }

    fn size_hint(&self) -> (usize, Option<usize>) {
        let n = self.end - self.id;
        (n, Some(n))
    }
}

impl ExactSizeIterator for Iter<'_> {}

#[cfg(test)]
mod tests;
