//! The lab's outputs: `table.md` (every measure per method and scene), the chart
//! `speed-vs-accuracy.svg`/`.png` (plotters: SVG backend, and the bitmap backend drawing into
//! a buffer that the crate's own `image` dependency encodes as PNG), and `err-*.png` images.

use super::measure::{FALSE_HIT, HOLE, Row, SceneResult};
use crate::Method;
use crate::scenes::LabScene;
use lanecast::compare::{class_colour, marked_render};
use lanecast::output;
use lanecast::{Error, Result};
use plotters::prelude::*;
use std::fmt::Write as _;
use std::path::Path;

/// Chart floor for a method with no error at all (log axis).
pub const ZERO_FLOOR_PPM: f64 = 0.1;

/// One method summed over scenes.
#[derive(Debug, Clone)]
pub struct Summary {
    pub method: Method,
    /// Chart pixels (unexcused | hole | false hit) per million stress-scene pixels.
    pub error_ppm: f64,
    /// Every id mismatch that is not a genuine tie (edge band counted), per million
    /// stress-scene pixels.
    pub nontie_ppm: f64,
    pub unexcused: usize,
    pub holes: usize,
    pub false_hits: usize,
    pub ties: usize,
    pub edges: usize,
    pub pixels: usize,
    /// Largest p99 depth error over the stress scenes.
    pub depth_p99: f64,
    /// Geometric mean rays/s over the seed scenes and over the stress scenes.
    pub seed_rays_per_s: f64,
    pub stress_rays_per_s: f64,
    /// Pixels re-decided in f64 (`auto`), per million pixels of the seed and of the stress
    /// scenes.
    pub seed_redecided_ppm: f64,
    pub stress_redecided_ppm: f64,
}

/// Re-decided pixels per million over `rows`.
fn ppm<'a>(rows: impl Iterator<Item = &'a Row>) -> f64 {
    let (n, px) = rows.fold((0, 0), |(n, px), r| (n + r.redecided, px + r.pixels));
    n as f64 * 1e6 / px.max(1) as f64
}

fn geomean(v: impl Iterator<Item = f64>) -> f64 {
    let (s, n) = v.fold((0.0, 0), |(s, n), x| (s + x.ln(), n + 1));
    if n == 0 { 0.0 } else { (s / n as f64).exp() }
}

pub fn summarise(results: &[SceneResult], methods: &[Method]) -> Vec<Summary> {
    methods
        .iter()
        .map(|&m| {
            let rows = |stress: bool| {
                results
                    .iter()
                    .filter(move |r| r.stress == stress)
                    .flat_map(move |r| r.rows.iter().filter(move |x| x.method == m))
            };
            let sum = |f: fn(&Row) -> usize| rows(true).map(f).sum::<usize>();
            let pixels = sum(|r| r.pixels);
            Summary {
                method: m,
                error_ppm: sum(|r| r.errors) as f64 * 1e6 / pixels.max(1) as f64,
                nontie_ppm: sum(|r| r.mismatches - r.ties) as f64 * 1e6 / pixels.max(1) as f64,
                unexcused: sum(|r| r.unexcused),
                holes: sum(|r| r.holes),
                false_hits: sum(|r| r.false_hits),
                ties: sum(|r| r.ties),
                edges: sum(|r| r.edges),
                pixels,
                depth_p99: rows(true).map(|r| r.depth_p99).fold(0.0, f64::max),
                seed_rays_per_s: geomean(rows(false).map(|r| r.rays_per_s)),
                stress_rays_per_s: geomean(rows(true).map(|r| r.rays_per_s)),
                seed_redecided_ppm: ppm(rows(false)),
                stress_redecided_ppm: ppm(rows(true)),
            }
        })
        .collect()
}

/// For `auto`: the fraction of pixels it re-decided in f64, seed and stress scenes.
fn redecided_note(s: &Summary) -> String {
    if s.method == Method::Auto {
        format!(
            "; re-decided {:.2}% of seed, {:.2}% of stress pixels",
            s.seed_redecided_ppm / 1e4,
            s.stress_redecided_ppm / 1e4
        )
    } else {
        String::new()
    }
}

/// The machine, for the table's header: CPU model from /proc/cpuinfo.
pub fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|t| {
            t.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_string())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{cpu}, {cores} cores available, one thread used")
}

fn e(x: f64) -> String {
    if x == 0.0 {
        "0".into()
    } else {
        format!("{x:.1e}")
    }
}

