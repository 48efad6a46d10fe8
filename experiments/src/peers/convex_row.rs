//! One row of the convex table: two convex solids of revolution as revdist solids (default
//! options and the convex path) and as the peers' exact primitives, timed and cross-checked.

use super::coal::CoalPeer;
use super::convex::primitive;
use super::parry::{self, ParryShape};
use super::rows::ConvexRow;
use super::{agrees, Res, COAL_GJK_TOLERANCE, CONVEX_EPS, PARRY_GROSS_EXCESS};
use crate::poses::{close_poses, pair_seed, CLOSE_GAPS};
use crate::shapes::{diagonal, profile};
use crate::stats::{median, time_each};
use revdist::query::{distance, Distance, QueryOptions};
use revdist::solid::Solid;
use std::sync::Arc;

/// One row of the convex table: models `a` and `b` as revdist solids and as exact primitives.
pub(super) fn convex_row(
    a: &str,
    b: &str,
    n: usize,
    seed: u64,
    coal: &mut Result<CoalPeer, String>,
) -> Res<ConvexRow> {
    let pair = format!("{a}-{b}");
    let (pa, pb) = (Arc::new(profile(a)?), Arc::new(profile(b)?));
    let poses = close_poses(&pa, &pb, n, CLOSE_GAPS, pair_seed(seed, &pair), || {})?;
    let size = diagonal(&pa) + diagonal(&pb);
    let sa = Solid::from_profile(Arc::clone(&pa), CONVEX_EPS)?;
    let sb = Solid::from_profile(Arc::clone(&pb), CONVEX_EPS)?;
    let opts = QueryOptions::default();
    let answers: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &opts))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |s| {
        std::hint::black_box(distance(&sa, &s, &opts));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev_us = median(&times);
    // revdist's convex path (GJK on the biarc solids, off by default): its own intervals,
    // cross-checked against coal like the default's.
    let fast = QueryOptions {
        convex_path: true,
        ..QueryOptions::default()
    };
    let answers_fast: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &fast))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |s| {
        std::hint::black_box(distance(&sa, &s, &fast));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev_convex_us = Some(median(&times));
    let max_width = answers
        .iter()
        .chain(&answers_fast)
        .map(|d| d.upper - d.lower)
        .fold(0.0, f64::max);
    let (ka, kb) = (
        primitive(a).ok_or_else(|| format!("no primitive for {a}"))?,
        primitive(b).ok_or_else(|| format!("no primitive for {b}"))?,
    );
    let mut violations = 0;
    let coal_us = match coal {
        Ok(peer) => {
            peer.primitive("PA", &ka)?;
            peer.primitive("PB", &kb)?;
            let ans = peer.query("PA", "PB", &poses)?;
            for (i, x) in ans.iter().enumerate() {
                let slack = COAL_GJK_TOLERANCE
                    * (1.0 + x.distance.abs() + ka.swept_radius() + kb.swept_radius());
                for (opts, ans) in [("default", &answers[i]), ("convex path", &answers_fast[i])] {
                    if !agrees(ans, x.distance, slack, &poses[i], size) {
                        violations += 1;
                        eprintln!(
                            "VIOLATION {pair} pose {i}: coal GJK {:e} outside revdist ({opts}) \
                             [{:e}, {:e}] widened by coal's GJK error bound {slack:e}",
                            x.distance, ans.lower, ans.upper
                        );
                    }
                }
            }
            Ok(median(&ans.iter().map(|x| x.us).collect::<Vec<_>>()))
        }
        Err(e) => Err(e.clone()),
    };
    let (qa, qb) = (ParryShape::primitive(&ka), ParryShape::primitive(&kb));
    let pp: Vec<_> = poses.iter().map(parry::pose).collect();
    let mut ds = Vec::with_capacity(pp.len());
    let times = time_each(&pp, |p| {
        ds.push(qa.distance(&qb, p)?);
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let parry_excess = ds
        .iter()
        .zip(&answers)
        .map(|(d, a)| (a.lower - d).max(d - a.upper).max(0.0))
        .fold(0.0, f64::max);
    if parry_excess > PARRY_GROSS_EXCESS {
        violations += 1;
        eprintln!("VIOLATION {pair}: parry3d off revdist's interval by {parry_excess:e}");
    }
    Ok(ConvexRow {
        pair,
        poses: poses.len(),
        rev_us,
        rev_convex_us,
        coal: coal_us,
        parry_us: median(&times),
        parry_excess,
        max_width,
        violations,
    })
}
