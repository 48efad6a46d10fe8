//! Independent queries on all cores: a batch of solid pairs measured in
//! parallel with rayon, results in input order. Each query is the same as [`distance`]
//! alone (no state is shared between queries); the number of threads follows rayon's
//! global pool (`RAYON_NUM_THREADS`).
//!
//! For motion sequences of one pair, where each frame's answer warm-starts the next, use
//! [`crate::query::distance_cached`] in order instead: frames are not independent.

use super::distance::{distance, try_distance, Distance, QueryError, QueryOptions};
use crate::solid::Solid;
use rayon::prelude::*;

/// Distances of every pair, in parallel ([`distance`] semantics: a pose outside the
/// representable range gets the trivial certificate).
pub fn distances(pairs: &[(Solid, Solid)], opts: &QueryOptions) -> Vec<Distance> {
    pairs
        .par_iter()
        .map(|(a, b)| distance(a, b, opts))
        .collect()
}

/// [`distances`] with per-pair errors ([`try_distance`] semantics).
pub fn try_distances(
    pairs: &[(Solid, Solid)],
    opts: &QueryOptions,
) -> Vec<Result<Distance, QueryError>> {
    pairs
        .par_iter()
        .map(|(a, b)| try_distance(a, b, opts))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
    use std::sync::Arc;

    /// The batch gives exactly the answers of the queries run one by one, in order.
    #[test]
    fn batch_equals_sequential() {
        let a = Solid::from_profile(Arc::new(model("pawn").unwrap()), 1e-3).unwrap();
        let b = Solid::from_profile(Arc::new(model("cup").unwrap()), 1e-3).unwrap();
        let pairs: Vec<(Solid, Solid)> = (0..12)
            .map(|k| {
                let t = 0.9 + 0.1 * k as f64;
                let pose = Isometry3::from_parts(
                    Translation3::new(t, 0.1 * k as f64, 0.2),
                    UnitQuaternion::from_scaled_axis(Vector3::new(0.3 * k as f64, 0.5, 0.0)),
                );
                (a.clone(), b.with_pose(pose))
            })
            .collect();
        let opts = QueryOptions::default();
        let batch = distances(&pairs, &opts);
        for ((a, b), d) in pairs.iter().zip(&batch) {
            let one = distance(a, b, &opts);
            // Everything but the wall-time counters.
            assert_eq!(
                (
                    one.value,
                    one.lower,
                    one.upper,
                    one.point_a,
                    one.point_b,
                    one.overlap
                ),
                (d.value, d.lower, d.upper, d.point_a, d.point_b, d.overlap)
            );
            assert_eq!(one.stats.node_pairs, d.stats.node_pairs);
        }
        let far = vec![(
            a.clone(),
            b.with_pose(Isometry3::translation(1e200, 0.0, 0.0)),
        )];
        assert!(matches!(
            try_distances(&far, &opts)[0],
            Err(QueryError::OutOfRange { .. })
        ));
    }
}