/// The Markdown table of every measure.
pub fn table(scenes: &[LabScene], results: &[SceneResult], sums: &[Summary]) -> String {
    let mut t = String::new();
    let _ = writeln!(t, "Machine: {}.\n", machine());
    let _ = writeln!(
        t,
        "### Summary (the chart's points)\n\n\
         errors = pixels that are unexcused id mismatches, holes or false hits, per million pixels \
         of all stress scenes (chart panel a); non-tie mismatches = every id mismatch except \
         genuine ties, edge band included (panel b); worst depth p99 = the largest 99th \
         percentile of the relative depth error over the stress scenes; Mrays/s = geometric \
         mean of one-thread throughput over the 7 seed scenes and over the 12 stress scenes.\n"
    );
    let _ = writeln!(
        t,
        "| method | errors (ppm) | non-tie mismatches (ppm) | unexcused | holes | false hits | ties | edge band | worst depth p99 | Mrays/s seed | Mrays/s stress |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
    );
    for s in sums {
        let _ = writeln!(
            t,
            "| `{}` | {:.1} | {:.0} | {} | {} | {} | {} | {} | {} | {:.2} | {:.2} |",
            s.method.name(),
            s.error_ppm,
            s.nontie_ppm,
            s.unexcused,
            s.holes,
            s.false_hits,
            s.ties,
            s.edges,
            e(s.depth_p99),
            s.seed_rays_per_s / 1e6,
            s.stress_rays_per_s / 1e6
        );
    }
    let _ = writeln!(t, "\nMethods:\n");
    for s in sums {
        let _ = writeln!(
            t,
            "- `{}`: {}{}",
            s.method.name(),
            s.method.describe(),
            redecided_note(s)
        );
    }
    let _ = writeln!(t, "\n### Per scene\n");
    for (sc, r) in scenes.iter().zip(results) {
        let (w, h) = (r.oracle.width, r.oracle.height);
        let _ = writeln!(
            t,
            "**{}** ({}, {w}x{h}, {} primitives; f64 scalar oracle {:.2} Mrays/s)\n",
            r.name,
            if r.stress { "stress" } else { "seed" },
            sc.scene.shapes.len(),
            r.oracle_rays_per_s / 1e6
        );
        let _ = writeln!(
            t,
            "| method | mismatch ppm | ties | edge | unexcused | holes | false hits | depth med | p99 | max | Mrays/s |\n|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|"
        );
        for x in &r.rows {
            let _ = writeln!(
                t,
                "| `{}` | {:.0} | {} | {} | {} | {} | {} | {} | {} | {} | {:.2} |",
                x.method.name(),
                x.ppm(x.mismatches),
                x.ties,
                x.edges,
                x.unexcused,
                x.holes,
                x.false_hits,
                e(x.depth_med),
                e(x.depth_p99),
                e(x.depth_max),
                x.rays_per_s / 1e6
            );
        }
        let _ = writeln!(t);
    }
    t
}

/// Non-dominated points (lower error, higher speed), sorted by error.
pub fn pareto(points: &[(f64, f64)]) -> Vec<usize> {
    let mut idx: Vec<usize> = (0..points.len()).collect();
    idx.sort_by(|&a, &b| {
        points[a]
            .0
            .total_cmp(&points[b].0)
            .then(points[b].1.total_cmp(&points[a].1))
    });
    let mut best = f64::NEG_INFINITY;
    idx.into_iter()
        .filter(|&i| {
            let keep = points[i].1 > best;
            best = best.max(points[i].1);
            keep
        })
        .collect()
}

const COLOURS: [RGBColor; 8] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(255, 127, 14),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(23, 190, 207),
    RGBColor(127, 127, 127),
];

fn draw<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    sums: &[Summary],
) -> std::result::Result<(), String>
where
    DB::ErrorType: 'static,
{
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let root = root
        .titled(
            "lanecast: one-thread throughput vs error of each intersection method (log-log)",
            ("sans-serif", 22),
        )
        .map_err(|e| e.to_string())?;
    let (w, _) = root.dim_in_pixel();
    let (left, right) = root.split_horizontally(w / 2);
    draw_panel(
        left,
        sums,
        |s| s.error_ppm,
        "(a) real failures: unexcused + holes + false hits",
        "errors, ppm of stress-scene pixels (edge band excused; 0 drawn at 0.1)",
        false,
    )?;
    draw_panel(
        right,
        sums,
        |s| s.nontie_ppm,
        "(b) every id mismatch except genuine ties",
        "non-tie mismatches, ppm of stress-scene pixels (0 drawn at 0.1)",
        true,
    )
}

