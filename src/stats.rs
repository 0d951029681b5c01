//! The record of one render: what ran, on what, and how long each phase took. `-time` prints
//! it for people (stderr), `--stats FILE.json` writes it for scripts.

use crate::scene::KINDS;
use crate::words::count;
use std::fmt::Write as _;
use std::path::Path;
use std::time::Duration;

/// One run's facts. Times in seconds.
#[derive(Debug, Clone, Default)]
pub struct Stats {
    /// lanecast's version (`CARGO_PKG_VERSION`).
    pub version: &'static str,
    /// The full command line, program name first (lossy where an argument is not UTF-8).
    pub command: Vec<String>,
    pub scene: String,
    pub width: usize,
    pub height: usize,
    /// Primitives by kind, in `scene::KINDS` order.
    pub primitives: [usize; KINDS.len()],
    pub kernel: &'static str,
    /// The precision that ran, as `--precision` names it: `auto`, `f32` or `f64`.
    pub precision: &'static str,
    pub accel: &'static str,
    pub threads: usize,
    /// Seed of the `random` colours.
    pub seed: u64,
    /// Every output file of the run: (what, path as given), `what` one of `image`, `ids`,
    /// `depth`, `zdepth`, `normals`, `stats`; a many-view run's numbered outputs as their
    /// patterns (`frames/view_%05d.png`; each view's own names are in `poses`).
    pub outputs: Vec<(&'static str, String)>,
    /// Phases in order: parse, setup, render (best of the repeats), shade, write.
    pub phases: Vec<(&'static str, f64)>,
    /// Render phase of every repeat.
    pub renders: Vec<f64>,
    /// Pixels whose f32 hit was decided again in f64 (`--precision auto` with the simd kernel;
    /// `None` where nothing is re-decided).
    pub redecided: Option<usize>,
    /// Per-view times of a many-view run (`--views`, `--orbit`); `None` for one view.
    pub views: Option<ViewTimes>,
    /// Every view's camera and outputs, in order (one for a one-view run): `views[i]` of the
    /// record.
    pub poses: Vec<ViewRecord>,
}

/// One view's camera and output names, as the record keeps them (`views[i]`): the camera as
/// used (eye, look, up and its lens, a default field of view filled in), its 3x3 K and 4x4
/// world-to-camera matrix (OpenCV axes: `camera::Camera::k_matrix`, `world_to_camera`).
#[derive(Debug, Clone)]
pub struct ViewRecord {
    /// Eye, look, up and lens.
    pub spec: crate::scene::CameraSpec,
    /// The camera made of it for the run's size.
    pub camera: crate::camera::Camera,
    /// (what, path) of each of its outputs, as `Stats::outputs`.
    pub outputs: Vec<(&'static str, String)>,
    /// Index into `ViewTimes::each` when it rendered in a many-view run; `None` when
    /// `--skip-existing` left it out, or in a one-view run.
    pub rendered: Option<usize>,
    /// Left out by `--skip-existing`.
    pub skipped: bool,
}

impl ViewRecord {
    /// The view's JSON object: `camera` (eye, look, up, and `fov` or `K` as fx, fy, cx, cy),
    /// `K`, `world_to_camera`, `outputs`, `skipped`, and its times when it rendered.
    fn json(&self, times: Option<&ViewTimes>) -> serde_json::Value {
        use crate::scene::Lens;
        // -0.0 (a rotation's zeros, negated) written as 0.0: `x + 0.0` is +0.0 for either zero
        let z = |x: f64| x + 0.0;
        let v = |v: glam::DVec3| serde_json::json!([z(v.x), z(v.y), z(v.z)]);
        let m3 = self.camera.k_matrix().map(|r| r.map(z));
        let m4 = self.camera.world_to_camera().map(|r| r.map(z));
        let mut camera = serde_json::json!({
            "eye": v(self.spec.eye), "look": v(self.spec.look), "up": v(self.spec.up),
        });
        match self.spec.lens {
            Some(Lens::Fov(f)) => camera["fov"] = f.into(),
            Some(Lens::Pinhole(k)) => {
                camera["K"] = serde_json::json!({"fx": k.fx, "fy": k.fy, "cx": k.cx, "cy": k.cy})
            }
            None => {}
        }
        let outputs: serde_json::Map<String, serde_json::Value> = (self.outputs.iter())
            .map(|(what, path)| (what.to_string(), path.clone().into()))
            .collect();
        let mut record = serde_json::json!({
            "camera": camera,
            "K": m3,
            "world_to_camera": m4,
            "outputs": outputs,
            "skipped": self.skipped,
        });
        if let Some(t) = self.rendered.and_then(|i| times?.each.get(i)) {
            for (key, value) in [
                ("setup_s", t.setup_s.into()),
                ("render_s", t.render_s.into()),
                ("output_s", t.output_s.into()),
                ("left_out", t.left_out.into()),
                ("renders", t.renders.into()),
            ] {
                record[key] = value;
            }
        }
        record
    }
}

/// The times of a many-view run's views, in seconds.
#[derive(Debug, Clone, Default)]
pub struct ViewTimes {
    /// Each rendered view, in order.
    pub each: Vec<ViewTime>,
    /// Views left out by `--skip-existing`.
    pub skipped: usize,
}

/// One rendered view's seconds and culling.
#[derive(Debug, Clone, Copy, Default)]
pub struct ViewTime {
    /// Preparing the scene for its camera (`Rendered::setup_s`).
    pub setup_s: f64,
    /// Tracing its rays (`Rendered::render_s`).
    pub render_s: f64,
    /// Shading, encoding, writing and committing its outputs.
    pub output_s: f64,
    /// Primitives it left out (`Rendered::left_out`).
    pub left_out: usize,
    /// Renders it took (`Rendered::renders`).
    pub renders: usize,
}

impl ViewTimes {
    /// Setup plus render of each view: the per-view cost, outputs excluded.
    pub fn costs(&self) -> Vec<f64> {
        self.each.iter().map(|t| t.setup_s + t.render_s).collect()
    }

    /// The median of `costs` (NaN when no view rendered).
    pub fn median_cost(&self) -> f64 {
        median(self.costs())
    }
}

/// The median of `v` (NaN when empty).
fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    match v.len() {
        0 => f64::NAN,
        n if n % 2 == 1 => v[n / 2],
        n => (v[n / 2 - 1] + v[n / 2]) / 2.0,
    }
}

impl Stats {
    pub fn render_best(&self) -> f64 {
        self.renders.iter().copied().fold(f64::INFINITY, f64::min)
    }

    pub fn render_median(&self) -> f64 {
        median(self.renders.clone())
    }

    /// Primary rays per second of the best render.
    pub fn rays_per_s(&self) -> f64 {
        (self.width * self.height) as f64 / self.render_best().max(1e-12)
    }

    /// The images [`Stats::redecided`] counts the pixels of: every rendered view of a
    /// many-view run, else the one image (of the last repeat).
    pub fn images(&self) -> usize {
        self.views.as_ref().map_or(1, |v| v.each.len())
    }

    /// The fraction of the rendered pixels re-decided in f64, over every rendered view of a
    /// many-view run (`None` unless `auto` ran).
    pub fn redecided_fraction(&self) -> Option<f64> {
        let pixels = self.width * self.height * self.images();
        self.redecided.map(|n| n as f64 / pixels.max(1) as f64)
    }

    /// The precision and SIMD width that ran: rays one at a time for the scalar kernels, f64x4
    /// lanes for the packets in f64, else the packet kernel's f32x8 as this build compiles it.
    pub fn lanes(&self) -> String {
        match (self.kernel, self.precision) {
            ("scalar", _) => "f64, one ray at a time".into(),
            ("scalar-f32", _) => "f32, one ray at a time".into(),
            (_, "f64") => "f64 in f64x4 lanes, two per 8-ray packet".into(),
            _ if self.redecided.is_some() => format!(
                "f32 in {}, hits f32 cannot hold re-decided in f64 one ray at a time",
                simd_in_use()
            ),
            _ => format!("f32 in {}", simd_in_use()),
        }
    }

    /// The `-time` report.
    pub fn text(&self) -> String {
        let counts: Vec<String> = (KINDS.iter().zip(self.primitives))
            .map(|(&(one, many), n)| count(n, one, many))
            .collect();
        let mut out = String::new();
        let _ = writeln!(
            out,
            "lanecast: {} {}x{} ({})",
            self.scene,
            self.width,
            self.height,
            counts.join(", ")
        );
        let _ = writeln!(
            out,
            "  kernel {}, precision {}, accel {}, {}, {}",
            self.kernel,
            self.precision,
            self.accel,
            count(self.threads, "thread", "threads"),
            self.lanes()
        );
        for (name, secs) in &self.phases {
            let _ = writeln!(out, "  {name:<7} {:>10.3} ms", secs * 1e3);
        }
        let total: f64 = self.phases.iter().map(|p| p.1).sum();
        let _ = writeln!(out, "  {:<7} {:>10.3} ms", "total", total * 1e3);
        if let Some(v) = &self.views
            && v.each.is_empty()
        {
            let _ = writeln!(
                out,
                "  no view rendered: all {} skipped (--skip-existing found their outputs \
                 complete, made by these settings)",
                v.skipped
            );
        } else if let Some(v) = &self.views {
            let costs = v.costs();
            let _ = writeln!(
                out,
                "  {} rendered, {} skipped; per view (setup + render): first {:.3} ms, \
                 median {:.3} ms, total {:.3} ms; outputs {:.3} ms",
                count(v.each.len(), "view", "views"),
                v.skipped,
                costs.first().copied().unwrap_or(f64::NAN) * 1e3,
                v.median_cost() * 1e3,
                costs.iter().sum::<f64>() * 1e3,
                v.each.iter().map(|t| t.output_s).sum::<f64>() * 1e3,
            );
        } else if self.renders.len() > 1 {
            let _ = writeln!(
                out,
                "  render over {} repeats: best {:.3} ms, median {:.3} ms",
                self.renders.len(),
                self.render_best() * 1e3,
                self.render_median() * 1e3
            );
        }
        if !self.renders.is_empty() {
            let _ = writeln!(
                out,
                "  {:.2} Mrays/s (render phase)",
                self.rays_per_s() / 1e6
            );
        }
        if let (Some(n), Some(f)) = (self.redecided, self.redecided_fraction()) {
            let of = match self.images() {
                1 if self.views.is_none() => "the image".to_string(),
                k => format!("{} pixels", count(k, "view's", "views'")),
            };
            let _ = writeln!(
                out,
                "  re-decided in f64: {} ({:.4}% of {of})",
                count(n, "pixel", "pixels"),
                f * 100.0
            );
        }
        if let Some(kib) = peak_rss_kib() {
            let _ = writeln!(out, "  peak memory {:.1} MiB", kib as f64 / 1024.0);
        }
        out
    }

    /// The `--stats` record, as JSON (non-finite numbers become `null`).
    pub fn json(&self) -> String {
        let primitives: serde_json::Map<String, serde_json::Value> = (KINDS.iter())
            .zip(self.primitives)
            .map(|(&(_, many), n)| (many.to_string(), n.into()))
            .collect();
        let phases: serde_json::Map<String, serde_json::Value> = self
            .phases
            .iter()
            .map(|(n, v)| (n.to_string(), (*v).into()))
            .collect();
        let outputs: serde_json::Map<String, serde_json::Value> = self
            .outputs
            .iter()
            .map(|(what, path)| (what.to_string(), path.clone().into()))
            .collect();
        let record = serde_json::json!({
            "version": self.version,
            "command": self.command,
            "scene": self.scene,
            "width": self.width,
            "height": self.height,
            "primitives": primitives,
            "kernel": self.kernel,
            "precision": self.precision,
            "accel": self.accel,
            "threads": self.threads,
            "seed": self.seed,
            "outputs": outputs,
            "simd": simd_in_use(),
            "lanes": self.lanes(),
            "redecided_pixels": self.redecided,
            "redecided_fraction": self.redecided_fraction(),
            "phases_s": phases,
            "renders_s": self.renders,
            "render_best_s": self.render_best(),
            "render_median_s": self.render_median(),
            // no render (every view skipped): no rate
            "rays_per_s": (!self.renders.is_empty()).then(|| self.rays_per_s()),
            "peak_rss_bytes": peak_rss_kib().map(|k| k * 1024),
        });
        let mut record = record;
        if let Some(v) = &self.views {
            record["views_summary"] = serde_json::json!({
                "rendered": v.each.len(),
                "skipped": v.skipped,
                "median_view_s": v.median_cost(),
            });
        }
        let views: Vec<_> = (self.poses.iter())
            .map(|p| p.json(self.views.as_ref()))
            .collect();
        record["views"] = views.into();
        let mut out = serde_json::to_string_pretty(&record).expect("a JSON value always prints");
        out.push('\n');
        out
    }
}

/// What the packet kernel's `f32x8` compiles to in this build (fixed at compile time).
pub fn simd_in_use() -> &'static str {
    if cfg!(all(target_feature = "avx2", target_feature = "fma")) {
        "f32x8 as one AVX2 register (FMA available, unused by the kernels)"
    } else if cfg!(target_feature = "avx") {
        "f32x8 as one AVX register"
    } else {
        "f32x8 as two SSE halves (portable build)"
    }
}

/// Peak resident memory of this process (VmHWM), in KiB, where the OS tells it.
pub fn peak_rss_kib() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = status.lines().find(|l| l.starts_with("VmHWM:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Seconds of a duration.
pub fn secs(d: Duration) -> f64 {
    d.as_secs_f64()
}

/// The scene path as recorded.
pub fn scene_name(p: &Path) -> String {
    p.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn stats() -> Stats {
        Stats {
            version: "9.8.7",
            command: vec!["lanecast".into(), "-i".into(), "a \"q\".sc".into()],
            seed: u64::MAX,
            outputs: vec![("image", "a.png".into()), ("stats", "s.json".into())],
            scene: "a \"q\".sc".into(),
            width: 10,
            height: 10,
            primitives: [1, 2, 3],
            kernel: "simd",
            precision: "f32",
            accel: "bvh",
            threads: 2,
            phases: vec![("parse", 0.001), ("render", 0.002)],
            renders: vec![0.004, 0.002, 0.003, 0.010],
            redecided: None,
            views: None,
            poses: Vec::new(),
        }
    }

    #[test]
    fn time_names_the_precision_and_lanes_that_ran_and_counts_threads() {
        let mut s = stats();
        assert!(
            s.text().contains(", 2 threads, f32 in f32x8"),
            "{}",
            s.text()
        );
        assert!(
            s.text().contains("kernel simd, precision f32, accel bvh,"),
            "{}",
            s.text()
        );
        s.threads = 1;
        s.kernel = "scalar";
        s.precision = "f64";
        assert!(
            s.text().contains(", 1 thread, f64, one ray at a time"),
            "{}",
            s.text()
        );
        s.kernel = "scalar-f32";
        assert_eq!(s.lanes(), "f32, one ray at a time");
        s.kernel = "simd";
        assert!(s.lanes().starts_with("f64 in f64x4 lanes"));
        let j: serde_json::Value = serde_json::from_str(&s.json()).unwrap();
        assert_eq!(j["precision"].as_str(), Some("f64"));
        assert!(j.get("method").is_none(), "no method: the lab's");
        // auto: the precision, the re-decisions, in words and as a fraction of the image
        s.precision = "auto";
        s.redecided = Some(1);
        let text = s.text();
        assert!(text.contains("precision auto, accel bvh,"), "{text}");
        assert!(
            text.contains("re-decided in f64: 1 pixel (1.0000% of the image)"),
            "{text}"
        );
        assert!(
            text.contains("hits f32 cannot hold re-decided in f64"),
            "{text}"
        );
        let j: serde_json::Value = serde_json::from_str(&s.json()).unwrap();
        assert_eq!(j["precision"], "auto");
        assert_eq!(j["redecided_pixels"].as_u64(), Some(1));
        assert_eq!(j["redecided_fraction"].as_f64(), Some(0.01));
    }

    #[test]
    fn best_median_and_rate() {
        let s = stats();
        assert_eq!(s.render_best(), 0.002);
        assert_eq!(s.render_median(), 0.0035);
        assert!((s.rays_per_s() - 50_000.0).abs() < 1e-6);
    }

    #[test]
    fn json_escapes_and_lists_every_field() {
        let j = stats().json();
        assert!(j.contains(r#""scene": "a \"q\".sc""#), "{j}");
        for key in [
            "primitives",
            "kernel",
            "precision",
            "accel",
            "threads",
            "simd",
            "phases_s",
        ] {
            assert!(j.contains(&format!("\"{key}\"")), "{key}");
        }
        let v: serde_json::Value = serde_json::from_str(&j).expect("valid JSON");
        assert_eq!(v["render_best_s"].as_f64(), Some(2e-3), "{j}");
        assert_eq!(v["scene"], "a \"q\".sc");
        assert_eq!(v["version"], "9.8.7");
        assert_eq!(v["command"][2], "a \"q\".sc");
        assert_eq!(v["seed"].as_u64(), Some(u64::MAX));
        assert_eq!(v["outputs"]["image"], "a.png");
        assert_eq!(v["outputs"]["stats"], "s.json");
    }
}
