//! Trees once per (model, eps) and the timing itself: one thread, one query at a time, each
//! run once (cold).

use super::query::{Placed, Row};
use crate::stats::us;
use rayon::prelude::*;
use revdist::profile::Profile;
use revdist::query::{try_distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

/// The trees of every (model, eps) the queries use, keyed by (model, eps bits); built on all
/// cores, before any timing.
pub(super) fn build_trees(
    placed: &[Placed],
    profiles: &HashMap<String, Arc<Profile>>,
) -> Result<HashMap<(String, u64), Solid>, revdist::biarc::TreeError> {
    let mut keys: Vec<(String, u64)> = placed
        .iter()
        .flat_map(|q| [q.a.clone(), q.b.clone()].map(|m| (m, q.spec.eps.to_bits())))
        .collect();
    keys.sort();
    keys.dedup();
    keys.into_par_iter()
        .map(|(m, e)| {
            let s = Solid::from_profile(Arc::clone(&profiles[&m]), f64::from_bits(e))?;
            Ok(((m, e), s))
        })
        .collect()
}

/// Times each query once, alone, on this thread, in the given order.
pub(super) fn time_queries(
    placed: Vec<Placed>,
    trees: &HashMap<(String, u64), Solid>,
) -> Result<Vec<Row>, String> {
    let mut rows = Vec::with_capacity(placed.len());
    for q in placed {
        let key = |m: &str| (m.to_owned(), q.spec.eps.to_bits());
        let sa = &trees[&key(&q.a)];
        let sb = trees[&key(&q.b)].with_pose(q.pose());
        let opts = QueryOptions {
            tolerance: if q.spec.tol0 {
                Tolerance::Absolute(0.0)
            } else {
                Tolerance::Trees
            },
            ..QueryOptions::default()
        };
        let t = Instant::now();
        let d = try_distance(sa, &sb, &opts);
        let time_us = us(t.elapsed());
        let d = d.map_err(|e| format!("query {}: {e}: {}", q.spec.index, q.reproducer()))?;
        rows.push(Row {
            q,
            time_us,
            node_pairs: d.stats.node_pairs,
            leaf_tests: d.stats.leaf_tests,
            lower: d.lower,
            upper: d.upper,
            overlap: d.overlap,
            budget_exhausted: d.stats.budget_exhausted,
        });
    }
    Ok(rows)
}
