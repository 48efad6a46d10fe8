//! Numerical stability near degenerate configurations: error against the
//! perturbation size `delta = 1e-16 .. 1e-1` away from each degenerate family, at the circle
//! level (double-precision circle/circle distance against exact rational arithmetic) and at
//! the solid level (certified queries against closed forms evaluated in MPFR). The cases,
//! references and bounds are documented in `experiments::stability`.
//!
//! Usage: `stability [--out DIR] [--seeds N] [--paper]` (default `figures`, 6 seeds per family
//! and delta; `--paper`: 64 seeds). Writes `DIR/stability.csv` (one row per level, family and
//! delta), `DIR/stability.md` (worst errors per family) and `DIR/stability.svg` (log-log error
//! against delta, circle and solid level in two panels).

use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use clap::Parser;
use experiments::args::positive_count;
use experiments::cli::{Out, Paper};
use experiments::driver::{self, DriverResult};
use experiments::plot::{colour, log_tick, PlotResult, CAPTION, FONT, LABEL, TICK};
use experiments::progress::bar;
use experiments::provenance::Provenance;
use experiments::stability::{
    circle_jobs, circle_samples_where, delta_value, solid_jobs, solid_samples_where, summarise,
    Config, Level, Row, Sample, CIRCLE_FAMILIES, CIRCLE_REL_BOUND, DEFAULT_EPS, DELTA_EXPONENTS,
    SOLID_FAMILIES, UNIT_ROUNDOFF,
};
use experiments::table::Table;
use plotters::prelude::*;

/// Seeds per family and delta of the default run and of `--paper`.
const DEFAULT_SEEDS: usize = 6;
const PAPER_SEEDS: usize = 64;
/// Errors at or below this (including exactly 0) are drawn at this floor of the log axis.
const PLOT_FLOOR: f64 = 1e-18;
/// Cases listed per level in the Markdown's "largest errors" lists.
const LARGEST_LISTED: usize = 5;

/// Numerical stability near degenerate configurations: the error of revdist against exact
/// references as each degenerate family is perturbed by delta = 0 and 1e-16 .. 1e-1, at the
/// circle level (double-precision circle/circle distance against exact rational arithmetic)
/// and at the solid level (certified queries against closed forms in MPFR), checked against
/// their bounds. Writes stability.csv, .md and .svg (6 seeds per family and delta; 64 with
/// --paper).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    /// Random perturbations and rigid motions per family and delta [default: 6; --paper: 64]
    #[arg(long, value_name = "N", value_parser = positive_count)]
    seeds: Option<usize>,
    #[command(flatten)]
    paper: Paper,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// The study's errors (shareable across threads) as a driver's error.
fn boxed(e: Box<dyn std::error::Error + Send + Sync>) -> Box<dyn std::error::Error> {
    e
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let seeds = args
        .seeds
        .unwrap_or(args.paper.pick(DEFAULT_SEEDS, PAPER_SEEDS));
    let out = &args.out.dir;
    let cfg = Config::full(seeds, DEFAULT_EPS);
    let settings = vec![
        ("seeds", seeds.to_string()),
        (
            "deltas",
            format!(
                "0 and 1e-{}..1e-{}",
                DELTA_EXPONENTS.end(),
                DELTA_EXPONENTS.start()
            ),
        ),
        ("solid_eps", format!("{DEFAULT_EPS:e}")),
        ("circle_rel_bound", format!("{CIRCLE_REL_BOUND:e}")),
    ];
    // The work units: the circle level's jobs, then the solid level's (one sample each,
    // seeded by its case); this run's.
    let circles = circle_jobs(&cfg);
    let units = circles + solid_jobs(&cfg);
    let mut wanted = vec![false; units];
    for u in args.shard.units(units) {
        wanted[u] = true;
    }
    let start = Instant::now();
    let pb = bar(0, "circles");
    let mut samples = circle_samples_where(&cfg, Some(&pb), &|k| wanted[k]).map_err(boxed)?;
    pb.finish_and_clear();
    let t_circles = start.elapsed().as_secs_f64();
    let pb = bar(0, "solids");
    let solids = solid_samples_where(&cfg, Some(&pb), &|k| wanted[circles + k]).map_err(boxed)?;
    samples.extend(solids.into_iter().map(|(k, s)| (circles + k, s)));
    pb.finish_and_clear();
    let seconds = start.elapsed().as_secs_f64();
    println!(
        "{} cases in {seconds:.1} s (circles {t_circles:.1} s, solids {:.1} s)",
        samples.len(),
        seconds - t_circles
    );
    let Some(samples) = args
        .shard
        .finish((out, "stability"), &settings, units, samples)?
    else {
        return Ok(()); // a shard: its raw rows are written
    };

    let rows = summarise(&samples);
    let prov = Provenance::collect(
        "stability",
        &settings
            .iter()
            .cloned()
            .chain([("seconds", format!("{seconds:.1}"))])
            .chain(args.shard.provenance())
            .collect::<Vec<_>>(),
    );
    let csv = prov.csv_preamble() + &delta_table().csv_text(&rows);
    let md = markdown(&prov, &rows, &samples, seeds);
    let (csv_path, md_path, svg_path) = (
        out.join("stability.csv"),
        out.join("stability.md"),
        out.join("stability.svg"),
    );
    std::fs::write(&csv_path, csv)?;
    std::fs::write(&md_path, &md)?;
    draw(&svg_path, &rows, seeds).map_err(|e| format!("drawing: {e}"))?;
    print!("{md}");
    let bad: Vec<&Sample> = samples.iter().filter(|s| !s.ok()).collect();
    for s in &bad {
        eprintln!("FAIL {}", s.describe());
    }
    println!(
        "wrote {}, {} and {}",
        csv_path.display(),
        md_path.display(),
        svg_path.display()
    );
    Ok(())
}

