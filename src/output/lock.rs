//! Locks on output folders: runs that replace outputs in the same folder take turns.
//!
//! A [`FolderLock`] holds an exclusive advisory lock (`flock`) on the folder of every path of a
//! set, each folder itself opened read-only: no lock file is ever created, so none can be left
//! behind, and the kernel releases the locks when the process ends, however it ends (a killed
//! holder never wedges later runs). Folders are locked in one global order, by device and
//! inode, so two runs locking overlapping sets never wait on each other in a cycle; a folder
//! named twice, by whatever path, is locked once.
//!
//! An output set takes the locks of its folders twice, briefly: while it removes stale
//! temporary files and creates its own ([`super::OutputSet::create`]), and for its commit, the
//! renames and folder syncs ([`super::OutputSet::commit`]). Renders run in parallel; only those
//! steps wait. A run that cannot get a lock within [`lock_wait`] fails with
//! [`Error::Locked`] (exit 75) and writes nothing.
//!
//! Where a folder cannot be locked at all (a file system without `flock`, or a platform where
//! folders cannot be opened), the run goes on without that lock: outputs are then as safe from
//! concurrent runs as they were before locks existed, and no less.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

#[cfg(unix)]
use super::parent_dir;
use crate::{Error, Result};

/// The environment variable that bounds the wait for a folder lock, in seconds.
pub const LOCK_WAIT_VAR: &str = "LANECAST_LOCK_WAIT";

/// How long a run waits for a folder lock when [`LOCK_WAIT_VAR`] is not set. A commit holds the
/// lock for a few renames and syncs; only a holder that is stopped or stuck keeps it this long.
pub const DEFAULT_LOCK_WAIT: Duration = Duration::from_secs(30);

/// The bound on the wait for a folder lock: [`LOCK_WAIT_VAR`] in seconds (0 or more, finite;
/// 0: fail at once), else [`DEFAULT_LOCK_WAIT`]. A bad value is a usage error naming it.
pub fn lock_wait() -> Result<Duration> {
    let Some(value) = std::env::var_os(LOCK_WAIT_VAR) else {
        return Ok(DEFAULT_LOCK_WAIT);
    };
    let text = value.to_string_lossy();
    match text.trim().parse::<f64>() {
        Ok(s) if s.is_finite() && (0.0..=1e9).contains(&s) => Ok(Duration::from_secs_f64(s)),
        _ => Err(Error::usage(format!(
            "{LOCK_WAIT_VAR}={text}: expected the seconds to wait for an output folder's lock, \
             a number from 0 (the default is {})",
            DEFAULT_LOCK_WAIT.as_secs()
        ))),
    }
}

/// Exclusive locks on the folders of a set of paths, released on drop.
#[derive(Debug)]
pub struct FolderLock {
    /// The locked folders, as first named, and open: closing them releases the locks.
    held: Vec<(PathBuf, std::fs::File)>,
}

impl FolderLock {
    /// Locks the folder of every path in `paths` (the current folder for a bare file name),
    /// waiting at most `wait` for each. A folder that does not exist or cannot be opened is
    /// skipped: the caller's own use of it reports that.
    pub fn acquire<'a>(
        paths: impl IntoIterator<Item = &'a Path>,
        wait: Duration,
    ) -> Result<FolderLock> {
        let deadline = Instant::now() + wait;
        let mut held = Vec::new();
        for (folder, dir) in open_folders(paths) {
            match lock_until(&dir, deadline) {
                Taken::Locked => held.push((folder, dir)),
                Taken::Unsupported => {}
                Taken::TimedOut => {
                    return Err(Error::Locked {
                        folder,
                        waited: wait,
                    });
                }
            }
        }
        Ok(FolderLock { held })
    }

    /// The folders locked, as first named.
    pub fn folders(&self) -> impl Iterator<Item = &Path> {
        self.held.iter().map(|(p, _)| p.as_path())
    }

    /// How many folders are locked.
    #[cfg(test)]
    pub fn len(&self) -> usize {
        self.held.len()
    }

    /// True when no folder is locked.
    #[cfg(test)]
    pub fn is_empty(&self) -> bool {
        self.held.is_empty()
    }
}

