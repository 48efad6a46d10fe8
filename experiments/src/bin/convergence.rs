//! Convergence study (Son et al. 2020, section 5, "cubic convergence"): approximation error
//! against the number of elements for every built-in model, G1 biarcs (joint on the curve,
//! notes `biarcs.md` section 1.4) against chords (a polyline), with fitted log-log slopes.
//!
//! Each spiral of a model is cut into `m` equal-parameter pieces (m = 1, 2, 4, ..., 64); a
//! piece gets one biarc (2 arcs) or 2 chords, so both methods use the same element count. The
//! error is the densely sampled two-sided Hausdorff distance (max over pieces); the biarcs'
//! guaranteed bound is written next to it. Slopes are least-squares fits of log(error) on
//! log(elements) over `m >= FIT_MIN_PIECES` (the asymptotic range).
//!
//! Usage: `cargo run --release -p experiments --bin convergence [OUT_DIR]` (default `figures`);
//! writes `OUT_DIR/convergence.csv` and `OUT_DIR/convergence.svg`.

use std::fmt::Write as _;
use std::path::PathBuf;

use plotters::prelude::*;
use revdist::biarc::oracle::sampled_hausdorff;
use revdist::biarc::{fit_biarc, Arc, BiarcTree, CurveSample};
use revdist::models;
use revdist::profile::Profile;

/// Pieces per spiral: 2^0 .. 2^MAX_LEVEL.
const MAX_LEVEL: u32 = 6;
/// Smallest pieces-per-spiral used in the slope fit (coarser levels are pre-asymptotic).
const FIT_MIN_PIECES: usize = 4;
/// Samples per piece and per element for the sampled Hausdorff distance.
const SAMPLES: usize = 64;
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

fn study(name: &str, profile: &Profile) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    // Any eps gives the same spirals; the tree is only used for its segmentation.
    let tree = BiarcTree::build(profile, 1e-2)?;
    let mut rows = Vec::new();
    for level in 0..=MAX_LEVEL {
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
                e_biarc = e_biarc.max(sampled_hausdorff(curve, a, b, &fit.arcs, SAMPLES));
                b_biarc = b_biarc.max(fit.eps);
                let mid = CurveSample::at(curve, 0.5 * (a + b));
                let chords: Vec<Arc> = [(&sa, &mid), (&mid, &sb)]
                    .iter()
                    .filter_map(|(p, q)| {
                        Arc::from_point_tangent_point(p.point, q.point - p.point, q.point)
                    })
                    .collect();
                e_chord = e_chord.max(sampled_hausdorff(curve, a, b, &chords, SAMPLES));
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
        .map(|r| ((r.elements as f64).log10(), r.max_error.log10()))
        .collect();
    if pts.len() < 3 {
        return None;
    }
    let n = pts.len() as f64;
    let (mx, my) = (
        pts.iter().map(|p| p.0).sum::<f64>() / n,
        pts.iter().map(|p| p.1).sum::<f64>() / n,
    );
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    Some(sxy / sxx)
}

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let out_dir = PathBuf::from(std::env::args().nth(1).unwrap_or_else(|| "figures".into()));
    std::fs::create_dir_all(&out_dir)?;
    let mut names: Vec<String> = models::model_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    names.push("morph@0.5".into());
    let mut rows = Vec::new();
    for name in &names {
        let profile = models::model(name)?;
        rows.extend(study(name, &profile)?);
    }

    let mut csv =
        String::from("model,method,pieces_per_spiral,elements,max_error,max_bound,fitted_slope\n");
    let mut slopes = Vec::new();
    for name in &names {
        for method in ["biarc", "chord"] {
            let sel: Vec<&Row> = rows
                .iter()
                .filter(|r| &r.model == name && r.method == method)
                .collect();
            let s = slope(&sel);
            slopes.push((name.clone(), method, s));
            for r in &sel {
                writeln!(
                    csv,
                    "{},{},{},{},{:.6e},{},{}",
                    r.model,
                    r.method,
                    r.pieces_per_spiral,
                    r.elements,
                    r.max_error,
                    if r.max_bound.is_nan() {
                        String::new()
                    } else {
                        format!("{:.6e}", r.max_bound)
                    },
                    s.map(|v| format!("{v:.3}")).unwrap_or_default()
                )?;
            }
        }
    }
    std::fs::write(out_dir.join("convergence.csv"), &csv)?;
    for (name, method, s) in &slopes {
        match s {
            Some(v) => println!("{name:>10} {method:>6} slope {v:+.3}"),
            None => println!("{name:>10} {method:>6} slope n/a (error at rounding level: exact)"),
        }
    }
    draw(&out_dir.join("convergence.svg"), &names, &rows)?;
    println!(
        "wrote {} and {}",
        out_dir.join("convergence.csv").display(),
        out_dir.join("convergence.svg").display()
    );
    Ok(())
}

fn draw(path: &PathBuf, names: &[String], rows: &[Row]) -> Result<(), Box<dyn std::error::Error>> {
    let shown: Vec<&Row> = rows.iter().filter(|r| r.max_error > NOISE_FLOOR).collect();
    let (xmin, xmax) = shown.iter().fold((f64::MAX, 0.0f64), |(a, b), r| {
        (a.min(r.elements as f64), b.max(r.elements as f64))
    });
    let (ymin, ymax) = shown.iter().fold((f64::MAX, 0.0f64), |(a, b), r| {
        (a.min(r.max_error), b.max(r.max_error))
    });
    let root = SVGBackend::new(path, (900, 600)).into_drawing_area();
    root.fill(&WHITE)?;
    let mut chart = ChartBuilder::on(&root)
        .caption(
            "Hausdorff error vs elements: biarcs (solid) and chords (dashed)",
            ("sans-serif", 18),
        )
        .margin(10)
        .margin_right(40)
        .x_label_area_size(45)
        .y_label_area_size(70)
        .build_cartesian_2d(
            (xmin * 0.8..xmax * 1.25).log_scale(),
            (ymin * 0.5..ymax * 2.0).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("elements (arcs or chords)")
        .y_desc("max sampled Hausdorff error")
        .x_label_formatter(&|v| format!("{v:.0}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 13))
        .draw()?;
    for (i, name) in names.iter().enumerate() {
        let color = Palette99::pick(i).to_rgba();
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
            if method == "biarc" {
                chart
                    .draw_series(LineSeries::new(pts.clone(), style))?
                    .label(name.as_str())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            } else {
                let series = chart.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))?;
                // models approximated exactly by biarcs have only a chord curve: label it
                if !shown
                    .iter()
                    .any(|r| &r.model == name && r.method == "biarc")
                {
                    series
                        .label(format!("{name} (chords only; biarcs exact)"))
                        .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
                }
            }
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, color.filled())))?;
        }
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK)
        .label_font(("sans-serif", 12))
        .draw()?;
    root.present()?;
    Ok(())
}
