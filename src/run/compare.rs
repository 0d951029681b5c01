//! `lanecast compare`: prints the packet-against-oracle report, writes the diff image, fails
//! past the tolerance. The comparison itself is the library's (`crate::compare`).

use super::load_view;
use super::say::{self, Stream};
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
    let mut text = format!(
        "scene       {}\nprecision   {}\nagainst     the f64 scalar oracle\n",
        s.view.input.display(),
        precision.name()
    );
    let (width, height, allowed) = (camera.width, camera.height, Some(s.max_mismatch_ppm));
    for line in r.lines(width, height, allowed, precision == Precision::Auto) {
        text += &line;
        text.push('\n');
    }
    // the diff image first: a standard output that fails or closes loses only the report
    if s.output.is_some() {
        set.write_image(
            "--output",
            camera.width,
            camera.height,
            &diff_picture(r, &oracle),
        )?;
    }
    set.commit()?;
    // a reader that closes the pipe (`| head -1`) wants no more: not an error
    let printed = say::write(Stream::Stdout, "write the comparison report", &text);
    if r.unexcused_ppm() > s.max_mismatch_ppm {
        // the verdict outranks a report that could not be written
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
    printed.map(|_| ())
}
