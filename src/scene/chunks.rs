//! Splitting a file's bytes at line boundaries into chunks that threads parse independently,
//! and the pieces the `.sc` and OBJ parsers share to join the chunks' results in file order.
//!
//! Every chunk but the last ends just after a `\n`, so no line (and, since `\n` is never part
//! of a multi-byte UTF-8 sequence, no character) straddles two chunks. Each chunk knows the
//! 1-based number of its first line: the newlines of every chunk are counted in parallel and
//! prefix-summed, so line numbers in messages are the file's own.

use crate::error::{Error, Result};
use crate::par::prelude::*;
use std::fs::File;
use std::io::Read;
use std::ops::Range;
use std::path::Path;
use std::sync::atomic::{AtomicUsize, Ordering};

/// How many bytes of a file are read first and searched for a NUL byte, which no text holds:
/// a binary file (or `/dev/zero`) is refused from them, before anything else is read.
pub const BINARY_PROBE: usize = 8192;

/// The bytes of the file at `path`, at most `limit + 1` of them (so that the caller can tell a
/// file that grew past the limit). The first [`BINARY_PROBE`] bytes are read before the rest:
/// a NUL among them refuses the file as binary ([`refuse_binary`], `text` naming the kind of
/// text expected), and nothing more is read; `text` is `None` for a format with a binary form
/// (PLY), read whatever it holds. `action` names I/O failures ("read scene").
///
/// The rest of a regular file is read in parallel, each thread of the current pool reading its
/// parts into one lazily zeroed buffer: mapping a fresh buffer's pages costs more than copying
/// the text in, and this way the threads share it. Anything else (a pipe, a file whose size
/// changes while it is read) is read from start to end.
pub fn read_file(
    path: &Path,
    limit: u64,
    action: &'static str,
    text: Option<&str>,
) -> Result<Vec<u8>> {
    let io = |e| Error::io(path, action, e);
    let mut file = File::open(path).map_err(io)?;
    let meta = file.metadata().map_err(io)?;
    let len = meta.len();
    let head = read_head(&mut file, path, limit, action, text)?;
    if (head.len() as u64) < probe_len(limit) {
        // the whole file
        return Ok(head);
    }
    #[cfg(unix)]
    if meta.is_file() && len > 0 && len <= limit {
        use std::os::unix::fs::FileExt;
        let mut bytes = vec![0u8; len as usize];
        let part = chunk_bytes(bytes.len());
        let read = bytes
            .par_chunks_mut(part)
            .enumerate()
            .try_for_each(|(k, b)| file.read_exact_at(b, (k * part) as u64));
        // exactly `len` bytes, and nothing after them
        if read.is_ok() && matches!(file.read_at(&mut [0], len), Ok(0)) {
            return Ok(bytes);
        }
    }
    #[cfg(not(unix))]
    let _ = len;
    read_rest(file, head, limit).map_err(io)
}

/// [`read_file`] for a stream (standard input): the first bytes checked as binary, then the
/// rest, at most `limit + 1` bytes in all. `name` names it in messages.
pub fn read_stream(
    mut r: impl Read,
    name: &Path,
    limit: u64,
    action: &'static str,
    text: &str,
) -> Result<Vec<u8>> {
    let head = read_head(&mut r, name, limit, action, Some(text))?;
    read_rest(r, head, limit).map_err(|e| Error::io(name, action, e))
}

/// How many bytes [`read_head`] asks for.
fn probe_len(limit: u64) -> u64 {
    (BINARY_PROBE as u64).min(limit.saturating_add(1))
}

/// The first bytes of `r` (all of them when it is shorter than [`BINARY_PROBE`]), refused as
/// binary when they hold a NUL.
fn read_head(
    r: &mut impl Read,
    path: &Path,
    limit: u64,
    action: &'static str,
    text: Option<&str>,
) -> Result<Vec<u8>> {
    let mut head = Vec::with_capacity(BINARY_PROBE);
    r.take(probe_len(limit))
        .read_to_end(&mut head)
        .map_err(|e| Error::io(path, action, e))?;
    if let Some(text) = text {
        refuse_binary(path, &head, text)?;
    }
    Ok(head)
}

/// `head` followed by the rest of `r`, up to `limit + 1` bytes in all. `take` guards against
/// files that grow after the size check, and special files.
fn read_rest(r: impl Read, mut head: Vec<u8>, limit: u64) -> std::io::Result<Vec<u8>> {
    let room = limit.saturating_add(1).saturating_sub(head.len() as u64);
    r.take(room).read_to_end(&mut head)?;
    Ok(head)
}