fn draw_panel<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    sums: &[Summary],
    metric: fn(&Summary) -> f64,
    title: &str,
    x_desc: &str,
    legend: bool,
) -> std::result::Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let pts: Vec<(f64, f64)> = sums
        .iter()
        .map(|s| (metric(s).max(ZERO_FLOOR_PPM), s.seed_rays_per_s / 1e6))
        .collect();
    // fixed decades: plotters 0.3.7's log-scale mesh (`LogCoord::key_points`) spun on some
    // data-dependent ranges (partial runs); these ranges are known to draw
    let xmax = pts.iter().map(|p| p.0).fold(1e7, f64::max) * 10.0;
    let ymin = pts.iter().map(|p| p.1).fold(10.0, f64::min) / 2.0;
    let ymax = pts.iter().map(|p| p.1).fold(500.0, f64::max) * 2.0;
    let mut chart = ChartBuilder::on(&root)
        .caption(title, ("sans-serif", 17))
        .margin(16)
        .x_label_area_size(50)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (ZERO_FLOOR_PPM / 2.0..xmax).log_scale(),
            (ymin..ymax).log_scale(),
        )
        .map_err(|e| err(&e))?;
    chart
        .configure_mesh()
        .x_desc(x_desc)
        .y_desc("throughput, Mrays/s (one thread, geomean of 7 seed scenes)")
        .axis_desc_style(("sans-serif", 14))
        .label_style(("sans-serif", 13))
        .draw()
        .map_err(|e| err(&e))?;
    let front = pareto(&pts);
    let mut line = Vec::new();
    for (j, &i) in front.iter().enumerate() {
        line.push(pts[i]);
        if let Some(&n) = front.get(j + 1) {
            line.push((pts[n].0, pts[i].1));
        }
    }
    chart
        .draw_series(LineSeries::new(line, BLACK.stroke_width(2)))
        .map_err(|e| err(&e))?
        .label("Pareto front (ringed: no other method is both faster and more accurate)")
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], BLACK.stroke_width(2)));
    for (i, (s, p)) in sums.iter().zip(&pts).enumerate() {
        let c = COLOURS[i % COLOURS.len()];
        chart
            .draw_series(std::iter::once(Circle::new(*p, 7, c.filled())))
            .map_err(|e| err(&e))?
            .label(format!(
                "{}: {}{}",
                s.method.name(),
                s.method.describe(),
                redecided_note(s)
            ))
            .legend(move |(x, y)| Circle::new((x + 10, y), 5, c.filled()));
        // labels of points that (nearly) coincide are stacked downwards
        let stacked = pts[..i]
            .iter()
            .filter(|q| (q.0 / p.0).ln().abs() < 0.5 && (q.1 / p.1).ln().abs() < 0.1)
            .count() as i32;
        chart
            .draw_series(std::iter::once(
                EmptyElement::at(*p)
                    + Text::new(
                        s.method.name().to_string(),
                        (12, 18 * stacked - 20),
                        ("sans-serif", 15).into_font().color(&c),
                    ),
            ))
            .map_err(|e| err(&e))?;
    }
    // ring the points on the front (a front of one point has no line to show)
    chart
        .draw_series(
            front
                .iter()
                .map(|&i| Circle::new(pts[i], 11, BLACK.stroke_width(2))),
        )
        .map_err(|e| err(&e))?;
    if !legend {
        return Ok(());
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerRight)
        .label_font(("sans-serif", 12))
        .background_style(WHITE.mix(0.85))
        .border_style(BLACK)
        .draw()
        .map_err(|e| err(&e))?;
    root.present().map_err(|e| err(&e))?;
    Ok(())
}

/// Registers a TrueType font for plotters' text (ab_glyph has no font lookup of its own).
fn register_font() -> Result<()> {
    static DONE: std::sync::OnceLock<bool> = std::sync::OnceLock::new();
    let ok = *DONE.get_or_init(|| {
        let candidates = [
            "/usr/share/fonts/truetype/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/TTF/DejaVuSans.ttf",
            "/usr/share/fonts/dejavu/DejaVuSans.ttf",
            "/usr/share/fonts/truetype/liberation/LiberationSans-Regular.ttf",
            "/Library/Fonts/Arial.ttf",
            "C:\\Windows\\Fonts\\arial.ttf",
        ];
        candidates.iter().any(|p| {
            std::fs::read(p).is_ok_and(|bytes| {
                let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
                plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
            })
        })
    });
    if ok {
        Ok(())
    } else {
        Err(Error::Failed(
            "no TrueType font found for the chart (looked for DejaVuSans.ttf)".into(),
        ))
    }
}

