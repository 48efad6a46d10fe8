//! Where a distance query spends its time (`docs/cost_model.md`): per model pair and eps,
//! over seeded poses near contact (gaps log-uniform in [1e-3, 1e-1]), the median query time, the
//! traversal counters, and the mean time per query in stage-1 leaf bounds (incl. stage 1b)
//! and in exact leaf solves (the rest is node bounds, the queue and solid semantics).
//!
//! Usage: `query_cost [--poses N] [--eps E,...] [--pairs a-b,...] [--seed S] [--tolerance T|trees]
//! [--repeat K] [--closed-form on|off] [--cold] [--best-first]` (`off`: balls and solid tori
//! go through the traversal too; `--cold`: before each timed query, write a buffer of
//! [`EVICT_BYTES`] so that the trees and the code come from memory, as when queries alternate
//! with other work, e.g. `fcl_bench`'s FCL queries).
//!
//! `--best-first`: each timed query is warm-started ([`revdist::query::QueryCache`]) from
//! the best leaf pair of an untimed query on the same pose (all of them run before the
//! timed loop), i.e. a search that knows where the minimum is before it starts. What such a
//! query still spends is the proof: the node pairs above that leaf pair whose keys are below
//! the distance, and the leaf pairs near it (the floor of the search order,
//! `docs/cost_model.md`).

use clap::Parser;
use experiments::args::{positive_count, ModelPair};
use experiments::cli::{Eps, Pairs, Poses, Seed};
use experiments::driver::{self, DriverResult};
use experiments::poses::{log_uniform, pose_at_gap};
use experiments::shapes::{centre, profile};
use experiments::stats::median;
use experiments::table::Table;
use experiments::SplitMix;
use revdist::query::{distance, distance_cached, QueryCache, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;

/// Bytes written between queries under `--cold`: above this machine's last-level cache.
const EVICT_BYTES: usize = 64 << 20;
/// Defaults: the pairs, eps and pose count of `fcl_bench`, and the seed (xor the pair's
/// length).
const DEFAULT_PAIRS: &str = "torus-torus,pawn-pawn,pawn-cup,cup-bottle,table-lightmill";
const DEFAULT_EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];
const DEFAULT_POSES: usize = 300;
const SEED: u64 = 0x11_2026;

/// Where a distance query spends its time: per model pair and eps, over seeded poses near
/// contact (gaps log-uniform in [1e-3, 1e-1]), the median and p90 query time, the traversal
/// counters (node pairs, bound tests, leaf and patch bounds, exact leaf and patch solves,
/// subdivisions), the widest certified interval, and the mean time per query in stage-1 leaf
/// bounds and in exact leaf solves. Prints a Markdown table (defaults: 300 poses per pair;
/// torus-torus, pawn-pawn, pawn-cup, cup-bottle, table-lightmill; eps 1e-3, 1e-4, 1e-5).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    pairs: Pairs,
    #[command(flatten)]
    poses: Poses,
    #[command(flatten)]
    seed: Seed,
    /// Query tolerance: `trees` (upper - lower <= eps_a + eps_b) or an absolute width >= 0
    #[arg(long, value_name = "T|trees", default_value = "trees", value_parser = tolerance)]
    tolerance: Tolerance,
    /// Untimed passes over all poses before the timed one
    #[arg(long, value_name = "K", default_value = "1", value_parser = positive_count)]
    repeat: usize,
    /// Closed forms for balls and solid tori (`off`: they go through the traversal too)
    #[arg(long, value_name = "on|off", default_value = "on", value_parser = on_off,
          action = clap::ArgAction::Set)]
    closed_form: bool,
    /// Evict the caches before each timed query (trees and code come from memory)
    #[arg(long)]
    cold: bool,
    /// Warm-start each timed query from the best leaf pair of an untimed query on its pose
    #[arg(long)]
    best_first: bool,
}

/// `--tolerance`: `trees` or an absolute width.
fn tolerance(s: &str) -> Result<Tolerance, String> {
    match s.trim() {
        "trees" => Ok(Tolerance::Trees),
        t => match t.parse::<f64>() {
            Ok(w) if w.is_finite() && w >= 0.0 => Ok(Tolerance::Absolute(w)),
            _ => Err("needs `trees` or a width >= 0".into()),
        },
    }
}

/// `--closed-form`: `on` or `off`.
fn on_off(s: &str) -> Result<bool, String> {
    match s.trim() {
        "on" => Ok(true),
        "off" => Ok(false),
        _ => Err("needs `on` or `off`".into()),
    }
}

/// Writes and reads `buf` once (one store per cache line), evicting the caches.
fn evict(buf: &mut [u8]) {
    for i in (0..buf.len()).step_by(64) {
        buf[i] = buf[i].wrapping_add(1);
    }
    std::hint::black_box(&buf);
}

/// One line of the table: a pair at one eps, counters as means per query.
struct CostRow {
    pair: String,
    eps: f64,
    median_us: f64,
    p90_us: f64,
    node_pairs: f64,
    bound_tests: f64,
    leaf_bounds: f64,
    leaf_tests: f64,
    patch_bounds: f64,
    patch_tests: f64,
    subdivided: f64,
    max_width: f64,
    stage1_us: f64,
    exact_us: f64,
}