/// Refuses `bytes` (the start of `path`) when they hold a NUL byte: binary data, not `text`.
/// The message names the line and column of the first NUL.
pub fn refuse_binary(path: &Path, bytes: &[u8], text: &str) -> Result<()> {
    let Some(at) = bytes.iter().position(|&b| b == 0) else {
        return Ok(());
    };
    let line_start = bytes[..at]
        .iter()
        .rposition(|&b| b == b'\n')
        .map_or(0, |i| i + 1);
    let line = bytes[..line_start].iter().filter(|&&b| b == b'\n').count() + 1;
    let prefix = String::from_utf8_lossy(&bytes[line_start..at]);
    let prefix = prefix.strip_prefix('\u{feff}').unwrap_or(&prefix);
    Err(Error::input(
        path,
        line,
        prefix.chars().count() + 1,
        format!("binary data (byte 0x00); {text} must be text"),
    ))
}

/// A run of whole lines: `bytes[range]`, whose first line is line `first_line` of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct Chunk {
    pub range: Range<usize>,
    pub first_line: usize,
}

/// The chunk size for `len` bytes: about four chunks per thread of the current rayon pool, so
/// that a slow chunk does not leave a thread idle, from 256 KiB (below which the split costs
/// more than it gains) to 4 MiB (chunks stay cache-sized).
pub fn chunk_bytes(len: usize) -> usize {
    let threads = crate::par::current_num_threads().max(1);
    (len / (4 * threads)).clamp(256 << 10, 4 << 20)
}

/// Splits `bytes` into chunks of at least `target` bytes (the last may be shorter), each ending
/// just after a newline, and numbers their first lines. Empty input is one empty chunk.
pub fn split(bytes: &[u8], target: usize) -> Vec<Chunk> {
    let target = target.max(1);
    let mut ends = Vec::with_capacity(bytes.len() / target + 1);
    let mut start = 0;
    while bytes.len() - start > target {
        // the chunk ends after the first newline at or beyond `start + target - 1`
        let from = start + target - 1;
        match bytes[from..].iter().position(|&b| b == b'\n') {
            Some(p) if from + p + 1 < bytes.len() => {
                start = from + p + 1;
                ends.push(start);
            }
            _ => break,
        }
    }
    ends.push(bytes.len());
    let newlines: Vec<usize> = ends
        .par_iter()
        .enumerate()
        .map(|(k, &end)| {
            let begin = if k == 0 { 0 } else { ends[k - 1] };
            count_newlines(&bytes[begin..end])
        })
        .collect();
    let mut first_line = 1;
    let mut begin = 0;
    ends.iter()
        .zip(newlines)
        .map(|(&end, n)| {
            let chunk = Chunk {
                range: begin..end,
                first_line,
            };
            begin = end;
            first_line += n;
            chunk
        })
        .collect()
}

/// The lines of `bytes` (split at each `\n`, which they do not include, the last one running to
/// the end) as ranges of `bytes`, in order: `bytes.split(|&b| b == b'\n')`, found 8 bytes at a
/// time (lines are a few dozen bytes: this spares `str::split` its `memchr` call and byte
/// comparison per line, 8% of an OBJ parse).
pub fn lines(bytes: &[u8]) -> impl Iterator<Item = Range<usize>> + '_ {
    let mut start = Some(0);
    std::iter::from_fn(move || {
        let from = start?;
        let end = newline(&bytes[from..]).map(|k| from + k);
        start = end.map(|e| e + 1);
        Some(from..end.unwrap_or(bytes.len()))
    })
}

/// The index of the first `\n` in `b`: a word at a time, then byte by byte.
fn newline(b: &[u8]) -> Option<usize> {
    const ONES: u64 = 0x0101_0101_0101_0101;
    let mut i = 0;
    while let Some(w) = b[i..].first_chunk::<8>() {
        // the lowest byte of `x` that is zero, i.e. the first `\n`, sets its high bit here
        let x = u64::from_le_bytes(*w) ^ (ONES * u64::from(b'\n'));
        let zero = x.wrapping_sub(ONES) & !x & (ONES << 7);
        if zero != 0 {
            return Some(i + zero.trailing_zeros() as usize / 8);
        }
        i += 8;
    }
    b[i..].iter().position(|&c| c == b'\n').map(|k| i + k)
}

