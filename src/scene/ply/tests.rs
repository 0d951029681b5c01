//! Header and body rules on small hand-written files; the random round trips over every type
//! and both byte orders, and the comparisons with the OBJ reader on real meshes, are in
//! tests/ply.rs.

use super::header::Type;
use super::*;
use crate::scene::mesh::parse_obj;

const F: &str = "m.ply";

fn parse(bytes: &[u8], max: usize) -> Result<(Mesh, usize)> {
    parse_ply(bytes, Path::new(F), max)
}

fn err(bytes: &[u8]) -> String {
    parse(bytes, 1000).unwrap_err().to_string()
}

/// `value` of type `t` in the byte order `big`.
fn put(out: &mut Vec<u8>, t: Type, big: bool, v: f64) {
    macro_rules! put {
        ($ty:ty) => {{
            let x = v as $ty;
            assert!(x as f64 == v || v.is_nan(), "{v} fits {t:?}");
            out.extend(if big {
                x.to_be_bytes()
            } else {
                x.to_le_bytes()
            })
        }};
    }
    match t {
        Type::I8 => put!(i8),
        Type::U8 => put!(u8),
        Type::I16 => put!(i16),
        Type::U16 => put!(u16),
        Type::I32 => put!(i32),
        Type::U32 => put!(u32),
        Type::F32 => put!(f32),
        Type::F64 => put!(f64),
    }
}

const TRI_HEADER: &str = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n\
                          element face 1\nproperty list uchar int vertex_indices\nend_header\n";

fn ascii(rest: &str) -> Vec<u8> {
    format!("ply\nformat ascii 1.0\n{rest}").into_bytes()
}

#[test]
fn ascii_polygons_extra_properties_and_other_elements_read_as_the_obj_text() {
    let ply = ascii(
        "comment a square, a pentagon and a triangle\nobj_info made by hand\n\
         element vertex 6\nproperty double x\nproperty float nx\nproperty float y\n\
         property int z\nproperty uchar red\n\
         element material 1\nproperty list uchar float name\n\
         element face 3\nproperty uchar flags\nproperty list uchar uint vertex_indices\n\
         property list uint8 float32 texcoord\n\
         element edge 2\nproperty int vertex1\nproperty int vertex2\nend_header\n\
         0 0.5 0 0 255\n1 nan 0 0 0\n1.25 -inf 1 0 7\n0 0 1 0 1\n0.5 0 2 -3 9\n-1 0 0 0 0\n\
         2 1.5 2.5\n\
         0 4 0 1 2 3 0\n1 5 0 1 2 3 4 2 0.5 0.5\n2 3 5 0 4 6 0 0 1 1 0 0\n\
         0 1\r\n1 2\r\n\n  \n",
    );
    let obj = "v 0 0 0\nv 1 0 0\nv 1.25 1 0\nv 0 1 0\nv 0.5 2 -3\nv -1 0 0\n\
               f 1 2 3 4\nf 1 2 3 4 5\nf 6 1 5\n";
    let (mesh, zero) = parse(&ply, 100).unwrap();
    let (want, want_zero) = parse_obj(obj.as_bytes(), Path::new("m.obj"), 100).unwrap();
    assert_eq!(mesh, want);
    assert_eq!(zero, want_zero);
    assert_eq!(mesh.len(), 2 + 3 + 1);
}

