//! The paper's Figure 12 (section 5): all 15 pairs of the five static models in continuous
//! motion, the average query time of revdist against FCL 0.7 at eps 1e-3, 1e-4 and 1e-5, as
//! grouped bars with the speed-up.
//!
//! **Motion.** Per pair, a seeded [`SmoothMotion`]: B's rotation and its approach direction
//! about A move smoothly through random keyframes while the target gap follows a
//! log-sinusoid in [`GAPS`] (often close, never touching); each frame slides B along the
//! direction to its gap with trees at placement accuracy. All poses are placed before any
//! timing, and the same poses serve every method and eps.
//!
//! **Methods.** revdist at its default tolerance (interval width <= eps_a + eps_b), warm
//! started from the previous frame's best leaf pair (`distance_cached`, the intended use in
//! motion); FCL `BVHModel<OBBRSS>` and `BVHModel<RSS>` on certified meshes of the same eps
//! in two layouts (balanced vertices, and meridian edges capped). The speed ratio of a row
//! is against the faster FCL method (lowest mean over the motion; the faster BV, RSS often
//! by 10-20%, in its faster layout), named in the `faster_fcl_bv` and `best_layout`
//! columns; all four FCL means are kept. Queries are timed one at a time on one thread, methods interleaved
//! per frame in a rotating order. Every revdist answer is cross-checked against FCL's
//! (`verify::crosscheck::criterion`); violations are reported and fail the run.
//!
//! Usage: `motion [--frames N] [--frames-1e-5 N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--seed S] [--out DIR]`. Writes `motion.csv`, `motion.md` and `motion_eps{E}.svg` (default `figures`).

use clap::Parser;
use experiments::args::ModelPair;
use experiments::baseline_mesh::{agrees_with_fcl, Layout, EDGE_CAP_REL, LAYOUT_NAMES};
use experiments::cli::{count_at, Eps, Frames, Out, Pairs, Paper, Seed};
use experiments::driver::{self, DriverResult};
use experiments::plot::{colour, grouped_bars_coloured, BarSeries};
use experiments::poses::{pair_seed, SmoothMotion};
use experiments::progress;
use experiments::provenance::Provenance;
use experiments::shapes::{diagonal, paper_pairs, PAPER_EPS};
use experiments::stats::{mean, median, time_each, us};
use experiments::table::Table;
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::{distance_cached, QueryCache, QueryOptions};
use revdist::solid::Solid;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::FclMesh;

/// Frames per pair at eps >= 5e-5 (default run).
const DEFAULT_FRAMES: usize = 200;
/// Frames per pair at eps < 5e-5 (default run; the same motion, its first frames).
const DEFAULT_FRAMES_FINE: usize = 100;
/// Frames with `--paper` (the paper's 50,000).
const PAPER_FRAMES: usize = 50_000;
/// Gap range of the motion (model units; the models are 1-3 units tall).
const GAPS: (f64, f64) = (1e-3, 3e-1);
/// Keyframes of the rotation and direction per 1,000 frames (at least 4).
const KEYS_PER_1000_FRAMES: usize = 8;
/// Gap oscillations per 1,000 frames.
const GAP_PERIODS_PER_1000_FRAMES: f64 = 5.0;
/// Default seed of the motions (xor a hash of the pair name).
const SEED: u64 = 0xf16_0012;

/// The paper's 15 model pairs in continuous motion (Figure 12): per pair and eps, the mean
/// query time of revdist (default tolerance, warm-started from the previous frame) against
/// the faster of FCL 0.7 OBBRSS and RSS on certified meshes of the same eps, over a smooth seeded rigid motion
/// that often comes close; methods interleaved per frame and also run blocked, every revdist
/// answer cross-checked against FCL's. Writes motion.csv, motion.md and motion_eps{E}.svg
/// (200 frames per pair, 100 below eps 5e-5; 50,000 with --paper).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    pairs: Pairs,
    #[command(flatten)]
    frames: Frames,
    #[command(flatten)]
    paper: Paper,
    #[command(flatten)]
    seed: Seed,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// FCL's structures of one shape at one eps: both layouts' certified meshes with their
