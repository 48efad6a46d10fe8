//! The measurement of one pair: seeded poses, every level built, every method timed per pose
//! in a rotating order, and every revdist answer cross-checked against every FCL answer.

use super::levels::{bvh, rev_level, FclLevel, LayoutPair, RevLevel};
use super::method::{Method, METHODS};
use super::row::Row;
use super::Settings;
use crate::baseline_mesh::agrees_with_fcl;
use crate::poses::{close_poses, pair_seed, CLOSE_GAPS};
use crate::progress::bar;
use crate::shapes::{diagonal, profile};
use crate::stats::{median, quantile, us};
use nalgebra::Isometry3;
use revdist::query::{distance, Distance};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::Instant;

/// One timed configuration: a revdist mode at a level, or an FCL hierarchy of a layout.
#[derive(Clone, Copy)]
struct Slot {
    method: Method,
    level: usize,
    layout: usize,
}

/// Per slot: query times, revdist widths, cross-checks and violations.
#[derive(Default, Clone)]
struct Samples {
    times: Vec<f64>,
    widths: Vec<f64>,
    node_pairs: usize,
    zero_lower: usize,
    checks: usize,
    violations: usize,
}

/// What one pair contributes: its rows and the FCL levels skipped by the triangle cap.
pub(super) struct PairResult {
    pub(super) rows: Vec<Row>,
    pub(super) skipped: Vec<String>,
}

