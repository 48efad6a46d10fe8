//! Statistics of the samples per (level, family, delta): the rows of `stability.csv`.

use super::{Key, Sample};

/// Statistics of the samples of one (level, family, delta).
#[derive(Debug, Clone)]
pub struct Row {
    pub key: Key,
    pub cases: usize,
    pub max_abs: f64,
    pub median_abs: f64,
    pub max_rel: f64,
    pub median_rel: f64,
    /// Largest absolute bound of the group.
    pub bound: f64,
    /// Largest `abs_err / bound`.
    pub max_over_bound: f64,
    /// Largest certified width (NaN for circles).
    pub max_width: f64,
    /// Samples with `lower <= exact <= upper` violated.
    pub certificate_violations: usize,
    /// Samples above their error bound.
    pub bound_exceeded: usize,
    /// Slowest answer (seconds).
    pub max_seconds: f64,
}

/// Groups samples by (level, family, delta) in the order of first appearance.
pub fn summarise(samples: &[Sample]) -> Vec<Row> {
    let mut keys: Vec<Key> = Vec::new();
    for s in samples {
        if !keys.contains(&s.key) {
            keys.push(s.key);
        }
    }
    keys.into_iter()
        .map(|key| {
            let g: Vec<&Sample> = samples.iter().filter(|s| s.key == key).collect();
            let col = |f: fn(&Sample) -> f64| g.iter().map(|s| f(s)).collect::<Vec<f64>>();
            let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
            let (abs, rel) = (col(|s| s.abs_err), col(|s| s.rel_err));
            Row {
                key,
                cases: g.len(),
                max_abs: max(&abs),
                median_abs: crate::stats::median(&abs),
                max_rel: max(&rel),
                median_rel: crate::stats::median(&rel),
                bound: max(&col(|s| s.bound)),
                max_over_bound: max(&col(|s| s.abs_err / s.bound)),
                max_width: max(&col(|s| s.width())),
                certificate_violations: g.iter().filter(|s| !s.certified).count(),
                bound_exceeded: g.iter().filter(|s| s.abs_err > s.bound).count(),
                max_seconds: max(&col(|s| s.seconds)),
            }
        })
        .collect()
}
