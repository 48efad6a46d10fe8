//! One checked answer of either level and its check against its bound and certificate.

use super::Key;

/// One checked answer.
#[derive(Debug, Clone)]
pub struct Sample {
    pub key: Key,
    pub variant: &'static str,
    pub seed: usize,
    /// Exact reference (rounded to f64).
    pub exact: f64,
    /// The answer revdist gave (the query's `value` for solids).
    pub value: f64,
    /// `|value - exact|`, computed exactly and rounded.
    pub abs_err: f64,
    /// `abs_err / size`.
    pub rel_err: f64,
    /// The absolute error this sample must stay within.
    pub bound: f64,
    /// Certified interval of a solid query (NaN for circles).
    pub lower: f64,
    pub upper: f64,
    /// Solids: `lower <= exact <= upper`, compared exactly (circles: true).
    pub certified: bool,
    /// Wall-clock time of revdist's answer in seconds, the exact reference excluded (circles:
    /// the fastest of a few runs; solids: one query).
    pub seconds: f64,
    /// Solids: the profiles' names and the relative pose the query used, B in A's frame
    /// (`revdist distance A B --eps E --pose-b '...'` reruns it when both are built-ins).
    pub reproducer: Option<String>,
}

impl Sample {
    /// Within the error bound and, for solids, with a valid certificate.
    pub fn ok(&self) -> bool {
        self.abs_err <= self.bound && self.certified
    }

    /// `upper - lower` (NaN for circles).
    pub fn width(&self) -> f64 {
        self.upper - self.lower
    }

    /// A one-line description with everything needed to rerun the case.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{} / {} / {} / delta {} / seed {}: value {:.17e}, exact {:.17e}, error {:.3e} (bound {:.3e})",
            self.key.level.name(),
            self.key.family,
            self.variant,
            self.key.delta.map_or("0".to_string(), |k| format!("1e-{k}")),
            self.seed,
            self.value,
            self.exact,
            self.abs_err,
            self.bound,
        );
        if !self.lower.is_nan() {
            s.push_str(&format!(
                ", interval [{:.17e}, {:.17e}]",
                self.lower, self.upper
            ));
        }
        s.push_str(&format!(", {:.1} us", self.seconds * 1e6));
        if let Some(r) = &self.reproducer {
            s.push_str("; rerun: ");
            s.push_str(r);
        }
        s
    }
}
