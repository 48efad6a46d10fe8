//! Many time-of-impact searches between the same two solids, in parallel (rayon), results
//! in input order; each search has its own query cache ([`super::advance`]).

use super::advance::{time_of_impact, TimeOfImpact, ToiError, ToiOptions};
use super::motion::Motion;
use crate::solid::Solid;
use rayon::prelude::*;

/// Why a batch cannot run at all (per-motion problems are per-result errors).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum BatchError {
    #[error("threads must be at least 1")]
    Threads,
    #[error("cannot start the worker threads: {0}")]
    Pool(String),
}

/// The search of [`time_of_impact`] for every `(motion of a, motion of b)`, in parallel on
/// `threads` workers (`None`: rayon's global pool, every core).
pub fn times_of_impact(
    a: &Solid,
    b: &Solid,
    motions: &[(Motion, Motion)],
    opts: &ToiOptions,
    threads: Option<usize>,
) -> Result<Vec<Result<TimeOfImpact, ToiError>>, BatchError> {
    let run = || {
        motions
            .par_iter()
            .map(|(ma, mb)| time_of_impact(a, ma, b, mb, opts))
            .collect()
    };
    match threads {
        None => Ok(run()),
        Some(0) => Err(BatchError::Threads),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map(|pool| pool.install(run))
            .map_err(|e| BatchError::Pool(e.to_string())),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
    use std::sync::Arc;

    /// The batch gives exactly the answers of the searches run one by one, in order (every
    /// field but the traversal's timers).
    #[test]
    fn batch_equals_sequential() {
        let a = Solid::from_profile(Arc::new(model("pawn").unwrap()), 1e-3).unwrap();
        let b = Solid::from_profile(Arc::new(model("cup").unwrap()), 1e-3).unwrap();
        let fixed = Motion::fixed(Isometry3::identity()).unwrap();
        let motions: Vec<(Motion, Motion)> = (0..8)
            .map(|k| {
                let k = f64::from(k);
                let start = Isometry3::from_parts(
                    Translation3::new(3.0 + 0.2 * k, 0.1 * k, 0.5),
                    UnitQuaternion::from_scaled_axis(Vector3::new(0.3 * k, 0.5, 0.0)),
                );
                let end = Isometry3::from_parts(
                    Translation3::new(-1.0, 0.05 * k, 0.3),
                    UnitQuaternion::from_scaled_axis(Vector3::new(0.0, 0.2 * k, 0.4)),
                );
                (fixed, Motion::new(start, end).unwrap())
            })
            .collect();
        let opts = ToiOptions::default();
        let batch = times_of_impact(&a, &b, &motions, &opts, Some(2)).unwrap();
        assert_eq!(batch.len(), motions.len());
        for ((ma, mb), got) in motions.iter().zip(&batch) {
            let want = time_of_impact(&a, ma, &b, mb, &opts).unwrap();
            let got = got.as_ref().unwrap();
            let key = |r: &TimeOfImpact| {
                let c = r
                    .contact
                    .as_ref()
                    .map(|c| (c.lower, c.upper, c.point_a, c.point_b));
                (
                    r.outcome,
                    r.t_lower,
                    r.t_upper,
                    c,
                    r.queries,
                    r.steps,
                    r.certificates,
                )
            };
            assert_eq!(key(got), key(&want));
        }
        assert_eq!(
            times_of_impact(&a, &b, &motions, &opts, Some(0)).unwrap_err(),
            BatchError::Threads
        );
    }
}