#[test]
fn header_errors_name_the_file_and_line() {
    let v = "element vertex 3\nproperty float x\nproperty float y\nproperty float z\n";
    let f = "element face 1\nproperty list uchar int vertex_indices\n";
    let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let cases: Vec<(String, usize, &str)> = vec![
        (
            format!("PLY\nformat ascii 1.0\n{v}{f}end_header\n"),
            1,
            "not a PLY file",
        ),
        (
            format!("ply\nformat ascii 2.0\n{v}{f}end_header\n"),
            2,
            "version '2.0'",
        ),
        (
            "ply\nformat binary_middle_endian 1.0\n".to_string(),
            2,
            "unknown format",
        ),
        (
            "ply\nformat ascii 1.0\nformat ascii 1.0\n".to_string(),
            3,
            "second format",
        ),
        (
            "ply\nformat ascii 1.0\nproperty float x\n".to_string(),
            3,
            "before any element",
        ),
        (
            format!("ply\nformat ascii 1.0\n{v}property half w\n"),
            7,
            "unknown property type",
        ),
        (
            format!("ply\nformat ascii 1.0\n{v}property float x\n"),
            7,
            "second property 'x'",
        ),
        (
            format!("ply\nformat ascii 1.0\n{v}vertex 3\n"),
            7,
            "unknown header keyword",
        ),
        (
            "ply\nformat ascii 1.0\nelement vertex -3\n".to_string(),
            3,
            "not an element count",
        ),
        ("ply\nformat ascii 1.0\n\n".to_string(), 3, "blank line"),
        (
            format!("ply\n{v}{f}end_header\n{body}"),
            8,
            "no format line",
        ),
        (format!("ply\nformat ascii 1.0\n{v}{f}"), 8, "no end_header"),
        (
            format!("ply\nformat ascii 1.0\n{f}end_header\n"),
            5,
            "no 'vertex' element",
        ),
        (
            format!("ply\nformat ascii 1.0\n{v}end_header\n{body}"),
            7,
            "no 'face' element",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float z\n{f}end_header\n"
            ),
            3,
            "no property 'y'",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\nelement vertex 1\nproperty list uchar float x\nproperty float y\nproperty float z\n{f}end_header\n"
            ),
            3,
            "'x' is a list",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\n{v}element face 1\nproperty list uchar int vertex_list\nend_header\n{body}"
            ),
            7,
            "no list 'vertex_indices'",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\n{v}element face 1\nproperty int vertex_indices\nend_header\n{body}"
            ),
            7,
            "is not a list",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\n{v}element face 1\nproperty list uchar float vertex_indices\nend_header\n{body}"
            ),
            7,
            "must be integers, not float",
        ),
        (
            format!(
                "ply\nformat ascii 1.0\n{v}element face 1\nproperty list float int vertex_indices\n"
            ),
            8,
            "list count must be an integer type",
        ),
        (
            format!("ply\nformat ascii 1.0\n{v}{f}element edge 2\nend_header\n{body}"),
            9,
            "records but no properties",
        ),
    ];
    for (text, line, word) in cases {
        let e = err(text.as_bytes());
        assert!(e.starts_with(&format!("{F}:{line}: ")), "{e}\n{text}");
        assert!(e.contains(word), "{e}\n{text}");
    }
}

#[test]
fn counts_the_file_cannot_hold_are_refused_from_the_header() {
    // 4e9 vertices of 12 bytes (48 GB) on a 40-byte body: refused before any allocation
    for (format, body) in [
        ("ascii", &b"0 0 0\n3 0 0 0\n"[..]),
        ("binary_little_endian", &[0u8; 40][..]),
        ("binary_big_endian", &[0u8; 40][..]),
    ] {
        let mut bytes = format!(
            "ply\nformat {format} 1.0\nelement vertex 4000000000\nproperty float x\n\
             property float y\nproperty float z\nelement face 1\n\
             property list uchar int vertex_indices\nend_header\n"
        )
        .into_bytes();
        bytes.extend(body);
        let e = err(&bytes);
        assert!(e.starts_with(&format!("{F}:3: 4000000000 'vertex'")), "{e}");
        assert!(e.contains("cut short"), "{e}");
    }
    // a face count past the triangle limit, before reading the body
    let body = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
    let e = parse(&ascii(&format!("{TRI_HEADER}{body}")), 0)
        .unwrap_err()
        .to_string();
    assert!(
        e.starts_with(&format!("{F}:7: 1 faces: too many triangles")),
        "{e}"
    );
}

