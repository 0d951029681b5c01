//! The outputs of one run as a set: checked before any work, written to temporary files, and
//! renamed into place together once every one of them is complete.
//!
//! [`OutputSet::create`] runs before the scene is parsed. It refuses (exit 2) an output whose
//! extension does not match what is written into it, and an output that names a file the run
//! reads or another output, however spelled ([`same_file`](super::same_file): `..`, `.`,
//! symbolic links, hard links). It refuses (exit 1) a destination that is a folder or not a
//! regular file, and then creates every output's temporary file beside its target, which
//! proves each folder exists and is writable before any work. Files read later (a scene's
//! meshes) are checked by [`OutputSet::check_reads`] once known.
//!
//! Each output is then written into its temporary file ([`OutputSet::write_with`] and the
//! typed writers), and [`OutputSet::commit`] renames them all. A run that fails or returns
//! early drops the set, which removes every temporary file: no previous output changes.
//!
//! The rename loop holds the lock of the pending-file registry, which the interrupt handler
//! takes before it removes anything, so a SIGINT or SIGTERM arriving during the renames waits
//! for the loop to end: either no output has been renamed (the handler removes the temporary
//! files and exits 130) or all have (the handler, once it runs, finds nothing to remove and
//! exits 130 with the new set complete; or the run finishes first and exits 0). Before the loop,
//! every existing target gets a hard link under a temporary name; if a rename fails (a target
//! replaced by a folder in the meantime, a file system error), the targets already renamed get
//! their previous files back from those links (or are removed when they did not exist), so a
//! failure leaves the previous set. Only where hard links are not supported, or a process is
//! killed (SIGKILL) inside the loop, can a mixed set remain.
//!
//! Concurrent runs: the temporary files are created, and the commit (the renames and the folder
//! syncs) runs, under exclusive locks on the folders of every output ([`FolderLock`]). Two runs
//! that share an output folder commit one after the other, so the set left is the whole set of
//! the last to commit, never a mix of both; their renders still run at the same time. Before
//! creating its temporary files, a set removes the stale ones of killed runs from its folders
//! (the `stale` module).

// The library writes one file at a time through a set of one; the rest serves the command line.
#![cfg_attr(not(feature = "cli"), allow(dead_code))]

use std::fs::{self, File};
use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};

use super::lock::{FolderLock, lock_wait};
use super::{
    TMP_COUNTER, create_temp, fill_file, image_fill, npy_fill, npy3_fill, parent_dir, pending,
    same_file, stale, sync_parent, unregister,
};
use crate::{Error, Result};
use std::time::Duration;

/// What an output holds, which decides the extensions its name may end in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum OutputKind {
    /// An image: `.png` or `.bmp` (the format follows the extension).
    Image,
    /// A NumPy array: `.npy`.
    Npy,
    /// A JSON record: `.json`.
    Json,
    /// A views file, text: `.txt` (`--save-views`).
    Views,
    /// The record of a view of a many-view run (`run/record.rs`): `.lanecast-view`.
    Record,
}

impl OutputKind {
    /// Refuses (usage error, naming `flag` and `path`) a name whose extension is not one this
    /// kind of output is written as (case-insensitive).
    pub fn check_extension(self, flag: &str, path: &Path) -> Result<()> {
        let ext = path
            .extension()
            .and_then(|e| e.to_str())
            .map(str::to_ascii_lowercase);
        let ok = match self {
            OutputKind::Image => matches!(ext.as_deref(), Some("png" | "bmp")),
            OutputKind::Npy => ext.as_deref() == Some("npy"),
            OutputKind::Json => ext.as_deref() == Some("json"),
            OutputKind::Views => ext.as_deref() == Some("txt"),
            OutputKind::Record => ext.as_deref() == Some("lanecast-view"),
        };
        if ok {
            return Ok(());
        }
        let what = match self {
            OutputKind::Image => "unsupported image format; the name must end in .png or .bmp",
            OutputKind::Npy => "written as NumPy data; the name must end in .npy",
            OutputKind::Json => "written as JSON; the name must end in .json",
            OutputKind::Views => "written as a views file (text); the name must end in .txt",
            OutputKind::Record => "a view's record; the name must end in .lanecast-view",
        };
        Err(Error::usage(format!("{flag} {}: {what}", path.display())))
    }
}

