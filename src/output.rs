//! Output files: PNG/BMP images and NumPy `.npy` buffers, each written atomically.
//!
//! Every file goes to a temporary file in the target's folder (`.{name}.{pid}.{n}.lanecast-tmp`),
//! is flushed and synced, then renamed onto the target. A failed write removes the temporary
//! file and leaves any existing target untouched; a missing folder is an error, never created.
//! Each temporary file is locked by its run while it exists, so that a later run can tell the
//! files of a killed run (SIGKILL) from a live one's and remove them (the `stale` module); runs
//! replacing outputs in the same folder take turns under the folder's lock (the `lock` module).
//!
//! Interrupts: the command line's `install_interrupt_cleanup` installs a SIGINT/SIGTERM
//! (Ctrl-C) handler that removes every temporary file created and not yet renamed, then exits
//! with code 130. The
//! registry of pending temporary files is locked across "create + register" and across
//! "rename + unregister", so the handler sees either a temporary file (and removes it) or a
//! finished rename (and leaves the complete target), never a half state.
//!
//! The functions here write one file each. The command line writes the outputs of a run as an
//! `OutputSet`: all checked and their temporary files created before any work, all renamed
//! together at the end (the `set` module).

use std::fs::{self, File, OpenOptions};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
#[cfg(feature = "cli")]
use std::sync::Once;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::{Mutex, MutexGuard};

use image::ExtendedColorType;
use image::ImageEncoder;
use image::codecs::bmp::BmpEncoder;
use image::codecs::png::{CompressionType, FilterType, PngEncoder};

use crate::{Error, Result};

#[cfg(feature = "cli")]
mod complete;
mod frame;
mod lock;
mod npy;
mod pattern;
mod set;
mod stale;
#[cfg(feature = "cli")]
pub(crate) use complete::{Expected, is_complete};
use lock::lock_wait;
pub use npy::{npy_f32, npy_f32x3, npy_i32, write_npy_f32, write_npy_f32x3, write_npy_i32};
use npy::{npy_fill, npy3_fill};
pub use pattern::Pattern;
#[cfg(feature = "cli")]
pub(crate) use set::OutputKind;
pub(crate) use set::OutputSet;
#[cfg(feature = "cli")]
pub(crate) use set::check_not_read;

/// Image formats lanecast writes, chosen by the output file's extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ImageFormat {
    /// PNG (`.png`), 8-bit RGB.
    Png,
    /// BMP (`.bmp`), 24-bit RGB.
    Bmp,
}

/// The image format for `path`, from its extension (case-insensitive).
pub fn image_format(path: &Path) -> Result<ImageFormat> {
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("png") => Ok(ImageFormat::Png),
        Some("bmp") => Ok(ImageFormat::Bmp),
        _ => Err(Error::usage(format!(
            "{}: unsupported image format; the output name must end in .png or .bmp",
            path.display()
        ))),
    }
}

/// Writes `rgb` (3 bytes per pixel, row 0 at the top) as a PNG or BMP, by `path`'s extension.
///
/// PNG uses `CompressionType::Fast` (fdeflate) with the `Adaptive` filter. Measured on
/// 1920x1080 synthetic renders (release build): a flat-shaded scene of spheres over a tiled
/// floor took 2.6 ms / 107 kB (zlib default: 15 ms / 62 kB); a worst case of 6x6-pixel
/// primitives with per-pixel depth took 11 ms / 2.9 MB (zlib default: 450 ms / 2.1 MB). The
/// `Sub` filter alone is faster on smooth scenes but 60% larger on busy ones. Both formats are
/// streamed into the temporary file through a 64 KiB buffer.
pub fn write_image(path: &Path, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
    write_atomic_with(path, image_fill(path, width, height, rgb)?)
}

