//! The flags of many-view runs (`--views`, `--orbit`, `--skip-existing`) and the rules that
//! tie them to the rest of the command line (README "Many views").

use super::{RenderSettings, Typed};
use crate::error::{Error, Result};
use crate::output::Pattern;
use std::path::{Path, PathBuf};

/// Where the cameras of a many-view run come from.
#[derive(Debug, Clone, PartialEq)]
pub enum ViewSource {
    /// `--views FILE`: one camera a line.
    File(PathBuf),
    /// `--orbit N`: a turntable of N views about the scene camera's up axis.
    Orbit(usize),
}

/// The view source the flags give (clap has refused both at once).
pub fn source(views: Option<PathBuf>, orbit: Option<u32>) -> Option<ViewSource> {
    match (views, orbit) {
        (Some(file), _) => Some(ViewSource::File(file)),
        (None, Some(n)) => Some(ViewSource::Orbit(n as usize)),
        (None, None) => None,
    }
}

/// The image pattern when `-o` is not given with several views: the input's name without its
/// extension, then `_%05d.png` (`scenes/scan.sc` -> `scenes/scan_%05d.png`).
pub fn default_output(input: &Path) -> Result<PathBuf> {
    if input == Path::new(crate::scene::STDIN) {
        return Err(Error::usage(
            "-i -: a scene from standard input has no file name to put the images beside; \
             give -o PATTERN (such as frames/view_%05d.png)",
        ));
    }
    let stem = input.with_extension("");
    let Some(stem) = stem.to_str() else {
        return Err(Error::usage(format!(
            "-i {}: the name is not UTF-8, so no default output pattern can be made from it; \
             give -o PATTERN",
            input.display()
        )));
    };
    Ok(PathBuf::from(format!(
        "{}_%05d.png",
        stem.replace('%', "%%")
    )))
}

/// Refuses the many-view flags that cannot apply: `--skip-existing` or a numbered output
/// without several views, `--skip-existing` with no file per view (`-o -` alone), `--repeat` or camera flags that a views file overrides, outputs that
/// are not numbered patterns, and a numbered `--stats` (one record covers the run).
pub fn check(s: &RenderSettings, typed: &Typed) -> Result<()> {
    if let Some(p) = &s.save_views
        && !matches!(s.views, Some(ViewSource::Orbit(_)))
    {
        return Err(Error::usage(format!(
            "--save-views {}: writes the cameras of --orbit N; a --views file already holds \
             its own, and one view's camera is the scene's",
            p.display()
        )));
    }
    let Some(source) = &s.views else {
        if s.skip_existing {
            return Err(Error::usage(
                "--skip-existing applies to runs of many views (--views FILE or --orbit N)",
            ));
        }
        return Ok(());
    };
    let flag = match source {
        ViewSource::File(f) => format!("--views {}", f.display()),
        ViewSource::Orbit(n) => format!("--orbit {n}"),
    };
    if typed.has("repeat") {
        return Err(Error::usage(format!(
            "--repeat {}: with {flag} each view is rendered once; --repeat times one view",
            s.repeat
        )));
    }
    if let ViewSource::File(_) = source {
        for f in ["eye", "look", "up"] {
            if typed.has(f) {
                return Err(Error::usage(format!(
                    "--{f}: {flag} gives every view's camera; --eye, --look and --up change the \
                     scene's camera (and --orbit's)"
                )));
            }
        }
    }
    let files = [
        ("--ids", &s.ids),
        ("--depth", &s.depth),
        ("--zdepth", &s.zdepth),
        ("--normals", &s.normals),
    ];
    if s.skip_existing && s.stdout_format.is_some() && files.iter().all(|f| f.1.is_none()) {
        // no view writes a file whose presence would tell that it is done
        return Err(Error::usage(
            "--skip-existing: with -o - and no --ids, --depth, --zdepth or --normals, no view \
             writes a file to find, so every view would stream again; leave out \
             --skip-existing, or write the views to files (-o PATTERN, --ids, --depth, \
             --zdepth, --normals)",
        ));
    }
    if let Some(p) = s.image_file() {
        Pattern::parse("-o", p)?;
    }
    for (name, path) in files {
        if let Some(p) = path {
            Pattern::parse(name, p)?;
        }
    }
    if let Some(p) = &s.stats
        && Pattern::is_pattern(p)
    {
        return Err(Error::usage(format!(
            "--stats {}: one record covers every view of the run; give it a plain name",
            p.display()
        )));
    }
    Ok(())
}
