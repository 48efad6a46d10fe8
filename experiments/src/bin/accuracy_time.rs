//! What accuracy costs in time (paper section 5, Tables 1-2 and Figures 9 and 12):
//!
//! 1. `tree_sizes.csv` / `.md`: biarc-tree nodes, leaves, depth, bytes and build time per model
//!    and eps (the paper's Tables 1-2 and Figure 9), including the mean over M_t frames.
//! 2. `query_times.csv` / `.md` / `.svg`: per pair of the five paper models and per eps, the
//!    median time of a certified distance query over seeded random poses near contact, with the
//!    node pairs, leaf tests and certified interval width `upper - lower` (Figure 12's setting).
//!
//! Usage: `accuracy_time [OUT_DIR] [--poses N]` (default `figures`, 200 poses per pair).
//! Timings are wall-clock medians on whatever machine runs it; the CSV records the setting.

use experiments::SplitMix;
use nalgebra::{Isometry3, Translation3, Vector3};
use plotters::prelude::*;
use revdist::biarc::BiarcTree;
use revdist::models;
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// The paper's five static models (section 5, Figure 7).
const PAPER_MODELS: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];
/// The precisions of the paper's tables.
const EPS_LEVELS: [f64; 3] = [1e-3, 1e-4, 1e-5];
/// M_t frames averaged for the deformable row of the tree table.
const MORPH_FRAMES: usize = 100;
/// Repetitions of each tree build (the median is reported).
const BUILD_REPEATS: usize = 5;
/// Fixed seed: the same poses on every run.
const SEED: u64 = 0x5eed_2020;

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    let n = v.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    }
}

/// Radius of a ball about the profile's mid-height axis point that holds the whole solid.
fn bounding_radius(profile: &revdist::profile::Profile) -> (f64, f64) {
    let b = profile.bounding_box();
    let zc = 0.5 * (b.min.y + b.max.y);
    let half_h = 0.5 * (b.max.y - b.min.y);
    ((b.max.x * b.max.x + half_h * half_h).sqrt(), zc)
}

struct TreeRow {
    model: String,
    eps: f64,
    spirals: usize,
    nodes: usize,
    leaves: usize,
    depth: usize,
    bytes: usize,
    build_us: f64,
}

fn tree_rows() -> Result<Vec<TreeRow>, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    for &eps in &EPS_LEVELS {
        for name in PAPER_MODELS {
            let profile = models::model(name)?;
            let mut times = Vec::new();
            let mut tree = BiarcTree::build(&profile, eps)?;
            for _ in 0..BUILD_REPEATS {
                let t = Instant::now();
                tree.rebuild(&profile, eps)?;
                times.push(t.elapsed().as_secs_f64() * 1e6);
            }
            let s = tree.stats();
            rows.push(TreeRow {
                model: name.into(),
                eps,
                spirals: s.spirals,
                nodes: s.nodes,
                leaves: s.leaves,
                depth: s.depth,
                bytes: s.bytes,
                build_us: median(&mut times),
            });
        }
        // The deformable model: frames t = k / MORPH_FRAMES, rebuilding one tree in place.
        let mut sums = [0.0f64; 5];
        let mut times = Vec::new();
        let mut tree = BiarcTree::build(&models::morph(0.0)?, eps)?;
        for k in 0..MORPH_FRAMES {
            let frame = models::morph(k as f64 / MORPH_FRAMES as f64)?;
            let t = Instant::now();
            tree.rebuild(&frame, eps)?;
            times.push(t.elapsed().as_secs_f64() * 1e6);
            let s = tree.stats();
            for (acc, v) in sums
                .iter_mut()
                .zip([s.spirals, s.nodes, s.leaves, s.depth, s.bytes])
            {
                *acc += v as f64;
            }
        }
        let avg = |i: usize| (sums[i] / MORPH_FRAMES as f64).round() as usize;
        rows.push(TreeRow {
            model: "M_t (mean)".into(),
            eps,
            spirals: avg(0),
            nodes: avg(1),
            leaves: avg(2),
            depth: avg(3),
            bytes: avg(4),
            build_us: median(&mut times),
        });
    }
    Ok(rows)
}

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

