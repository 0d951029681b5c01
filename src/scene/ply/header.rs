//! The PLY header: `ply`, one `format` line, `comment` / `obj_info` lines, and `element` lines
//! each followed by its `property` lines, up to `end_header` (see `ply.rs` for the format).
//! [`parse`] reads it into a [`Header`], checks what the mesh needs (a `vertex` element with
//! scalar `x`, `y`, `z`; a `face` element with an integer list `vertex_indices` or
//! `vertex_index`), and checks that the bytes after it can hold the records it declares, before
//! anything is allocated for them.

use crate::error::Error;
use crate::limits::MAX_LINE_BYTES;
use std::path::Path;

/// A property's value type. The names and their aliases, with sizes in bytes: `char`/`int8`
/// (1), `uchar`/`uint8` (1), `short`/`int16` (2), `ushort`/`uint16` (2), `int`/`int32` (4),
/// `uint`/`uint32` (4), `float`/`float32` (4), `double`/`float64` (8).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Type {
    I8,
    U8,
    I16,
    U16,
    I32,
    U32,
    F32,
    F64,
}

impl Type {
    fn parse(name: &str) -> Option<Type> {
        Some(match name {
            "char" | "int8" => Type::I8,
            "uchar" | "uint8" => Type::U8,
            "short" | "int16" => Type::I16,
            "ushort" | "uint16" => Type::U16,
            "int" | "int32" => Type::I32,
            "uint" | "uint32" => Type::U32,
            "float" | "float32" => Type::F32,
            "double" | "float64" => Type::F64,
            _ => return None,
        })
    }

    /// Size in a binary body, in bytes.
    pub fn size(self) -> usize {
        match self {
            Type::I8 | Type::U8 => 1,
            Type::I16 | Type::U16 => 2,
            Type::I32 | Type::U32 | Type::F32 => 4,
            Type::F64 => 8,
        }
    }

    pub fn is_int(self) -> bool {
        !matches!(self, Type::F32 | Type::F64)
    }

    /// The smallest and largest value of an integer type.
    pub fn int_range(self) -> (i64, i64) {
        match self {
            Type::I8 => (i8::MIN.into(), i8::MAX.into()),
            Type::U8 => (0, u8::MAX.into()),
            Type::I16 => (i16::MIN.into(), i16::MAX.into()),
            Type::U16 => (0, u16::MAX.into()),
            Type::I32 => (i32::MIN.into(), i32::MAX.into()),
            Type::U32 => (0, u32::MAX.into()),
            Type::F32 | Type::F64 => (i64::MIN, i64::MAX),
        }
    }

    /// The name the header spells it with (the short one).
    pub fn name(self) -> &'static str {
        match self {
            Type::I8 => "char",
            Type::U8 => "uchar",
            Type::I16 => "short",
            Type::U16 => "ushort",
            Type::I32 => "int",
            Type::U32 => "uint",
            Type::F32 => "float",
            Type::F64 => "double",
        }
    }
}

/// A property: one value, or a list (a count, then that many items).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    Scalar(Type),
    List { count: Type, item: Type },
}

#[derive(Debug)]
pub struct Property {
    pub name: String,
    pub kind: Kind,
}

#[derive(Debug)]
pub struct Element {
    pub name: String,
    /// How many records (at most the body's size, once [`parse`] has checked it).
    pub count: usize,
    pub props: Vec<Property>,
    /// The header line of its `element` statement.
    pub line: usize,
}

impl Element {
    /// The size of every record in a binary body when all properties are scalars.
    pub fn fixed_size(&self) -> Option<usize> {
        (self.props.iter())
            .map(|p| match p.kind {
                Kind::Scalar(t) => Some(t.size()),
                Kind::List { .. } => None,
            })
            .sum()
    }

    /// Where property `k` starts in a binary record, when every property before it is a scalar.
    pub fn offset(&self, k: usize) -> Option<usize> {
        (self.props[..k].iter())
            .map(|p| match p.kind {
                Kind::Scalar(t) => Some(t.size()),
                Kind::List { .. } => None,
            })
            .sum()
    }
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    Ascii,
    /// Binary, little-endian (`big: false`) or big-endian.
    Binary {
        big: bool,
    },
}

/// A checked header.
#[derive(Debug)]
pub struct Header {
    pub format: Format,
    pub elements: Vec<Element>,
    /// Where the body starts: just after the `\n` that ends `end_header`.
    pub body: usize,
    /// How many lines the header has: the body's first line is the next one.
    pub lines: usize,
    /// Which element is `vertex`, and the indices of its `x`, `y`, `z` properties.
    pub vertex: usize,
    pub xyz: [usize; 3],
    /// Which element is `face`, and the index of its vertex index list.
    pub face: usize,
    pub list: usize,
}