/// The encoder of an image file, checked (format from `path`'s extension, pixel count) before
/// any file is touched.
fn image_fill<'a>(
    path: &Path,
    width: u32,
    height: u32,
    rgb: &'a [u8],
) -> Result<impl FnOnce(&mut BufWriter<File>) -> io::Result<()> + 'a> {
    let format = image_format(path)?;
    if u64::from(width) * u64::from(height) * 3 != rgb.len() as u64 {
        return Err(Error::Failed(format!(
            "{}: internal error: {} bytes of pixels for a {width}x{height} image",
            path.display(),
            rgb.len()
        )));
    }
    Ok(move |w: &mut BufWriter<File>| encode_image(w, format, width, height, rgb))
}

/// Encodes `rgb` (3 bytes per pixel, row 0 at the top) as `format` into `w`: the one encoder
/// setting of every image lanecast writes (see [`write_image`]).
pub fn encode_image(
    w: &mut impl Write,
    format: ImageFormat,
    width: u32,
    height: u32,
    rgb: &[u8],
) -> io::Result<()> {
    let mut w = KeepError {
        inner: w,
        first: None,
    };
    let encoded = match format {
        ImageFormat::Png => {
            PngEncoder::new_with_quality(&mut w, CompressionType::Fast, FilterType::Adaptive)
                .write_image(rgb, width, height, ExtendedColorType::Rgb8)
        }
        ImageFormat::Bmp => {
            BmpEncoder::new(&mut w).encode(rgb, width, height, ExtendedColorType::Rgb8)
        }
    };
    match (encoded, w.first) {
        (Ok(()), _) => Ok(()),
        // the writer's own error, kind and all (a closed pipe, a full disk)
        (Err(_), Some(e)) => Err(e),
        (Err(image::ImageError::IoError(e)), None) => Err(e),
        (Err(other), None) => Err(io::Error::other(format!("cannot encode image: {other}"))),
    }
}

/// A writer that keeps the first error its inner writer returned. The PNG encoder turns an
/// I/O error into a new one of kind `Other` holding only its text, so the caller could no
/// longer tell a closed pipe (`BrokenPipe`) from any other failure; the error kept here is
/// the original.
struct KeepError<W> {
    inner: W,
    first: Option<io::Error>,
}

impl<W> KeepError<W> {
    fn keep<T>(&mut self, r: io::Result<T>) -> io::Result<T> {
        match r {
            // retried by `write_all`: not a failure
            Err(e) if e.kind() == io::ErrorKind::Interrupted => Err(e),
            Err(e) => {
                let kind = e.kind();
                self.first.get_or_insert(e);
                Err(io::Error::from(kind))
            }
            ok => ok,
        }
    }
}

impl<W: Write> Write for KeepError<W> {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        let r = self.inner.write(buf);
        self.keep(r)
    }

    fn flush(&mut self) -> io::Result<()> {
        let r = self.inner.flush();
        self.keep(r)
    }
}

/// Writes `bytes` to `path` atomically: temporary file in the same folder, sync, rename.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    write_atomic_with(path, |w| w.write_all(bytes))
}

/// Distinguishes temporary files of concurrent writes within one process.
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

/// Temporary files created and not yet renamed or removed: what an interrupt must clean up.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> MutexGuard<'static, Vec<PathBuf>> {
    // A panic while holding the lock leaves the list itself intact.
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

fn unregister(list: &mut Vec<PathBuf>, tmp: &Path) {
    list.retain(|p| p != tmp);
}

/// Exit code after an interrupt (128 + SIGINT, the shell convention).
#[cfg(feature = "cli")]
pub(crate) const INTERRUPTED_EXIT: i32 = 130;

/// Installs (once per process) the Ctrl-C / SIGTERM handler: it removes every pending temporary
/// file, prints `lanecast: interrupted` and exits with [`INTERRUPTED_EXIT`]. Any existing
/// target file is untouched (it is only ever replaced by a rename of a complete file).
#[cfg(feature = "cli")]
pub(crate) fn install_interrupt_cleanup() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let _ = ctrlc::set_handler(|| {
            // Held until exit: no write can create or rename a temporary file after this.
            let list = pending();
            for tmp in list.iter() {
                let _ = fs::remove_file(tmp);
            }
            let _ = writeln!(io::stderr().lock(), "lanecast: interrupted");
            std::process::exit(INTERRUPTED_EXIT);
        });
    });
}

