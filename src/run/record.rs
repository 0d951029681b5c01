//! The record of a view of a many-view run: which scene, camera, size, precision and output
//! settings made its files, and each file's length and fingerprint. `--skip-existing` leaves a
//! view out only when its record says this run would make the files it finds, byte for byte;
//! any other view is rendered again (README "Many views").
//!
//! The record is a small text file beside the view's first output, named after it
//! (`frames/f03.png` -> `frames/.f03.png.lanecast-view`), written into the view's output set
//! and renamed into place with its files, all or nothing. The outputs themselves stay plain
//! (no chunk in the PNG, no key in the `.npy` header). Its lines:
//!
//! ```text
//! lanecast view record 1
//! version 0.1.0
//! scene 3674 primitives, fingerprint 5c0ffee15c0ffee1
//! size 640x480
//! render precision auto, accel auto, kernel simd
//! camera eye [0.0, 2.0, 9.0] look [0.0, 0.0, 0.0] up [0.0, 1.0, 0.0] fov 60.0
//! image colours random, variation linear, seed 0        (only with an image file)
//! output --output "frames/f03.png" 40321 0123456789abcdef
//! output --ids "ids/i03.npy" 1228928 fedcba9876543210
//! ```
//!
//! The scene is known by its primitives (each one's kind and f64 numbers, in id order: the
//! scene file's and its meshes' content as the run reads it), the camera by its spec in full
//! (Rust's round-trip form), a file by its length and a 64-bit fingerprint of its bytes.
//! Fingerprints tell files apart, not adversaries: a file changed on purpose to match is not
//! guarded against.

use crate::cli::RenderSettings;
use crate::output::{OutputKind, OutputSet};
use crate::scene::{CameraSpec, Lens, Scene};
use std::fs::File;
use std::io::{self, Read};
use std::path::{Path, PathBuf};

/// The flag of the record in a view's output set (for its messages).
pub(super) const FLAG: &str = "--skip-existing record";
/// The extension of a record's name.
pub(crate) const EXTENSION: &str = "lanecast-view";
/// The first line of every record; a record of another layout is not this run's.
const HEAD: &str = "lanecast view record 1";
/// The most a record may hold (a line a view's output and a few more): a larger file is not
/// one.
const MAX_RECORD_BYTES: u64 = 1 << 16;

/// A 64-bit fingerprint of a sequence of words: each step mixes the word into the state with
/// splitmix64's finalizer, a bijection, so one changed word always changes the state, and two
/// changes cancel only by chance (about 2^-64).
struct Fingerprint {
    state: u64,
    len: u64,
}

impl Fingerprint {
    fn new() -> Fingerprint {
        Fingerprint {
            state: 0x6c61_6e65_6361_7374, // "lanecast"
            len: 0,
        }
    }

