//! The representable range of revdist's inputs, stated once for the library, the command
//! line, batch mode and scenes.
//!
//! Every number a user gives (profile coordinates and weights, poses, motion amplitudes,
//! approximation bounds) is checked against these limits before any geometry runs, so that
//! nothing downstream meets an overflow: squared lengths of the largest configuration stay
//! finite, and the query's own range check (`query::MAX_SCALE`, `1e150`) is never the first
//! to see a value out of range.
//!
//! Why these numbers:
//! * [`MAX_COORDINATE`] and [`MAX_TRANSLATION`] (`1e100`): a configuration is at most a few
//!   times `1e100` across, far inside the query's `1e150`, whose squares (`1e300`) are finite.
//!   Derivatives of a curve scale with its coordinates over its knot spans, so the margin of
//!   `1e50` also absorbs knot spans down to `1e-50` of the domain.
//! * [`MAX_WEIGHT_RATIO`] (`1e12`): a rational curve's points are weighted averages of its
//!   control points; a weight ratio `r` lets the curve sit `r` times closer to one control
//!   point than the control polygon suggests, and the rounding of the homogeneous coordinates
//!   grows with `r`. CAD weights stay within `1e3`.
//! * [`MIN_EPS_REL`] and [`MAX_EPS_REL`]: the approximation bound `eps` relative to the
//!   profile's size; below `1e-12` rounding (`~1e-14` of the coordinates) dominates the
//!   certified bounds, above `0.1` the "approximation" no longer resembles the solid.

/// Largest absolute value of a profile coordinate (rho or z).
pub const MAX_COORDINATE: f64 = 1e100;

/// Largest absolute value of a knot.
pub const MAX_KNOT: f64 = 1e100;

/// Shortest non-empty knot span. A curve's third derivative grows as its coordinates times
/// its weight ratio over the span cubed: with [`MAX_COORDINATE`] and [`MAX_WEIGHT_RATIO`],
/// spans of `1e-12` keep it below `1e150`, whose square is still finite.
pub const MIN_KNOT_SPAN: f64 = 1e-12;

/// Smallest size (bounding-box diagonal) of a profile: squared lengths of its features stay
/// normal floating-point numbers.
pub const MIN_PROFILE_SIZE: f64 = 1e-100;

/// Largest ratio between the largest and the smallest weight of a rational piece.
pub const MAX_WEIGHT_RATIO: f64 = 1e12;

/// Largest length of a translation (a pose's, a keyframe's, a random motion's amplitude).
pub const MAX_TRANSLATION: f64 = 1e100;

/// Smallest accepted approximation bound, relative to the profile's size.
pub const MIN_EPS_REL: f64 = 1e-12;

/// Largest accepted approximation bound, relative to the profile's size.
pub const MAX_EPS_REL: f64 = 0.1;

/// A value outside the representable range; `field` names where it was given (e.g.
/// `piece 2, point 3, rho` or `pose_b.translation`).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum RangeError {
    /// NaN or infinite.
    #[error("{field} is {value}, not a finite number")]
    NotFinite { field: String, value: f64 },
    /// Finite but beyond the stated limit.
    #[error("{field} = {value:e} is outside the representable range (|{field}| <= {limit:e})")]
    TooLarge {
        field: String,
        value: f64,
        limit: f64,
    },
    /// Must not be negative.
    #[error("{field} = {value:e} must be >= 0")]
    Negative { field: String, value: f64 },
}

/// `value` is finite with `|value| <= limit`.
pub fn check_magnitude(field: &str, value: f64, limit: f64) -> Result<f64, RangeError> {
    if !value.is_finite() {
        return Err(RangeError::NotFinite {
            field: field.to_string(),
            value,
        });
    }
    if value.abs() > limit {
        return Err(RangeError::TooLarge {
            field: field.to_string(),
            value,
            limit,
        });
    }
    Ok(value)
}

/// A profile coordinate: finite with `|value| <= MAX_COORDINATE`.
pub fn check_coordinate(field: &str, value: f64) -> Result<f64, RangeError> {
    check_magnitude(field, value, MAX_COORDINATE)
}

/// A translation (or a motion's amplitude): every component finite and its length at most
/// [`MAX_TRANSLATION`].
pub fn check_translation(field: &str, t: [f64; 3]) -> Result<[f64; 3], RangeError> {
    for (axis, v) in ["x", "y", "z"].iter().zip(t) {
        if !v.is_finite() {
            return Err(RangeError::NotFinite {
                field: format!("{field}.{axis}"),
                value: v,
            });
        }
    }
    // Scaled by the largest component, so that no square overflows.
    let largest = t.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let length = if largest > 0.0 {
        largest * t.iter().map(|v| (v / largest).powi(2)).sum::<f64>().sqrt()
    } else {
        0.0
    };
    check_magnitude(field, length, MAX_TRANSLATION)?;
    Ok(t)
}

/// A length such as a motion amplitude: finite, `>= 0` and at most [`MAX_TRANSLATION`].
pub fn check_length(field: &str, value: f64) -> Result<f64, RangeError> {
    check_magnitude(field, value, MAX_TRANSLATION)?;
    if value < 0.0 {
        return Err(RangeError::Negative {
            field: field.to_string(),
            value,
        });
    }
    Ok(value)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn errors_name_the_field_and_the_value() {
        let e = check_coordinate("piece 0, point 1, rho", 1e200).unwrap_err();
        assert_eq!(
            e.to_string(),
            "piece 0, point 1, rho = 1e200 is outside the representable range (|piece 0, point 1, rho| <= 1e100)"
        );
        let e = check_translation("pose_b.translation", [0.0, f64::NAN, 0.0]).unwrap_err();
        assert!(e.to_string().contains("pose_b.translation.y is NaN"), "{e}");
        assert!(check_translation("t", [1e100, 1e100, 0.0]).is_err());
        assert!(check_translation("t", [7e99, 7e99, 0.0]).is_ok());
        let e = check_translation("t", [1e200, 0.0, 0.0]).unwrap_err();
        assert!(
            matches!(e, RangeError::TooLarge { value, .. } if value == 1e200),
            "{e}"
        );
        assert!(check_length("amplitude", -1.0).is_err());
        assert_eq!(check_length("amplitude", 0.0), Ok(0.0));
    }
}
