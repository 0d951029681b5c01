//! Errors carried as values up to `main`, which prints them once and picks the exit code.

use std::fmt;
use std::path::PathBuf;

/// Every way a lanecast run can fail. `exit_code` maps each to the documented code:
/// 2 for bad usage or bad input (content), 75 for an output folder whose lock another run held
/// too long, 1 for everything else: I/O (a missing or unreadable scene or mesh file, an
/// unwritable output) and failed comparisons.
#[derive(Debug)]
pub enum Error {
    /// A bad command-line argument; the message names the argument.
    Usage(String),
    /// Bad content in an input file, at a 1-based line and column (column 0: whole line).
    Input {
        /// The file, as the path it was opened by.
        file: PathBuf,
        /// 1-based line number.
        line: usize,
        /// 1-based column, or 0 when the message is about the whole line.
        col: usize,
        /// What is wrong, without the location.
        msg: String,
    },
    /// An input file as a whole is unusable (unreadable, not UTF-8, no camera line...).
    InputFile {
        /// The file, as the path it was opened by.
        file: PathBuf,
        /// What is wrong with it.
        msg: String,
    },
    /// Reading or writing a file failed.
    Io {
        /// The file or folder the operation was on.
        path: PathBuf,
        /// What was being done, as a verb phrase after "cannot" ("read scene", "write output").
        action: &'static str,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// Reading a file that an input file names failed (a scene's `mesh` file): an I/O error
    /// like [`Error::Io`], reported at the line that names the file.
    IoAt {
        /// The input file whose line names `path`.
        file: PathBuf,
        /// 1-based line of `file` that names `path`.
        line: usize,
        /// 1-based column of `path` on that line (0: none known).
        col: usize,
        /// The file the operation was on, as resolved (relative to `file`'s folder).
        path: PathBuf,
        /// What was being done, as a verb phrase after "cannot" ("read mesh").
        action: &'static str,
        /// The underlying I/O error.
        source: std::io::Error,
    },
    /// Another run held the lock of an output folder for longer than the run would wait
    /// (`LANECAST_LOCK_WAIT`): nothing was written.
    Locked {
        /// The folder, as the output's path names it.
        folder: PathBuf,
        /// How long the run waited.
        waited: std::time::Duration,
    },
    /// Anything else that is not the user's input: encoder failures, failed comparisons.
    Failed(String),
}

/// The exit code of [`Error::Locked`]: sysexits' `EX_TEMPFAIL`, a failure that a later retry
/// may not meet.
pub const LOCKED_EXIT: i32 = 75;

impl Error {
    /// The process exit code for this error: 2 for usage and input errors, 75
    /// for a lock another run held too long, 1 for I/O and other failures. A file that
    /// cannot be read is an I/O error whether the command line names it (the scene) or the
    /// scene does (a mesh).
    pub fn exit_code(&self) -> i32 {
        match self {
            Error::Usage(_) | Error::Input { .. } | Error::InputFile { .. } => 2,
            Error::Locked { .. } => LOCKED_EXIT,
            Error::Io { .. } | Error::IoAt { .. } | Error::Failed(_) => 1,
        }
    }

    /// A [`Error::Usage`] with the given message.
    pub fn usage(msg: impl Into<String>) -> Error {
        Error::Usage(msg.into())
    }

    /// An [`Error::Input`] at `file`, 1-based `line` and `col` (0 for the whole line).
    pub fn input(
        file: impl Into<PathBuf>,
        line: usize,
        col: usize,
        msg: impl Into<String>,
    ) -> Error {
        Error::Input {
            file: file.into(),
            line,
            col,
            msg: msg.into(),
        }
    }

    /// An [`Error::Io`]: `action` on `path` failed with `source`.
    pub fn io(path: impl Into<PathBuf>, action: &'static str, source: std::io::Error) -> Error {
        Error::Io {
            path: path.into(),
            action,
            source,
        }
    }
}

impl fmt::Display for Error {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Error::Usage(m) => write!(f, "{m}"),
            Error::Input {
                file,
                line,
                col,
                msg,
            } if *col > 0 => {
                write!(f, "{}:{line}:{col}: {msg}", file.display())
            }
            Error::Input {
                file, line, msg, ..
            } => write!(f, "{}:{line}: {msg}", file.display()),
            Error::InputFile { file, msg } => write!(f, "{}: {msg}", file.display()),
            Error::Io {
                path,
                action,
                source,
            } => {
                write!(f, "{}: cannot {action}: {source}", path.display())
            }
            Error::IoAt {
                file,
                line,
                col,
                path,
                action,
                source,
            } => {
                let col = if *col > 0 {
                    format!(":{col}")
                } else {
                    String::new()
                };
                write!(
                    f,
                    "{}:{line}{col}: cannot {action} {}: {source}",
                    file.display(),
                    path.display()
                )
            }
            Error::Locked { folder, waited } => write!(
                f,
                "{}: another lanecast run held this output folder's lock for {} s (it replaces \
                 outputs there one run at a time); nothing written, try again",
                folder_name(folder),
                waited.as_secs_f64()
            ),
            Error::Failed(m) => write!(f, "{m}"),
        }
    }
}

impl std::error::Error for Error {}

/// A folder as a message names it: as given, or, for the current folder (`.`, or the empty
/// folder of a bare file name), "the current folder (ITS ABSOLUTE PATH)".
fn folder_name(folder: &std::path::Path) -> String {
    if !(folder.as_os_str().is_empty() || folder == std::path::Path::new(".")) {
        return folder.display().to_string();
    }
    match std::env::current_dir() {
        Ok(d) => format!("the current folder ({})", d.display()),
        Err(_) => "the current folder".into(),
    }
}

/// `std::result::Result` with lanecast's [`Error`] as the default error type.
pub type Result<T, E = Error> = std::result::Result<T, E>;
