//! The PLY reader in process: ASCII, binary little-endian and binary big-endian files of the
//! same data give the mesh (and the degenerate count) that the OBJ reader gives on that data
//! written as OBJ text: the real meshes of scenes/meshes/, and seeded random meshes over every
//! property type and alias, with extra vertex properties, polygons, other lists, elements to
//! skip and elements in any order.

mod common;
mod ply_write;

use common::{Rng, TempDir};
use lanecast::experimental::scene::mesh::{load_mesh, load_obj, parse_obj, parse_ply};
use lanecast::scene::Mesh;
use ply_write::*;
use std::path::Path;

fn obj_mesh(verts: &[[f64; 3]], faces: &[Vec<u32>]) -> (Mesh, usize) {
    let text = obj(verts, faces);
    parse_obj(text.as_bytes(), Path::new("m.obj"), usize::MAX).unwrap()
}

fn ply_mesh(bytes: &[u8], what: &str) -> (Mesh, usize) {
    parse_ply(bytes, Path::new("m.ply"), usize::MAX).unwrap_or_else(|e| panic!("{what}: {e}"))
}

/// The vertices and faces of an OBJ file of scenes/meshes/.
fn real(name: &str) -> (Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("scenes/meshes/{name}.obj"));
    let (mesh, _) = load_obj(&path, usize::MAX).unwrap();
    let verts = mesh.vertices.iter().map(|v| v.to_array()).collect();
    let faces = mesh.faces.iter().map(|f| f.to_vec()).collect();
    (verts, faces)
}

#[test]
fn real_meshes_in_every_encoding_read_as_the_obj() {
    for name in ["bunny", "teapot", "armadillo"] {
        let (verts, faces) = real(name);
        // as f32, which the `float` files hold exactly
        let rounded: Vec<[f64; 3]> = (verts.iter()).map(|v| v.map(|c| c as f32 as f64)).collect();
        for (verts, ty) in [(&verts, "double"), (&rounded, "float")] {
            let want = obj_mesh(verts, &faces);
            assert_eq!(want.0.len(), faces.len());
            for enc in ENCODINGS {
                let bytes = ply(enc, &mesh_elems(verts, &faces, ty), &[], "\n");
                let got = ply_mesh(&bytes, &format!("{name} {ty} {enc:?}"));
                assert!(got == want, "{name} {ty} {enc:?}: meshes differ");
            }
        }
    }
}

/// A value of type `ty`: integers anywhere in a range that fits the type, floats that the
/// type holds exactly (f32 for `float`).
fn value(rng: &mut Rng, ty: &str) -> f64 {
    match int_range(ty) {
        Some((lo, hi)) => {
            let (lo, hi) = (lo.max(-1_000_000), hi.min(1_000_000));
            lo as f64 + (rng.next_u64() % (hi - lo + 1) as u64) as f64
        }
        None if ty.starts_with("float") && ty != "float64" => {
            rng.range(-100.0, 100.0) as f32 as f64
        }
        None => rng.range(-100.0, 100.0),
    }
}

fn pick<T: Copy>(rng: &mut Rng, from: &[T]) -> T {
    from[(rng.next_u64() % from.len() as u64) as usize]
}

fn below(rng: &mut Rng, n: usize) -> usize {
    (rng.next_u64() % n as u64) as usize
}