/// How [`lock_until`] ended.
enum Taken {
    Locked,
    /// The file system cannot lock this folder (see the module docs).
    Unsupported,
    /// Still held elsewhere at the deadline.
    TimedOut,
}

/// The distinct folders of `paths`, open, in the global lock order (device, inode), each with
/// the folder as first named.
#[cfg(unix)]
fn open_folders<'a>(paths: impl IntoIterator<Item = &'a Path>) -> Vec<(PathBuf, std::fs::File)> {
    use std::os::unix::fs::MetadataExt;
    let mut folders: Vec<((u64, u64), PathBuf, std::fs::File)> = Vec::new();
    for path in paths {
        let folder = parent_dir(path);
        let Ok(dir) = std::fs::File::open(folder) else {
            continue;
        };
        let Ok(meta) = dir.metadata() else {
            continue;
        };
        let key = (meta.dev(), meta.ino());
        if meta.is_dir() && !folders.iter().any(|f| f.0 == key) {
            folders.push((key, folder.to_path_buf(), dir));
        }
    }
    folders.sort_by_key(|f| f.0);
    folders.into_iter().map(|(_, p, d)| (p, d)).collect()
}

/// No folder locks where folders cannot be opened as files.
#[cfg(not(unix))]
fn open_folders<'a>(paths: impl IntoIterator<Item = &'a Path>) -> Vec<(PathBuf, std::fs::File)> {
    let _ = paths.into_iter().count();
    Vec::new()
}

/// Takes the exclusive lock of `dir`, polling until `deadline`.
fn lock_until(dir: &std::fs::File, deadline: Instant) -> Taken {
    let mut pause = Duration::from_millis(1);
    loop {
        match dir.try_lock() {
            Ok(()) => return Taken::Locked,
            Err(std::fs::TryLockError::WouldBlock) => {}
            Err(std::fs::TryLockError::Error(_)) => return Taken::Unsupported,
        }
        let now = Instant::now();
        if now >= deadline {
            return Taken::TimedOut;
        }
        std::thread::sleep(pause.min(deadline - now));
        pause = (pause * 2).min(Duration::from_millis(10));
    }
}

#[cfg(all(test, unix))]
mod tests {
    use super::*;
    use crate::output::tests::TestDir;

    #[test]
    fn a_folder_named_twice_is_locked_once_and_released_on_drop() {
        let dir = TestDir::new("lock-once");
        std::fs::create_dir(dir.0.join("sub")).unwrap();
        let (a, b, c) = (
            dir.0.join("a.png"),
            dir.0.join("sub/../b.npy"),
            dir.0.join("sub/c.json"),
        );
        let wait = Duration::from_millis(50);
        let lock = FolderLock::acquire([a.as_path(), b.as_path(), c.as_path()], wait).unwrap();
        assert_eq!(lock.len(), 2);
        // held: another open of either folder cannot take it
        let e = FolderLock::acquire([c.as_path()], Duration::ZERO).unwrap_err();
        assert_eq!(e.exit_code(), 75);
        assert!(
            matches!(&e, Error::Locked { folder, .. } if folder.ends_with("sub")),
            "{e}"
        );
        drop(lock);
        let again = FolderLock::acquire([a.as_path(), c.as_path()], Duration::ZERO).unwrap();
        assert_eq!(again.len(), 2);
        // a missing folder is left to the caller
        let none = FolderLock::acquire([dir.0.join("nope/x.png").as_path()], wait).unwrap();
        assert!(none.is_empty());
    }

    #[test]
    fn a_lock_held_briefly_is_waited_for() {
        let dir = TestDir::new("lock-wait");
        let out = dir.0.join("a.png");
        let lock = FolderLock::acquire([out.as_path()], Duration::ZERO).unwrap();
        let waiter = {
            let out = out.clone();
            std::thread::spawn(move || {
                FolderLock::acquire([out.as_path()], Duration::from_secs(60)).map(|l| l.len())
            })
        };
        std::thread::sleep(Duration::from_millis(30));
        drop(lock);
        assert_eq!(waiter.join().unwrap().unwrap(), 1);
    }
}
