//! Convergence study (Son et al. 2020, section 5, "cubic convergence"): approximation error
//! against the number of elements for every built-in model, G1 biarcs (joint on the curve,
//! notes `biarcs.md` section 1.4) against chords (a polyline), with fitted log-log slopes.
//!
//! Each spiral of a model is cut into `m` equal-parameter pieces (m = 1, 2, 4, ..., 16, or 64
//! with `--paper`); a
//! piece gets one biarc (2 arcs) or 2 chords, so both methods use the same element count. The
//! error is the densely sampled two-sided Hausdorff distance (max over pieces); the biarcs'
//! guaranteed bound is written next to it. Slopes are least-squares fits of log(error) on
//! log(elements) over `m >= FIT_MIN_PIECES` (the asymptotic range).
//!
//! Usage: `cargo run --release -p experiments --bin convergence -- [--out DIR] [--paper]`
//! (default `figures`; `--paper` refines to 64 pieces per spiral with 4 times the samples);
//! writes `DIR/convergence.csv` and `DIR/convergence.svg`.

use std::path::PathBuf;

use clap::Parser;
use experiments::cli::{Out, Paper};
use experiments::driver::{self, DriverResult};
use experiments::table::Table;
use plotters::prelude::*;
use revdist::biarc::oracle::sampled_hausdorff;
use revdist::biarc::{fit_biarc, Arc, BiarcTree, CurveSample};
use revdist::models;
use revdist::profile::Profile;

/// Pieces per spiral: 2^0 .. 2^MAX_LEVEL (default run; the slope is fitted on 4, 8, 16).
const MAX_LEVEL: u32 = 4;
/// Finest level with `--paper` (slopes fitted on 4..64 pieces per spiral).
const PAPER_MAX_LEVEL: u32 = 6;
/// Smallest pieces-per-spiral used in the slope fit (coarser levels are pre-asymptotic).
const FIT_MIN_PIECES: usize = 4;
/// Samples per piece and per element for the sampled Hausdorff distance in the default run.
/// (Each element's farthest point is then refined by golden-section search, so the estimate
/// is accurate to far below the errors plotted: the 32 fitted slopes of 16 and of 32 samples
/// differ by at most 0.001, 4 of them at all, measured 2026-11-28; 16 cut the models' summed
/// time from 78 to 56 s on the shared 2-core machine.)
const SAMPLES: usize = 16;
/// Samples per piece and per element with `--paper`.
const PAPER_SAMPLES: usize = 64;
/// Errors below this are rounding noise (straight or circular pieces approximate exactly) and
/// are left out of the fit and the log plot.
const NOISE_FLOOR: f64 = 1e-13;

#[derive(Debug, Clone)]
struct Row {
    model: String,
    method: &'static str,
    pieces_per_spiral: usize,
    elements: usize,
    max_error: f64,
    max_bound: f64,
}

fn study(
    name: &str,
    profile: &Profile,
    (max_level, samples): (u32, usize),
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    // Any eps gives the same spirals; the tree is only used for its segmentation.
    let tree = BiarcTree::build(profile, 1e-2)?;
    let mut rows = Vec::new();
    for level in 0..=max_level {
        let m = 1usize << level;
        let (mut e_biarc, mut b_biarc, mut e_chord) = (0.0f64, 0.0f64, 0.0f64);
        let mut elements = 0;
        for s in tree.spirals() {
            let curve = &profile.pieces()[s.piece];
            let (t0, t1) = s.param_range;
            for i in 0..m {
                let a = t0 + (t1 - t0) * i as f64 / m as f64;
                let b = t0 + (t1 - t0) * (i + 1) as f64 / m as f64;
                let (sa, sb) = (CurveSample::at(curve, a), CurveSample::at(curve, b));
                let fit = fit_biarc(curve, &sa, &sb)?;
                e_biarc = e_biarc.max(sampled_hausdorff(curve, a, b, &fit.arcs, samples));
                b_biarc = b_biarc.max(fit.eps);
                let mid = CurveSample::at(curve, 0.5 * (a + b));
                let chords: Vec<Arc> = [(&sa, &mid), (&mid, &sb)]
                    .iter()
                    .filter_map(|(p, q)| {
                        Arc::from_point_tangent_point(p.point, q.point - p.point, q.point)
                    })
                    .collect();
                e_chord = e_chord.max(sampled_hausdorff(curve, a, b, &chords, samples));
                elements += 2;
            }
        }
        for (method, err, bound) in [("biarc", e_biarc, b_biarc), ("chord", e_chord, f64::NAN)] {
            rows.push(Row {
                model: name.to_string(),
                method,
                pieces_per_spiral: m,
                elements,
                max_error: err,
                max_bound: bound,
            });
        }
    }
    Ok(rows)
}