fn query_rows(poses: usize) -> Result<Vec<QueryRow>, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    for &eps in &EPS_LEVELS {
        let solids: Vec<(Solid, (f64, f64))> = PAPER_MODELS
            .iter()
            .map(|name| {
                let p = models::model(name)?;
                let r = bounding_radius(&p);
                Ok((Solid::from_profile(Arc::new(p), eps)?, r))
            })
            .collect::<Result<_, Box<dyn std::error::Error>>>()?;
        for i in 0..solids.len() {
            for j in i..solids.len() {
                let mut rng = SplitMix(SEED ^ ((i * 8 + j) as u64));
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
                let median_us = median(&mut times); // sorts `times`
                rows.push(QueryRow {
                    a: PAPER_MODELS[i].into(),
                    b: PAPER_MODELS[j].into(),
                    eps,
                    queries: poses,
                    overlaps,
                    median_us,
                    p90_us: times[(0.9 * (n - 1.0)).round() as usize],
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

fn write_tree_outputs(out: &std::path::Path, rows: &[TreeRow]) -> std::io::Result<()> {
    let mut csv = String::from("model,eps,spirals,nodes,leaves,depth,bytes,build_us_median\n");
    for r in rows {
        writeln!(
            csv,
            "{},{:e},{},{},{},{},{},{:.3}",
            r.model, r.eps, r.spirals, r.nodes, r.leaves, r.depth, r.bytes, r.build_us
        )
        .unwrap();
    }
    std::fs::write(out.join("tree_sizes.csv"), csv)?;
    let mut md = String::from(
        "# Biarc-tree sizes and build times (paper Tables 1-2, Figure 9)\n\n\
         Generated by `experiments/src/bin/accuracy_time.rs`; build time is the median of \
         in-place rebuilds on the machine that ran it.\n\n\
         | model | eps | spirals | nodes | leaves | depth | KiB | build (us) |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for r in rows {
        writeln!(
            md,
            "| {} | {:.0e} | {} | {} | {} | {} | {:.1} | {:.1} |",
            r.model,
            r.eps,
            r.spirals,
            r.nodes,
            r.leaves,
            r.depth,
            r.bytes as f64 / 1024.0,
            r.build_us
        )
        .unwrap();
    }
    std::fs::write(out.join("tree_sizes.md"), md)
}

fn write_query_outputs(
    out: &std::path::Path,
    rows: &[QueryRow],
) -> Result<(), Box<dyn std::error::Error>> {
    let mut csv = String::from(
        "a,b,eps,queries,overlaps,median_us,p90_us,mean_node_pairs,mean_leaf_bounds,mean_exact_leaves,mean_exact_patches,time_share_leaf_bounds,time_share_exact,max_upper_minus_lower\n",
    );
    for r in rows {
        writeln!(
            csv,
            "{},{},{:e},{},{},{:.3},{:.3},{:.1},{:.1},{:.1},{:.1},{:.3},{:.3},{:e}",
            r.a,
            r.b,
            r.eps,
            r.queries,
            r.overlaps,
            r.median_us,
            r.p90_us,
            r.node_pairs,
            r.leaf_bounds,
            r.leaf_tests,
            r.patch_tests,
            r.bounds_share,
            r.exact_share,
            r.max_width
        )?;
    }
    std::fs::write(out.join("query_times.csv"), csv)?;
    let mut md = String::from(
        "# Certified distance queries: time per model pair and eps (paper Figure 12 setting)\n\n\
         Seeded random poses near contact; default tolerance (the query stops once \
         upper - lower <= eps_a + eps_b, or as narrow as the leaves allow). Median and 90th \
         percentile wall-clock time per query; per query on average: node pairs popped, leaf \
         pairs given stage-1 bounds, leaf pairs and patch pairs solved exactly, and the share \
         of the total time spent in stage-1 bounds and in exact solves (the rest is node \
         bounds, the queue and the solid checks).\n\n\
         | pair | eps | median (us) | p90 (us) | node pairs | leaf bounds | exact leaves | exact patches | time in bounds / exact | max upper-lower | overlaps |\n\
         | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |\n",
    );
    for r in rows {
        writeln!(
            md,
            "| {}-{} | {:.0e} | {:.1} | {:.1} | {:.0} | {:.1} | {:.1} | {:.1} | {:.0}% / {:.0}% | {:.1e} | {}/{} |",
            r.a,
            r.b,
            r.eps,
            r.median_us,
            r.p90_us,
            r.node_pairs,
            r.leaf_bounds,
            r.leaf_tests,
            r.patch_tests,
            100.0 * r.bounds_share,
            100.0 * r.exact_share,
            r.max_width,
            r.overlaps,
            r.queries
        )?;
    }
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

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut out = PathBuf::from("figures");
    let mut poses = 200usize;
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        match a.as_str() {
            "--poses" => {
                poses = args
                    .next()
                    .and_then(|v| v.parse().ok())
                    .filter(|&n: &usize| n > 0)
                    .ok_or("--poses needs a positive integer")?
            }
            _ => out = PathBuf::from(a),
        }
    }
    std::fs::create_dir_all(&out)?;
    let trees = tree_rows()?;
    write_tree_outputs(&out, &trees)?;
    let queries = query_rows(poses)?;
    write_query_outputs(&out, &queries)?;
    println!(
        "wrote tree_sizes.{{csv,md}} ({} rows) and query_times.{{csv,md,svg}} ({} rows) to {}",
        trees.len(),
        queries.len(),
        out.display()
    );
    Ok(())
}
