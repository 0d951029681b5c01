//! `lanecast compare`: prints the packet-against-oracle report, writes the diff image, fails
//! past the tolerance. The comparison itself is the library's (`crate::compare`).

use super::load_view;
use crate::cli::CompareSettings;
use crate::compare::{EDGE_BAND, LIST_UNEXCUSED, TIE_REL, compare_precision, diff_picture};
use crate::error::{Error, Result};
use crate::output::{self, OutputKind, OutputSet};
use crate::precision::Precision;
use crate::words::count;

/// Runs the compare command: prints the report, writes the diff image, fails past tolerance.
pub(crate) fn compare_command(s: &CompareSettings) -> Result<()> {
    output::install_interrupt_cleanup();
    // The diff image follows the render command's rules: checked, and its temporary file
    // created, before the scene is read; renamed into place only after the whole comparison.
    let outs: Vec<_> = s
        .output
        .as_deref()
        .map(|p| ("--output", p, OutputKind::Image))
        .into_iter()
        .collect();
    let mut set = OutputSet::create(&outs, &[("the input scene", &s.view.input)])?;
    let (scene, camera) = load_view(&s.view, &set)?;
    let precision = s.view.precision;
    let (report, oracle) = compare_precision(&scene, &camera, precision, s.view.accel);
    let r = &report;
    let ppm = |n: usize| n as f64 * 1e6 / r.pixels.max(1) as f64;
    println!("scene       {}", s.view.input.display());
    println!("precision   {}", precision.name());
    println!("against     the f64 scalar oracle");
    println!(
        "pixels      {} ({}x{})",
        r.pixels, camera.width, camera.height
    );
    println!(
        "mismatches  {} ({:.1} ppm)",
        r.mismatches,
        ppm(r.mismatches)
    );
    println!(
        "  ties      {} (f64 distances within {TIE_REL:e} relative)",
        r.ties
    );
    println!(
        "  edge band {} (ray within {EDGE_BAND:.2e} rad of a boundary)",
        r.edges
    );
    println!(
        "  unexcused {} ({:.1} ppm; allowed {} ppm)",
        r.unexcused,
        r.unexcused_ppm(),
        s.max_mismatch_ppm
    );
    if r.unexcused > 0 {
        let first: Vec<String> = (r.unexcused_pixels(camera.width))
            .take(LIST_UNEXCUSED)
            .map(|(x, y)| format!("({x}, {y})"))
            .collect();
        let shown = if r.unexcused > LIST_UNEXCUSED {
            format!("first {LIST_UNEXCUSED}")
        } else {
            "all".to_string()
        };
        println!("  unexcused at (x, y), {shown}: {}", first.join(" "));
    }
    if precision == Precision::Auto {
        println!(
            "re-decided  {} in f64 ({:.4}%)",
            count(r.redecided.len(), "pixel", "pixels"),
            r.redecided.len() as f64 * 100.0 / r.pixels.max(1) as f64
        );
    }
    println!(
        "depth rel   max {:.3e}, p99 {:.3e} over {}",
        r.depth_rel_max,
        r.depth_rel_p99,
        count(r.same_hits, "same-id hit", "same-id hits")
    );
    if s.output.is_some() {
        set.write_image(
            "--output",
            camera.width,
            camera.height,
            &diff_picture(r, &oracle),
        )?;
    }
    set.commit()?;
    if r.unexcused_ppm() > s.max_mismatch_ppm {
        return Err(Error::Failed(format!(
            "{} ({:.1} ppm) exceed --max-mismatch-ppm {}",
            count(
                r.unexcused,
                "unexcused id mismatch",
                "unexcused id mismatches"
            ),
            r.unexcused_ppm(),
            s.max_mismatch_ppm
        )));
    }
    Ok(())
}
