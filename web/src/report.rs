//! What the module reports back as JSON: a pick ([`Pick`]) and a scene's summary
//! ([`scene_json`]).

use glam::DVec3;
use lanecast::Scene;
use std::fmt::Write as _;

/// What a click on a primitive reports, as `--ids` and `--depth` would give it.
#[derive(Debug, Clone, PartialEq)]
pub struct Pick {
    /// The primitive's id (its index among the scene's primitives).
    pub id: i32,
    /// `sphere`, `triangle` or `quad`.
    pub kind: &'static str,
    /// Its 1-based scene line (a mesh face: the `mesh` line; 0 for a bare mesh).
    pub line: usize,
    /// Its face index within its mesh, for a mesh triangle.
    pub face: Option<usize>,
    /// The depth at the pixel: distance from the eye along the ray (f32, as `--depth`).
    pub depth: f32,
    /// The hit point, eye + depth * ray direction.
    pub point: [f64; 3],
}

impl Pick {
    /// As JSON.
    pub fn json(&self) -> String {
        let face = self.face.map_or("null".to_string(), |f| f.to_string());
        let [x, y, z] = self.point;
        format!(
            "{{\"id\":{},\"type\":\"{}\",\"line\":{},\"face\":{face},\"depth\":{},\"point\":[{x},{y},{z}]}}",
            self.id, self.kind, self.line, self.depth
        )
    }
}

/// A scene's summary, as JSON: its name, camera, the box around its primitives (`bounds`:
/// min and max corners, as the session keeps them: `Loaded::bounds`), primitive counts and
/// warnings.
pub fn scene_json(s: &Scene, bounds: [DVec3; 2]) -> String {
    let c = s.camera;
    let v = |v: DVec3| format!("[{},{},{}]", v.x, v.y, v.z);
    let fov = c.fov_deg().map_or("null".to_string(), |f| f.to_string());
    let mut counts = String::new();
    for (&(_, many), n) in lanecast::scene::KINDS.iter().zip(s.counts()) {
        let _ = write!(counts, "\"{many}\":{n},");
    }
    let mut warnings = String::new();
    for (k, w) in s.warnings.iter().enumerate() {
        let sep = if k > 0 { "," } else { "" };
        let _ = write!(warnings, "{sep}{}", json_string(w));
    }
    format!(
        "{{\"source\":{},\"camera\":{{\"eye\":{},\"look\":{},\"up\":{},\"fov\":{fov}}},\"default_fov\":{},\"bounds\":[{},{}],\"primitives\":{},{counts}\"warnings\":[{warnings}]}}",
        json_string(&s.source.to_string_lossy()),
        v(c.eye),
        v(c.look),
        v(c.up),
        lanecast::DEFAULT_FOV,
        v(bounds[0]),
        v(bounds[1]),
        s.shapes.len(),
    )
}

fn json_string(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for ch in s.chars() {
        match ch {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out.push('"');
    out
}
