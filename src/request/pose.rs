//! A rigid pose from what a user writes: a translation and a unit quaternion `[w, x, y, z]`
//! (the command line's JSON, the rows of a Python `(N, 7)` array) or a homogeneous 4x4
//! matrix (a Python `(N, 4, 4)` array). A point `x` of the solid's frame is at `R x + t`.

use nalgebra::{Isometry3, Matrix3, Quaternion, Rotation3, Translation3, UnitQuaternion, Vector3};

use crate::limits::{check_translation, RangeError};

/// A quaternion whose norm differs from 1 by more than this is rejected; closer ones are
/// normalised, and the pose is that of the normalised quaternion. 1e-3 admits a unit
/// quaternion typed with 3 decimals (each of the 4 components off by at most 5e-4, so the
/// norm by at most 1e-3), such as `[0.7071, 0, 0.7071, 0]` (norm 0.99999), while a
/// quaternion further off is more likely a mistake (a component missing or mistyped) than
/// a rounding.
pub const UNIT_QUATERNION_SLACK: f64 = 1e-3;

/// A rotation block `R` with some entry of `R^T R - I` larger than this is rejected, the
/// ~7 significant digits of a matrix computed by a program; closer ones are taken through
/// their quaternion, which is normalised.
pub const ROTATION_MATRIX_SLACK: f64 = 1e-6;

/// Why numbers do not form a pose.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PoseError {
    /// The translation is not finite or out of range ([`crate::limits::MAX_TRANSLATION`]).
    #[error(transparent)]
    Translation(#[from] RangeError),
    /// The quaternion's norm is not within [`UNIT_QUATERNION_SLACK`] of 1 (or not finite);
    /// the message shows the normalised quaternion when there is one, ready to paste.
    #[error("{}", not_unit_message(rotation, *norm))]
    NotUnit { rotation: [f64; 4], norm: f64 },
    /// A matrix entry is NaN or infinite.
    #[error("matrix entry [{row}][{col}] is {value}, not a finite number")]
    MatrixNotFinite { row: usize, col: usize, value: f64 },
    /// The last row of a homogeneous matrix is not exactly `[0, 0, 0, 1]`.
    #[error("the last row of a homogeneous matrix must be [0, 0, 0, 1], got {0:?}")]
    NotHomogeneous([f64; 4]),
    /// The upper-left 3x3 block is not a rotation (not orthonormal, or a reflection).
    #[error("the upper-left 3x3 block is not a rotation matrix (largest entry of R^T R - I: {deviation:e}, determinant {det})")]
    NotRotation { deviation: f64, det: f64 },
}

fn not_unit_message(rotation: &[f64; 4], norm: f64) -> String {
    let mut text = format!(
        "rotation {rotation:?} is not a unit quaternion [w, x, y, z] (norm {norm}, more than {UNIT_QUATERNION_SLACK:e} from 1)"
    );
    if norm.is_finite() && norm > 0.0 {
        let unit = rotation.map(|c| c / norm);
        text.push_str(&format!("; normalised it is {unit:?}"));
    }
    text
}

/// The rotation of the quaternion `rotation = [w, x, y, z]`, normalised when its norm is
/// within [`UNIT_QUATERNION_SLACK`] of 1, refused otherwise.
pub fn unit_quaternion(rotation: [f64; 4]) -> Result<UnitQuaternion<f64>, PoseError> {
    let r = rotation;
    let q = Quaternion::new(r[0], r[1], r[2], r[3]);
    let norm = q.norm();
    if !norm.is_finite() || (norm - 1.0).abs() > UNIT_QUATERNION_SLACK {
        return Err(PoseError::NotUnit { rotation, norm });
    }
    Ok(UnitQuaternion::from_quaternion(q))
}

/// The pose `x -> R x + t`, `R` the rotation of the quaternion `rotation = [w, x, y, z]`
/// ([`unit_quaternion`]: normalised when its norm is within [`UNIT_QUATERNION_SLACK`] of 1).
pub fn pose_from_quaternion(
    translation: [f64; 3],
    rotation: [f64; 4],
) -> Result<Isometry3<f64>, PoseError> {
    let t = check_translation("translation", translation)?;
    Ok(Isometry3::from_parts(
        Translation3::from(Vector3::from(t)),
        unit_quaternion(rotation)?,
    ))
}