fn delta_text(d: Option<i32>) -> String {
    d.map_or("0".into(), |k| format!("1e-{k}"))
}

fn opt(x: f64) -> String {
    if x.is_nan() {
        String::new()
    } else {
        format!("{x:.3e}")
    }
}

/// The columns of `stability.csv`: one line per level, family and delta.
fn delta_table() -> Table<'static, Row> {
    let sci3 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.3e}", f(r));
    Table::new()
        .csv("level", |r: &Row| r.key.level.name().to_owned())
        .csv("family", |r| r.key.family.to_owned())
        .csv("delta", |r| format!("{:e}", delta_value(r.key.delta)))
        .csv("cases", |r| r.cases.to_string())
        .csv("max_abs_error", sci3(|r| r.max_abs))
        .csv("median_abs_error", sci3(|r| r.median_abs))
        .csv("max_rel_error", sci3(|r| r.max_rel))
        .csv("median_rel_error", sci3(|r| r.median_rel))
        .csv("bound", sci3(|r| r.bound))
        .csv("max_error_over_bound", sci3(|r| r.max_over_bound))
        .csv("max_certified_width", |r| opt(r.max_width))
        .csv("certificate_violations", |r| match r.key.level {
            Level::Solid => r.certificate_violations.to_string(),
            Level::Circle => String::new(),
        })
        .csv("bound_exceeded", |r| r.bound_exceeded.to_string())
        .csv("max_time_us", |r| format!("{:.1}", r.max_seconds * 1e6))
}

/// One line of the Markdown table: a family's worst cases over all deltas.
struct FamilyLine<'a> {
    level: Level,
    family: &'a str,
    variants: &'a [&'a str],
    rows: Vec<&'a Row>,
}

impl FamilyLine<'_> {
    /// The family's row maximising `key`.
    fn worst(&self, key: fn(&Row) -> f64) -> &Row {
        worst(&self.rows, key)
    }
    fn solid(&self) -> bool {
        self.level == Level::Solid
    }
    /// `count` summed over the family's rows.
    fn total(&self, count: fn(&Row) -> usize) -> usize {
        self.rows.iter().map(|r| count(r)).sum()
    }
}

/// The columns of the Markdown table: worst errors per family.
fn family_table<'a>() -> Table<'static, FamilyLine<'a>> {
    Table::new()
        .markdown("level", |f: &FamilyLine| f.level.name().to_owned())
        .markdown("family", |f| f.family.to_owned())
        .markdown("configurations", |f| f.variants.join(", "))
        .markdown("cases", |f| f.total(|r| r.cases).to_string())
        .markdown("worst abs error (at delta)", |f| {
            let w = f.worst(|r| r.max_abs);
            format!("{:.2e} ({})", w.max_abs, delta_text(w.key.delta))
        })
        .markdown("worst rel error", |f| {
            format!("{:.2e}", f.worst(|r| r.max_rel).max_rel)
        })
        .markdown("worst error / bound", |f| {
            format!("{:.2e}", f.worst(|r| r.max_over_bound).max_over_bound)
        })
        .markdown("widest certified interval", |f| match f.solid() {
            true => format!("{:.2e}", f.worst(|r| r.max_width).max_width),
            false => "-".into(),
        })
        .markdown("certificate violations", |f| match f.solid() {
            true => f.total(|r| r.certificate_violations).to_string(),
            false => "-".into(),
        })
        .markdown("above bound", |f| f.total(|r| r.bound_exceeded).to_string())
        .markdown("slowest answer (us; circles: best of 5 runs)", |f| {
            format!("{:.0}", f.worst(|r| r.max_seconds).max_seconds * 1e6)
        })
}

