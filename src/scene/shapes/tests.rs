use super::*;

/// Localizing renumbers the vertices in first-use order, unused ones last in their old
/// order, and keeps every face's points: over random meshes, faces read the same
/// triangles, the first uses run 0, 1, 2, ..., and a second pass changes nothing.
#[test]
fn localize_keeps_every_face_and_numbers_vertices_by_first_use() {
    let mut rng = crate::test_rng::Rng(0x9E37_79B9_7F4A_7C15);
    let mut next = |n: u32| rng.below(n);
    for case in 0..50 {
        let nv = 1 + next(200);
        let vertices: Vec<DVec3> = (0..nv)
            .map(|i| DVec3::new(f64::from(i), f64::from(next(1000)), f64::from(case)))
            .collect();
        let faces: Vec<[u32; 3]> = (0..next(300))
            .map(|_| [next(nv), next(nv), next(nv)])
            .collect();
        let mut mesh = Mesh { vertices, faces };
        let before = mesh.clone();
        mesh.localize();
        assert_eq!(mesh.vertices.len(), before.vertices.len(), "case {case}");
        for f in 0..mesh.len() {
            assert_eq!(mesh.triangle(f), before.triangle(f), "case {case} face {f}");
        }
        let mut seen = 0;
        for &v in mesh.faces.iter().flatten() {
            assert!(v <= seen, "case {case}: vertex {v} before {seen}");
            seen = seen.max(v + 1);
        }
        // the unused vertices, last, in their old order (their x is their old index)
        let unused = &mesh.vertices[seen as usize..];
        assert!(unused.windows(2).all(|w| w[0].x < w[1].x), "case {case}");
        let once = mesh.clone();
        mesh.localize();
        assert_eq!(mesh, once, "case {case}: a fixed point");
    }
}

fn sphere(r: f64) -> Shape {
    Shape::Sphere {
        center: DVec3::ZERO,
        radius: r,
    }
}

fn mesh(n: u32) -> Mesh {
    Mesh {
        vertices: (0..n + 2).map(|i| DVec3::new(i as f64, 0.0, 1.0)).collect(),
        faces: (0..n).map(|i| [i, i + 1, i + 2]).collect(),
    }
}

#[test]
fn ids_run_over_loose_shapes_and_meshes_in_order() {
    let mut s = Shapes::new();
    s.push(sphere(1.0), 3);
    s.push_mesh(mesh(3), 4);
    s.push_mesh(Mesh::default(), 5); // no faces: no ids
    s.push(sphere(2.0), 6);
    s.push(sphere(3.0), 7);
    s.push_mesh(mesh(2), 8);
    assert_eq!(s.len(), 8);
    let lines: Vec<usize> = (0..8).map(|i| s.line(i)).collect();
    assert_eq!(lines, [3, 4, 4, 4, 6, 7, 8, 8]);
    assert_eq!(s.lines().collect::<Vec<_>>(), lines);
    assert_eq!(s.get(0), sphere(1.0));
    assert_eq!(s.get(5), sphere(3.0));
    let m = mesh(3);
    assert_eq!(s.get(2), Shape::Triangle(m.triangle(1)));
    assert_eq!(
        m.triangle(1),
        [1.0, 2.0, 3.0].map(|x| DVec3::new(x, 0.0, 1.0))
    );
    let all: Vec<Shape> = s.iter().collect();
    assert_eq!(all, (0..8).map(|i| s.get(i)).collect::<Vec<_>>());
    for a in 0..=8 {
        for b in a..=8 {
            let r: Vec<Shape> = s.range(a..b).collect();
            assert_eq!(r, all[a..b], "{a}..{b}");
        }
    }
    let chunks: Vec<(usize, Vec<Shape>)> = s
        .par_chunks(1..8, 3)
        .map(|(f, it)| (f, it.collect()))
        .collect();
    assert_eq!(chunks.len(), 3);
    assert_eq!(chunks[0], (1, all[1..4].to_vec()));
    assert_eq!(chunks[2], (7, all[7..].to_vec()));
}

#[test]
fn assemble_matches_pushing_one_by_one() {
    let loose = vec![sphere(1.0), sphere(2.0), sphere(3.0)];
    let built = Shapes::assemble(
        loose.clone(),
        vec![1, 2, 9],
        [
            Part::Loose(2),
            Part::Mesh(mesh(2), 5),
            Part::Loose(0),
            Part::Loose(1),
        ],
    );
    let mut pushed = Shapes::new();
    pushed.push(loose[0], 1);
    pushed.push(loose[1], 2);
    pushed.push_mesh(mesh(2), 5);
    pushed.push(loose[2], 9);
    assert_eq!(built, pushed);
    assert_eq!(built.len(), 5);
    assert_eq!(built.line(4), 9);
    let other: Shapes = loose.into_iter().collect();
    assert_ne!(built, other);
}