#[test]
fn ascii_body_errors_name_the_line_and_record() {
    // the body's first line is line 10; vertex 0 is long enough for every body to pass the
    // header's size check
    let v0 = "0.000 0.000 0.000\n";
    for (body, line, word) in [
        (
            "1 0 x\n0 1 0\n3 0 1 2\n",
            11,
            "vertex 1: 'x' is not a number",
        ),
        ("1 0 0\n0 nan 0\n3 0 1 2\n", 12, "vertex 2: y is NaN"),
        ("1 0 1e400\n0 1 0\n3 0 1 2\n", 11, "vertex 1: z is infinite"),
        (
            "1 0\n0 1 0\n3 0 1 2\n",
            11,
            "vertex 1: the line ends before",
        ),
        ("1 0 0 0\n0 1 0\n3 0 1 2\n", 11, "vertex 1: more values"),
        (
            "\n1 0 0\n0 1 0\n3 0 1 2\n",
            11,
            "vertex 1: the line ends before",
        ),
        (
            "1 0 0\n0 1 0\n3 0 1 3\n",
            13,
            "face 0: vertex index 3 is out of range",
        ),
        (
            "1 0 0\n0 1 0\n3 0 -1 2\n",
            13,
            "face 0: vertex index -1 is out of range",
        ),
        (
            "1 0 0\n0 1 0\n2 0 1\n",
            13,
            "face 0: a face needs at least 3 vertices, got 2",
        ),
        (
            "1 0 0\n0 1 0\n3 0 1.5 2\n",
            13,
            "face 0: '1.5' is not a valid int",
        ),
        (
            "1 0 0\n0 1 0\n256 0 1 2\n",
            13,
            "'256' is not a valid uchar",
        ),
        (
            "1 0 0\n0 1 0\n3 0 1 2\n0 0 0\n",
            14,
            "'0' after the last element",
        ),
        (
            "1 0 0\n0 1 0\n4 0 1 2\n",
            13,
            "face 0: the line ends before",
        ),
        (
            "1 0 0\n0 1 0\n",
            12,
            "face 0: the file ends before this record",
        ),
        (
            "1 0 0\n0 1 0",
            12,
            "face 0: the file ends before this record",
        ),
    ] {
        let e = err(&ascii(&format!("{TRI_HEADER}{v0}{body}")));
        assert!(e.starts_with(&format!("{F}:{line}: ")), "{e}\n{body}");
        assert!(e.contains(word), "{e}\n{body}");
    }
}

#[test]
fn triangle_limit_counts_triangles_of_polygons() {
    let text = ascii(&format!("{TRI_HEADER}0 0 0\n1 0 0\n0 1 0\n4 0 1 2 0\n"));
    assert_eq!(parse(&text, 2).unwrap().0.len(), 2);
    let e = parse(&text, 1).unwrap_err().to_string();
    assert!(
        e.starts_with(&format!("{F}:13: face 0: too many triangles")),
        "{e}"
    );
}

/// A binary file: the triangle header with `float` coordinates and `uchar`/`int` lists, then
/// `verts` and `faces` (count and indices) in byte order `big`; and where the body starts.
fn binary(big: bool, verts: &[[f64; 3]], faces: &[&[f64]], extra: &[u8]) -> (Vec<u8>, usize) {
    let order = if big { "big" } else { "little" };
    let header = format!(
        "ply\nformat binary_{order}_endian 1.0\ncomment body follows\n{}",
        TRI_HEADER
            .replace("vertex 3", &format!("vertex {}", verts.len()))
            .replace("face 1", &format!("face {}", faces.len()))
    );
    let mut b = header.into_bytes();
    let body = b.len();
    for v in verts {
        for &c in v {
            put(&mut b, Type::F32, big, c);
        }
    }
    for f in faces {
        put(&mut b, Type::U8, big, f.len() as f64);
        for &i in *f {
            put(&mut b, Type::I32, big, i);
        }
    }
    b.extend(extra);
    (b, body)
}