    fn mix(mut z: u64) -> u64 {
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    fn word(&mut self, w: u64) {
        self.state = Fingerprint::mix(self.state ^ w);
        self.len += 8;
    }

    /// Bytes, 8 at a time, little-endian; only the last call of a sequence may end with a
    /// partial word (zero-padded; the length, mixed in by `finish`, tells it apart).
    fn bytes(&mut self, b: &[u8]) {
        let mut words = b.chunks_exact(8);
        for w in &mut words {
            self.word(u64::from_le_bytes(w.try_into().expect("8 bytes")));
        }
        let rest = words.remainder();
        if !rest.is_empty() {
            let mut last = [0u8; 8];
            last[..rest.len()].copy_from_slice(rest);
            self.word(u64::from_le_bytes(last));
            self.len -= 8 - rest.len() as u64;
        }
    }

    fn finish(&self) -> u64 {
        Fingerprint::mix(self.state ^ self.len)
    }
}

/// A file's length and fingerprint.
fn file_fingerprint(path: &Path) -> io::Result<(u64, u64)> {
    let mut file = File::open(path)?;
    let mut buf = vec![0u8; 1 << 20];
    let mut f = Fingerprint::new();
    let mut len = 0;
    loop {
        // the buffer filled whole (a multiple of 8) but at the end of the file
        let mut n = 0;
        while n < buf.len() {
            match file.read(&mut buf[n..]) {
                Ok(0) => break,
                Ok(k) => n += k,
                Err(e) if e.kind() == io::ErrorKind::Interrupted => {}
                Err(e) => return Err(e),
            }
        }
        f.bytes(&buf[..n]);
        len += n as u64;
        if n < buf.len() {
            return Ok((len, f.finish()));
        }
    }
}

/// The fingerprint of a scene's primitives: each one's kind and numbers, in id order.
pub(super) fn scene_fingerprint(scene: &Scene) -> u64 {
    let mut f = Fingerprint::new();
    let mut numbers = Vec::with_capacity(12);
    for shape in scene.shapes.iter() {
        numbers.clear();
        shape.write_numbers(&mut numbers);
        f.word(shape.kind() as u64);
        for x in &numbers {
            f.word(x.to_bits());
        }
    }
    f.finish()
}

/// Where the record of a view whose first output is `first` lies: beside it, named after it.
pub(super) fn path_for(first: &Path) -> PathBuf {
    let name = first.file_name().unwrap_or_default().to_string_lossy();
    first.with_file_name(format!(".{name}.{EXTENSION}"))
}

/// The lines every view of a run shares: the record's layout, the build, the scene, the size,
/// how it renders, and how the image is coloured when it writes one (`image`).
pub(super) fn run_lines(s: &RenderSettings, scene: &Scene, image: bool) -> String {
    let mut text = format!(
        "{HEAD}\nversion {}\nscene {} primitives, fingerprint {:016x}\nsize {}x{}\n\
         render precision {}, accel {}, kernel {}\n",
        env!("CARGO_PKG_VERSION"),
        scene.shapes.len(),
        scene_fingerprint(scene),
        s.view.width,
        s.view.height,
        s.view.precision.name(),
        s.view.accel.name(),
        s.kernel.name(),
    );
    if image {
        text += &format!(
            "image colours {}, variation {}, seed {}\n",
            s.color_mode.name(),
            s.variation.name(),
            s.seed
        );
    }
    text
}

/// The line of a view's camera, every number in full.
fn camera_line(spec: &CameraSpec) -> String {
    let v = |p: glam::DVec3| format!("{:?}", p.to_array());
    let lens = match spec.lens {
        Some(Lens::Fov(f)) => format!("fov {f:?}"),
        Some(Lens::Pinhole(k)) => format!("K {:?} {:?} {:?} {:?}", k.fx, k.fy, k.cx, k.cy),
        None => "no lens".to_string(),
    };
    format!(
        "camera eye {} look {} up {} {lens}\n",
        v(spec.eye),
        v(spec.look),
        v(spec.up)
    )
}

/// The line of one output file.
fn output_line(flag: &str, path: &Path, (len, fingerprint): (u64, u64)) -> String {
    format!(
        "output {flag} {:?} {len} {fingerprint:016x}\n",
        path.display().to_string()
    )
}

/// The record's own entry in a view's output set.
pub(super) fn output(record: &Path) -> (&'static str, &Path, OutputKind) {
    (FLAG, record, OutputKind::Record)
}

/// Writes the record of a view into `set`, whose `outputs` (flag, target) are written: the
/// run's lines, the view's camera, and each output's length and fingerprint, read back from
/// its temporary file.
pub(super) fn write(
    set: &mut OutputSet,
    run: &str,
    spec: &CameraSpec,
    outputs: &[(&'static str, &Path)],
) -> crate::Result<()> {
    let mut text = format!("{run}{}", camera_line(spec));
    for &(flag, path) in outputs {
        let tmp = set.written(flag)?;
        let print = file_fingerprint(&tmp)
            .map_err(|e| crate::Error::io(path, "read back a written output", e))?;
        text += &output_line(flag, path, print);
    }
    set.write_bytes(FLAG, text.as_bytes())
}

/// Whether the record at `record` says the files of `outputs` (flag, target) were made by this
/// run's settings (`run`) and the camera `spec`, and each still holds the bytes it was written
/// with. Anything missing, unreadable or different means no.
pub(super) fn matches(
    record: &Path,
    run: &str,
    spec: &CameraSpec,
    outputs: &[(&'static str, &Path)],
) -> bool {
    let Ok(file) = File::open(record) else {
        return false;
    };
    let mut text = String::new();
    let read = file.take(MAX_RECORD_BYTES + 1).read_to_string(&mut text);
    if read.is_err() || text.len() as u64 > MAX_RECORD_BYTES {
        return false;
    }
    let head = format!("{run}{}", camera_line(spec));
    let Some(rest) = text.strip_prefix(&head) else {
        return false;
    };
    let lines: Vec<&str> = rest.lines().collect();
    lines.len() == outputs.len()
        && outputs.iter().zip(lines).all(|(&(flag, path), line)| {
            file_fingerprint(path)
                .is_ok_and(|print| output_line(flag, path, print).trim_end() == line)
        })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Rng;

    /// Every changed byte, and every changed length, changes a file's fingerprint; so do two
    /// changes of the same bit in different words (which a plain multiply-and-xor loses).
    #[test]
    fn fingerprints_change_with_every_byte_and_length() {
        let dir = std::env::temp_dir().join(format!("lanecast-record-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("a.bin");
        let mut rng = Rng(48);
        let bytes: Vec<u8> = (0..3000).map(|_| rng.below(256) as u8).collect();
        std::fs::write(&path, &bytes).unwrap();
        let whole = file_fingerprint(&path).unwrap();
        assert_eq!(whole.0, 3000);
        let mut seen = std::collections::HashSet::new();
        for at in (0..bytes.len()).step_by(7) {
            let mut b = bytes.clone();
            b[at] ^= 1 << (at % 8);
            std::fs::write(&path, &b).unwrap();
            let print = file_fingerprint(&path).unwrap();
            assert_ne!(print, whole, "byte {at}");
            assert!(seen.insert(print.1), "byte {at}");
        }
        let mut b = bytes.clone();
        b[7] ^= 0x80;
        b[15] ^= 0x80;
        std::fs::write(&path, &b).unwrap();
        assert_ne!(file_fingerprint(&path).unwrap(), whole);
        for len in [0, 1, 7, 8, 9, 2999] {
            std::fs::write(&path, &bytes[..len]).unwrap();
            assert!(seen.insert(file_fingerprint(&path).unwrap().1), "{len}");
        }
        // a zero byte more is another file
        let mut b = bytes.clone();
        b.push(0);
        std::fs::write(&path, &b).unwrap();
        assert_ne!(file_fingerprint(&path).unwrap().1, whole.1);
        // past the read buffer: the same bytes in one piece or many give one fingerprint
        let big: Vec<u8> = (0..(1 << 20) + 13).map(|_| rng.below(256) as u8).collect();
        std::fs::write(&path, &big).unwrap();
        let mut f = Fingerprint::new();
        f.bytes(&big);
        assert_eq!(
            file_fingerprint(&path).unwrap(),
            (big.len() as u64, f.finish())
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A scene's fingerprint follows its primitives, and only them.
    #[test]
    fn scene_fingerprints_follow_the_primitives() {
        let parse = |t: &str| crate::parse_scene(t, Path::new("s.sc")).unwrap();
        let a = parse("camera eye 0 0 9 look 0 0 0 up 0 1 0\nsphere 0 0 0 1\n");
        let b = parse("# moved\ncamera eye 0 1 9 look 0 0 0 up 0 1 0\n\nsphere 0 0 0 1\n");
        let c = parse("camera eye 0 0 9 look 0 0 0 up 0 1 0\nsphere 0 0 0 1.0000001\n");
        let d = parse("camera eye 0 0 9 look 0 0 0 up 0 1 0\nsphere 0 0 0 1\nsphere 0 0 0 1\n");
        assert_eq!(scene_fingerprint(&a), scene_fingerprint(&b));
        assert_ne!(scene_fingerprint(&a), scene_fingerprint(&c));
        assert_ne!(scene_fingerprint(&a), scene_fingerprint(&d));
    }

    #[test]
    fn a_record_lies_beside_the_first_output() {
        assert_eq!(
            path_for(Path::new("frames/f03.png")),
            Path::new("frames/.f03.png.lanecast-view")
        );
        assert_eq!(
            path_for(Path::new("i.npy")),
            Path::new(".i.npy.lanecast-view")
        );
    }
}