/// Least-squares slope of log10(error) on log10(elements) over the asymptotic rows above the
/// noise floor; `None` with fewer than 3 such points.
fn slope(rows: &[&Row]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = rows
        .iter()
        .filter(|r| r.pieces_per_spiral >= FIT_MIN_PIECES && r.max_error > NOISE_FLOOR)
        .map(|r| (r.elements as f64, r.max_error))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    experiments::stats::log_log_slope(&pts)
}

/// Convergence of the profile approximation (the paper's cubic convergence): for every
/// built-in model, the densely sampled Hausdorff error of G1 biarcs against chords (a
/// polyline) with the same number of elements, as each spiral is cut into 1, 2, 4, ... 16
/// pieces (64 with --paper), with the biarcs' guaranteed bound and the fitted log-log slopes.
/// Writes convergence.csv and convergence.svg.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    #[command(flatten)]
    paper: Paper,
}

/// A CSV line: a row and the slope fitted on its model and method.
type SlopedRow<'a> = (&'a Row, Option<f64>);

/// The columns of `convergence.csv`.
fn convergence_table<'r>() -> Table<'static, SlopedRow<'r>> {
    Table::new()
        .csv("model", |(r, _): &SlopedRow| r.model.clone())
        .csv("method", |(r, _)| r.method.to_owned())
        .csv("pieces_per_spiral", |(r, _)| {
            r.pieces_per_spiral.to_string()
        })
        .csv("elements", |(r, _)| r.elements.to_string())
        .csv("max_error", |(r, _)| format!("{:.6e}", r.max_error))
        .csv("max_bound", |(r, _)| match r.max_bound.is_nan() {
            true => String::new(),
            false => format!("{:.6e}", r.max_bound),
        })
        .csv("fitted_slope", |(_, s)| {
            s.map(|v| format!("{v:.3}")).unwrap_or_default()
        })
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let out_dir = args.out.dir;
    let setting = args
        .paper
        .pick((MAX_LEVEL, SAMPLES), (PAPER_MAX_LEVEL, PAPER_SAMPLES));
    let mut names: Vec<String> = models::model_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    names.push("morph@0.5".into());
    // Models are independent: study them on all cores (results are deterministic).
    use rayon::prelude::*;
    let bar = experiments::progress::bar(names.len() as u64, "convergence");
    let per_model: Vec<Result<(Vec<Row>, f64), String>> = names
        .par_iter()
        .map(|name| {
            let t = std::time::Instant::now();
            let profile = models::model(name).map_err(|e| e.to_string())?;
            let rows = study(name, &profile, setting).map_err(|e| format!("{name}: {e}"))?;
            bar.inc(1);
            Ok((rows, t.elapsed().as_secs_f64()))
        })
        .collect();
    bar.finish_and_clear();
    let mut rows = Vec::new();
    for (name, r) in names.iter().zip(per_model) {
        let (r, secs) = r?;
        eprintln!("{name:>12}: {secs:.1} s");
        rows.extend(r);
    }

    let prov = experiments::provenance::Provenance::collect(
        "convergence (biarcs vs chords)",
        &[
            ("max_level", setting.0.to_string()),
            ("samples_per_element", setting.1.to_string()),
            ("fit_min_pieces", FIT_MIN_PIECES.to_string()),
        ],
    );
    let mut slopes = Vec::new();
    let mut lines: Vec<SlopedRow> = Vec::new();
    for name in &names {
        for method in ["biarc", "chord"] {
            let sel: Vec<&Row> = rows
                .iter()
                .filter(|r| &r.model == name && r.method == method)
                .collect();
            let s = slope(&sel);
            slopes.push((name.clone(), method, s));
            lines.extend(sel.into_iter().map(|r| (r, s)));
        }
    }
    let csv = prov.csv_preamble() + &convergence_table().csv_text(&lines);
    std::fs::write(out_dir.join("convergence.csv"), &csv)?;
    for (name, method, s) in &slopes {
        match s {
            Some(v) => println!("{name:>10} {method:>6} slope {v:+.3}"),
            None => println!("{name:>10} {method:>6} slope n/a (error at rounding level: exact)"),
        }
    }
    // Two panels: shapes drawn with exact lines and arcs, and freeform B-spline shapes.
    let (freeform, exact): (Vec<String>, Vec<String>) = names
        .iter()
        .cloned()
        .partition(|n| n.ends_with("_ff") || n.starts_with("morph@"));
    draw(
        &out_dir.join("convergence.svg"),
        &[
            ("built-in models (exact lines and arcs)", exact),
            ("freeform cubic B-spline models", freeform),
        ],
        &rows,
        &slopes,
    )?;
    println!(
        "wrote {} and {}",
        out_dir.join("convergence.csv").display(),
        out_dir.join("convergence.svg").display()
    );
    Ok(())
}

