//! Numbered output names for runs of many views, in ffmpeg's image-sequence convention:
//! `frames/view_%05d.png` names view 0 `frames/view_00000.png`, view 12 `frames/view_00012.png`.
//!
//! A pattern holds exactly one number conversion, `%d` or `%0Nd` (N from 1 to 20: zero-padded
//! to N digits), and any number of `%%` (a literal `%`). Views are numbered from 0 in the order
//! they are rendered (the views file's order, or the orbit's).

use crate::error::{Error, Result};
use std::path::{Path, PathBuf};

/// An output path with one view-number conversion.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Pattern {
    /// Text before the number (`%%` already turned into `%`).
    head: String,
    /// Text after the number.
    tail: String,
    /// Zero-padded width of the number (0: no padding).
    width: usize,
}

/// The widest padding a pattern may ask for (u64's 20 digits).
const MAX_WIDTH: usize = 20;

impl Pattern {
    /// The pattern `path` given to `flag` (for messages): refused, naming the flag, unless it
    /// holds exactly one `%d` or `%0Nd` and no other `%` but `%%`.
    pub fn parse(flag: &str, path: &Path) -> Result<Pattern> {
        let shown = path.display();
        let bad = |why: String| {
            Error::usage(format!(
                "{flag} {shown}: {why}; several views need a numbered name in ffmpeg's \
                 convention, such as frames/view_%05d.png (%d, or %0Nd for N digits)"
            ))
        };
        let Some(text) = path.to_str() else {
            return Err(bad("the name is not UTF-8".into()));
        };
        let (mut head, mut tail) = (String::new(), String::new());
        let mut width = None;
        let mut chars = text.chars().peekable();
        while let Some(c) = chars.next() {
            let out = if width.is_some() {
                &mut tail
            } else {
                &mut head
            };
            if c != '%' {
                out.push(c);
                continue;
            }
            if chars.peek() == Some(&'%') {
                chars.next();
                out.push('%');
                continue;
            }
            let mut digits = String::new();
            while let Some(&d) = chars.peek().filter(|d| d.is_ascii_digit()) {
                digits.push(d);
                chars.next();
            }
            let next = chars.next();
            if next != Some('d') || (!digits.is_empty() && !digits.starts_with('0')) {
                // the conversion as typed: its digits and the character that ends it
                let conversion = format!("%{digits}{}", next.map(String::from).unwrap_or_default());
                return Err(bad(format!(
                    "'{conversion}' is not a number conversion (the accepted ones are %d and \
                     %0Nd, N from 1 to {MAX_WIDTH}; %% for a percent sign)"
                )));
            }
            if width.is_some() {
                return Err(bad("it holds more than one number conversion".into()));
            }
            let w: usize = digits.parse().unwrap_or(0);
            if w > MAX_WIDTH {
                return Err(bad(format!("pads to {w} digits; at most {MAX_WIDTH}")));
            }
            width = Some(w);
        }
        match width {
            Some(width) => Ok(Pattern { head, tail, width }),
            None => Err(bad("it holds no %d".into())),
        }
    }

    /// Whether `path` holds a `%` conversion other than `%%` (so it is meant as a pattern).
    pub fn is_pattern(path: &Path) -> bool {
        let text = path.to_string_lossy();
        let mut chars = text.chars();
        while let Some(c) = chars.next() {
            if c == '%' && chars.next() != Some('%') {
                return true;
            }
        }
        false
    }

    /// The name of view `n`.
    pub fn name(&self, n: usize) -> PathBuf {
        PathBuf::from(format!(
            "{}{:0width$}{}",
            self.head,
            n,
            self.tail,
            width = self.width
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn p(s: &str) -> Result<Pattern> {
        Pattern::parse("-o", Path::new(s))
    }

    #[test]
    fn ffmpeg_conversions_name_views() {
        let v = p("frames/view_%05d.png").unwrap();
        assert_eq!(v.name(0), PathBuf::from("frames/view_00000.png"));
        assert_eq!(v.name(123_456), PathBuf::from("frames/view_123456.png"));
        assert_eq!(p("%d.npy").unwrap().name(7), PathBuf::from("7.npy"));
        assert_eq!(
            p("100%%/a%%_%3d.bmp").unwrap_err().to_string(),
            "-o 100%%/a%%_%3d.bmp: '%3d' is not a number conversion (the accepted ones are %d \
             and %0Nd, N from 1 to 20; %% for a percent sign); several views need a numbered name in ffmpeg's convention, such as \
             frames/view_%05d.png (%d, or %0Nd for N digits)"
        );
        assert_eq!(
            p("100%%/a_%03d.bmp").unwrap().name(5),
            PathBuf::from("100%/a_005.bmp")
        );
    }

    #[test]
    fn names_without_one_number_are_refused() {
        for bad in [
            "out.png",
            "a_%d_%d.png",
            "a_%s.png",
            "a_%",
            "a_%021d.png",
            "a_%%.png",
        ] {
            let e = p(bad).unwrap_err().to_string();
            assert!(e.starts_with(&format!("-o {bad}: ")), "{e}");
        }
        assert!(Pattern::is_pattern(Path::new("a_%d.png")));
        assert!(Pattern::is_pattern(Path::new("a_%s.png")));
        assert!(!Pattern::is_pattern(Path::new("100%%.png")));
        assert!(!Pattern::is_pattern(Path::new("plain.png")));
    }

    #[test]
    fn distinct_views_get_distinct_names() {
        for s in ["v%d.png", "v%01d.png", "v%04d.png"] {
            let v = p(s).unwrap();
            let names: std::collections::HashSet<_> = (0..20_000).map(|n| v.name(n)).collect();
            assert_eq!(names.len(), 20_000, "{s}");
        }
    }
}