impl Header {
    /// How many vertices the file declares.
    pub fn vertices(&self) -> usize {
        self.elements[self.vertex].count
    }
}

/// Reads and checks the header at the start of `bytes` (the file `path`).
pub fn parse(bytes: &[u8], path: &Path) -> Result<Header, Error> {
    let mut format = None;
    let mut elements: Vec<Element> = Vec::new();
    let (mut pos, mut line) = (0, 0);
    let body = loop {
        if pos >= bytes.len() && line > 0 {
            let msg = "the header has no end_header line";
            return Err(Error::input(path, line, 0, msg));
        }
        let end = (bytes[pos..].iter().position(|&b| b == b'\n')).map_or(bytes.len(), |k| pos + k);
        let raw = bytes[pos..end]
            .strip_suffix(b"\r")
            .unwrap_or(&bytes[pos..end]);
        pos = (end + 1).min(bytes.len());
        line += 1;
        let err = |msg: String| Error::input(path, line, 0, msg);
        if line == 1 {
            if raw.trim_ascii_end() != b"ply" {
                return Err(err("not a PLY file: the first line must be 'ply'".into()));
            }
            continue;
        }
        if raw.len() > MAX_LINE_BYTES {
            let n = raw.len();
            return Err(err(format!(
                "header line is {n} bytes long; the limit is {MAX_LINE_BYTES}"
            )));
        }
        let word = raw.split(|b| b.is_ascii_whitespace()).next().unwrap_or(b"");
        if word == b"comment" || word == b"obj_info" {
            continue; // free text, any bytes
        }
        // printable ASCII and tabs: anything else is most likely a binary body
        let text = std::str::from_utf8(raw)
            .ok()
            .filter(|t| t.bytes().all(|b| b == b'\t' || (b' '..=b'~').contains(&b)))
            .ok_or_else(|| err("the header is not ASCII text (is end_header missing?)".into()))?;
        let toks: Vec<&str> = text.split_ascii_whitespace().collect();
        match toks.as_slice() {
            [] => return Err(err("blank line in the header".into())),
            ["format", name, version] => {
                if format.is_some() {
                    return Err(err("a second format line".into()));
                }
                format = Some(match *name {
                    "ascii" => Format::Ascii,
                    "binary_little_endian" => Format::Binary { big: false },
                    "binary_big_endian" => Format::Binary { big: true },
                    _ => {
                        return Err(err(format!(
                            "unknown format '{}' (expected ascii, binary_little_endian or \
                             binary_big_endian)",
                            clip(name)
                        )));
                    }
                });
                if *version != "1.0" {
                    let v = clip(version);
                    return Err(err(format!("PLY version '{v}' (lanecast reads 1.0)")));
                }
            }
            ["format", ..] => return Err(err("expected 'format FORMAT 1.0'".into())),
            ["element", name, count] => {
                if elements.iter().any(|e| e.name == *name) {
                    return Err(err(format!("a second '{}' element", clip(name))));
                }
                let count = (count.bytes().all(|b| b.is_ascii_digit()))
                    .then(|| count.parse::<u64>().ok())
                    .flatten()
                    .ok_or_else(|| err(format!("'{}' is not an element count", clip(count))))?;
                elements.push(Element {
                    name: name.to_string(),
                    // a count past the address space cannot fit in the file: `usize::MAX`
                    // keeps it refused by `check_sizes`
                    count: usize::try_from(count).unwrap_or(usize::MAX),
                    props: Vec::new(),
                    line,
                });
            }
            ["element", ..] => return Err(err("expected 'element NAME COUNT'".into())),
            ["property", rest @ ..] => {
                let Some(el) = elements.last_mut() else {
                    return Err(err("a property before any element".into()));
                };
                let (kind, name) = property(rest).map_err(err)?;
                if el.props.iter().any(|p| p.name == name) {
                    let msg = format!("a second property '{}' in element '{}'", name, el.name);
                    return Err(err(msg));
                }
                el.props.push(Property {
                    name: name.to_string(),
                    kind,
                });
            }
            ["end_header"] => break pos,
            [word, ..] => {
                return Err(err(format!("unknown header keyword '{}'", clip(word))));
            }
        }
    };
    let err = |line: usize, msg: String| Error::input(path, line, 0, msg);
    let Some(format) = format else {
        return Err(err(line, "the header has no format line".into()));
    };
    for e in &elements {
        if e.props.is_empty() && e.count > 0 {
            let msg = format!("element '{}' has records but no properties", e.name);
            return Err(err(e.line, msg));
        }
    }
    let find = |name: &str| elements.iter().position(|e| e.name == name);
    let vertex = find("vertex").ok_or_else(|| err(line, "no 'vertex' element".into()))?;
    let v = &elements[vertex];
    let mut xyz = [0; 3];
    for (k, axis) in ["x", "y", "z"].into_iter().enumerate() {
        let p = (v.props.iter().position(|p| p.name == axis))
            .ok_or_else(|| err(v.line, format!("element 'vertex' has no property '{axis}'")))?;
        if let Kind::List { .. } = v.props[p].kind {
            return Err(err(v.line, format!("vertex property '{axis}' is a list")));
        }
        xyz[k] = p;
    }
    let no_faces = "no 'face' element (lanecast renders faces, not point clouds)";
    let face = find("face").ok_or_else(|| err(line, no_faces.into()))?;
    let f = &elements[face];
    let list = (f.props.iter())
        .position(|p| p.name == "vertex_indices" || p.name == "vertex_index")
        .ok_or_else(|| {
            let msg = "element 'face' has no list 'vertex_indices' (or 'vertex_index')";
            err(f.line, msg.into())
        })?;
    match f.props[list].kind {
        Kind::List { item, .. } if item.is_int() => {}
        Kind::List { item, .. } => {
            let msg = format!("face vertex indices must be integers, not {}", item.name());
            return Err(err(f.line, msg));
        }
        Kind::Scalar(_) => {
            let name = &f.props[list].name;
            return Err(err(f.line, format!("face property '{name}' is not a list")));
        }
    }
    let header = Header {
        format,
        elements,
        body,
        lines: line,
        vertex,
        xyz,
        face,
        list,
    };
    check_sizes(&header, bytes.len() - body, path)?;
    Ok(header)
}

