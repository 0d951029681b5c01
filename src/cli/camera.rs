//! `--eye`, `--look` and `--up`: the camera overrides and their `X,Y,Z` values.

use crate::error::{Error, Result};

/// `--eye`, `--look` and `--up`: each replaces that part of the scene's camera.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct CameraOverrides {
    pub eye: Option<glam::DVec3>,
    pub look: Option<glam::DVec3>,
    pub up: Option<glam::DVec3>,
    /// The flags given, each with its value as typed (`--eye 1e30,0,0`), for messages.
    pub typed: Vec<String>,
}

impl CameraOverrides {
    /// `spec` with the overrides applied, checked by the camera line's own rules; an error
    /// names the flags typed.
    pub fn apply(&self, spec: &mut crate::scene::CameraSpec) -> Result<()> {
        if *self == CameraOverrides::default() {
            return Ok(());
        }
        spec.eye = self.eye.unwrap_or(spec.eye);
        spec.look = self.look.unwrap_or(spec.look);
        spec.up = self.up.unwrap_or(spec.up);
        crate::scene::validate::camera(spec).map_err(|m| self.blame(m))
    }

    /// A usage error naming the flags given, as typed, before `why`: what the camera they
    /// make cannot do (`--eye 1e30,0,0: ...`).
    pub fn blame(&self, why: impl std::fmt::Display) -> Error {
        Error::usage(format!("{}: {why}", self.typed.join(" ")))
    }
}

/// A point or direction `X,Y,Z` of `flag`: three finite decimal numbers.
pub(super) fn parse_vec3(flag: &str, text: &str) -> Result<glam::DVec3> {
    let bad = || {
        Error::usage(format!(
            "{flag} {text}: expected three finite numbers X,Y,Z"
        ))
    };
    let v: Vec<f64> = text
        .split(',')
        .map(|p| p.trim().parse::<f64>().ok().filter(|x| x.is_finite()))
        .collect::<Option<_>>()
        .ok_or_else(bad)?;
    match v[..] {
        [x, y, z] => Ok(glam::DVec3::new(x, y, z)),
        _ => Err(bad()),
    }
}
