//! What the commands write to standard output and standard error: reports, help, warnings and
//! `-time`, through writers that return their errors instead of panicking as `println!` does.
//!
//! A reader that closes the pipe (`lanecast compare ... | head -1`) ends that stream's writing
//! quietly, as `-o -` does for images: the run goes on to its end and exits 0 (unless it fails
//! for another reason). Any other write error (`> /dev/full`, a closed descriptor) is an
//! [`Error::Io`] naming the stream (`<stdout>`, `<stderr>`): exit 1, after every output file of
//! the run is in place.

use crate::error::{Error, Result};
use std::io::{self, Write};

/// A standard stream.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Stream {
    Stdout,
    Stderr,
}

impl Stream {
    /// How messages name the stream.
    fn name(self) -> &'static str {
        match self {
            Stream::Stdout => "<stdout>",
            Stream::Stderr => "<stderr>",
        }
    }
}

/// Writes `text` to `stream` and flushes it: `Ok(true)` when written, `Ok(false)` when the
/// reader has closed the pipe (nothing more should go to that stream), an error naming the
/// stream and `what` (a verb phrase after "cannot") for any other failure.
pub(super) fn write(stream: Stream, what: &'static str, text: &str) -> Result<bool> {
    let written = match stream {
        Stream::Stdout => write_to(&mut io::stdout().lock(), text),
        Stream::Stderr => write_to(&mut io::stderr().lock(), text),
    };
    match written {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == io::ErrorKind::BrokenPipe => Ok(false),
        Err(e) => Err(Error::io(stream.name(), what, e)),
    }
}

/// Writes a warning line (`lanecast: warning: ...`) to standard error. A warning that cannot
/// be written is an error, a closed pipe included: the run stops before its outputs rather
/// than finish with a warning nobody saw.
pub(super) fn warn(warning: &str) -> Result<()> {
    line("warning", warning)
}

/// Writes a note (`lanecast: note: ...`) to standard error, as [`warn`] does a warning.
pub(super) fn note(note: &str) -> Result<()> {
    line("note", note)
}

/// `lanecast: KIND: TEXT` on standard error; a closed pipe is an error too.
fn line(kind: &'static str, text: &str) -> Result<()> {
    let what = match kind {
        "warning" => "write a warning",
        _ => "write a note",
    };
    match write(Stream::Stderr, what, &format!("lanecast: {kind}: {text}\n"))? {
        true => Ok(()),
        false => Err(Error::io(
            Stream::Stderr.name(),
            what,
            io::Error::from(io::ErrorKind::BrokenPipe),
        )),
    }
}

fn write_to(w: &mut impl Write, text: &str) -> io::Result<()> {
    w.write_all(text.as_bytes())?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A writer whose every write fails with `kind`.
    struct Failing(io::ErrorKind);

    impl Write for Failing {
        fn write(&mut self, _: &[u8]) -> io::Result<usize> {
            Err(io::Error::from(self.0))
        }
        fn flush(&mut self) -> io::Result<()> {
            Ok(())
        }
    }

    #[test]
    fn write_errors_are_returned_not_panicked() {
        for kind in [io::ErrorKind::BrokenPipe, io::ErrorKind::StorageFull] {
            let e = write_to(&mut Failing(kind), "text").unwrap_err();
            assert_eq!(e.kind(), kind);
        }
        let mut buf = Vec::new();
        write_to(&mut buf, "text").unwrap();
        assert_eq!(buf, b"text");
    }
}