/// `property TYPE NAME` or `property list COUNT_TYPE ITEM_TYPE NAME`, after `property`.
fn property<'a>(toks: &[&'a str]) -> Result<(Kind, &'a str), String> {
    let ty = |name: &str| {
        Type::parse(name).ok_or_else(|| format!("unknown property type '{}'", clip(name)))
    };
    match toks {
        ["list", count, item, name] => {
            let count = ty(count)?;
            if !count.is_int() {
                let t = count.name();
                return Err(format!("a list count must be an integer type, not {t}"));
            }
            Ok((
                Kind::List {
                    count,
                    item: ty(item)?,
                },
                name,
            ))
        }
        ["list", ..] => Err("expected 'property list COUNT_TYPE ITEM_TYPE NAME'".into()),
        [t, name] => Ok((Kind::Scalar(ty(t)?), name)),
        _ => Err("expected 'property TYPE NAME'".into()),
    }
}

/// The fewest bytes a record of `e` takes: in binary, its scalars and list counts (and the
/// face list's 3 indices); in ASCII, a character and a separator for each of those values.
pub fn min_record(h: &Header, e: usize) -> usize {
    let el = &h.elements[e];
    let mut n = 0;
    for (k, p) in el.props.iter().enumerate() {
        let (size, items, item_size) = match p.kind {
            Kind::Scalar(t) => (t.size(), 0, 0),
            Kind::List { count, item } => {
                let items = if e == h.face && k == h.list { 3 } else { 0 };
                (count.size(), items, item.size())
            }
        };
        n += match h.format {
            Format::Binary { .. } => size + items * item_size,
            Format::Ascii => 2 * (1 + items),
        };
    }
    n
}

/// Refuses, at its `element` line, the first element whose records cannot fit in what the
/// `len` bytes of the body leave after the elements before it (each at its smallest).
fn check_sizes(h: &Header, len: usize, path: &Path) -> Result<(), Error> {
    // an ASCII body's last line needs no line end
    let mut left = (len as u128) + u128::from(h.format == Format::Ascii);
    for (e, el) in h.elements.iter().enumerate() {
        let min = min_record(h, e) as u128;
        let need = min * el.count as u128;
        if need > left {
            let msg = format!(
                "{} '{}' records of at least {min} bytes need {need} bytes, but only {} are left \
                 after the header and the elements before (is the file cut short?)",
                el.count,
                el.name,
                left.min(len as u128)
            );
            return Err(Error::input(path, el.line, 0, msg));
        }
        left -= need;
    }
    Ok(())
}

/// A token as quoted in a message: at most 40 characters.
pub fn clip(t: &str) -> String {
    match t.char_indices().nth(40) {
        Some((k, _)) => format!("{}...", &t[..k]),
        None => t.to_string(),
    }
}