/// The row of `rows` (one family) maximising `key`.
fn worst<'a>(rows: &[&'a Row], key: fn(&Row) -> f64) -> &'a Row {
    rows.iter()
        .copied()
        .max_by(|a, b| key(a).total_cmp(&key(b)))
        .expect("a family has rows")
}

fn markdown(prov: &Provenance, rows: &[Row], samples: &[Sample], seeds: usize) -> String {
    let mut s = String::from("# Numerical stability near degenerate configurations\n\n");
    let _ = writeln!(
        s,
        "Error of revdist against exact references as each configuration is moved `delta` away \
         from a degenerate one (`delta` = 0 and 1e-16 .. 1e-1, {seeds} random perturbation \
         directions and rigid motions per family and delta). Written by \
         `target/release/stability`; cases, references and bounds are documented in \
         `experiments/src/stability/`.\n"
    );
    let _ = writeln!(
        s,
        "**Circle level**: `revdist::circle::min_distance` in double precision against the exact \
         minimum distance of the rational data (degree-8 polynomial in exact rationals, Sturm \
         isolation, MPFR). Relative error = |error| / size, size = max(ra, rb, |C_b - C_a|) + \
         |rigid-motion translation|. Bound checked: 64 u size = {CIRCLE_REL_BOUND:.1e} size \
         (u = 2^-53: input rounding and the solver's own rounding, with a margin of 4; the \
         solver's documented guarantee is {TIE:.0e} size, `TIE_REL_TOL`).\n",
        TIE = revdist::circle::TIE_REL_TOL
    );
    let _ = writeln!(
        s,
        "**Solid level**: certified queries (trees at eps {DEFAULT_EPS:.0e}, default tolerance \
         eps_a + eps_b) against closed forms evaluated in 256-bit MPFR. Each answer must have \
         lower <= exact <= upper (compared exactly) and |value - exact| <= eps_a + eps_b = \
         {:.0e}; relative error = |error| / (sum of the profiles' diagonals). A query stops as \
         soon as its interval is narrower than eps_a + eps_b and may return any value inside \
         it: the occasional errors of ~1e-5 are such early stops (value at the upper end of a \
         certified interval that holds the exact distance), not a loss of accuracy.\n",
        2.0 * DEFAULT_EPS
    );
    let families: Vec<FamilyLine> = CIRCLE_FAMILIES
        .iter()
        .map(|(f, v)| (Level::Circle, *f, *v))
        .chain(SOLID_FAMILIES.iter().map(|(f, v)| (Level::Solid, *f, *v)))
        .map(|(level, family, variants)| FamilyLine {
            level,
            family,
            variants,
            rows: rows
                .iter()
                .filter(|r| r.key.level == level && r.key.family == family)
                .collect(),
        })
        .filter(|f| !f.rows.is_empty())
        .collect();
    s.push_str(&family_table().markdown_text(&families));
    let bad: Vec<&Sample> = samples.iter().filter(|x| !x.ok()).collect();
    if bad.is_empty() {
        s.push_str("\nEvery case is within its bound, and every certified interval holds the exact distance.\n");
    } else {
        let _ = writeln!(s, "\n{} cases fail:\n", bad.len());
        for b in bad.iter().take(40) {
            let _ = writeln!(s, "- {}", b.describe());
        }
    }
    for level in [Level::Circle, Level::Solid] {
        let mut v: Vec<&Sample> = samples.iter().filter(|x| x.key.level == level).collect();
        v.sort_by(|a, b| (b.abs_err / b.bound).total_cmp(&(a.abs_err / a.bound)));
        let _ = writeln!(
            s,
            "\nLargest errors relative to their bound, {} level:\n",
            level.name()
        );
        for x in v.iter().take(LARGEST_LISTED) {
            let _ = writeln!(s, "- {}", x.describe());
        }
    }
    let mut slow: Vec<&Sample> = samples
        .iter()
        .filter(|x| x.key.level == Level::Solid)
        .collect();
    slow.sort_by(|a, b| b.seconds.total_cmp(&a.seconds));
    s.push_str("\nSlowest solid queries (wall clock, this run):\n\n");
    for x in slow.iter().take(LARGEST_LISTED) {
        let _ = writeln!(s, "- {}", x.describe());
    }
    s.push_str(&prov.markdown_footer());
    s
}