/// One output of the set.
#[derive(Debug)]
struct Out {
    flag: &'static str,
    path: PathBuf,
    tmp: PathBuf,
    /// The temporary file, open (and locked) while it exists under its temporary name: its
    /// lock tells other runs it is not stale. Written through a clone of the handle.
    hold: File,
    /// Set once the temporary file has been written.
    written: bool,
    /// Set once the temporary file has been renamed onto `path`.
    renamed: bool,
}

/// Every output file of one run: temporary files that become the outputs together, in
/// [`OutputSet::commit`], or not at all (dropping the set removes them).
#[derive(Debug)]
pub struct OutputSet {
    outs: Vec<Out>,
    /// How long to wait for the folders' locks ([`lock_wait`]).
    wait: Duration,
}

/// The verb phrase of I/O messages about the output of `flag`.
fn action(flag: &str) -> &'static str {
    match flag {
        "--output" => "write the --output image",
        "--ids" => "write the --ids file",
        "--depth" => "write the --depth file",
        "--zdepth" => "write the --zdepth file",
        "--normals" => "write the --normals file",
        "--stats" => "write the --stats file",
        "--save-views" => "write the --save-views file",
        "--skip-existing record" => "write the view's record (what --skip-existing reads)",
        _ => "write output",
    }
}

/// Refuses a target that exists and is not a regular file (a folder, a device, a pipe), nor a
/// symbolic link to one: renaming onto it would replace it.
fn check_target(flag: &str, path: &Path) -> Result<()> {
    let fail = |msg: &str| Error::io(path, action(flag), io::Error::other(msg.to_string()));
    for meta in [fs::symlink_metadata(path), fs::metadata(path)] {
        match meta {
            Ok(m) if m.is_dir() => return Err(fail("it is a folder")),
            Ok(m) if !m.is_file() && !m.is_symlink() => {
                return Err(fail("it is not a regular file"));
            }
            _ => {}
        }
    }
    Ok(())
}

/// How a target's previous file can be put back if the set fails halfway through its renames.
enum Backup {
    /// There was no previous file: remove the new one.
    Absent,
    /// A hard link to the previous file, under a temporary name.
    Link(PathBuf),
    /// The previous file could not be linked: it cannot be put back.
    Unavailable,
}

/// A hard link to `path`'s current file beside it, named like a temporary file.
fn backup(path: &Path) -> Backup {
    if let Err(e) = fs::symlink_metadata(path) {
        return if e.kind() == io::ErrorKind::NotFound {
            Backup::Absent
        } else {
            Backup::Unavailable
        };
    }
    let Some(name) = path.file_name() else {
        return Backup::Unavailable;
    };
    for _ in 0..100 {
        let n = TMP_COUNTER.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
        let link = parent_dir(path).join(stale::temp_name(name, std::process::id(), n));
        match fs::hard_link(path, &link) {
            Ok(()) => return Backup::Link(link),
            Err(e) if e.kind() == io::ErrorKind::AlreadyExists => continue,
            Err(_) => return Backup::Unavailable,
        }
    }
    Backup::Unavailable
}

