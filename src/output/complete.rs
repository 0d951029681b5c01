//! Whether an output file already on disk is whole: what `--skip-existing` asks of every output
//! of a view before it leaves the view out. A file counts only when its header is the one this
//! run would write and its length the one that header implies (a 0-byte file, a write cut
//! short, a file of another size all fail); the pixels themselves are not read.

use super::ImageFormat;
use std::fs::File;
use std::io::{Read, Seek, SeekFrom};
use std::path::Path;

/// What a file must hold to be whole for a `width` x `height` view.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Expected {
    /// An image, PNG or BMP by the extension.
    Image,
    /// A `.npy` array of `<i4` (ids) or `<f4` (depths, z-depths, normals) with this many values
    /// a pixel: 1, shape (height, width), or 3, shape (height, width, 3).
    Npy(&'static str, usize),
}

/// Whether `path` is a whole file of `what` for a `width` x `height` view. Any error reading
/// it (missing, unreadable, a folder) means no.
pub(crate) fn is_complete(path: &Path, what: Expected, width: u32, height: u32) -> bool {
    let Ok(mut file) = File::open(path) else {
        return false;
    };
    let Ok(meta) = file.metadata() else {
        return false;
    };
    if !meta.is_file() {
        return false;
    }
    let len = meta.len();
    match what {
        Expected::Npy(descr, per_pixel) => {
            npy_complete(&mut file, len, (descr, per_pixel), width, height)
        }
        Expected::Image => match super::image_format(path) {
            Ok(ImageFormat::Png) => png_complete(&mut file, len, width, height),
            Ok(ImageFormat::Bmp) => bmp_complete(&mut file, len, width, height),
            Err(_) => Ok(false),
        },
    }
    .unwrap_or(false)
}

/// The `.npy` header lanecast writes for this shape, then exactly 4 bytes per value.
fn npy_complete(
    f: &mut File,
    len: u64,
    (descr, per_pixel): (&str, usize),
    w: u32,
    h: u32,
) -> std::io::Result<bool> {
    let header = match per_pixel {
        1 => super::npy::npy_header(descr, w as usize, h as usize),
        _ => super::npy::npy3_header(descr, w as usize, h as usize),
    };
    if len != header.len() as u64 + 4 * per_pixel as u64 * w as u64 * h as u64 {
        return Ok(false);
    }
    let mut got = vec![0; header.len()];
    f.read_exact(&mut got)?;
    Ok(got == header)
}

/// The PNG signature, an `IHDR` chunk of this size first, then chunk after chunk (length, type,
/// data, CRC) to an `IEND` that ends the file exactly.
fn png_complete(f: &mut File, len: u64, w: u32, h: u32) -> std::io::Result<bool> {
    let mut sig = [0; 8];
    f.read_exact(&mut sig)?;
    if &sig != b"\x89PNG\r\n\x1a\n" {
        return Ok(false);
    }
    let mut at = 8u64;
    let mut first = true;
    while at + 12 <= len {
        let mut head = [0; 8];
        f.seek(SeekFrom::Start(at))?;
        f.read_exact(&mut head)?;
        let size = u32::from_be_bytes(head[..4].try_into().expect("4 bytes")) as u64;
        let kind = &head[4..];
        if first {
            let mut ihdr = [0; 8];
            f.read_exact(&mut ihdr)?;
            let size_ok = ihdr == [w.to_be_bytes(), h.to_be_bytes()].concat()[..];
            if kind != b"IHDR" || size != 13 || !size_ok {
                return Ok(false);
            }
            first = false;
        }
        at += 12 + size;
        if kind == b"IEND" {
            return Ok(size == 0 && at == len);
        }
    }
    Ok(false)
}

/// `BM`, the file size field equal to the length, a 24-bit header of this size, and the
/// pixel rows (each padded to 4 bytes) ending the file exactly.
fn bmp_complete(f: &mut File, len: u64, w: u32, h: u32) -> std::io::Result<bool> {
    let mut head = [0; 30];
    f.read_exact(&mut head)?;
    let u32_at = |i: usize| u32::from_le_bytes(head[i..i + 4].try_into().expect("4 bytes"));
    let i32_at = |i: usize| i32::from_le_bytes(head[i..i + 4].try_into().expect("4 bytes"));
    let bpp = u16::from_le_bytes([head[28], head[29]]);
    let row = (3 * w as u64).div_ceil(4) * 4;
    Ok(&head[..2] == b"BM"
        && u32_at(2) as u64 == len
        && i32_at(18) == w as i32
        && i32_at(22).unsigned_abs() == h
        && bpp == 24
        && u32_at(10) as u64 + row * h as u64 == len)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::tests::TestDir;
    use std::fs;

    /// Each format's whole file counts; every shorter prefix, and the same file for another
    /// size, does not.
    #[test]
    fn whole_files_count_and_cut_or_resized_ones_do_not() {
        let dir = TestDir::new("complete");
        let (w, h) = (5, 3);
        let rgb: Vec<u8> = (0..w * h * 3).map(|i| i as u8).collect();
        let ids: Vec<i32> = (0..(w * h) as i32).collect();
        let mut cases = Vec::new();
        for (name, format) in [("a.png", ImageFormat::Png), ("a.bmp", ImageFormat::Bmp)] {
            let mut bytes = Vec::new();
            crate::output::encode_image(&mut bytes, format, w, h, &rgb).unwrap();
            cases.push((name, Expected::Image, bytes));
        }
        cases.push((
            "a.npy",
            Expected::Npy("<i4", 1),
            crate::output::npy_i32(w, h, &ids),
        ));
        let normals: Vec<[f32; 3]> = (0..w * h).map(|i| [i as f32, 0.5, -1.0]).collect();
        cases.push((
            "n.npy",
            Expected::Npy("<f4", 3),
            crate::output::npy_f32x3(w, h, &normals),
        ));
        for (name, what, bytes) in cases {
            let path = dir.0.join(name);
            fs::write(&path, &bytes).unwrap();
            assert!(is_complete(&path, what, w, h), "{name}");
            assert!(
                !is_complete(&path, what, w + 1, h),
                "{name} at another width"
            );
            assert!(
                !is_complete(&path, what, w, h + 1),
                "{name} at another height"
            );
            // another dtype, or one value a pixel where three are due (and back)
            if let Expected::Npy(descr, per_pixel) = what {
                let other = if descr == "<i4" { "<f4" } else { "<i4" };
                assert!(
                    !is_complete(&path, Expected::Npy(other, per_pixel), w, h),
                    "{name}: dtype"
                );
                assert!(
                    !is_complete(&path, Expected::Npy(descr, 4 - per_pixel), w, h),
                    "{name}: values a pixel"
                );
            }
            for cut in 0..bytes.len() {
                fs::write(&path, &bytes[..cut]).unwrap();
                assert!(!is_complete(&path, what, w, h), "{name} cut to {cut} bytes");
            }
            let mut longer = bytes.clone();
            longer.push(0);
            fs::write(&path, &longer).unwrap();
            assert!(!is_complete(&path, what, w, h), "{name} with a byte more");
        }
        assert!(!is_complete(
            &dir.0.join("missing.png"),
            Expected::Image,
            w,
            h
        ));
        assert!(!is_complete(&dir.0, Expected::Image, w, h));
    }
}