/// How many `\n` bytes `bytes` holds, 64 bytes at a time (a form the compiler vectorises).
fn count_newlines(bytes: &[u8]) -> usize {
    let blocks = bytes.chunks_exact(64);
    let tail = blocks.remainder();
    let whole: usize = blocks
        .map(|b| b.iter().map(|&c| u8::from(c == b'\n')).sum::<u8>() as usize)
        .sum();
    whole + tail.iter().filter(|&&c| c == b'\n').count()
}

/// A bound on what all chunks together may allocate: every chunk records its items here in
/// batches, and stops once more than `max` have been recorded in all. Run in parallel, chunks
/// may spend the budget out of file order, so a stop there only means "redo this in order";
/// run one chunk after the other, a stop means the file itself holds more than `max` items
/// before that point (the batches only record items already parsed).
pub struct Budget {
    used: AtomicUsize,
    max: usize,
    /// Items per batch: 1024 for the real limits, fewer for small ones (tests).
    pub batch: usize,
}

impl Budget {
    pub fn new(max: usize) -> Budget {
        Budget {
            used: AtomicUsize::new(0),
            max,
            batch: (max / 4096).clamp(1, 1024),
        }
    }

    /// Records `n` more items; false once more than `max` have been recorded.
    pub fn take(&self, n: usize) -> bool {
        self.used.fetch_add(n, Ordering::Relaxed) + n <= self.max
    }
}

/// Concatenates pieces of the given lengths in parallel: element `j` of piece `p` is
/// `get(p, j)`. An indexed iterator, so that `collect` writes the result in place, once.
pub fn gather<T, F>(lens: &[usize], get: F) -> impl IndexedParallelIterator<Item = T>
where
    T: Send,
    F: Fn(usize, usize) -> T + Send + Sync,
{
    let mut starts = Vec::with_capacity(lens.len());
    let mut total = 0;
    for &n in lens {
        starts.push(total);
        total += n;
    }
    (0..total).into_par_iter().with_min_len(4096).map(move |i| {
        // the last piece starting at or before i; empty pieces are skipped over
        let p = starts.partition_point(|&s| s <= i) - 1;
        get(p, i - starts[p])
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn chunks_end_after_newlines_and_number_their_lines() {
        let text = b"a\nbb\n\nccc\r\nd";
        for target in 1..=text.len() + 1 {
            let chunks = split(text, target);
            assert_eq!(chunks[0].range.start, 0);
            assert_eq!(chunks.last().unwrap().range.end, text.len());
            for w in chunks.windows(2) {
                assert_eq!(w[0].range.end, w[1].range.start);
                assert_eq!(text[w[0].range.end - 1], b'\n');
            }
            for c in &chunks {
                assert!(!c.range.is_empty());
                let before = text[..c.range.start].iter().filter(|&&b| b == b'\n');
                assert_eq!(c.first_line, before.count() + 1);
            }
        }
        assert_eq!(split(text, 1).len(), 5, "one chunk per line");
        assert_eq!(
            split(b"", 4),
            vec![Chunk {
                range: 0..0,
                first_line: 1
            }]
        );
    }

    #[test]
    fn lines_split_like_the_standard_split() {
        for text in [
            &b""[..],
            b"\n",
            b"a",
            b"a\n",
            b"\n\nabc\r\n0123456789abcdef\n01234567\n0123456\nx",
            b"0123456789abcdefghij\x8a\n\x0a\x0b\xff\xfe\n",
        ] {
            let want: Vec<&[u8]> = text.split(|&b| b == b'\n').collect();
            let got: Vec<&[u8]> = lines(text).map(|r| &text[r]).collect();
            assert_eq!(got, want);
        }
    }

    #[test]
    fn newline_count_matches_naive_count() {
        let text: Vec<u8> = (0..1000u32)
            .map(|i| if i % 7 == 0 { b'\n' } else { b'x' })
            .collect();
        for n in [0, 1, 63, 64, 65, 200, 1000] {
            let want = text[..n].iter().filter(|&&b| b == b'\n').count();
            assert_eq!(count_newlines(&text[..n]), want);
        }
    }

    #[test]
    fn gather_concatenates_in_order() {
        let parts: Vec<Vec<u32>> =
            vec![vec![], (0..5000).collect(), vec![], (5000..5003).collect()];
        let lens: Vec<usize> = parts.iter().map(Vec::len).collect();
        let all: Vec<u32> = gather(&lens, |p, j| parts[p][j]).collect();
        assert_eq!(all, (0..5003).collect::<Vec<u32>>());
    }

    #[test]
    fn budget_stops_past_its_max() {
        let b = Budget::new(3);
        assert_eq!(b.batch, 1);
        assert!(b.take(2) && b.take(1));
        assert!(!b.take(1));
    }
}