impl OutputSet {
    /// Checks every output and creates its temporary file; nothing else is touched.
    ///
    /// `outputs`: (flag, path, kind) of each output, the flag as the user would type its long
    /// form (`--output`, `--ids`, ...), used in messages and to pick the output to write.
    /// `reads`: (description, path) of every file the run reads that is known before parsing
    /// (the scene: `("the input scene", path)`).
    ///
    /// In order, so that a usage error is reported before an I/O error: the lock wait
    /// ([`lock_wait`]), every extension, every output against `reads` and against the outputs
    /// before it (exit 2), then every target (a folder or a non-regular file is refused) and
    /// every temporary file (a missing or read-only folder fails here, exit 1), created under
    /// the folders' locks after the folders' stale temporary files are removed (the `stale`
    /// module; a lock held elsewhere too long: exit 75).
    pub fn create(
        outputs: &[(&'static str, &Path, OutputKind)],
        reads: &[(&str, &Path)],
    ) -> Result<OutputSet> {
        let wait = lock_wait()?;
        for &(flag, path, kind) in outputs {
            kind.check_extension(flag, path)?;
        }
        for (i, &(flag, path, _)) in outputs.iter().enumerate() {
            check_not_read(flag, path, reads.iter().copied())?;
            for &(other, opath, _) in &outputs[..i] {
                if same_file(path, opath) {
                    return Err(Error::usage(format!(
                        "{flag} {} and {other} {} name the same file",
                        path.display(),
                        opath.display()
                    )));
                }
            }
        }
        let outputs: Vec<(&'static str, &Path)> = outputs.iter().map(|o| (o.0, o.1)).collect();
        OutputSet::open(&outputs, wait)
    }

    /// The second half of [`OutputSet::create`], for outputs already checked against each
    /// other: every target, then the temporary files, under the folders' locks (waiting at most
    /// `wait` for them).
    pub(super) fn open(outputs: &[(&'static str, &Path)], wait: Duration) -> Result<OutputSet> {
        for &(flag, path) in outputs {
            check_target(flag, path)?;
        }
        let lock = FolderLock::acquire(outputs.iter().map(|o| o.1), wait)?;
        for folder in lock.folders() {
            stale::remove_stale(folder);
        }
        let mut set = OutputSet {
            outs: Vec::new(),
            wait,
        };
        for &(flag, path) in outputs {
            let (tmp, hold) = create_temp(path).map_err(|e| {
                let dir = parent_dir(path);
                let e = if dir.is_dir() {
                    e
                } else if dir.exists() {
                    io::Error::new(e.kind(), format!("{} is not a folder", dir.display()))
                } else {
                    io::Error::new(e.kind(), format!("no folder {}", dir.display()))
                };
                Error::io(path, action(flag), e)
            })?;
            // From here on, dropping the set removes the temporary file.
            set.outs.push(Out {
                flag,
                path: path.to_path_buf(),
                tmp,
                hold,
                written: false,
                renamed: false,
            });
        }
        Ok(set)
    }

    /// Refuses an output that names one of `reads` (description, path): the files the run read
    /// after [`OutputSet::create`], such as the meshes a scene loads.
    pub fn check_reads(&self, reads: &[(String, PathBuf)]) -> Result<()> {
        for o in &self.outs {
            check_not_read(
                o.flag,
                &o.path,
                reads.iter().map(|(w, p)| (w.as_str(), &**p)),
            )?;
        }
        Ok(())
    }

    /// The outputs as (flag, path), in the order given to [`OutputSet::create`].
    pub fn paths(&self) -> impl Iterator<Item = (&'static str, &Path)> {
        self.outs.iter().map(|o| (o.flag, o.path.as_path()))
    }

    /// Writes the output of `flag`: `fill` produces its content into the temporary file, which
    /// is then flushed, synced and closed. The target is untouched until [`OutputSet::commit`].
    pub fn write_with(
        &mut self,
        flag: &str,
        fill: impl FnOnce(&mut BufWriter<File>) -> io::Result<()>,
    ) -> Result<()> {
        let Some(o) = self.outs.iter_mut().find(|o| o.flag == flag) else {
            return Err(Error::Failed(format!(
                "internal error: no output {flag} in the set"
            )));
        };
        if o.written {
            return Err(Error::Failed(format!(
                "internal error: {flag} {} written twice",
                o.path.display()
            )));
        }
        o.written = true;
        let fail = |e| Error::io(&o.path, action(o.flag), e);
        // a clone shares the lock, which stays with `hold` when the clone is closed
        fill_file(o.hold.try_clone().map_err(fail)?, fill).map_err(fail)
    }

    /// The temporary file of the output of `flag`, once written: what [`OutputSet::commit`]
    /// renames onto its target.
    pub fn written(&self, flag: &str) -> Result<PathBuf> {
        match self.outs.iter().find(|o| o.flag == flag && o.written) {
            Some(o) => Ok(o.tmp.clone()),
            None => Err(Error::Failed(format!(
                "internal error: no output {flag} written in the set"
            ))),
        }
    }

    /// The path of the output of `flag`.
    fn path_of(&self, flag: &str) -> Result<PathBuf> {
        match self.outs.iter().find(|o| o.flag == flag) {
            Some(o) => Ok(o.path.clone()),
            None => Err(Error::Failed(format!(
                "internal error: no output {flag} in the set"
            ))),
        }
    }

    /// Writes `rgb` (3 bytes per pixel, row 0 at the top) as the image of `flag`, PNG or BMP by
    /// its extension (see [`write_image`](super::write_image)).
    pub fn write_image(&mut self, flag: &str, width: u32, height: u32, rgb: &[u8]) -> Result<()> {
        let path = self.path_of(flag)?;
        self.write_with(flag, image_fill(&path, width, height, rgb)?)
    }

    /// Writes a `height` x `width` i32 array as the `.npy` file of `flag`.
    pub fn write_npy_i32(&mut self, flag: &str, w: usize, h: usize, data: &[i32]) -> Result<()> {
        let path = self.path_of(flag)?;
        self.write_with(
            flag,
            npy_fill(&path, "<i4", (w, h), data, i32::to_le_bytes)?,
        )
    }

    /// Writes a `height` x `width` f32 array as the `.npy` file of `flag`.
    pub fn write_npy_f32(&mut self, flag: &str, w: usize, h: usize, data: &[f32]) -> Result<()> {
        let path = self.path_of(flag)?;
        self.write_with(
            flag,
            npy_fill(&path, "<f4", (w, h), data, f32::to_le_bytes)?,
        )
    }

    /// Writes a `height` x `width` x 3 f32 array (three values a pixel) as the `.npy` file of
    /// `flag`.
    pub fn write_npy_f32x3(
        &mut self,
        flag: &str,
        w: usize,
        h: usize,
        data: &[[f32; 3]],
    ) -> Result<()> {
        let path = self.path_of(flag)?;
        self.write_with(flag, npy3_fill(&path, (w, h), data)?)
    }

    /// Writes `bytes` as the output of `flag`.
    pub fn write_bytes(&mut self, flag: &str, bytes: &[u8]) -> Result<()> {
        self.write_with(flag, |w| w.write_all(bytes))
    }

    /// Renames every temporary file onto its target, all or none (see the module
    /// documentation). Every output must have been written.
    pub fn commit(mut self) -> Result<()> {
        if let Some(o) = self.outs.iter().find(|o| !o.written) {
            return Err(Error::Failed(format!(
                "internal error: {} {} was never written",
                o.flag,
                o.path.display()
            )));
        }
        // Runs replacing outputs in the same folders commit one at a time (the `lock` module);
        // taken before the registry, so that an interrupt while waiting ends the run at once.
        let lock = FolderLock::acquire(self.outs.iter().map(|o| o.path.as_path()), self.wait)?;
        // Held across the whole loop: an interrupt waits for it (see the module docs).
        let mut list = pending();
        let backups: Vec<Backup> = self.outs.iter().map(|o| backup(&o.path)).collect();
        let mut failure = None;
        for o in &mut self.outs {
            if let Err(e) = fs::rename(&o.tmp, &o.path) {
                failure = Some(Error::io(&o.path, action(o.flag), e));
                break;
            }
            o.renamed = true;
            unregister(&mut list, &o.tmp);
        }
        for (o, b) in self.outs.iter().zip(&backups) {
            // After a failure, an output already renamed gets its previous file back.
            let restore = failure.is_some() && o.renamed;
            let leftover = match b {
                Backup::Link(link) if restore && fs::rename(link, &o.path).is_ok() => None,
                Backup::Link(link) => Some(link.as_path()),
                Backup::Absent if restore => Some(o.path.as_path()),
                Backup::Absent | Backup::Unavailable => None,
            };
            if let Some(p) = leftover {
                let _ = fs::remove_file(p);
            }
        }
        drop(list);
        if let Some(e) = failure {
            // Dropping the set removes the temporary files not renamed.
            return Err(e);
        }
        let mut synced: Vec<&Path> = Vec::new();
        for o in &self.outs {
            let dir = parent_dir(&o.path);
            if !synced.contains(&dir) {
                sync_parent(&o.path);
                synced.push(dir);
            }
        }
        drop(lock);
        Ok(())
    }
}

/// Refuses `path` (the output of `flag`) when it names one of `reads` (description, path).
pub(crate) fn check_not_read<'a>(
    flag: &str,
    path: &Path,
    reads: impl IntoIterator<Item = (&'a str, &'a Path)>,
) -> Result<()> {
    for (what, read) in reads {
        if same_file(path, read) {
            return Err(Error::usage(format!(
                "{flag} {}: is {what}; refusing to overwrite it",
                path.display()
            )));
        }
    }
    Ok(())
}

impl Drop for OutputSet {
    /// Removes every temporary file not renamed: an unfinished set leaves nothing behind.
    fn drop(&mut self) {
        let mut list = pending();
        for o in &mut self.outs {
            if !o.renamed {
                // removed before `hold` closes: never unlocked under its temporary name
                let _ = fs::remove_file(&o.tmp);
                unregister(&mut list, &o.tmp);
            }
        }
    }
}

#[cfg(test)]
mod tests;
