//! The accuracy lab: every intersection method ([`methods`], plus lanecast's own kernels and
//! precisions) on the stress scenes (`scenes/stress/`) and the seed scenes, measured against the
//! f64 scalar oracle, with throughput on one thread; writes a chart, a table and error images
//! to `docs/lab/`. Run it with `cargo bench -p lanecast-lab --bench lab` (see [`lab_main`]).
//!
//! The lab is its own crate on top of lanecast: it uses the library's public API (scenes,
//! cameras, `compare`'s mismatch classes) and its inner layers (`lanecast::experimental`:
//! kernels, ray tables, constant records), and nothing in lanecast imports it, so the
//! `lanecast` binary never links the chart's plotting crate nor the lab's methods.
//!
//! - `methods/`: the other intersection methods (Möller–Trumbore, watertight, plane, the
//!   textbook sphere, f32 world-space setup), 1-lane and 8-lane forms side by side;
//! - `kits.rs`: their brute-force drivers, and the f64 scalar oracle;
//! - `method.rs`: [`Method`], one point on the chart, and its driver;
//! - `render.rs`: `lab-render` (`src/bin/lab-render.rs`), one scene with any method against
//!   the oracle, reported as `lanecast compare` reports lanecast's precisions;
//! - `scenes.rs`: the scenes the lab measures on ([`LabScene`]), with their `# lab:` lines;
//! - `measure.rs`: mismatches (ties, edge band, unexcused), holes, false hits, depth error,
//!   throughput;
//! - `report.rs`: the Markdown table, the chart (plotters), the error images;
//! - `bvh_spike/`: a world-space BVH traversed by pixel tiles, the many-view design measured
//!   against `--accel world` and Embree (`examples/bvh_spike`, `scripts/bvh_spike_table.py`;
//!   docs/architecture.md, "Many views: object order against a world-space BVH").

pub mod bvh_spike;
pub mod kits;
pub mod measure;
pub mod method;
pub mod methods;
pub mod render;
pub mod report;
pub mod scenes;

use lanecast::{Error, Result};
pub use method::Method;
pub use scenes::{DEFAULT_SIZE, LabFrame, LabScene, load_all};
use std::path::{Path, PathBuf};

/// Runs the whole lab: `args` may hold `--out DIR` (default `docs/lab`), `--only SCENE` (a
/// scene name, repeatable, for quick runs) and `--method NAME` (repeatable). Writes
/// `speed-vs-accuracy.svg`/`.png`, `table.md` and `err-*.png`, and prints one line per scene
/// and method to stderr.
pub fn lab_main(args: impl IntoIterator<Item = String>) -> Result<()> {
    // The lab crate sits in `lab/` beside the product's `src/`; scenes and docs are the root's.
    let root = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("lab/ has a parent")
        .to_path_buf();
    let mut out = root.join("docs/lab");
    let mut only: Vec<String> = Vec::new();
    let mut methods: Vec<Method> = Vec::new();
    let mut it = args.into_iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--out" => {
                out = PathBuf::from(
                    it.next()
                        .ok_or_else(|| Error::usage("--out needs a folder"))?,
                )
            }
            "--only" => only.push(
                it.next()
                    .ok_or_else(|| Error::usage("--only needs a scene"))?,
            ),
            "--method" => {
                let m = it
                    .next()
                    .ok_or_else(|| Error::usage("--method needs a name"))?;
                methods.push(
                    Method::parse(&m).ok_or_else(|| Error::usage(format!("unknown method {m}")))?,
                );
            }
            // cargo bench passes --bench; ignore flags meant for the harness
            "--bench" => {}
            other => return Err(Error::usage(format!("unknown lab argument {other}"))),
        }
    }
    if methods.is_empty() {
        methods = Method::ALL.to_vec();
    }
    let mut scenes = load_all(&root)?;
    if !only.is_empty() {
        scenes.retain(|s| only.contains(&s.name));
    }
    std::fs::create_dir_all(&out).map_err(|e| Error::Failed(format!("{}: {e}", out.display())))?;
    let started = std::time::Instant::now();
    let mut results = Vec::new();
    for s in &scenes {
        let r = measure::run_scene(s, &methods);
        for m in &r.rows {
            eprintln!(
                "{:<14} {:<14} mism {:>7} unexc {:>6} holes {:>6} false {:>6} dmed {:.1e} dp99 {:.1e} {:>7.2} Mrays/s",
                s.name,
                m.method.name(),
                m.mismatches,
                m.unexcused,
                m.holes,
                m.false_hits,
                m.depth_med,
                m.depth_p99,
                m.rays_per_s / 1e6
            );
        }
        results.push(r);
    }
    report::write_all(&out, &scenes, &results, &methods)?;
    eprintln!(
        "lab: {} scenes x {} methods in {:.1} s, written to {}",
        scenes.len(),
        methods.len(),
        started.elapsed().as_secs_f64(),
        out.display()
    );
    Ok(())
}
