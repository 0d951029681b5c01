//! Temporary file names, and the removal of stale ones: those left by a run that was killed
//! (SIGKILL, a power loss) before it could remove them.
//!
//! Every temporary file lanecast creates is named `.{NAME}.{PID}.{N}.lanecast-tmp` beside its
//! target `NAME`, and is locked (`flock`, exclusive) by the process that created it from its
//! creation, under its folder's lock, until it is renamed or removed: a temporary file whose
//! lock can be taken has no live owner. [`remove_stale`] runs under the folder's lock
//! ([`super::lock::FolderLock`]), so no run is between creating a temporary file and locking
//! it while it looks. It removes a file only when all of these hold:
//! - the name is a temporary file's name, and the entry a regular file (never a link);
//! - its lock can be taken;
//! - where `/proc` tells, no process with its PID exists (a lanecast from before temporary files
//!   were locked may still be writing it; a reused PID only keeps a stale file longer).

use std::ffi::{OsStr, OsString};
use std::fs::{self, File};
use std::path::Path;

/// The suffix of every temporary file's name.
const SUFFIX: &str = ".lanecast-tmp";

/// The temporary file name for target file name `name`, process `pid` and counter `n`.
pub(super) fn temp_name(name: &OsStr, pid: u32, n: u64) -> OsString {
    let mut tmp = OsString::from(".");
    tmp.push(name);
    tmp.push(format!(".{pid}.{n}{SUFFIX}"));
    tmp
}

/// The PID in a temporary file's name, or `None` when `name` is not one.
fn temp_pid(name: &OsStr) -> Option<u32> {
    let rest = name.to_str()?.strip_prefix('.')?.strip_suffix(SUFFIX)?;
    let mut parts = rest.rsplitn(3, '.');
    let (n, pid, target) = (parts.next()?, parts.next()?, parts.next()?);
    let digits = |s: &str| !s.is_empty() && s.bytes().all(|b| b.is_ascii_digit());
    if target.is_empty() || !digits(n) || !digits(pid) {
        return None;
    }
    pid.parse().ok()
}

/// Whether process `pid` may be alive: known dead only where `/proc` lists processes. This
/// process's own PID counts as dead: its own temporary files are locked, so the lock decides.
fn may_be_alive(pid: u32) -> bool {
    if pid == std::process::id() {
        return false;
    }
    if cfg!(target_os = "linux") && Path::new("/proc/self").exists() {
        return Path::new("/proc").join(pid.to_string()).exists();
    }
    false
}

/// Removes the stale temporary files in `folder` (see the module documentation). The caller
/// holds the folder's lock. Best effort: an entry that cannot be read, opened or removed is
/// left as it is. Returns how many were removed.
pub(super) fn remove_stale(folder: &Path) -> usize {
    let Ok(entries) = fs::read_dir(folder) else {
        return 0;
    };
    let mut removed = 0;
    for entry in entries.flatten() {
        let name = entry.file_name();
        let Some(pid) = temp_pid(&name) else {
            continue;
        };
        let path = folder.join(&name);
        if is_stale(&path, pid) && fs::remove_file(&path).is_ok() {
            removed += 1;
        }
    }
    removed
}

/// Whether the temporary file at `path`, named with `pid`, is stale.
fn is_stale(path: &Path, pid: u32) -> bool {
    // a regular file, not a link (nor a pipe, which opening could block on)
    let Ok(meta) = fs::symlink_metadata(path) else {
        return false;
    };
    if !meta.is_file() {
        return false;
    }
    let Ok(file) = File::open(path) else {
        return false;
    };
    if !same_entry(&meta, &file) {
        return false;
    }
    // taken, the lock is held until `file` closes, after the removal
    file.try_lock().is_ok() && !may_be_alive(pid)
}

/// Whether `file` is the entry `meta` was read from (not one swapped in meanwhile).
fn same_entry(meta: &fs::Metadata, file: &File) -> bool {
    #[cfg(unix)]
    {
        use std::os::unix::fs::MetadataExt;
        file.metadata()
            .is_ok_and(|m| m.dev() == meta.dev() && m.ino() == meta.ino())
    }
    #[cfg(not(unix))]
    {
        let _ = (meta, file);
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn temporary_names_round_trip_and_others_are_not_taken_for_them() {
        let name = temp_name(OsStr::new("out.v2.png"), 4321, 7);
        assert_eq!(name, ".out.v2.png.4321.7.lanecast-tmp");
        assert_eq!(temp_pid(&name), Some(4321));
        for other in [
            "out.png",
            ".out.png.12.lanecast-tmp",
            "..1.2.lanecast-tmp",
            ".out.png.x.2.lanecast-tmp",
            ".out.png.1.2.lanecast-tmp.bak",
            "out.png.1.2.lanecast-tmp",
            ".lanecast-tmp",
        ] {
            assert_eq!(temp_pid(OsStr::new(other)), None, "{other}");
        }
    }
}
