//! Where a distance query spends its time (issue 11): per model pair and eps, over seeded
//! poses near contact (gaps log-uniform in [1e-3, 1e-1]), the median query time, the
//! traversal counters, and the mean time per query in stage-1 leaf bounds (incl. stage 1b)
//! and in exact leaf solves (the rest is node bounds, the queue and solid semantics).
//!
//! Usage: `query_cost [--poses N] [--eps E]... [--pairs a-b,...] [--tolerance T|trees]
//! [--repeat K] [--closed-form on|off] [--cold] [--best-first]` (`off`: balls and solid tori
//! go through the traversal too; `--cold`: before each timed query, write a buffer of
//! [`EVICT_BYTES`] so that the trees and the code come from memory, as when queries alternate
//! with other work, e.g. `fcl_bench`'s FCL queries).
//!
//! `--best-first`: each timed query is warm-started ([`revdist::query::QueryCache`]) from
//! the best leaf pair of an untimed query on the same pose (all of them run before the
//! timed loop), i.e. a search that knows where the minimum is before it starts. What such a
//! query still spends is the proof: the node pairs above that leaf pair whose keys are below
//! the distance, and the leaf pairs near it (the floor of the search order, issue 11).

use experiments::poses::{log_uniform, pose_at_gap};
use experiments::SplitMix;
use revdist::models;
use revdist::query::{distance, distance_cached, QueryCache, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;

/// Bytes written between queries under `--cold`: above this machine's last-level cache.
const EVICT_BYTES: usize = 64 << 20;

/// Writes and reads `buf` once (one store per cache line), evicting the caches.
fn evict(buf: &mut [u8]) {
    for i in (0..buf.len()).step_by(64) {
        buf[i] = buf[i].wrapping_add(1);
    }
    std::hint::black_box(&buf);
}

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

fn profile(name: &str) -> Result<revdist::profile::Profile, Box<dyn std::error::Error>> {
    if name == "torus" {
        // R 1, r 0.25 (the torus).
        use revdist::models::primitives::{arc, deg};
        let p = revdist::profile::Profile::new(
            "torus",
            vec![arc([1.0, 0.0], 0.25, deg(-90.0), deg(270.0))?],
        )?;
        return Ok(p);
    }
    Ok(models::model(name)?)
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut poses = 300usize;
    let mut eps_list = vec![];
    let mut pairs = "torus-torus,pawn-pawn,pawn-cup,cup-bottle,table-lightmill".to_string();
    let mut tol_mode = "trees".to_string();
    let mut repeat = 1usize;
    let mut closed_form = true;
    let mut cold = false;
    let mut best_first = false;
    let mut i = 0;
    while i < args.len() {
        match args[i].as_str() {
            "--poses" => poses = args[i + 1].parse()?,
            "--eps" => eps_list.push(args[i + 1].parse::<f64>()?),
            "--pairs" => pairs = args[i + 1].clone(),
            "--tolerance" => tol_mode = args[i + 1].clone(),
            "--repeat" => repeat = args[i + 1].parse()?,
            "--cold" => {
                cold = true;
                i += 1;
                continue;
            }
            "--best-first" => {
                best_first = true;
                i += 1;
                continue;
            }
            "--closed-form" => {
                closed_form = match args[i + 1].as_str() {
                    "on" => true,
                    "off" => false,
                    o => return Err(format!("--closed-form on|off, got {o}").into()),
                }
            }
            o => return Err(format!("unknown argument {o}").into()),
        }
        i += 2;
    }
    if eps_list.is_empty() {
        eps_list = vec![1e-3, 1e-4, 1e-5];
    }
    println!("| pair | eps | median us | p90 us | node pairs | bound tests | leaf bounds | exact leaves | patch bounds | exact patches | subdivided | max width | stage-1 us (mean) | exact us (mean) |");
    println!("| --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- | --- |");
    for &eps in &eps_list {
        for pair in pairs.split(',') {
            let (na, nb) = pair.split_once('-').ok_or("pair a-b")?;
            let (pa, pb) = (profile(na)?, profile(nb)?);
            let centre = |p: &revdist::profile::Profile| {
                let b = p.bounding_box();
                let zc = 0.5 * (b.min.y + b.max.y);
                let h = 0.5 * (b.max.y - b.min.y);
                (zc, (b.max.x * b.max.x + h * h).sqrt())
            };
            let ((za, ra), (zb, rb)) = (centre(&pa), centre(&pb));
            let sa = Solid::from_profile(Arc::new(pa), eps)?;
            let sb = Solid::from_profile(Arc::new(pb), eps)?;
            let mut rng = SplitMix(0x11_2026 ^ pair.len() as u64);
            let mut placed = Vec::new();
            while placed.len() < poses {
                let gap = log_uniform(&mut rng, 1e-3, 1e-1);
                if let Some(p) = pose_at_gap(&sa, &sb, (za, zb), ra + rb, gap, &mut rng) {
                    placed.push(sb.with_pose(p));
                }
            }
            let tolerance = match tol_mode.as_str() {
                "trees" => revdist::query::Tolerance::Trees,
                t => revdist::query::Tolerance::Absolute(t.parse()?),
            };
            let opts = QueryOptions {
                tolerance,
                closed_form,
                ..QueryOptions::default()
            };
            let mut times = Vec::new();
            let (mut np, mut lt, mut pt, mut sd, mut w) = (0.0, 0.0, 0.0, 0.0, 0.0f64);
            let (mut bt, mut lb, mut pb) = (0.0, 0.0, 0.0);
            let (mut stage1_ns, mut exact_ns) = (0.0, 0.0);
            for _ in 1..repeat {
                for b in &placed {
                    std::hint::black_box(distance(&sa, b, &opts));
                }
            }
            let mut evict_buf = vec![0u8; if cold { EVICT_BYTES } else { 0 }];
            // Best-first caches for all poses before any timed query: priming right before
            // the timed query would also leave that pose's code path and tree nodes in the
            // caches and branch predictors (an identical untimed query first made the cold
            // medians 15-25% faster on its own).
            let primed: Vec<QueryCache> = if best_first {
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
                if cold {
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
            let med = median(&mut times);
            let p90 = times[(0.9 * (n - 1.0)) as usize];
            println!(
                "| {pair} | {eps:.0e} | {med:.1} | {p90:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.1} | {:.2} | {w:.2e} | {:.1} | {:.1} |",
                np / n,
                bt / n,
                lb / n,
                lt / n,
                pb / n,
                pt / n,
                sd / n,
                stage1_ns / n / 1e3,
                exact_ns / n / 1e3
            );
        }
    }
    Ok(())
}
