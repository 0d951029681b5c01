//! `lanecast compare`: prints the packet-against-oracle report, writes the diff image, fails
//! past the tolerance. The comparison itself is the library's (`crate::compare`).

use super::load_view;
use crate::cli::CompareSettings;
use crate::compare::{compare_precision, diff_picture};
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
    println!("scene       {}", s.view.input.display());
    println!("precision   {}", precision.name());
    println!("against     the f64 scalar oracle");
    let (width, height, allowed) = (camera.width, camera.height, Some(s.max_mismatch_ppm));
    for line in r.lines(width, height, allowed, precision == Precision::Auto) {
        println!("{line}");
    }
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