#[test]
fn binary_body_errors_name_the_byte_offset() {
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
    ];
    let vbytes = 12 * v.len();
    for big in [false, true] {
        let (ok, _) = binary(big, &v, &[&[0.0, 1.0, 2.0], &[0.0, 2.0, 3.0, 1.0]], &[]);
        assert_eq!(parse(&ok, 10).unwrap().0.len(), 3);
        let at = |bytes: &[u8], body: usize, off: usize, word: &str| {
            let e = err(bytes);
            let want = format!("{F}: at byte {}: ", body + off);
            assert!(
                e.starts_with(&want) && e.contains(word),
                "{e}, want {want} {word}"
            );
        };
        // uniform triangles (the parallel path) and polygons (record by record)
        for quad in [false, true] {
            let second: &[f64] = if quad {
                &[0.0, 2.0, 3.0, 1.0]
            } else {
                &[0.0, 2.0, 3.0]
            };
            let (b, body) = binary(
                big,
                &v,
                &[&[0.0, 1.0, 2.0], &[0.0, 2.0, 4.0, 1.0][..second.len()]],
                &[],
            );
            at(
                &b,
                body,
                vbytes + 13 + 1 + 8,
                "face 1: vertex index 4 is out of range",
            );
            let (b, body) = binary(big, &v, &[&[0.0, 1.0, 2.0], second], &[7]);
            at(
                &b,
                body,
                vbytes + 13 + 1 + 4 * second.len(),
                "1 byte after the last element",
            );
            let (b, body) = binary(big, &v, &[&[0.0, 1.0, 2.0], second], &[]);
            let cut = &b[..b.len() - 1];
            if quad {
                at(
                    cut,
                    body,
                    cut.len() - body,
                    "face 1: the file ends within this record",
                );
            } else {
                // every record has its full size: the header check finds it
                let e = err(cut);
                assert!(e.starts_with(&format!("{F}:8: 2 'face' records")), "{e}");
            }
        }
        let mut nan = v;
        nan[2][1] = f64::NAN;
        let (b, body) = binary(big, &nan, &[&[0.0, 1.0, 2.0]], &[]);
        at(&b, body, 2 * 12 + 4, "vertex 2: y is NaN");
        let mut inf = v;
        inf[3][0] = f64::NEG_INFINITY;
        let (b, body) = binary(big, &inf, &[&[0.0, 1.0, 2.0]], &[]);
        at(&b, body, 3 * 12, "vertex 3: x is infinite");
        let long = [0.0, 1.0, 2.0, 3.0, 0.0, 1.0];
        let (b, body) = binary(big, &v, &[&[0.0, 1.0, 2.0], &[0.0, 1.0], &long], &[]);
        at(
            &b,
            body,
            vbytes + 13,
            "face 1: a face needs at least 3 vertices, got 2",
        );
        let (b, body) = binary(big, &v, &[&[0.0, 1.0, 2.0, 3.0, 0.0]], &[]);
        let e = parse(&b, 2).unwrap_err().to_string();
        assert!(e.starts_with(&format!("{F}: at byte {}: face 0: too many", body + vbytes)));
    }
}

#[test]
fn degenerate_triangles_are_kept_and_counted() {
    let v = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [2.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
    ];
    for big in [false, true] {
        let (b, _) = binary(
            big,
            &v,
            &[&[0.0, 1.0, 2.0], &[0.0, 1.0, 3.0], &[3.0, 3.0, 1.0]],
            &[],
        );
        let (mesh, zero) = parse(&b, 10).unwrap();
        assert_eq!((mesh.len(), zero), (3, 2));
        assert_eq!(mesh.faces[1], [0, 1, 3]);
    }
}