/// OBBRSS and RSS hierarchies.
struct FclShape {
    layouts: Vec<Layout>,
}

impl FclShape {
    fn build(p: &Profile, eps: f64) -> Result<FclShape, Box<dyn std::error::Error>> {
        let mut layouts = Vec::new();
        for cap in [None, Some(EDGE_CAP_REL * diagonal(p))] {
            // The capped layout needs a cap above 2 eps (the tessellator's requirement).
            let cap = cap.filter(|&c| c > 2.0 * eps);
            layouts.push(Layout::build(p, eps, cap)?);
        }
        Ok(FclShape { layouts })
    }

    /// The hierarchy of FCL method `m` ([`method_name`]).
    fn bvh(&self, m: usize) -> &FclMesh {
        let l = &self.layouts[m / 2];
        [&l.obbrss, &l.rss][m % 2]
    }
}

/// FCL's BV types, in the order of the methods of a layout.
const BV_NAMES: [&str; 2] = ["OBBRSS", "RSS"];

/// FCL method `m`: layout `m / 2` ([`LAYOUT_NAMES`]), BV `m % 2` ([`BV_NAMES`]).
fn method_name(m: usize) -> (&'static str, &'static str) {
    (LAYOUT_NAMES[m / 2], BV_NAMES[m % 2])
}

/// One pair at one eps.
struct Row {
    pair: String,
    eps: f64,
    frames: usize,
    /// revdist's query times: (mean, median).
    rev: (f64, f64),
    /// Per FCL method (layout `m / 2`, BV `m % 2`: [`method_name`]): query times (mean,
    /// median).
    fcl: Vec<(f64, f64)>,
    /// Blocked: revdist alone over the whole motion (warm starts), then the faster FCL
    /// method alone: mean query times.
    rev_blocked_mean: f64,
    fcl_blocked_mean: f64,
    /// The faster FCL method (lowest mean): BV and layout, the faster of OBBRSS and RSS.
    best: usize,
    triangles: Vec<usize>,
    node_pairs: f64,
    exact_leaves: f64,
    /// Smallest distance revdist returned over the motion (-1 if it reported an overlap).
    min_gap: f64,
    violations: usize,
}

experiments::shard_record!(Row {
    pair,
    eps,
    frames,
    rev,
    fcl,
    rev_blocked_mean,
    fcl_blocked_mean,
    best,
    triangles,
    node_pairs,
    exact_leaves,
    min_gap,
    violations,
});

impl Row {
    fn fcl_mean_of(&self, bv: usize, layout: usize) -> String {
        self.fcl
            .get(2 * layout + bv)
            .map(|v| format!("{:.2}", v.0))
            .unwrap_or_default()
    }
    fn fcl_mean(&self) -> f64 {
        self.fcl[self.best].0
    }
    fn fcl_median(&self) -> f64 {
        self.fcl[self.best].1
    }
    fn ratio(&self) -> f64 {
        self.fcl_mean() / self.rev.0
    }
    fn blocked_ratio(&self) -> f64 {
        self.fcl_blocked_mean / self.rev_blocked_mean
    }
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let eps_list = args.eps.or(&PAPER_EPS);
    let paper_pairs: Vec<ModelPair> = paper_pairs()
        .into_iter()
        .map(|(a, b)| (a.to_owned(), b.to_owned()))
        .collect();
    let pairs = args.pairs.or(&paper_pairs);
    let (frames, frames_fine) = args.frames.or(args.paper.pick(
        (DEFAULT_FRAMES, DEFAULT_FRAMES_FINE),
        (PAPER_FRAMES, PAPER_FRAMES),
    ));
    // The fine eps run the motion's first frames.
    let frames = (frames, frames_fine.min(frames));
    let seed = args.seed.or(SEED);
    let started = Instant::now();
    let frames_at = |eps: f64| count_at(eps, frames);
    let keys = (KEYS_PER_1000_FRAMES * frames.0 / 1000).max(4);
    let periods = (GAP_PERIODS_PER_1000_FRAMES * frames.0 as f64 / 1000.0).max(1.0);
    let settings = vec![
        ("frames", frames.0.to_string()),
        ("frames_eps_below_5e-5", frames.1.to_string()),
        ("eps", format!("{eps_list:?}")),
        ("gaps", format!("{GAPS:?}")),
        ("keyframes", keys.to_string()),
        ("gap_periods", format!("{periods}")),
        (
            "revdist",
            "default tolerance, warm start (distance_cached)".into(),
        ),
        (
            "fcl",
            "OBBRSS and RSS on certified meshes, two layouts; ratio vs the faster".into(),
        ),
        ("seed", format!("{seed:#x}")),
        ("pairs", experiments::args::pair_list(&pairs)),
    ];
    let prov = Provenance::collect(
        "motion (paper Figure 12: 15 pairs in continuous motion)",
        &settings
            .iter()
            .cloned()
            .chain(args.shard.provenance())
            .collect::<Vec<_>>(),
    );
    // The work units, in the order of the table: (eps, index of the pair); this run's units.
    let units: Vec<(f64, usize)> = eps_list
        .iter()
        .flat_map(|&e| (0..pairs.len()).map(move |p| (e, p)))
        .collect();
    let mine = args.shard.units(units.len());
    let mut profiles: HashMap<String, Arc<Profile>> = HashMap::new();
    for &u in &mine {
        let (a, b) = &pairs[units[u].1];
        for n in [a, b] {
            if !profiles.contains_key(n) {
                profiles.insert(n.clone(), Arc::new(experiments::shapes::profile(n)?));
            }
        }
    }

