//! Where a certified query spends its time (`docs/cost_model.md`, per pair of the paper's
//! models): `query_times.csv` / `.md` / `.svg`, per pair of the five paper models and per
//! eps, the median time of a certified distance query over seeded random poses near contact,
//! with the node pairs, leaf bounds, exact leaf solves, the share of time in each stage, and
//! the certified interval width `upper - lower`. Tree sizes and build times (the paper's
//! Tables 1-2 and Figure 9) are in `bvh_tables`; revdist against FCL in `fcl_bench`,
//! `motion` and `pareto`.
//!
//! Usage: `accuracy_time [--out DIR] [--poses N] [--seed S]` (default `figures`, 200 poses
//! per pair).
//! Timings are wall-clock medians on whatever machine runs it; the CSV records the setting.

use clap::Parser;
use experiments::cli::{Out, Poses, Seed};
use experiments::driver::{self, DriverResult};
use experiments::table::Table;
use experiments::{Draw, SplitMix};
use nalgebra::{Isometry3, Translation3, Vector3};
use plotters::prelude::*;
use revdist::models;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;

use experiments::shapes::{centre, PAPER_EPS as EPS_LEVELS, PAPER_MODELS};
use experiments::stats::{median, quantile};
/// Default seed: the same poses on every run.
const SEED: u64 = 0x5eed_2020;
/// Poses per pair by default.
const DEFAULT_POSES: usize = 200;

struct QueryRow {
    a: String,
    b: String,
    eps: f64,
    queries: usize,
    overlaps: usize,
    median_us: f64,
    p90_us: f64,
    node_pairs: f64,
    leaf_bounds: f64,
    leaf_tests: f64,
    patch_tests: f64,
    /// Share of the query time in stage-1 leaf bounds and in exact leaf solves.
    bounds_share: f64,
    exact_share: f64,
    max_width: f64,
}

fn query_rows(poses: usize, seed: u64) -> Result<Vec<QueryRow>, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    for &eps in &EPS_LEVELS {
        let solids: Vec<(Solid, (f64, f64))> = PAPER_MODELS
            .iter()
            .map(|name| {
                let p = models::model(name)?;
                let (z, r) = centre(&p);
                let r = (r, z);
                Ok((Solid::from_profile(Arc::new(p), eps)?, r))
            })
            .collect::<Result<_, Box<dyn std::error::Error>>>()?;
        for i in 0..solids.len() {
            for j in i..solids.len() {
                let mut rng = SplitMix(seed ^ ((i * 8 + j) as u64));
                let (sa, (ra, za)) = &solids[i];
                let (sb, (rb, zb)) = &solids[j];
                let mut times = Vec::with_capacity(poses);
                let (mut pairs, mut leaves, mut width, mut overlaps) = (0.0, 0.0, 0.0f64, 0);
                let (mut bounded, mut patches, mut t_bounds, mut t_exact, mut t_all) =
                    (0.0, 0.0, 0.0, 0.0, 0.0);
                for _ in 0..poses {
                    // B's mid-height axis point at a random direction and distance in
                    // [0.6, 1.1] x (sum of bounding radii): mostly separated, close to contact.
                    let rot = rng.rotation();
                    let dir = rng.unit_vector();
                    let dist = (ra + rb) * (0.6 + 0.5 * rng.next_f64());
                    let centre_b = Vector3::new(0.0, 0.0, *za) + dir * dist;
                    let t = centre_b - rot * Vector3::new(0.0, 0.0, *zb);
                    let pose = Isometry3::from_parts(Translation3::from(t), rot);
                    let b_posed = sb.with_pose(pose);
                    let opts = QueryOptions::default();
                    let start = Instant::now();
                    let d = distance(sa, &b_posed, &opts);
                    let us = start.elapsed().as_secs_f64() * 1e6;
                    times.push(us);
                    t_all += us;
                    t_bounds += d.stats.leaf_bounds_ns as f64 * 1e-3;
                    t_exact += d.stats.leaf_tests_ns as f64 * 1e-3;
                    bounded += d.stats.leaf_bounds as f64;
                    patches += d.stats.patch_tests as f64;
                    if d.overlap {
                        overlaps += 1;
                    }
                    pairs += d.stats.node_pairs as f64;
                    leaves += d.stats.leaf_tests as f64;
                    width = width.max(d.upper - d.lower);
                }
                let n = poses as f64;
                let median_us = median(&times);
                rows.push(QueryRow {
                    a: PAPER_MODELS[i].into(),
                    b: PAPER_MODELS[j].into(),
                    eps,
                    queries: poses,
                    overlaps,
                    median_us,
                    p90_us: quantile(&times, 0.9),
                    node_pairs: pairs / n,
                    leaf_bounds: bounded / n,
                    leaf_tests: leaves / n,
                    patch_tests: patches / n,
                    bounds_share: t_bounds / t_all,
                    exact_share: t_exact / t_all,
                    max_width: width,
                });
            }
        }
    }
    Ok(rows)
}