/// A random mesh as PLY elements (in a random order, with elements to skip) and as vertices
/// and faces. `big`: thousands of vertices and faces, all triangles (the binary fast paths,
/// split over threads).
fn random_case(rng: &mut Rng, big: bool) -> (Vec<Elem>, Vec<[f64; 3]>, Vec<Vec<u32>>) {
    let nv = if big {
        5000 + below(rng, 15000)
    } else {
        1 + below(rng, 200)
    };
    let nf = if big {
        10000 + below(rng, 20000)
    } else {
        below(rng, 60)
    };
    let triangles = big || rng.unit() < 0.5;
    // x, y, z of any types, at random places among other scalars and a list
    let mut props = vec![];
    for name in ["nx", "ny", "nz", "red", "alpha", "confidence"] {
        if rng.unit() < 0.4 {
            props.push(scalar(name, pick(rng, &TYPES)));
        }
    }
    if rng.unit() < 0.3 {
        props.push(list("tags", pick(rng, &INT_TYPES), pick(rng, &TYPES)));
    }
    for axis in ["x", "y", "z"] {
        let at = below(rng, props.len() + 1);
        props.insert(at, scalar(axis, pick(rng, &TYPES)));
    }
    let mut verts = vec![];
    let records = (0..nv)
        .map(|_| {
            let mut v = [0.0; 3];
            let rec = (props.iter())
                .map(|p| match p.count {
                    Some(_) => (0..below(rng, 4)).map(|_| value(rng, p.ty)).collect(),
                    None => {
                        let x = value(rng, p.ty);
                        if let Some(a) = ["x", "y", "z"].iter().position(|&a| a == p.name) {
                            v[a] = x;
                        }
                        vec![x]
                    }
                })
                .collect();
            verts.push(v);
            rec
        })
        .collect();
    let vertex = Elem {
        name: "vertex".into(),
        props,
        records,
    };
    // the index list, of an integer type that holds every index, among other properties
    let fits: Vec<&str> = (INT_TYPES.iter().copied())
        .filter(|t| int_range(t).unwrap().1 >= nv as i64)
        .collect();
    let name = pick(rng, &["vertex_indices", "vertex_index"]);
    let mut props = vec![list(name, pick(rng, &INT_TYPES), pick(rng, &fits))];
    if rng.unit() < 0.4 {
        props.insert(below(rng, 2), scalar("flags", pick(rng, &TYPES)));
    }
    if !big && rng.unit() < 0.4 {
        let at = below(rng, props.len() + 1);
        props.insert(
            at,
            list("texcoord", pick(rng, &INT_TYPES), pick(rng, &TYPES)),
        );
    }
    let mut faces = vec![];
    let records = (0..nf)
        .map(|_| {
            let n = if triangles { 3 } else { 3 + below(rng, 6) };
            let f: Vec<u32> = (0..n).map(|_| below(rng, nv) as u32).collect();
            let rec = (props.iter())
                .map(|p| match (p.count, p.name == name) {
                    (Some(_), true) => f.iter().map(|&i| i as f64).collect(),
                    (Some(_), false) => (0..2 * below(rng, 4)).map(|_| value(rng, p.ty)).collect(),
                    (None, _) => vec![value(rng, p.ty)],
                })
                .collect();
            faces.push(f);
            rec
        })
        .collect();
    let face = Elem {
        name: "face".into(),
        props,
        records,
    };
    let mut elems = vec![vertex, face];
    // elements to skip: edges (scalars only) and materials (a list)
    if rng.unit() < 0.5 {
        let props = vec![scalar("vertex1", "int"), scalar("vertex2", "int")];
        let records = (0..below(rng, 20))
            .map(|_| vec![vec![value(rng, "int")], vec![value(rng, "int")]])
            .collect();
        elems.push(Elem {
            name: "edge".into(),
            props,
            records,
        });
    }
    if rng.unit() < 0.5 {
        let props = vec![list("name", "uchar", "uchar"), scalar("shininess", "float")];
        let records = (0..below(rng, 5))
            .map(|_| {
                let name = (0..below(rng, 12)).map(|_| value(rng, "uchar")).collect();
                vec![name, vec![value(rng, "float")]]
            })
            .collect();
        elems.push(Elem {
            name: "material".into(),
            props,
            records,
        });
    }
    for k in (1..elems.len()).rev() {
        elems.swap(k, below(rng, k + 1));
    }
    (elems, verts, faces)
}