/// Creates a fresh temporary file next to `path`, locks it (see the `stale` module: the lock,
/// held as long as the returned file or a clone of it is open, marks it as a live run's) and
/// registers it for interrupt cleanup. `create_new` never reuses or follows an existing entry
/// (a stale file from a crashed run with the same pid just moves us on). The caller holds the
/// folder's lock (`lock::FolderLock`), so no other run looks for stale files meanwhile.
fn create_temp(path: &Path) -> io::Result<(PathBuf, File)> {
    let name = path
        .file_name()
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "not a file name"))?;
    let dir = parent_dir(path);
    let mut attempts = 0;
    let mut list = pending();
    loop {
        let n = TMP_COUNTER.fetch_add(1, Ordering::Relaxed);
        let tmp = dir.join(stale::temp_name(name, std::process::id(), n));
        match OpenOptions::new().write(true).create_new(true).open(&tmp) {
            Ok(file) => {
                list.push(tmp.clone());
                // A file system without locks leaves it unlocked: then never taken for stale.
                let _ = file.try_lock();
                return Ok((tmp, file));
            }
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists && attempts < 100 => attempts += 1,
            Err(e) => return Err(e),
        }
    }
}

/// Fills `file` through a buffered writer, flushes and syncs it, and closes it.
fn fill_file(
    file: File,
    fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
) -> io::Result<()> {
    let mut w = BufWriter::with_capacity(1 << 16, file);
    fill(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()
}

/// The atomic write, with the content produced by `fill` into a buffered writer: a set of one
/// output ([`OutputSet`]).
fn write_atomic_with(
    path: &Path,
    fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
) -> Result<()> {
    let mut set = OutputSet::open(&[("output", path)], lock_wait()?)?;
    set.write_with("output", fill)?;
    set.commit()
}

/// Best effort: make the rename itself durable. The output is complete either way.
fn sync_parent(path: &Path) {
    #[cfg(unix)]
    if let Ok(d) = File::open(parent_dir(path)) {
        let _ = d.sync_all();
    }
    #[cfg(not(unix))]
    let _ = path;
}

/// The folder holding `path`: "." for a bare file name.
fn parent_dir(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// True if `a` and `b` name the same file, whether or not it exists yet: existing files are
/// compared by identity (device and inode on Unix, so hard links and symlinks count), others by
/// canonical parent folder plus file name.
#[cfg_attr(not(feature = "cli"), allow(dead_code))]
pub(crate) fn same_file(a: &Path, b: &Path) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        if let (Ok(ma), Ok(mb)) = (fs::metadata(a), fs::metadata(b)) {
            return ma.dev() == mb.dev() && ma.ino() == mb.ino();
        }
    }
    match (resolve(a), resolve(b)) {
        (Some(ra), Some(rb)) => ra == rb,
        _ => a == b,
    }
}

/// What names the same file as `path`, for telling many output names apart: [`resolve`]'s
/// answer, else `path` as given.
#[cfg(feature = "cli")]
pub(crate) fn identity(path: &Path) -> PathBuf {
    resolve(path).unwrap_or_else(|| path.to_path_buf())
}

/// `path` made absolute and free of links: the whole path if it exists, else its canonical
/// parent joined with its file name. `None` if the parent does not resolve either.
fn resolve(path: &Path) -> Option<PathBuf> {
    if let Ok(p) = fs::canonicalize(path) {
        return Some(p);
    }
    let name = path.file_name()?;
    Some(fs::canonicalize(parent_dir(path)).ok()?.join(name))
}

#[cfg(test)]
mod tests;
