//! NumPy `.npy` files (format 1.0): the id and depth buffers, little-endian, C order.

use std::fs::File;
use std::io::{self, BufWriter, Write};
use std::path::Path;

use super::write_atomic_with;
use crate::{Error, Result};

/// The `.npy` (format 1.0) header for a C-order `(height, width)` array of `descr` elements.
/// Magic, version, u16 length and dict together are padded with spaces to a multiple of 64
/// bytes and end in `\n`, as NumPy itself writes them.
pub(super) fn npy_header(descr: &str, width: usize, height: usize) -> Vec<u8> {
    npy_header_shape(descr, &format!("({height}, {width})"))
}

/// The `.npy` header for a C-order `(height, width, 3)` array: three values a pixel (normals).
pub(super) fn npy3_header(descr: &str, width: usize, height: usize) -> Vec<u8> {
    npy_header_shape(descr, &format!("({height}, {width}, 3)"))
}

/// The `.npy` header for an array of `shape`, as Python writes the tuple.
fn npy_header_shape(descr: &str, shape: &str) -> Vec<u8> {
    let dict = format!("{{'descr': '{descr}', 'fortran_order': False, 'shape': {shape}, }}");
    let unpadded = 10 + dict.len() + 1; // magic (6) + version (2) + length (2) + dict + '\n'
    let total = unpadded.div_ceil(64) * 64;
    let header_len = (total - 10) as u16; // the dict is < 100 bytes: always fits
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"\x93NUMPY\x01\x00");
    out.extend_from_slice(&header_len.to_le_bytes());
    out.extend_from_slice(dict.as_bytes());
    out.resize(total - 1, b' ');
    out.push(b'\n');
    out
}

/// Writes `data` as little-endian 4-byte values, in chunks to bound the staging buffer.
fn write_le<T: Copy>(w: &mut impl Write, data: &[T], le: impl Fn(T) -> [u8; 4]) -> io::Result<()> {
    let mut buf = Vec::with_capacity(4 * 16384);
    for chunk in data.chunks(16384) {
        buf.clear();
        buf.extend(chunk.iter().flat_map(|&v| le(v)));
        w.write_all(&buf)?;
    }
    Ok(())
}

/// A complete `.npy` file for a `height` x `width` array of i32, row-major.
/// Panics if `data.len() != width * height`.
pub fn npy_i32(width: u32, height: u32, data: &[i32]) -> Vec<u8> {
    npy_bytes(
        "<i4",
        width as usize,
        height as usize,
        data,
        i32::to_le_bytes,
    )
}

/// A complete `.npy` file for a `height` x `width` array of f32, row-major.
/// Panics if `data.len() != width * height`.
pub fn npy_f32(width: u32, height: u32, data: &[f32]) -> Vec<u8> {
    npy_bytes(
        "<f4",
        width as usize,
        height as usize,
        data,
        f32::to_le_bytes,
    )
}

fn npy_bytes<T: Copy>(
    descr: &str,
    w: usize,
    h: usize,
    data: &[T],
    le: impl Fn(T) -> [u8; 4],
) -> Vec<u8> {
    assert_eq!(data.len(), w * h, "npy data does not match its shape");
    let mut out = npy_header(descr, w, h);
    write_le(&mut out, data, le).expect("writing to a Vec cannot fail");
    out
}

/// The writer of a `.npy` file, streamed, never built whole in memory; the shape is checked
/// before any file is touched.
pub(super) fn npy_fill<'a, T: Copy>(
    path: &Path,
    descr: &'a str,
    (width, height): (usize, usize),
    data: &'a [T],
    le: impl Fn(T) -> [u8; 4] + 'a,
) -> Result<impl FnOnce(&mut BufWriter<File>) -> io::Result<()> + 'a> {
    if width.checked_mul(height) != Some(data.len()) {
        return Err(Error::Failed(format!(
            "{}: internal error: {} values for a {width}x{height} array",
            path.display(),
            data.len()
        )));
    }
    Ok(move |w: &mut BufWriter<File>| {
        w.write_all(&npy_header(descr, width, height))?;
        write_le(w, data, le)
    })
}

/// A complete `.npy` file for a `height` x `width` x 3 array of f32 (three values a pixel,
/// row-major: the `--normals` file). Panics if `data.len() != width * height`.
pub fn npy_f32x3(width: u32, height: u32, data: &[[f32; 3]]) -> Vec<u8> {
    assert_eq!(
        data.len(),
        width as usize * height as usize,
        "npy data does not match its shape"
    );
    let mut out = npy3_header("<f4", width as usize, height as usize);
    write_le(&mut out, data.as_flattened(), f32::to_le_bytes)
        .expect("writing to a Vec cannot fail");
    out
}