    // 1. Motions of this run's pairs, placed before any timing.
    let mut my_pairs: Vec<usize> = mine.iter().map(|&u| units[u].1).collect();
    my_pairs.sort_unstable();
    my_pairs.dedup();
    let bar = progress::bar((my_pairs.len() * frames.0) as u64, "motion: place");
    let mut motions: HashMap<usize, Vec<Isometry3<f64>>> = HashMap::new();
    for &p in &my_pairs {
        let (a, b) = &pairs[p];
        let name = format!("{a}-{b}");
        let m = SmoothMotion::new(pair_seed(seed, &name), keys, GAPS, periods);
        motions.insert(
            p,
            m.poses(&profiles[a], &profiles[b], frames.0, || bar.inc(1))?,
        );
    }
    bar.finish_and_clear();

    // 2. Per eps: structures once per shape, then every pair's motion, methods interleaved.
    let mut rows = Vec::new();
    for &eps in &eps_list {
        let here: Vec<usize> = mine
            .iter()
            .copied()
            .filter(|&u| units[u].0 == eps)
            .collect();
        if here.is_empty() {
            continue;
        }
        let n = frames_at(eps);
        let mut names: Vec<&String> = here
            .iter()
            .flat_map(|&u| {
                let (a, b) = &pairs[units[u].1];
                [a, b]
            })
            .collect();
        names.sort_unstable();
        names.dedup();
        let bar = progress::bar(names.len() as u64, &format!("meshes {eps:.0e}"));
        let mut solids: HashMap<String, Solid> = HashMap::new();
        let mut fcl: HashMap<String, FclShape> = HashMap::new();
        for name in names {
            let p = &profiles[name];
            solids.insert(name.clone(), Solid::from_profile(Arc::clone(p), eps)?);
            fcl.insert(name.clone(), FclShape::build(p, eps)?);
            bar.inc(1);
        }
        bar.finish_and_clear();
        let bar = progress::bar((here.len() * n) as u64, &format!("motion {eps:.0e}"));
        for &u in &here {
            let (a, b) = &pairs[units[u].1];
            let poses = &motions[&units[u].1];
            let row = {
                let (sa, sb) = (&solids[a], &solids[b]);
                let (fa, fb) = (&fcl[a], &fcl[b]);
                let size = diagonal(&profiles[a]) + diagonal(&profiles[b]);
                let opts = QueryOptions::default();
                let mut cache = QueryCache::default();
                let layouts = fa.layouts.len().min(fb.layouts.len());
                let mut rev_us: Vec<f64> = Vec::with_capacity(n);
                let mut fcl_us: Vec<Vec<f64>> = vec![Vec::with_capacity(n); 2 * layouts];
                let mut row = Row {
                    pair: format!("{a}-{b}"),
                    eps,
                    frames: n,
                    rev: (0.0, 0.0),
                    fcl: Vec::new(),
                    rev_blocked_mean: 0.0,
                    fcl_blocked_mean: 0.0,
                    best: 0,
                    triangles: (0..layouts)
                        .map(|l| fa.layouts[l].triangles() + fb.layouts[l].triangles())
                        .collect(),
                    node_pairs: 0.0,
                    exact_leaves: 0.0,
                    min_gap: f64::INFINITY,
                    violations: 0,
                };
                for (k, pose) in poses[..n].iter().enumerate() {
                    let posed = sb.with_pose(*pose);
                    let methods = 1 + 2 * layouts;
                    // Answers of this frame: revdist's, and FCL OBBRSS's on the balanced layout
                    // (the timed call's result is reused for the cross-check).
                    let (mut rev, mut fcl_balanced) = (None, None);
                    for j in 0..methods {
                        let m = (j + k) % methods;
                        if m == 0 {
                            let t = Instant::now();
                            let d = distance_cached(sa, &posed, &opts, &mut cache);
                            rev_us.push(us(t.elapsed()));
                            rev = Some(d);
                        } else {
                            let f_m = m - 1;
                            let t = Instant::now();
                            let f =
                                fa.bvh(f_m)
                                    .distance(fb.bvh(f_m), &Isometry3::identity(), pose)?;
                            fcl_us[f_m].push(us(t.elapsed()));
                            if f_m == 0 {
                                fcl_balanced = Some(f.distance);
                            }
                        }
                    }
                    let (d, f) = (
                        rev.expect("revdist ran this frame"),
                        fcl_balanced.expect("FCL ran this frame"),
                    );
                    row.node_pairs += d.stats.node_pairs as f64;
                    row.exact_leaves += d.stats.leaf_tests as f64;
                    row.min_gap = row.min_gap.min(if d.overlap { -1.0 } else { d.value });
                    let h = fa.layouts[0].cm.bound + fb.layouts[0].cm.bound;
                    if !agrees_with_fcl(&d, f, h, pose, size) {
                        row.violations += 1;
                        eprintln!(
                            "violation: {a}-{b} eps {eps:e} frame {k}: revdist [{}, {}], FCL {f} +- {h}",
                            d.lower, d.upper
                        );
                    }
                    bar.inc(1);
                }
                row.node_pairs /= n as f64;
                row.exact_leaves /= n as f64;
                row.rev = (mean(&rev_us), median(&rev_us));
                row.fcl = fcl_us.iter().map(|t| (mean(t), median(t))).collect();
                row.best = (0..2 * layouts)
                    .min_by(|&x, &y| row.fcl[x].0.total_cmp(&row.fcl[y].0))
                    .unwrap_or(0);
                // Blocked: each method alone over the whole motion, as a simulation loop over
                // one pair runs it (answers were cross-checked above).
                let mut cache = QueryCache::default();
                let times =
                    time_each(poses[..n].iter().map(|pose| sb.with_pose(*pose)), |posed| {
                        std::hint::black_box(distance_cached(sa, &posed, &opts, &mut cache));
                        Ok::<(), Box<dyn std::error::Error>>(())
                    })?;
                row.rev_blocked_mean = mean(&times);
                let best = row.best;
                let times = time_each(&poses[..n], |pose| {
                    std::hint::black_box(fa.bvh(best).distance(
                        fb.bvh(best),
                        &Isometry3::identity(),
                        pose,
                    )?);
                    Ok::<(), Box<dyn std::error::Error>>(())
                })?;
                row.fcl_blocked_mean = mean(&times);
                row
            };
            rows.push((u, row));
        }
        bar.finish_and_clear();
        eprintln!(
            "motion eps {eps:.0e}: {} pairs, {n} frames each [{:.0} s]",
            here.len(),
            started.elapsed().as_secs_f64()
        );
    }
    let Some(rows) = args
        .shard
        .finish((&args.out.dir, "motion"), &settings, units.len(), rows)?
    else {
        return Ok(()); // a shard: its raw rows are written
    };

