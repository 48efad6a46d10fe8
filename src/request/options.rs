//! The accuracy and budget of a query: the trees' eps, the interval's tolerance and the
//! anytime time budget, checked with one message for each front end.

use std::time::Duration;

use crate::query::{Budget, QueryOptions, Tolerance};

/// A query option out of its range; the message names the option and the value.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum OptionError {
    /// eps is not a positive finite number.
    #[error("eps must be a positive number, got {0}")]
    Eps(f64),
    /// The tolerance is negative, NaN or infinite.
    #[error("tolerance must be a non-negative number, got {0}")]
    Tolerance(f64),
    /// The time budget is not a positive finite number of milliseconds; `name` is how the
    /// caller spells the option (`--max-time-ms`, `max_time_ms`).
    #[error("{name} must be a positive number, got {value}")]
    MaxTime { name: &'static str, value: f64 },
}

/// The trees' approximation bound when the caller names none: the command line's
/// `distance` and `toi` (`--eps`) and the Python package's constructors.
pub const DEFAULT_EPS: f64 = 1e-4;

/// The approximation bound of a tree: positive and finite (its range relative to the
/// profile's size is checked when the tree is built, `crate::limits`).
pub fn check_eps(eps: f64) -> Result<f64, OptionError> {
    if eps.is_finite() && eps > 0.0 {
        Ok(eps)
    } else {
        Err(OptionError::Eps(eps))
    }
}

/// The requested width of the certified interval: `None` for the trees' own accuracy
/// ([`Tolerance::Trees`]), else a non-negative finite width.
pub fn check_tolerance(tolerance: Option<f64>) -> Result<Tolerance, OptionError> {
    match tolerance {
        None => Ok(Tolerance::Trees),
        Some(t) if t.is_finite() && t >= 0.0 => Ok(Tolerance::Absolute(t)),
        Some(t) => Err(OptionError::Tolerance(t)),
    }
}

/// A time budget in milliseconds, positive and finite; `name` spells the option in the
/// error message.
pub fn max_time(name: &'static str, ms: Option<f64>) -> Result<Option<Duration>, OptionError> {
    match ms {
        None => Ok(None),
        Some(ms) if ms.is_finite() && ms > 0.0 => Ok(Some(Duration::from_secs_f64(ms / 1e3))),
        Some(value) => Err(OptionError::MaxTime { name, value }),
    }
}

/// The options of a query as the command line and the Python package set them: the
/// tolerance ([`check_tolerance`]), a budget of node pairs and of time ([`max_time`]) and
/// refinement; every other field keeps its default.
pub fn query_options(
    tolerance: Option<f64>,
    max_node_pairs: Option<usize>,
    max_time_ms: (&'static str, Option<f64>),
    refine: bool,
) -> Result<QueryOptions, OptionError> {
    Ok(QueryOptions {
        tolerance: check_tolerance(tolerance)?,
        budget: Budget {
            max_node_pairs,
            max_time: max_time(max_time_ms.0, max_time_ms.1)?,
        },
        refine,
        ..QueryOptions::default()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn options_are_checked_with_their_names() {
        assert_eq!(check_eps(1e-4), Ok(1e-4));
        assert_eq!(
            check_eps(f64::NAN).unwrap_err().to_string(),
            "eps must be a positive number, got NaN"
        );
        assert!(check_eps(0.0).is_err());
        assert_eq!(check_tolerance(None), Ok(Tolerance::Trees));
        assert_eq!(check_tolerance(Some(0.0)), Ok(Tolerance::Absolute(0.0)));
        assert_eq!(
            check_tolerance(Some(-1.0)).unwrap_err().to_string(),
            "tolerance must be a non-negative number, got -1"
        );
        assert_eq!(
            max_time("max_time_ms", Some(0.0)).unwrap_err().to_string(),
            "max_time_ms must be a positive number, got 0"
        );
        assert_eq!(max_time("t", Some(2.0)), Ok(Some(Duration::from_millis(2))));
        let o = query_options(Some(1e-3), Some(10), ("t", Some(1.0)), true).unwrap();
        assert_eq!(o.tolerance, Tolerance::Absolute(1e-3));
        assert_eq!(o.budget.max_node_pairs, Some(10));
        assert!(o.refine);
        assert_eq!(o.closed_form, QueryOptions::default().closed_form);
    }
}