/// One line of a panel.
struct Series {
    name: String,
    /// Index into the palette ([`colour`]).
    colour: usize,
    points: Vec<(f64, f64)>,
    /// Dashed, thin, no markers (the solids' certified widths).
    dashed: bool,
}

/// One panel: error against delta per family, reference lines, legend on the right.
struct Panel<'a> {
    title: String,
    y_desc: &'a str,
    series: Vec<Series>,
    /// (label, y, colour): horizontal reference lines.
    refs: Vec<(String, f64, RGBColor)>,
}

fn panel_series(rows: &[Row], level: Level, families: &[&str], seeds: usize) -> Panel<'static> {
    let mut series = Vec::new();
    for (k, fam) in families.iter().enumerate() {
        let pts = |f: fn(&Row) -> f64| -> Vec<(f64, f64)> {
            rows.iter()
                .filter(|r| r.key.level == level && r.key.family == *fam && r.key.delta.is_some())
                .map(|r| (delta_value(r.key.delta), f(r).max(PLOT_FLOOR)))
                .collect()
        };
        match level {
            Level::Circle => series.push(Series {
                name: fam.to_string(),
                colour: k,
                points: pts(|r| r.max_rel),
                dashed: false,
            }),
            Level::Solid => {
                let err = pts(|r| r.max_abs);
                // Nested pairs: every answer a certified overlap, value = lower = upper = 0.
                let zero = if err.iter().all(|p| p.1 <= PLOT_FLOOR) {
                    " (all 0)"
                } else {
                    ""
                };
                series.push(Series {
                    name: format!("{fam}: error{zero}"),
                    colour: k,
                    points: err,
                    dashed: false,
                });
                series.push(Series {
                    name: format!("{fam}: width{zero}"),
                    colour: k,
                    points: pts(|r| r.max_width),
                    dashed: true,
                });
            }
        }
    }
    match level {
        Level::Circle => Panel {
            title: format!(
                "Circle level: double-precision circle/circle distance vs exact (max over {seeds} seeds)"
            ),
            y_desc: "max |d - d_exact| / size  (dimensionless)",
            series,
            refs: vec![
                (
                    format!(
                        "solver's guarantee {:.0e}",
                        revdist::circle::TIE_REL_TOL
                    ),
                    revdist::circle::TIE_REL_TOL,
                    RGBColor(120, 40, 140),
                ),
                (
                    format!("bound checked 64 u = {CIRCLE_REL_BOUND:.1e}"),
                    CIRCLE_REL_BOUND,
                    RGBColor(0, 0, 0),
                ),
                (
                    "unit roundoff u = 2^-53".into(),
                    UNIT_ROUNDOFF,
                    RGBColor(110, 110, 110),
                ),
            ],
        },
        Level::Solid => Panel {
            title: format!(
                "Solid level: certified query vs closed form, eps {DEFAULT_EPS:.0e} (max over {seeds} seeds)"
            ),
            y_desc: "max |value - d_exact|, width  (length units)",
            series,
            refs: vec![
                (
                    format!("bound eps_a + eps_b = {:.0e}", 2.0 * DEFAULT_EPS),
                    2.0 * DEFAULT_EPS,
                    RGBColor(0, 0, 0),
                ),
                (
                    "unit roundoff u = 2^-53".into(),
                    UNIT_ROUNDOFF,
                    RGBColor(110, 110, 110),
                ),
            ],
        },
    }
}

