//! `lanecast compare`: prints the packet-against-oracle report, writes the diff image, fails
//! past the tolerance. The comparison itself is the library's (`crate::compare`).

use super::load_view;
use crate::cli::CompareSettings;
use crate::compare::{
    EDGE_BAND, Report, TIE_REL, class_colour, compare_method, compare_with, marked_render,
};
use crate::error::{Error, Result};
use crate::output;
use crate::render::{Frame, Method};

/// The diff image of `compare -o`.
fn diff_image(report: &Report, oracle: &Frame<f64>) -> Vec<u8> {
    marked_render(oracle, |i| class_colour(report.class[i]))
}

/// Runs the compare command: prints the report, writes the diff image, fails past tolerance.
pub(crate) fn compare_command(s: &CompareSettings) -> Result<()> {
    output::install_interrupt_cleanup();
    if let Some(out) = &s.output {
        output::image_format(out)?;
        if output::same_file(out, &s.view.input) {
            return Err(Error::usage(format!(
                "--output {}: is the input scene",
                out.display()
            )));
        }
    }
    let (scene, camera) = load_view(&s.view)?;
    let method = s.view.method;
    let (report, oracle) = match method {
        Method::Default => compare_with(&scene, &camera, s.view.accel),
        m => compare_method(&scene, &camera, m),
    };
    let r = &report;
    let ppm = |n: usize| n as f64 * 1e6 / r.pixels.max(1) as f64;
    println!("scene       {}", s.view.input.display());
    println!(
        "method      {} against the f64 scalar oracle",
        method.name()
    );
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
    println!(
        "depth rel   max {:.3e}, p99 {:.3e} over {} same-id hits",
        r.depth_rel_max, r.depth_rel_p99, r.same_hits
    );
    if let Some(out) = &s.output {
        output::write_image(out, camera.width, camera.height, &diff_image(r, &oracle))?;
    }
    if r.unexcused_ppm() > s.max_mismatch_ppm {
        return Err(Error::Failed(format!(
            "{} unexcused id mismatches ({:.1} ppm) exceed --max-mismatch-ppm {}",
            r.unexcused,
            r.unexcused_ppm(),
            s.max_mismatch_ppm
        )));
    }
    Ok(())
}