/// The columns of `query_times.csv` and of the table in `query_times.md`.
fn query_table() -> Table<'static, QueryRow> {
    Table::new()
        .csv("a", |r: &QueryRow| r.a.clone())
        .csv("b", |r| r.b.clone())
        .markdown("pair", |r| format!("{}-{}", r.a, r.b))
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("queries", |r| r.queries.to_string())
        .csv("overlaps", |r| r.overlaps.to_string())
        .csv("median_us", |r| format!("{:.3}", r.median_us))
        .with_markdown("median (us)", |r| format!("{:.1}", r.median_us))
        .csv("p90_us", |r| format!("{:.3}", r.p90_us))
        .with_markdown("p90 (us)", |r| format!("{:.1}", r.p90_us))
        .csv("mean_node_pairs", |r| format!("{:.1}", r.node_pairs))
        .with_markdown("node pairs", |r| format!("{:.0}", r.node_pairs))
        .csv("mean_leaf_bounds", |r| format!("{:.1}", r.leaf_bounds))
        .with_markdown_header("leaf bounds")
        .csv("mean_exact_leaves", |r| format!("{:.1}", r.leaf_tests))
        .with_markdown_header("exact leaves")
        .csv("mean_exact_patches", |r| format!("{:.1}", r.patch_tests))
        .with_markdown_header("exact patches")
        .csv("time_share_leaf_bounds", |r| {
            format!("{:.3}", r.bounds_share)
        })
        .csv("time_share_exact", |r| format!("{:.3}", r.exact_share))
        .markdown("time in bounds / exact", |r| {
            format!(
                "{:.0}% / {:.0}%",
                100.0 * r.bounds_share,
                100.0 * r.exact_share
            )
        })
        .csv("max_upper_minus_lower", |r| format!("{:e}", r.max_width))
        .with_markdown("max upper-lower", |r| format!("{:.1e}", r.max_width))
        .markdown("overlaps", |r| format!("{}/{}", r.overlaps, r.queries))
}

fn write_query_outputs(
    out: &std::path::Path,
    rows: &[QueryRow],
    prov: &experiments::provenance::Provenance,
) -> Result<(), Box<dyn std::error::Error>> {
    let table = query_table();
    std::fs::write(
        out.join("query_times.csv"),
        prov.csv_preamble() + &table.csv_text(rows),
    )?;
    let md = String::from(
        "# Certified distance queries: time per model pair and eps (paper Figure 12 setting)\n\n\
         Seeded random poses near contact; default tolerance (the query stops once \
         upper - lower <= eps_a + eps_b, or as narrow as the leaves allow). Median and 90th \
         percentile wall-clock time per query; per query on average: node pairs popped, leaf \
         pairs given stage-1 bounds, leaf pairs and patch pairs solved exactly, and the share \
         of the total time spent in stage-1 bounds and in exact solves (the rest is node \
         bounds, the queue and the solid checks).\n\n",
    ) + &table.markdown_text(rows)
        + &prov.markdown_footer();
    std::fs::write(out.join("query_times.md"), md)?;

    let path = out.join("query_times.svg");
    let root = SVGBackend::new(&path, (820, 480)).into_drawing_area();
    root.fill(&WHITE)?;
    let (plot_area, legend_area) = root.split_horizontally(640);
    let t_max = rows.iter().map(|r| r.median_us).fold(1.0, f64::max) * 2.0;
    let t_min = rows
        .iter()
        .map(|r| r.median_us)
        .fold(f64::INFINITY, f64::min)
        / 2.0;
    let mut chart = ChartBuilder::on(&plot_area)
        .caption("median certified query time vs eps", ("sans-serif", 18))
        .margin(12)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d(
            (5e-6f64..2e-3f64).log_scale(),
            (t_min.max(0.1)..t_max).log_scale(),
        )?;
    chart
        .configure_mesh()
        .x_desc("eps (biarc-tree bound)")
        .y_desc("median time per query (us)")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0}"))
        .draw()?;
    let pairs: Vec<(String, String)> = {
        let mut v: Vec<(String, String)> =
            rows.iter().map(|r| (r.a.clone(), r.b.clone())).collect();
        v.sort();
        v.dedup();
        v
    };
    for (k, (a, b)) in pairs.iter().enumerate() {
        let colour = Palette99::pick(k).to_rgba();
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| &r.a == a && &r.b == b)
            .map(|r| (r.eps, r.median_us))
            .collect();
        chart.draw_series(LineSeries::new(pts.clone(), colour.stroke_width(2)))?;
        chart.draw_series(pts.iter().map(|&p| Circle::new(p, 3, colour.filled())))?;
        // Legend outside the plot: one coloured line and label per pair.
        let y = 40 + 22 * k as i32;
        legend_area.draw(&PathElement::new(
            vec![(8, y), (32, y)],
            colour.stroke_width(2),
        ))?;
        legend_area.draw(&Text::new(
            format!("{a}-{b}"),
            (38, y - 7),
            ("sans-serif", 12),
        ))?;
    }
    root.present()?;
    Ok(())
}

/// Where a certified distance query spends its time: for every pair of the paper's five
/// models and eps 1e-3, 1e-4 and 1e-5, the median and 90th-percentile time of a query over
/// seeded random poses near contact, with the node pairs, leaf bounds and exact leaf solves
/// per query, the share of time in stage-1 bounds and exact solves, and the widest certified
/// interval. Writes query_times.csv, .md and .svg (200 poses per pair by default).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    #[command(flatten)]
    poses: Poses,
    #[command(flatten)]
    seed: Seed,
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let (out, poses, seed) = (
        args.out.dir,
        args.poses.or(DEFAULT_POSES),
        args.seed.or(SEED),
    );
    let queries = query_rows(poses, seed)?;
    let prov = experiments::provenance::Provenance::collect(
        "accuracy_time (query cost per pair)",
        &[
            ("poses_per_pair", poses.to_string()),
            ("seed", format!("{seed:#x}")),
            (
                "tolerance",
                "default (Trees: upper - lower <= eps_a + eps_b)".into(),
            ),
        ],
    );
    write_query_outputs(&out, &queries, &prov)?;
    println!(
        "wrote query_times.{{csv,md,svg}} ({} rows) to {}",
        queries.len(),
        out.display()
    );
    Ok(())
}
