//! The measurement of one (pair, eps) row: revdist's trees and FCL's certified meshes in both
//! layouts, timed cold, warm and blocked, and every answer cross-checked.

use super::row::Row;
use super::EDGE_CAP_REL;
use crate::baseline_mesh::{agrees_with_fcl, Layout};
use crate::shapes::{diagonal, query_tree_bytes, timed_pair};
use crate::stats::{median, quantile, time_each, us};
use nalgebra::Isometry3;
use revdist::biarc::BiarcTree;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions, Tolerance};
use std::sync::Arc;
use std::time::Instant;

/// Times one row: `pair` at `eps` on `poses`.
pub(super) fn bench_row(
    pair: &str,
    (pa, pb): (&Arc<Profile>, &Arc<Profile>),
    eps: f64,
    poses: &[Isometry3<f64>],
) -> Result<Row, Box<dyn std::error::Error>> {
    let same = Arc::ptr_eq(pa, pb) || pa.name() == pb.name();
    // Configuration size for the cross-check's rounding slack.
    let size = diagonal(pa) + diagonal(pb);
    // revdist: tree build (biarc tree + query tree), timed per distinct shape.
    let (sa, sb, rev_build_ms) = timed_pair(pa, pb, eps)?;
    let tree_bytes = |p: &Profile| -> Result<usize, Box<dyn std::error::Error>> {
        Ok(BiarcTree::build(p, eps)?.stats().bytes)
    };
    let rev_tree_bytes = tree_bytes(pa)? + if same { 0 } else { tree_bytes(pb)? };
    let rev_bytes = query_tree_bytes(&sa.tree) + if same { 0 } else { query_tree_bytes(&sb.tree) };

    // FCL: both layouts of both shapes.
    let mut layouts = Vec::new();
    for cap_rel in [None, Some(EDGE_CAP_REL)] {
        let la = Layout::build(pa, eps, cap_rel.map(|c| c * diagonal(pa)))?;
        let lb = if same {
            None
        } else {
            Some(Layout::build(pb, eps, cap_rel.map(|c| c * diagonal(pb)))?)
        };
        layouts.push((la, lb));
    }
    let mut row = Row {
        pair: pair.to_owned(),
        eps,
        poses: poses.len(),
        rev_build_ms,
        rev_bytes,
        rev_tree_bytes,
        ..Row::default()
    };
    for (la, lb) in &layouts {
        let lb = lb.as_ref().unwrap_or(la);
        let sum = |f: &dyn Fn(&Layout) -> f64| f(la) + if same { 0.0 } else { f(lb) };
        row.tris
            .push(la.cm.mesh.triangle_count() + lb.cm.mesh.triangle_count());
        row.h_sum.push(la.cm.bound + lb.cm.bound);
        row.mesh_ms.push(sum(&|l| l.mesh_time.as_secs_f64() * 1e3));
        row.obbrss_build_ms
            .push(sum(&|l| l.obbrss.build_time().as_secs_f64() * 1e3));
        row.rss_build_ms
            .push(sum(&|l| l.rss.build_time().as_secs_f64() * 1e3));
        row.obbrss_bytes
            .push(sum(&|l| l.obbrss.bytes() as f64) as usize);
        row.rss_bytes.push(sum(&|l| l.rss.bytes() as f64) as usize);
    }

    // Timing: every method once per pose, in a rotating order.
    let trees = QueryOptions::default();
    // Tolerance 0 and no closed form: the traversal itself, also for the torus pair (whose
    // default query is the closed form of `revdist::query::offset`).
    let exact = QueryOptions {
        tolerance: Tolerance::Absolute(0.0),
        closed_form: false,
        ..QueryOptions::default()
    };
    let n_methods = 2 + 2 * layouts.len();
    let id = Isometry3::identity();
    // The cross-check's reference answers first, in a pass of their own: an untimed FCL
    // query between the timed ones would warm the caches for the FCL method after it.
    let reference: Vec<f64> = {
        let (la, lb) = &layouts[0];
        let lb = lb.as_ref().unwrap_or(la);
        poses
            .iter()
            .map(|pose| {
                la.obbrss
                    .distance(&lb.obbrss, &id, pose)
                    .map(|f| f.distance)
            })
            .collect::<Result<_, _>>()?
    };
    let mut times = vec![Vec::with_capacity(poses.len()); n_methods];
    // Every method is repeated at once (warm), also those whose warm time is not reported,
    // so that each cold query follows the same kind of work whatever method came before.
    let mut warm_times = vec![Vec::with_capacity(poses.len()); n_methods];
    for (i, pose) in poses.iter().enumerate() {
        let b = sb.with_pose(*pose);
        for k in 0..n_methods {
            let m = (k + i) % n_methods;
            match m {
                0 | 1 => {
                    let opts = if m == 0 { &trees } else { &exact };
                    let t = Instant::now();
                    let d = distance(&sa, &b, opts);
                    times[m].push(us(t.elapsed()));
                    let t = Instant::now();
                    std::hint::black_box(distance(&sa, &b, opts));
                    warm_times[m].push(us(t.elapsed()));
                    if m == 0 {
                        row.max_width = row.max_width.max(d.upper - d.lower);
                    }
                    // Cross-check against the balanced OBBRSS answer (the reference pass).
                    if !agrees_with_fcl(&d, reference[i], row.h_sum[0], pose, size) {
                        row.violations += 1;
                    }
                }
                _ => {
                    let l = (m - 2) / 2;
                    let (la, lb) = &layouts[l];
                    let lb = lb.as_ref().unwrap_or(la);
                    let (ma, mb) = if (m - 2) % 2 == 0 {
                        (&la.obbrss, &lb.obbrss)
                    } else {
                        (&la.rss, &lb.rss)
                    };
                    let t = Instant::now();
                    let f = ma.distance(mb, &id, pose)?;
                    times[m].push(us(t.elapsed()));
                    std::hint::black_box(f);
                    let t = Instant::now();
                    std::hint::black_box(ma.distance(mb, &id, pose)?);
                    warm_times[m].push(us(t.elapsed()));
                }
            }
        }
    }
    row.rev_trees = (median(&times[0]), quantile(&times[0], 0.9));
    row.rev_exact = (median(&times[1]), quantile(&times[1], 0.9));
    for l in 0..layouts.len() {
        row.fcl
            .push((median(&times[2 + 2 * l]), median(&times[3 + 2 * l])));
        row.fcl_obbrss_warm.push(median(&warm_times[2 + 2 * l]));
        row.fcl_rss_warm.push(median(&warm_times[3 + 2 * l]));
    }
    row.rev_trees_warm = median(&warm_times[0]);
    let best = |f: &dyn Fn(&(f64, f64)) -> f64| {
        (0..row.fcl.len())
            .min_by(|&x, &y| f(&row.fcl[x]).total_cmp(&f(&row.fcl[y])))
            .expect("a layout")
    };
    row.best_obbrss = best(&|x| x.0);
    row.best_rss = best(&|x| x.1);
    // Blocked: each method alone over all poses (answers were cross-checked above).
    let blocked = time_each(poses.iter().map(|pose| sb.with_pose(*pose)), |b| {
        std::hint::black_box(distance(&sa, &b, &trees));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    row.rev_trees_blocked = median(&blocked);
    for (la, lb) in &layouts {
        let lb = lb.as_ref().unwrap_or(la);
        let blocked = time_each(poses, |pose| {
            std::hint::black_box(la.obbrss.distance(&lb.obbrss, &id, pose)?);
            Ok::<(), Box<dyn std::error::Error>>(())
        })?;
        row.fcl_obbrss_blocked.push(median(&blocked));
    }
    // FCL RSS blocked in its faster cold layout only (the blocked ratio takes the faster BV).
    let (la, lb) = &layouts[row.best_rss];
    let lb = lb.as_ref().unwrap_or(la);
    let blocked = time_each(poses, |pose| {
        std::hint::black_box(la.rss.distance(&lb.rss, &id, pose)?);
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    row.fcl_rss_blocked = median(&blocked);
    Ok(row)
}
