//! A PLY writer for the tests: any elements in any order, any property types (aliases
//! included), lists, ASCII or binary in either byte order; and the same data as Wavefront OBJ
//! text, for the OBJ reader to give the mesh to compare with.
#![allow(dead_code)]

use std::fmt::Write as _;

/// How the body is written.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Encoding {
    Ascii,
    Little,
    Big,
}

pub const ENCODINGS: [Encoding; 3] = [Encoding::Ascii, Encoding::Little, Encoding::Big];

/// Every type name PLY spells, aliases included.
pub const TYPES: [&str; 16] = [
    "char", "uchar", "short", "ushort", "int", "uint", "float", "double", "int8", "uint8", "int16",
    "uint16", "int32", "uint32", "float32", "float64",
];

/// The integer type names.
pub const INT_TYPES: [&str; 12] = [
    "char", "uchar", "short", "ushort", "int", "uint", "int8", "uint8", "int16", "uint16", "int32",
    "uint32",
];

/// A property: `count` is the list count type, `None` for a scalar.
#[derive(Clone, Debug)]
pub struct Prop {
    pub name: String,
    pub ty: &'static str,
    pub count: Option<&'static str>,
}

pub fn scalar(name: &str, ty: &'static str) -> Prop {
    Prop {
        name: name.into(),
        ty,
        count: None,
    }
}

pub fn list(name: &str, count: &'static str, ty: &'static str) -> Prop {
    Prop {
        name: name.into(),
        ty,
        count: Some(count),
    }
}

/// An element: each record holds one value list per property (one value for a scalar).
#[derive(Clone, Debug)]
pub struct Elem {
    pub name: String,
    pub props: Vec<Prop>,
    pub records: Vec<Vec<Vec<f64>>>,
}

/// The smallest and largest value of an integer type, or `None` for a float type.
pub fn int_range(ty: &str) -> Option<(i64, i64)> {
    Some(match ty {
        "char" | "int8" => (-128, 127),
        "uchar" | "uint8" => (0, 255),
        "short" | "int16" => (-32768, 32767),
        "ushort" | "uint16" => (0, 65535),
        "int" | "int32" => (i32::MIN.into(), i32::MAX.into()),
        "uint" | "uint32" => (0, u32::MAX.into()),
        _ => return None,
    })
}

/// Appends `v` as type `ty` in the byte order `big`; panics unless `v` is exact in `ty`.
pub fn put(out: &mut Vec<u8>, ty: &str, big: bool, v: f64) {
    macro_rules! put {
        ($t:ty) => {{
            let x = v as $t;
            assert!(x as f64 == v || v.is_nan(), "{v} is not a {ty}");
            out.extend(if big {
                x.to_be_bytes()
            } else {
                x.to_le_bytes()
            })
        }};
    }
    match ty {
        "char" | "int8" => put!(i8),
        "uchar" | "uint8" => put!(u8),
        "short" | "int16" => put!(i16),
        "ushort" | "uint16" => put!(u16),
        "int" | "int32" => put!(i32),
        "uint" | "uint32" => put!(u32),
        "float" | "float32" => put!(f32),
        "double" | "float64" => put!(f64),
        _ => panic!("unknown type {ty}"),
    }
}

/// `v` as ASCII PLY writes it: integers plainly, floats as f64's shortest exact form.
fn text(v: f64) -> String {
    if v.is_nan() {
        "nan".into()
    } else {
        format!("{v}")
    }
}

/// The PLY file of `elems`, with `comments` as comment lines, and `eol` ending every line.
pub fn ply(enc: Encoding, elems: &[Elem], comments: &[&str], eol: &str) -> Vec<u8> {
    let format = match enc {
        Encoding::Ascii => "ascii",
        Encoding::Little => "binary_little_endian",
        Encoding::Big => "binary_big_endian",
    };
    let mut h = format!("ply{eol}format {format} 1.0{eol}");
    for c in comments {
        write!(h, "comment {c}{eol}").unwrap();
    }
    for e in elems {
        write!(h, "element {} {}{eol}", e.name, e.records.len()).unwrap();
        for p in &e.props {
            match p.count {
                None => write!(h, "property {} {}{eol}", p.ty, p.name).unwrap(),
                Some(c) => write!(h, "property list {c} {} {}{eol}", p.ty, p.name).unwrap(),
            }
        }
    }
    write!(h, "end_header{eol}").unwrap();
    let mut out = h.into_bytes();
    for e in elems {
        for r in &e.records {
            assert_eq!(r.len(), e.props.len(), "one value list per property");
            match enc {
                Encoding::Ascii => {
                    let mut line = Vec::new();
                    for (p, vals) in e.props.iter().zip(r) {
                        if p.count.is_some() {
                            line.push(vals.len().to_string());
                        }
                        line.extend(vals.iter().map(|&v| text(v)));
                    }
                    out.extend(line.join(" ").bytes());
                    out.extend(eol.bytes());
                }
                Encoding::Little | Encoding::Big => {
                    let big = enc == Encoding::Big;
                    for (p, vals) in e.props.iter().zip(r) {
                        if let Some(c) = p.count {
                            put(&mut out, c, big, vals.len() as f64);
                        }
                        for &v in vals {
                            put(&mut out, p.ty, big, v);
                        }
                    }
                }
            }
        }
    }
    out
}

/// A plain mesh element pair: `vertex` with x, y, z of type `ty`, `face` with a `uchar` count
/// and `int` indices.
pub fn mesh_elems(verts: &[[f64; 3]], faces: &[Vec<u32>], ty: &'static str) -> Vec<Elem> {
    vec![
        Elem {
            name: "vertex".into(),
            props: vec![scalar("x", ty), scalar("y", ty), scalar("z", ty)],
            records: verts
                .iter()
                .map(|v| v.iter().map(|&c| vec![c]).collect())
                .collect(),
        },
        Elem {
            name: "face".into(),
            props: vec![list("vertex_indices", "uchar", "int")],
            records: faces
                .iter()
                .map(|f| vec![f.iter().map(|&i| i as f64).collect()])
                .collect(),
        },
    ]
}

/// The same vertices and faces (0-based) as OBJ text.
pub fn obj(verts: &[[f64; 3]], faces: &[Vec<u32>]) -> String {
    let mut t = String::from("# written by the PLY tests\n");
    for [x, y, z] in verts {
        writeln!(t, "v {x} {y} {z}").unwrap();
    }
    for f in faces {
        t.push('f');
        for i in f {
            write!(t, " {}", i + 1).unwrap();
        }
        t.push('\n');
    }
    t
}