    let out = &args.out.dir;
    let csv = prov.csv_preamble() + &motion_table().csv_text(&rows);
    std::fs::write(out.join("motion.csv"), csv)?;
    let md = markdown(&rows, &prov, started.elapsed().as_secs_f64());
    std::fs::write(out.join("motion.md"), &md)?;
    for &eps in &eps_list {
        draw(out, &rows, eps)?;
    }
    print!("{md}");
    let violations = rows.iter().map(|r| r.violations).sum();
    driver::check_violations(violations, "(see above)")
}

/// The columns of `motion.csv` and of the table in `motion.md`.
fn motion_table() -> Table<'static, Row> {
    let fcl_mean = |bv: usize, layout: usize| move |r: &Row| r.fcl_mean_of(bv, layout);
    Table::new()
        .csv("pair", |r: &Row| r.pair.clone())
        .with_markdown_header("pair")
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("frames", |r| r.frames.to_string())
        .with_markdown_header("frames")
        .right()
        .csv("revdist_mean_us", |r| format!("{:.2}", r.rev.0))
        .csv("revdist_median_us", |r| format!("{:.2}", r.rev.1))
        .markdown("revdist mean / median (us)", |r| {
            format!("{:.0} / {:.0}", r.rev.0, r.rev.1)
        })
        .right()
        .csv("fcl_obbrss_balanced_mean_us", fcl_mean(0, 0))
        .csv("fcl_obbrss_capped_mean_us", fcl_mean(0, 1))
        .csv("fcl_rss_balanced_mean_us", fcl_mean(1, 0))
        .csv("fcl_rss_capped_mean_us", fcl_mean(1, 1))
        .markdown("FCL OBBRSS / RSS mean (us)", |r| {
            let best = |bv: usize| {
                (0..r.fcl.len() / 2)
                    .map(|l| r.fcl[2 * l + bv].0)
                    .fold(f64::INFINITY, f64::min)
            };
            format!("{:.0} / {:.0}", best(0), best(1))
        })
        .right()
        .csv("faster_fcl_bv", |r| method_name(r.best).1.to_owned())
        .with_markdown_header("faster FCL BV")
        .csv("best_layout", |r| method_name(r.best).0.to_owned())
        .with_markdown_header("layout")
        .csv("fcl_best_mean_us", |r| format!("{:.2}", r.fcl_mean()))
        .csv("fcl_best_median_us", |r| format!("{:.2}", r.fcl_median()))
        .markdown("faster FCL BV mean / median (us)", |r| {
            format!("{:.0} / {:.0}", r.fcl_mean(), r.fcl_median())
        })
        .right()
        .csv("ratio_vs_faster_fcl_bv_mean", |r| {
            format!("{:.3}", r.ratio())
        })
        .with_markdown("ratio vs faster FCL BV", |r| format!("{:.2}x", r.ratio()))
        .right()
        .markdown("blocked revdist / FCL mean (us)", |r| {
            format!("{:.0} / {:.0}", r.rev_blocked_mean, r.fcl_blocked_mean)
        })
        .right()
        .markdown("blocked ratio vs faster FCL BV", |r| {
            format!("{:.2}x", r.blocked_ratio())
        })
        .right()
        .csv("triangles_best", |r| r.triangles[r.best / 2].to_string())
        .with_markdown_header("triangles A+B")
        .right()
        .csv("mean_node_pairs", |r| format!("{:.1}", r.node_pairs))
        .with_markdown("node pairs", |r| format!("{:.0}", r.node_pairs))
        .right()
        .csv("mean_leaf_tests", |r| format!("{:.1}", r.exact_leaves))
        .with_markdown_header("leaf tests")
        .right()
        .csv("min_distance", |r| format!("{:.3e}", r.min_gap))
        .csv("violations", |r| r.violations.to_string())
        .with_markdown_header("violations")
        .right()
        .csv("revdist_blocked_mean_us", |r| {
            format!("{:.2}", r.rev_blocked_mean)
        })
        .csv("fcl_best_blocked_mean_us", |r| {
            format!("{:.2}", r.fcl_blocked_mean)
        })
        .csv("ratio_blocked_vs_faster_fcl_bv", |r| {
            format!("{:.3}", r.blocked_ratio())
        })
}