/// Writes the chart as SVG and PNG.
pub fn chart(out: &Path, sums: &[Summary]) -> Result<()> {
    register_font()?;
    let (w, h) = (1800u32, 760u32);
    let svg = out.join("speed-vs-accuracy.svg");
    draw(SVGBackend::new(&svg, (w, h)).into_drawing_area(), sums).map_err(Error::Failed)?;
    let mut buf = vec![0u8; (w * h * 3) as usize];
    draw(
        BitMapBackend::with_buffer(&mut buf, (w, h)).into_drawing_area(),
        sums,
    )
    .map_err(Error::Failed)?;
    output::write_image(&out.join("speed-vs-accuracy.png"), w, h, &buf)
}

/// The error image: the oracle's render at a third of its brightness, mismatches marked: tie
/// yellow, edge band cyan, unexcused red, hole magenta, false hit white.
pub fn error_image(oracle: &crate::scenes::LabFrame, row: &Row) -> Vec<u8> {
    marked_render(oracle, |i| {
        let c = row.class[i];
        if c & FALSE_HIT != 0 {
            Some([255, 255, 255])
        } else if c & HOLE != 0 {
            Some([255, 0, 255])
        } else {
            class_colour(c & 3)
        }
    })
}

/// A measure of a row, for ranking.
type RowMetric = fn(&Row) -> usize;

/// The (scene, method) pairs to draw: the 8 with the most chart errors (panel a), then the 4
/// with the most non-tie mismatches (panel b) among the rest; at most 2 per scene.
pub fn worst(results: &[SceneResult]) -> Vec<(usize, usize)> {
    let mut per_scene = std::collections::HashMap::new();
    let mut out: Vec<(usize, usize)> = Vec::new();
    let metrics: [(RowMetric, usize); 2] = [(|x| x.errors, 8), (|x| x.mismatches - x.ties, 12)];
    for (metric, upto) in metrics {
        let mut all: Vec<(usize, usize, usize)> = results
            .iter()
            .enumerate()
            .flat_map(|(si, r)| {
                r.rows
                    .iter()
                    .enumerate()
                    .map(move |(mi, x)| (si, mi, metric(x)))
            })
            .filter(|x| x.2 > 0)
            .collect();
        all.sort_by_key(|x| std::cmp::Reverse(x.2));
        for (si, mi, _) in all {
            let n = per_scene.entry(si).or_insert(0);
            if *n < 2 && out.len() < upto && !out.contains(&(si, mi)) {
                *n += 1;
                out.push((si, mi));
            }
        }
    }
    out
}

/// Writes everything into `out`.
pub fn write_all(
    out: &Path,
    scenes: &[LabScene],
    results: &[SceneResult],
    methods: &[Method],
) -> Result<()> {
    let sums = summarise(results, methods);
    output::write_atomic(
        &out.join("table.md"),
        table(scenes, results, &sums).as_bytes(),
    )?;
    // old error images would outlive a run that no longer produces them
    if let Ok(dir) = std::fs::read_dir(out) {
        for f in dir.flatten() {
            let n = f.file_name().to_string_lossy().into_owned();
            if n.starts_with("err-") && n.ends_with(".png") {
                let _ = std::fs::remove_file(f.path());
            }
        }
    }
    for (si, mi) in worst(results) {
        let r = &results[si];
        let row = &r.rows[mi];
        let path = out.join(format!("err-{}-{}.png", r.name, row.method.name()));
        let (w, h) = (r.oracle.width, r.oracle.height);
        output::write_image(&path, w, h, &error_image(&r.oracle, row))?;
    }
    // plotters 0.3.7 spins in its log-scale mesh (`LogCoord::key_points`) when every point sits
    // on the zero floor (seen with `--only behind`): partial runs without any error skip the chart
    if sums.len() < 2 || sums.iter().all(|s| s.nontie_ppm == 0.0) {
        eprintln!("lab: chart skipped (fewer than 2 methods, or no error to plot)");
        return Ok(());
    }
    chart(out, &sums)
}