/// The writer of a `(height, width, 3)` f32 `.npy` file, as [`npy_fill`].
pub(super) fn npy3_fill<'a>(
    path: &Path,
    (width, height): (usize, usize),
    data: &'a [[f32; 3]],
) -> Result<impl FnOnce(&mut BufWriter<File>) -> io::Result<()> + 'a> {
    if width.checked_mul(height) != Some(data.len()) {
        return Err(Error::Failed(format!(
            "{}: internal error: {} normals for a {width}x{height} array",
            path.display(),
            data.len()
        )));
    }
    Ok(move |w: &mut BufWriter<File>| {
        w.write_all(&npy3_header("<f4", width, height))?;
        write_le(w, data.as_flattened(), f32::to_le_bytes)
    })
}

/// Shared by the `write_npy_*` functions.
fn write_npy<T: Copy>(
    path: &Path,
    descr: &str,
    shape: (usize, usize),
    data: &[T],
    le: impl Fn(T) -> [u8; 4],
) -> Result<()> {
    write_atomic_with(path, npy_fill(path, descr, shape, data, le)?)
}

/// Writes a `height` x `width` i32 array as `.npy`, atomically.
pub fn write_npy_i32(path: &Path, width: u32, height: u32, data: &[i32]) -> Result<()> {
    write_npy(
        path,
        "<i4",
        (width as usize, height as usize),
        data,
        i32::to_le_bytes,
    )
}

/// Writes a `height` x `width` f32 array as `.npy`, atomically.
pub fn write_npy_f32(path: &Path, width: u32, height: u32, data: &[f32]) -> Result<()> {
    write_npy(
        path,
        "<f4",
        (width as usize, height as usize),
        data,
        f32::to_le_bytes,
    )
}

/// Writes a `height` x `width` x 3 f32 array (three values a pixel, row-major) as `.npy`,
/// atomically: the `--normals` file, byte for byte ([`npy_f32x3`]; `Frame::write_normals`).
pub fn write_npy_f32x3(path: &Path, width: u32, height: u32, data: &[[f32; 3]]) -> Result<()> {
    write_atomic_with(
        path,
        npy3_fill(path, (width as usize, height as usize), data)?,
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::tests::TestDir;
    use std::fs;

    #[test]
    fn npy_header_exact_bytes() {
        let bytes = npy_i32(3, 2, &[1, -1, 2, 3, 0x0102_0304, 5]);
        // 10 bytes of preamble + 59 of dict + '\n' = 70: padded to 128.
        let dict = b"{'descr': '<i4', 'fortran_order': False, 'shape': (2, 3), }";
        assert_eq!(dict.len(), 59);
        assert_eq!(&bytes[..8], b"\x93NUMPY\x01\x00");
        assert_eq!(u16::from_le_bytes([bytes[8], bytes[9]]), 128 - 10);
        assert_eq!(&bytes[10..69], dict);
        assert!(bytes[69..127].iter().all(|&b| b == b' '));
        assert_eq!(bytes[127], b'\n');
        let data = &bytes[128..];
        assert_eq!(data.len(), 24);
        assert_eq!(&data[..8], &[1, 0, 0, 0, 0xFF, 0xFF, 0xFF, 0xFF]);
        assert_eq!(&data[16..20], &[4, 3, 2, 1]);

        let f = npy_f32(1, 1, &[1.5]);
        assert_eq!(f.len(), 128 + 4);
        let text = String::from_utf8_lossy(&f[10..128]);
        assert!(text.starts_with("{'descr': '<f4', 'fortran_order': False, 'shape': (1, 1), }"));
        assert_eq!(&f[128..], &1.5f32.to_le_bytes());
        // Long shapes still pad to a multiple of 64.
        for (w, h) in [(65_536, 4096), (0, 0), (12345, 1)] {
            let header = npy_header("<i4", w, h);
            assert_eq!(header.len() % 64, 0);
            assert_eq!(*header.last().unwrap(), b'\n');
            assert_eq!(
                usize::from(u16::from_le_bytes([header[8], header[9]])),
                header.len() - 10
            );
        }
    }

    #[test]
    fn write_npy_files_match_in_memory_encoding() {
        let dir = TestDir::new("npy");
        let (ids, depth) = ([7, -1, 3, 9], [1.0, f32::INFINITY, 2.5, 0.125]);
        let (ids_path, depth_path) = (dir.0.join("ids.npy"), dir.0.join("depth.npy"));
        write_npy_i32(&ids_path, 2, 2, &ids).unwrap();
        write_npy_f32(&depth_path, 2, 2, &depth).unwrap();
        assert_eq!(fs::read(ids_path).unwrap(), npy_i32(2, 2, &ids));
        assert_eq!(fs::read(depth_path).unwrap(), npy_f32(2, 2, &depth));
        assert!(write_npy_i32(&dir.0.join("bad.npy"), 3, 2, &ids).is_err());
        assert_eq!(dir.entries(), ["depth.npy", "ids.npy"]);
    }
}