fn draw(path: &Path, rows: &[Row], seeds: usize) -> PlotResult {
    let circle_fams: Vec<&str> = CIRCLE_FAMILIES.iter().map(|f| f.0).collect();
    let solid_fams: Vec<&str> = SOLID_FAMILIES.iter().map(|f| f.0).collect();
    let panels = [
        panel_series(rows, Level::Circle, &circle_fams, seeds),
        panel_series(rows, Level::Solid, &solid_fams, seeds),
    ];
    let size = (1100u32, 1000u32);
    let root = SVGBackend::new(path, size).into_drawing_area();
    root.fill(&WHITE)?;
    let halves = root.split_evenly((2, 1));
    let x_lo = delta_value(Some(*DELTA_EXPONENTS.end())) / 2.0;
    let x_hi = delta_value(Some(*DELTA_EXPONENTS.start())) * 2.0;
    for (area, panel) in halves.iter().zip(&panels) {
        let legend_w = 290;
        let (plot, legend) = area.split_horizontally(size.0 - legend_w);
        // Whole decades on both axes, every decade labelled.
        let top = panel
            .series
            .iter()
            .flat_map(|s| s.points.iter().map(|p| p.1))
            .chain(panel.refs.iter().map(|r| r.1))
            .fold(PLOT_FLOOR, f64::max);
        let (y_lo_exp, y_hi_exp) = (
            PLOT_FLOOR.log10().round() as i32,
            top.log10().floor() as i32 + 1,
        );
        let y_keys: Vec<f64> = (y_lo_exp..=y_hi_exp).map(|k| 10f64.powi(k)).collect();
        let x_keys: Vec<f64> = DELTA_EXPONENTS.map(|k| delta_value(Some(k))).collect();
        let mut chart = ChartBuilder::on(&plot)
            .caption(&panel.title, (FONT, CAPTION - 3))
            .margin(12)
            .margin_right(20)
            .x_label_area_size(48)
            .y_label_area_size(78)
            .build_cartesian_2d(
                (x_lo..x_hi).log_scale().with_key_points(x_keys),
                (PLOT_FLOOR / 2.0..10f64.powi(y_hi_exp) * 1.5)
                    .log_scale()
                    .with_key_points(y_keys),
            )?;
        chart
            .configure_mesh()
            .x_desc("perturbation size delta  (length units; circle A and the solids have size ~1)")
            .y_desc(panel.y_desc)
            .x_label_formatter(&log_tick)
            .y_label_formatter(&|v: &f64| {
                if *v <= PLOT_FLOOR * 1.01 {
                    format!("<={}", log_tick(&PLOT_FLOOR))
                } else {
                    log_tick(v)
                }
            })
            .label_style((FONT, TICK))
            .axis_desc_style((FONT, LABEL))
            .light_line_style(WHITE.mix(0.0))
            .bold_line_style(BLACK.mix(0.08))
            .draw()?;
        for (_, y, c) in &panel.refs {
            chart.draw_series(DashedLineSeries::new(
                vec![(x_lo, *y), (x_hi, *y)],
                8,
                5,
                c.stroke_width(2),
            ))?;
        }
        for Series {
            colour: k,
            points: pts,
            dashed,
            ..
        } in &panel.series
        {
            let c = colour(*k);
            if *dashed {
                chart.draw_series(DashedLineSeries::new(
                    pts.clone(),
                    4,
                    4,
                    c.mix(0.8).stroke_width(1),
                ))?;
            } else {
                chart.draw_series(LineSeries::new(pts.clone(), c.stroke_width(2)))?;
                chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, c.filled())))?;
            }
        }
        // Legend: families, then the reference lines.
        let mut y = 58;
        let entry = |y: i32, dashed: bool, c: RGBColor, marker: bool, text: &str| -> PlotResult {
            if dashed {
                for x0 in [4, 14, 24] {
                    legend.draw(&PathElement::new(
                        vec![(x0, y), (x0 + 6, y)],
                        c.stroke_width(2),
                    ))?;
                }
            } else {
                legend.draw(&PathElement::new(vec![(4, y), (30, y)], c.stroke_width(2)))?;
            }
            if marker {
                legend.draw(&Circle::new((17, y), 3, c.filled()))?;
            }
            legend.draw(&Text::new(text.to_string(), (38, y - 8), (FONT, LABEL)))?;
            Ok(())
        };
        for line in &panel.series {
            entry(
                y,
                line.dashed,
                colour(line.colour),
                !line.dashed,
                &line.name,
            )?;
            y += 24;
        }
        y += 10;
        for (label, _, c) in &panel.refs {
            entry(y, true, *c, false, label)?;
            y += 24;
        }
        y += 6;
        legend.draw(&Text::new(
            format!(
                "errors <= {} (incl. 0) drawn at the bottom",
                log_tick(&PLOT_FLOOR)
            ),
            (4, y - 8),
            (FONT, TICK),
        ))?;
    }
    root.present()?;
    Ok(())
}