/// The printed table's columns.
fn cost_table() -> Table<'static, CostRow> {
    let mean = |f: fn(&CostRow) -> f64| move |r: &CostRow| format!("{:.1}", f(r));
    Table::new()
        .markdown("pair", |r: &CostRow| r.pair.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
        .markdown("median us", mean(|r| r.median_us))
        .markdown("p90 us", mean(|r| r.p90_us))
        .markdown("node pairs", mean(|r| r.node_pairs))
        .markdown("bound tests", mean(|r| r.bound_tests))
        .markdown("leaf bounds", mean(|r| r.leaf_bounds))
        .markdown("exact leaves", mean(|r| r.leaf_tests))
        .markdown("patch bounds", mean(|r| r.patch_bounds))
        .markdown("exact patches", mean(|r| r.patch_tests))
        .markdown("subdivided", |r| format!("{:.2}", r.subdivided))
        .markdown("max width", |r| format!("{:.2e}", r.max_width))
        .markdown("stage-1 us (mean)", mean(|r| r.stage1_us))
        .markdown("exact us (mean)", mean(|r| r.exact_us))
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let pairs = args
        .pairs
        .or(&experiments::args::model_pairs(DEFAULT_PAIRS));
    let mut rows = Vec::new();
    for &eps in &args.eps.or(&DEFAULT_EPS) {
        for pair in &pairs {
            rows.push(measure(pair, eps, &args)?);
        }
    }
    print!("{}", cost_table().markdown_text(&rows));
    Ok(())
}

/// Times and counts the queries of one pair at one eps.
fn measure(
    (na, nb): &ModelPair,
    eps: f64,
    args: &Args,
) -> Result<CostRow, Box<dyn std::error::Error>> {
    let pair = format!("{na}-{nb}");
    let (pa, pb) = (profile(na)?, profile(nb)?);
    let ((za, ra), (zb, rb)) = (centre(&pa), centre(&pb));
    let sa = Solid::from_profile(Arc::new(pa), eps)?;
    let sb = Solid::from_profile(Arc::new(pb), eps)?;
    let mut rng = SplitMix(args.seed.or(SEED) ^ pair.len() as u64);
    let poses = args.poses.or(DEFAULT_POSES);
    let mut placed = Vec::new();
    while placed.len() < poses {
        let gap = log_uniform(&mut rng, 1e-3, 1e-1);
        if let Some(p) = pose_at_gap(&sa, &sb, (za, zb), ra + rb, gap, &mut rng) {
            placed.push(sb.with_pose(p));
        }
    }
    let opts = QueryOptions {
        tolerance: args.tolerance,
        closed_form: args.closed_form,
        ..QueryOptions::default()
    };
    let mut times = Vec::new();
    let (mut np, mut lt, mut pt, mut sd, mut w) = (0.0, 0.0, 0.0, 0.0, 0.0f64);
    let (mut bt, mut lb, mut pb) = (0.0, 0.0, 0.0);
    let (mut stage1_ns, mut exact_ns) = (0.0, 0.0);
    for _ in 1..args.repeat {
        for b in &placed {
            std::hint::black_box(distance(&sa, b, &opts));
        }
    }
    let mut evict_buf = vec![0u8; if args.cold { EVICT_BYTES } else { 0 }];
    // Best-first caches for all poses before any timed query: priming right before the timed
    // query would also leave that pose's code path and tree nodes in the caches and branch
    // predictors (an identical untimed query first made the cold medians 15-25% faster on
    // its own).
    let primed: Vec<QueryCache> = if args.best_first {
        placed
            .iter()
            .map(|b| {
                let mut cache = QueryCache::default();
                distance_cached(&sa, b, &opts, &mut cache);
                cache
            })
            .collect()
    } else {
        Vec::new()
    };
    for (k, b) in placed.iter().enumerate() {
        if args.cold {
            evict(&mut evict_buf);
        }
        let mut cache = primed.get(k).cloned().unwrap_or_default();
        let t0 = Instant::now();
        let d = distance_cached(&sa, b, &opts, &mut cache);
        times.push(t0.elapsed().as_secs_f64() * 1e6);
        np += d.stats.node_pairs as f64;
        bt += d.stats.bound_tests as f64;
        lb += d.stats.leaf_bounds as f64;
        pb += d.stats.patch_bounds as f64;
        lt += d.stats.leaf_tests as f64;
        pt += d.stats.patch_tests as f64;
        sd += d.stats.subdivided_pairs as f64;
        stage1_ns += d.stats.leaf_bounds_ns as f64;
        exact_ns += d.stats.leaf_tests_ns as f64;
        w = w.max(d.upper - d.lower);
    }
    let n = placed.len() as f64;
    times.sort_by(f64::total_cmp);
    Ok(CostRow {
        pair,
        eps,
        median_us: median(&times),
        p90_us: times[(0.9 * (n - 1.0)) as usize],
        node_pairs: np / n,
        bound_tests: bt / n,
        leaf_bounds: lb / n,
        leaf_tests: lt / n,
        patch_bounds: pb / n,
        patch_tests: pt / n,
        subdivided: sd / n,
        max_width: w,
        stage1_us: stage1_ns / n / 1e3,
        exact_us: exact_ns / n / 1e3,
    })
}
