//! Checks of single values (counts, numbers, lengths, vectors, poses); errors name the field.
//! Translations and lengths are held to the range `revdist distance` accepts
//! ([`revdist::limits`]).

use super::error::{field_error, SceneError};
use super::spec::PoseSpec;
use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};
use revdist::limits::{check_magnitude, check_translation, MAX_TRANSLATION};
use revdist::request::unit_quaternion;

/// A count given or defaulted, within `range`; `unit` follows the range in the message
/// (e.g. `" pixels"`).
pub(super) fn count_in(
    field: &str,
    v: Option<usize>,
    default: usize,
    range: std::ops::RangeInclusive<usize>,
    unit: &str,
) -> Result<usize, SceneError> {
    let n = v.unwrap_or(default);
    if range.contains(&n) {
        Ok(n)
    } else {
        Err(field_error(
            field,
            format!("must be {}..{}{unit}, got {n}", range.start(), range.end()),
        ))
    }
}

/// A finite number `> 0`.
pub(super) fn positive(field: &str, v: f64) -> Result<f64, SceneError> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(field_error(
            field,
            format!("must be a positive number, got {v}"),
        ))
    }
}

/// A positive length (a radius, a spacing, a skin) within [`MAX_TRANSLATION`].
pub(super) fn positive_length(field: &str, v: f64) -> Result<f64, SceneError> {
    positive(field, v)?;
    Ok(check_magnitude(field, v, MAX_TRANSLATION)?)
}

/// A translation (or a position in the scene): 3 finite numbers whose length is within
/// [`MAX_TRANSLATION`].
pub(super) fn translation(field: &str, v: &[f64]) -> Result<Vector3<f64>, SceneError> {
    let [x, y, z] = v[..] else {
        return Err(field_error(
            field,
            format!("expected 3 numbers, got {}", v.len()),
        ));
    };
    // A component beyond the limit is reported as given (the length of the vector could
    // overflow to inf).
    for v in [x, y, z].into_iter().filter(|v| v.is_finite()) {
        check_magnitude(field, v, MAX_TRANSLATION)?;
    }
    check_translation(field, [x, y, z])?;
    Ok(Vector3::new(x, y, z))
}

/// 3 finite numbers (a velocity, an acceleration).
pub(super) fn vec3(field: &str, v: &[f64]) -> Result<Vector3<f64>, SceneError> {
    if v.len() != 3 {
        return Err(field_error(
            field,
            format!("expected 3 numbers, got {}", v.len()),
        ));
    }
    if !v.iter().all(|x| x.is_finite()) {
        return Err(field_error(field, "numbers must be finite"));
    }
    Ok(Vector3::new(v[0], v[1], v[2]))
}

/// A pose from its spec; `field` names it in errors.
pub fn pose_of(field: &str, p: &PoseSpec) -> Result<Isometry3<f64>, SceneError> {
    let t = match &p.translation {
        Some(v) => translation(&format!("{field}.translation"), v)?,
        None => Vector3::zeros(),
    };
    let r = match (&p.quaternion, &p.axis, p.angle) {
        (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
            return Err(field_error(
                field,
                "give either quaternion or axis and angle, not both",
            ))
        }
        (Some(q), None, None) => {
            if q.len() != 4 {
                return Err(field_error(
                    format!("{field}.quaternion"),
                    format!("expected 4 numbers [w, x, y, z], got {}", q.len()),
                ));
            }
            // The command line's rule (`docs/inputs.md`, section 3): normalised within
            // the slack of 1, refused beyond it with the normalised value to paste.
            unit_quaternion([q[0], q[1], q[2], q[3]])
                .map_err(|e| field_error(format!("{field}.quaternion"), e.to_string()))?
        }
        (None, Some(_), None) => {
            return Err(field_error(
                format!("{field}.angle"),
                "an axis needs an angle",
            ));
        }
        (None, Some(axis), Some(angle)) => {
            let a = vec3(&format!("{field}.axis"), axis)?;
            if !angle.is_finite() {
                return Err(field_error(format!("{field}.angle"), "must be finite"));
            }
            if a.norm() == 0.0 {
                return Err(field_error(format!("{field}.axis"), "must not be zero"));
            }
            UnitQuaternion::from_axis_angle(&Unit::new_normalize(a), angle)
        }
        (None, None, Some(_)) => {
            return Err(field_error(format!("{field}.angle"), "needs an axis"));
        }
        (None, None, None) => UnitQuaternion::identity(),
    };
    Ok(Isometry3::from_parts(Translation3::from(t), r))
}