#[test]
fn random_meshes_over_every_type_and_encoding_read_as_the_obj() {
    let (mut checked, mut big_checked) = (0, 0);
    for seed in 0..160 {
        let mut rng = Rng::new(seed);
        let big = seed % 16 == 0;
        let (elems, verts, faces) = random_case(&mut rng, big);
        let want = obj_mesh(&verts, &faces);
        let eol = if rng.unit() < 0.3 { "\r\n" } else { "\n" };
        let comments = ["random mesh", "", "comment  with  spaces"];
        for enc in ENCODINGS {
            let bytes = ply(enc, &elems, &comments[..below(&mut rng, 4)], eol);
            let got = ply_mesh(&bytes, &format!("seed {seed} {enc:?}"));
            assert!(got == want, "seed {seed} {enc:?}: meshes differ");
        }
        checked += 1;
        big_checked += usize::from(big && want.0.len() > 10000);
    }
    assert_eq!((checked, big_checked), (160, 10));
}

/// A big all-triangle mesh (the parallel paths) with errors at two records: the first in the
/// file is reported, the same record in every encoding.
#[test]
fn the_first_bad_record_is_reported_in_big_files() {
    let mut rng = Rng::new(7);
    let (_, mut verts, mut faces) = random_case(&mut rng, true);
    let (nv, nf) = (verts.len(), faces.len());
    let (v1, v2) = (
        nv / 3 + below(&mut rng, nv / 3),
        nv - 1 - below(&mut rng, nv / 4),
    );
    let (f1, f2) = (
        nf / 3 + below(&mut rng, nf / 3),
        nf - 1 - below(&mut rng, nf / 4),
    );
    faces[f1][2] = nv as u32;
    faces[f2][0] = nv as u32 + 5;
    let elems = mesh_elems(&verts, &faces, "double");
    for enc in ENCODINGS {
        let e = parse_ply(&ply(enc, &elems, &[], "\n"), Path::new("m.ply"), usize::MAX);
        let e = e.unwrap_err().to_string();
        let want = format!("face {f1}: vertex index {nv} is out of range");
        assert!(e.contains(&want), "{enc:?}: {e}, want {want}");
    }
    verts[v2][0] = f64::INFINITY;
    verts[v1][1] = f64::NAN;
    let elems = mesh_elems(&verts, &faces, "double");
    for enc in ENCODINGS {
        let e = parse_ply(&ply(enc, &elems, &[], "\n"), Path::new("m.ply"), usize::MAX);
        let e = e.unwrap_err().to_string();
        let want = format!("vertex {v1}: y is NaN");
        assert!(e.contains(&want), "{enc:?}: {e}, want {want}");
    }
}

#[test]
fn mesh_files_are_read_by_their_extension_in_any_case() {
    let dir = TempDir::new("ply-ext");
    let (verts, faces) = real("teapot");
    let want = obj_mesh(&verts, &faces);
    for (name, bytes) in [
        (
            "t.ply",
            ply(
                Encoding::Little,
                &mesh_elems(&verts, &faces, "double"),
                &[],
                "\n",
            ),
        ),
        (
            "t.PLY",
            ply(
                Encoding::Big,
                &mesh_elems(&verts, &faces, "double"),
                &[],
                "\n",
            ),
        ),
        (
            "t.Ply",
            ply(
                Encoding::Ascii,
                &mesh_elems(&verts, &faces, "double"),
                &[],
                "\n",
            ),
        ),
        ("t.obj", obj(&verts, &faces).into_bytes()),
        ("t.OBJ", obj(&verts, &faces).into_bytes()),
        // any other name is read as OBJ, as `mesh` lines always have been
        ("t.mesh", obj(&verts, &faces).into_bytes()),
    ] {
        let path = dir.join(name);
        std::fs::write(&path, bytes).unwrap();
        let got = load_mesh(&path, usize::MAX).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert!(got == want, "{name}: meshes differ");
    }
    // a PLY named .obj is read as OBJ, and refused as one
    std::fs::copy(dir.join("t.ply"), dir.join("p.obj")).unwrap();
    let e = load_mesh(&dir.join("p.obj"), usize::MAX)
        .unwrap_err()
        .to_string();
    assert!(e.contains("p.obj:"), "{e}");
}