/// The pose of a homogeneous matrix `m` (row-major, `m[row][col]`): the rotation block is
/// converted to its quaternion and the pose is then exactly [`pose_from_quaternion`] of that
/// quaternion and the last column, so that a matrix and the quaternion it holds give the
/// same bits.
pub fn pose_from_matrix(m: &[[f64; 4]; 4]) -> Result<Isometry3<f64>, PoseError> {
    for (row, r) in m.iter().enumerate() {
        for (col, &value) in r.iter().enumerate() {
            if !value.is_finite() {
                return Err(PoseError::MatrixNotFinite { row, col, value });
            }
        }
    }
    if m[3] != [0.0, 0.0, 0.0, 1.0] {
        return Err(PoseError::NotHomogeneous(m[3]));
    }
    let r = Matrix3::from_fn(|i, j| m[i][j]);
    let gram = r.transpose() * r - Matrix3::identity();
    let deviation = gram.amax();
    let det = r.determinant();
    if deviation > ROTATION_MATRIX_SLACK || det <= 0.0 {
        return Err(PoseError::NotRotation { deviation, det });
    }
    let q = UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(r));
    let c = q.into_inner().coords; // [x, y, z, w]
    pose_from_quaternion([m[0][3], m[1][3], m[2][3]], [c.w, c.x, c.y, c.z])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quaternions_near_unit_are_normalised_and_others_rejected() {
        let p = pose_from_quaternion(
            [1.0, 2.0, 3.0],
            [2f64.sqrt() / 2.0, 0.0, 0.0, 2f64.sqrt() / 2.0],
        )
        .unwrap();
        let x = p * nalgebra::Point3::new(1.0, 0.0, 0.0);
        assert!((x - nalgebra::Point3::new(1.0, 3.0, 3.0)).norm() < 1e-15);
        assert!(pose_from_quaternion([0.0; 3], [1.0 + 5e-7, 0.0, 0.0, 0.0]).is_ok());
        let e = pose_from_quaternion([0.0; 3], [1.1, 0.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "rotation [1.1, 0.0, 0.0, 0.0] is not a unit quaternion [w, x, y, z] (norm 1.1, \
             more than 1e-3 from 1); normalised it is [1.0, 0.0, 0.0, 0.0]"
        );
        let e = unit_quaternion([0.0; 4]).unwrap_err();
        assert_eq!(
            e.to_string(),
            "rotation [0.0, 0.0, 0.0, 0.0] is not a unit quaternion [w, x, y, z] (norm 0, \
             more than 1e-3 from 1)"
        );
    }

    /// A quaternion as people type it, 4 or 3 decimals, is taken as the rotation of its
    /// normalisation, compared with the exact quarter turn about y: the rotated points agree
    /// to the rounding of the typed digits (the normalised axis is exact here, so only the
    /// angle moves: `2 atan(x / w)` with `x = w`, a quarter turn to rounding).
    #[test]
    #[allow(clippy::approx_constant)] // the digits a person types, on purpose
    fn quaternions_typed_with_few_decimals_are_normalised() {
        for c in [0.7071, 0.707] {
            let p = pose_from_quaternion([0.0; 3], [c, 0.0, c, 0.0]).unwrap();
            let q = p.rotation.into_inner();
            assert!((q.norm() - 1.0).abs() < 1e-15, "{c}: normalised");
            assert!((q.w - q.j).abs() == 0.0, "{c}: w and y stay equal");
            let x = p * nalgebra::Point3::new(1.0, 0.0, 0.0);
            assert!((x - nalgebra::Point3::new(0.0, 0.0, -1.0)).norm() < 1e-15);
            // The typed norm is within the slack, but further off than the 1e-6 once asked...
            let typed: f64 = (2.0 * c * c).sqrt();
            assert!((typed - 1.0).abs() < UNIT_QUATERNION_SLACK && (typed - 1.0).abs() > 1e-6);
        }
        // ... and one further off than the slack names the normalised value to paste.
        let e = pose_from_quaternion([0.0; 3], [0.7, 0.0, 0.7, 0.0]).unwrap_err();
        let text = e.to_string();
        assert!(
            text.ends_with("normalised it is [0.7071067811865476, 0.0, 0.7071067811865476, 0.0]"),
            "{text}"
        );
        let just_inside = 1.0 + 0.999e-3;
        assert!(unit_quaternion([just_inside, 0.0, 0.0, 0.0]).is_ok());
        assert!(unit_quaternion([1.0 + 1.001e-3, 0.0, 0.0, 0.0]).is_err());
        assert!(unit_quaternion([f64::INFINITY, 0.0, 0.0, 0.0]).is_err());
        let e = pose_from_quaternion([0.0, f64::NAN, 0.0], [1.0, 0.0, 0.0, 0.0]).unwrap_err();
        assert_eq!(e.to_string(), "translation.y is NaN, not a finite number");
    }

    /// A matrix built independently from an axis and an angle (Rodrigues) gives the pose of
    /// the quaternion of the same axis and angle.
    #[test]
    fn a_matrix_gives_the_pose_of_its_quaternion() {
        let (axis, angle) = (Vector3::new(1.0, -2.0, 0.5).normalize(), 2.4f64);
        let (s, c) = angle.sin_cos();
        let k = Matrix3::new(
            0.0, -axis.z, axis.y, axis.z, 0.0, -axis.x, -axis.y, axis.x, 0.0,
        );
        let r = Matrix3::identity() + k * s + k * k * (1.0 - c);
        let mut m = [[0.0; 4]; 4];
        for i in 0..3 {
            for j in 0..3 {
                m[i][j] = r[(i, j)];
            }
        }
        m[0][3] = 0.5;
        m[2][3] = -1.0;
        m[3][3] = 1.0;
        let from_m = pose_from_matrix(&m).unwrap();
        let (hs, hc) = (angle / 2.0).sin_cos();
        let from_q = pose_from_quaternion(
            [0.5, 0.0, -1.0],
            [hc, hs * axis.x, hs * axis.y, hs * axis.z],
        )
        .unwrap();
        let p = nalgebra::Point3::new(0.3, -0.7, 1.1);
        assert!((from_m * p - from_q * p).norm() < 1e-15);
        let mut reflect = m;
        reflect[0][0] = -reflect[0][0];
        reflect[1][0] = -reflect[1][0];
        reflect[2][0] = -reflect[2][0];
        assert!(matches!(
            pose_from_matrix(&reflect),
            Err(PoseError::NotRotation { det, .. }) if det < 0.0
        ));
        let mut skew = m;
        skew[0][1] += 1e-3;
        assert!(matches!(
            pose_from_matrix(&skew),
            Err(PoseError::NotRotation { .. })
        ));
        let mut bottom = m;
        bottom[3][0] = 1e-9;
        assert!(matches!(
            pose_from_matrix(&bottom),
            Err(PoseError::NotHomogeneous(_))
        ));
        let mut nan = m;
        nan[1][2] = f64::NAN;
        assert_eq!(
            pose_from_matrix(&nan).unwrap_err().to_string(),
            "matrix entry [1][2] is NaN, not a finite number"
        );
    }

    /// Poses arrive as JSON text (the CLI, batch lines) and must parse to the same double
    /// as Rust's correctly rounded `str::parse`, so that the CLI, a batch line and a Python
    /// array give the same query bit for bit (serde_json's default fast path may be one ulp
    /// off on 17-digit decimals; the workspace enables `float_roundtrip`).
    #[test]
    fn json_numbers_parse_to_the_nearest_double() {
        let mut rng = crate::test_rng::SplitMix64(0x5eed_f10a);
        for _ in 0..20_000 {
            let x = rng.range(-1.0, 1.0) * 10f64.powf(rng.range(-30.0, 30.0));
            for text in [
                format!("{x:.16e}"),
                format!("{x}"),
                format!("{:.17}", x * 1e-3),
            ] {
                let exact: f64 = text.parse().unwrap();
                let json: f64 = serde_json::from_str(&text).unwrap();
                assert_eq!(json.to_bits(), exact.to_bits(), "{text}");
            }
        }
    }
}