fn markdown(rows: &[Row], prov: &Provenance, secs: f64) -> String {
    let mut s = String::from(
        "# The 15 model pairs in continuous motion (paper Figure 12)\n\n\
         Mean query time over a smooth random rigid motion per pair (gap between 1e-3 and 0.3, \
         often close), revdist at its default tolerance with warm starts against FCL \
         `BVHModel<OBBRSS>` and `BVHModel<RSS>` on certified meshes of the same eps (two \
         layouts each), one query at a time, methods interleaved per frame (so each query finds \
         the caches holding the other methods' data: revdist's trees and code come from \
         memory). Ratio = mean of the faster FCL BV (in its faster layout, both named) / \
         revdist mean (> 1: revdist faster). Every revdist answer is checked against \
         FCL's. *Blocked*: each method alone over the whole motion, as a simulation loop over \
         one pair runs it.\n\n",
    );
    let eps_list: Vec<f64> = {
        let mut v: Vec<f64> = rows.iter().map(|r| r.eps).collect();
        v.dedup();
        v
    };
    for &e in &eps_list {
        let _ = writeln!(s, "![eps {e:.0e}](motion_eps{e:.0e}.svg)\n");
    }
    s.push_str(&motion_table().markdown_text(rows));
    s.push('\n');
    for &e in &eps_list {
        let sel: Vec<&Row> = rows.iter().filter(|r| r.eps == e).collect();
        let ratios: Vec<f64> = sel.iter().map(|r| r.ratio()).collect();
        let behind: Vec<&str> = sel
            .iter()
            .filter(|r| r.ratio() < 1.0)
            .map(|r| r.pair.as_str())
            .collect();
        let blocked: Vec<f64> = sel.iter().map(|r| r.blocked_ratio()).collect();
        let _ = writeln!(
            s,
            "- eps {e:.0e}, blocked: speed-up {:.2}x to {:.2}x (median {:.2}x).",
            blocked.iter().copied().fold(f64::INFINITY, f64::min),
            blocked.iter().copied().fold(0.0, f64::max),
            median(&blocked)
        );
        let _ = writeln!(
            s,
            "- eps {e:.0e}: speed-up {:.2}x to {:.2}x (median {:.2}x); revdist behind on {}.",
            ratios.iter().copied().fold(f64::INFINITY, f64::min),
            ratios.iter().copied().fold(0.0, f64::max),
            median(&ratios),
            if behind.is_empty() {
                "no pair".to_string()
            } else {
                format!(
                    "{} of {} pairs ({})",
                    behind.len(),
                    sel.len(),
                    behind.join(", ")
                )
            }
        );
    }
    let _ = writeln!(
        s,
        "\nGenerated by `experiments/src/bin/motion.rs` in {secs:.0} s."
    );
    s.push_str(&prov.markdown_footer());
    s
}

/// Figure 12 at one eps: one group per pair, revdist and FCL, ratio above each group.
fn draw(out: &std::path::Path, rows: &[Row], eps: f64) -> Result<(), Box<dyn std::error::Error>> {
    let sel: Vec<&Row> = rows.iter().filter(|r| r.eps == eps).collect();
    let cats: Vec<String> = sel.iter().map(|r| r.pair.clone()).collect();
    let series = vec![
        BarSeries {
            name: "revdist".into(),
            values: sel.iter().map(|r| r.rev.0).collect(),
        },
        BarSeries {
            name: "FCL (faster of OBBRSS, RSS)".into(),
            values: sel.iter().map(|r| r.fcl_mean()).collect(),
        },
    ];
    let notes: Vec<String> = sel.iter().map(|r| format!("{:.1}x", r.ratio())).collect();
    grouped_bars_coloured(
        &out.join(format!("motion_eps{eps:.0e}.svg")),
        &format!("Pairs in continuous motion, eps {eps:.0e}: mean query time (speed-up above)"),
        &cats,
        &series,
        &[colour(0), colour(1)],
        "mean query time (us)",
        true,
        Some(&notes),
        (1500, 520),
    )
}