type Slopes = [(String, &'static str, Option<f64>)];

fn draw(
    path: &PathBuf,
    panels: &[(&str, Vec<String>)],
    rows: &[Row],
    slopes: &Slopes,
) -> Result<(), Box<dyn std::error::Error>> {
    use experiments::plot::{colour, log_tick, CAPTION, FONT, LABEL, TICK};
    let shown: Vec<&Row> = rows.iter().filter(|r| r.max_error > NOISE_FLOOR).collect();
    let (xmin, xmax) = shown.iter().fold((f64::MAX, 0.0f64), |(a, b), r| {
        (a.min(r.elements as f64), b.max(r.elements as f64))
    });
    let (ymin, ymax) = shown.iter().fold((f64::MAX, 0.0f64), |(a, b), r| {
        (a.min(r.max_error), b.max(r.max_error))
    });
    let slope_of = |name: &str, method: &str| {
        slopes
            .iter()
            .find(|(n, m, _)| n == name && *m == method)
            .and_then(|s| s.2)
    };
    let root = SVGBackend::new(path, (1400, 640)).into_drawing_area();
    root.fill(&WHITE)?;
    let (title, body) = root.split_vertically(36);
    title.draw(&Text::new(
        "Hausdorff error vs elements: biarcs (solid) and chords (dashed); legend: fitted slopes biarcs / chords",
        (200, 8),
        (FONT, CAPTION),
    ))?;
    let areas = body.split_evenly((1, panels.len()));
    for ((caption, names), area) in panels.iter().zip(areas.iter()) {
        let mut chart = ChartBuilder::on(area)
            .caption(*caption, (FONT, LABEL + 2))
            .margin(10)
            .margin_right(30)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (xmin * 0.8..xmax * 1.25).log_scale(),
                (ymin * 0.5..ymax * 2.0).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("elements (arcs or chords)")
            .y_desc("max sampled Hausdorff error (model units)")
            .x_label_formatter(&|v| log_tick(v))
            .y_label_formatter(&|v| log_tick(v))
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, LABEL))
            .draw()?;
        for (i, name) in names.iter().enumerate() {
            let color = colour(i);
            let fmt = |s: Option<f64>| {
                s.map(|v| format!("{v:.2}"))
                    .unwrap_or_else(|| "exact".into())
            };
            let label = format!(
                "{name}: {} / {}",
                fmt(slope_of(name, "biarc")),
                fmt(slope_of(name, "chord"))
            );
            let mut labelled = false;
            for method in ["biarc", "chord"] {
                let pts: Vec<(f64, f64)> = shown
                    .iter()
                    .filter(|r| &r.model == name && r.method == method)
                    .map(|r| (r.elements as f64, r.max_error))
                    .collect();
                if pts.is_empty() {
                    continue;
                }
                let style = ShapeStyle::from(&color).stroke_width(2);
                let series = if method == "biarc" {
                    chart.draw_series(LineSeries::new(pts.clone(), style))?
                } else {
                    chart.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))?
                };
                if !labelled {
                    series.label(label.clone()).legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
                    });
                    labelled = true;
                }
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .label_font((FONT, TICK))
            .draw()?;
        // Legend key: what the two numbers are.
    }
    root.present()?;
    Ok(())
}