/// Measures one pair: its poses, levels and timed slots, and the rows they give.
pub(super) fn run_pair(
    na: &str,
    nb: &str,
    args: &Settings,
) -> Result<PairResult, Box<dyn std::error::Error>> {
    let pair_started = Instant::now();
    let pair = format!("{na}-{nb}");
    let (pa, pb) = (Arc::new(profile(na)?), Arc::new(profile(nb)?));
    let same = na == nb;
    let size = diagonal(&pa) + diagonal(&pb);

    let pb_bar = bar(args.poses as u64, &format!("poses {pair}"));
    let poses = close_poses(
        &pa,
        &pb,
        args.poses,
        CLOSE_GAPS,
        pair_seed(args.seed, &pair),
        || pb_bar.inc(1),
    )?;
    pb_bar.finish_and_clear();

    // revdist levels (every eps of either list).
    let mut rev_eps: Vec<f64> = args
        .rev_eps
        .iter()
        .chain(&args.refine_eps)
        .copied()
        .collect();
    rev_eps.sort_by(|x, y| y.total_cmp(x));
    rev_eps.dedup();
    let rev: Vec<RevLevel> = rev_eps
        .iter()
        .map(|&e| rev_level(&pa, &pb, same, e))
        .collect::<Result<_, _>>()?;

    // FCL levels, coarse to fine, until the predicted triangle count exceeds the cap.
    let mut fcl: Vec<FclLevel> = Vec::new();
    let mut skipped = Vec::new();
    let build_bar = bar(args.fcl_eps.len() as u64, &format!("meshes {pair}"));
    for &eps in &args.fcl_eps {
        if let Some(prev) = fcl.last() {
            let tris = prev
                .layouts
                .iter()
                .map(LayoutPair::triangles)
                .max()
                .unwrap_or(0);
            let predicted = tris as f64 * prev.eps / eps;
            if predicted > args.max_triangles as f64 {
                skipped.push(format!(
                    "{pair}: FCL at eps {eps:.0e} and finer not run: predicted {:.1}M triangles \
                     ({tris} at eps {:.0e} times {:.0}) exceed the cap of {:.1}M",
                    predicted / 1e6,
                    prev.eps,
                    prev.eps / eps,
                    args.max_triangles as f64 / 1e6
                ));
                break;
            }
        }
        fcl.push(FclLevel::build(&pa, &pb, same, eps)?);
        build_bar.inc(1);
    }
    build_bar.finish_and_clear();
    for s in &skipped {
        eprintln!("{s}");
    }

    // The timed slots.
    let mut slots = Vec::new();
    for (k, lv) in rev.iter().enumerate() {
        let modes: &[Method] = match (
            args.rev_eps.contains(&lv.eps),
            args.refine_eps.contains(&lv.eps),
        ) {
            (true, true) => &[Method::Rev, Method::RevTol0, Method::RevRefined],
            (true, false) => &[Method::Rev, Method::RevTol0],
            (false, true) => &[Method::RevRefined],
            (false, false) => &[],
        };
        for &method in modes {
            slots.push(Slot {
                method,
                level: k,
                layout: 0,
            });
        }
    }
    for (k, lv) in fcl.iter().enumerate() {
        for layout in 0..lv.layouts.len() {
            for method in [Method::FclObbrss, Method::FclRss] {
                slots.push(Slot {
                    method,
                    level: k,
                    layout,
                });
            }
        }
    }
    let mut samples = vec![Samples::default(); slots.len()];
    let id = Isometry3::identity();
    let time_bar = bar(poses.len() as u64, &format!("timing {pair}"));
    for (i, pose) in poses.iter().enumerate() {
        let posed: Vec<Solid> = rev.iter().map(|lv| lv.b.with_pose(*pose)).collect();
        let mut rev_answers: Vec<(usize, Distance)> = Vec::new();
        let mut fcl_answers: Vec<(usize, f64, f64)> = Vec::new();
        for j in 0..slots.len() {
            let s_idx = (j + i) % slots.len();
            let s = slots[s_idx];
            if s.method.is_fcl() {
                let lp = &fcl[s.level].layouts[s.layout];
                let (ma, mb) = (bvh(&lp.a, s.method), bvh(lp.b(), s.method));
                let t = Instant::now();
                let f = ma.distance(mb, &id, pose)?;
                samples[s_idx].times.push(us(t.elapsed()));
                fcl_answers.push((s_idx, f.distance, lp.h_sum()));
            } else {
                let opts = s.method.options();
                let t = Instant::now();
                let d = distance(&rev[s.level].a, &posed[s.level], &opts);
                samples[s_idx].times.push(us(t.elapsed()));
                samples[s_idx].widths.push(d.upper - d.lower);
                samples[s_idx].node_pairs += d.stats.node_pairs;
                samples[s_idx].zero_lower += usize::from(d.lower <= 0.0);
                rev_answers.push((s_idx, d));
            }
        }
        for (r, d) in &rev_answers {
            for &(f, fd, h) in &fcl_answers {
                let ok = agrees_with_fcl(d, fd, h, pose, size);
                for k in [*r, f] {
                    samples[k].checks += 1;
                    samples[k].violations += usize::from(!ok);
                }
            }
        }
        time_bar.inc(1);
    }
    time_bar.finish_and_clear();

    let mut rows = Vec::new();
    for (s, smp) in slots
        .iter()
        .zip(&samples)
        .filter(|(s, _)| !s.method.is_fcl())
    {
        let lv = &rev[s.level];
        rows.push(Row {
            method: s.method,
            pair: pair.clone(),
            eps: lv.eps,
            poses: smp.times.len(),
            width_max: smp.widths.iter().copied().fold(0.0, f64::max),
            width_median: median(&smp.widths),
            median_us: median(&smp.times),
            p90_us: quantile(&smp.times, 0.9),
            build_ms: lv.build_ms,
            bytes: lv.bytes,
            node_pairs: Some(smp.node_pairs as f64 / smp.times.len().max(1) as f64),
            zero_lower: Some(smp.zero_lower),
            triangles: None,
            layout: None,
            checks: smp.checks,
            violations: smp.violations,
        });
    }
    for (k, lv) in fcl.iter().enumerate() {
        for method in [Method::FclObbrss, Method::FclRss] {
            // The faster layout for this hierarchy.
            let (idx, best) = slots
                .iter()
                .enumerate()
                .filter(|(_, s)| s.method == method && s.level == k)
                .min_by(|x, y| median(&samples[x.0].times).total_cmp(&median(&samples[y.0].times)))
                .expect("a layout per level");
            let lp = &lv.layouts[best.layout];
            let smp = &samples[idx];
            let h = lp.h_sum();
            let build_ms =
                lp.sum(|x| (x.mesh_time + bvh(x, method).build_time()).as_secs_f64() * 1e3);
            let bytes = lp.sum(|x| bvh(x, method).bytes() as f64) as usize;
            rows.push(Row {
                method,
                pair: pair.clone(),
                eps: lv.eps,
                poses: smp.times.len(),
                width_max: h,
                width_median: h,
                median_us: median(&smp.times),
                p90_us: quantile(&smp.times, 0.9),
                build_ms,
                bytes,
                node_pairs: None,
                zero_lower: None,
                triangles: Some(lp.triangles()),
                layout: Some(lp.name),
                checks: smp.checks,
                violations: smp.violations,
            });
        }
    }
    rows.sort_by(|x, y| {
        let m = |r: &Row| METHODS.iter().position(|&m| m == r.method);
        m(x).cmp(&m(y)).then(y.eps.total_cmp(&x.eps))
    });
    if let Some(r) = rows.iter().find(|r| r.method == Method::Rev) {
        eprintln!(
            "{pair}: {} poses, {} revdist and {} FCL configurations [{:.0} s]",
            r.poses,
            slots.iter().filter(|s| !s.method.is_fcl()).count(),
            slots.iter().filter(|s| s.method.is_fcl()).count(),
            pair_started.elapsed().as_secs_f64()
        );
    }
    Ok(PairResult { rows, skipped })
}
