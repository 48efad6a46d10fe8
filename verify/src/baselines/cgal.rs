//! CGAL 5.5 exact references: triangle-triangle and mesh-mesh squared distances (Epeck) and the
//! distance between convex hulls (`Polytope_distance_d`, Gmpzf arithmetic).
//!
//! Exact values cross the FFI as rationals and are rounded here, once, with rug:
//! [`ExactSquaredDistance::squared`] is the correctly rounded squared distance and
//! [`ExactSquaredDistance::distance`] the correctly rounded distance (square root of the exact
//! rational, rounding decided by exact comparisons).

use super::cgal_ffi::ffi;
use super::{flatten, pose_rows, BaselineError, TriMesh};
use nalgebra::{Isometry3, Point3};
use rug::float::Round;
use rug::{Float, Rational};
use std::cmp::Ordering;

const LIBRARY: &str = "CGAL";

/// Default cap on triangle pairs of [`mesh_distance_exact`]: the float pass costs about 0.1 µs
/// per pair that survives the bounding-box test, so 1e8 pairs are ~10 s at worst.
pub const DEFAULT_MAX_PAIRS: u64 = 100_000_000;

/// Default cap on pairs evaluated exactly (about 50 µs each with Epeck, so ~1 s).
pub const DEFAULT_MAX_CANDIDATES: u64 = 20_000;

/// Precision (bits) of the first approximation of a square root before the exact rounding
/// check; anything well above 53 makes the correction loop run at most once or twice.
const SQRT_PREC: u32 = 128;

/// An exact squared distance and its correctly rounded images.
#[derive(Debug, Clone, PartialEq)]
pub struct ExactSquaredDistance {
    /// The exact squared distance.
    pub exact: Rational,
    /// `exact` rounded to nearest (ties to even).
    pub squared: f64,
    /// `sqrt(exact)` rounded to nearest (ties to even).
    pub distance: f64,
}

impl ExactSquaredDistance {
    fn new(exact: Rational) -> Self {
        ExactSquaredDistance {
            squared: round_to_f64(&exact),
            distance: sqrt_to_f64(&exact),
            exact,
        }
    }

    fn parse(r: &ffi::ExactRational) -> Result<Self, BaselineError> {
        let bad = |what: &str| BaselineError::Cpp {
            library: LIBRARY,
            message: format!("unparsable exact {what} from the shim"),
        };
        let num = rug::Integer::from_str_radix(&r.num, 16).map_err(|_| bad("numerator"))?;
        let den = rug::Integer::from_str_radix(&r.den, 16).map_err(|_| bad("denominator"))?;
        if den.cmp0() != Ordering::Greater || num.cmp0() == Ordering::Less {
            return Err(bad("squared distance (negative or zero denominator)"));
        }
        Ok(Self::new(Rational::from((num, den))))
    }
}

/// Exact mesh-mesh distance with its minimising pair.
#[derive(Debug, Clone, PartialEq)]
pub struct MeshDistanceExact {
    pub value: ExactSquaredDistance,
    /// Index of the minimising triangle of A (first in (A, B) index order among exact ties).
    pub triangle_a: u32,
    /// Index of the minimising triangle of B.
    pub triangle_b: u32,
    /// Number of pairs evaluated exactly.
    pub candidates: usize,
    /// The float (Epick) minimum squared distance that selected the candidates.
    pub float_squared: f64,
}

/// Limits of [`mesh_distance_exact`] (both give `Err` when exceeded).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct MeshLimits {
    /// Maximum number of triangle pairs (brute force).
    pub max_pairs: u64,
    /// Maximum number of near-tied pairs evaluated exactly.
    pub max_candidates: u64,
}

impl Default for MeshLimits {
    fn default() -> Self {
        MeshLimits {
            max_pairs: DEFAULT_MAX_PAIRS,
            max_candidates: DEFAULT_MAX_CANDIDATES,
        }
    }
}

/// Exact distance between the convex hulls of two point sets.
#[derive(Debug, Clone, PartialEq)]
pub struct PolytopeDistanceExact {
    pub value: ExactSquaredDistance,
    /// Realizing point on hull P (rounded from CGAL's exact homogeneous coordinates, so
    /// approximate; the distance is exact).
    pub point_p: Point3<f64>,
    /// Realizing point on hull Q (approximate).
    pub point_q: Point3<f64>,
}

/// Exact squared distance between triangles `a` and `b` (Epeck).
pub fn triangle_distance_exact(
    a: &[Point3<f64>; 3],
    b: &[Point3<f64>; 3],
) -> Result<ExactSquaredDistance, BaselineError> {
    let out =
        ffi::cgal_triangle_sqd(&flatten(a), &flatten(b)).map_err(BaselineError::cpp(LIBRARY))?;
    ExactSquaredDistance::parse(&out)
}

/// Exact distance between mesh `a` placed by `pose_a` and mesh `b` placed by `pose_b` (the pose
/// matrices' double entries are applied exactly, so this is the exact distance of the meshes
/// FCL is asked about, not of double-rounded copies). Brute force: an Epick pass over all
/// pairs (with bounding-box rejection) selects the pairs within a rounding slack of the float
/// minimum, which Epeck then evaluates exactly. The result is exact provided Epick's error on
/// the minimising pair is below the slack (`1e-12 * scale^2`, ~100x its observed error); it is
/// meant for meshes of a few thousand triangles.
pub fn mesh_distance_exact(
    a: &TriMesh,
    pose_a: &Isometry3<f64>,
    b: &TriMesh,
    pose_b: &Isometry3<f64>,
    limits: &MeshLimits,
) -> Result<MeshDistanceExact, BaselineError> {
    let out = ffi::cgal_mesh_sqd(
        &a.vertices,
        &a.triangles,
        &pose_rows(pose_a),
        &b.vertices,
        &b.triangles,
        &pose_rows(pose_b),
        limits.max_pairs,
        limits.max_candidates,
    )
    .map_err(BaselineError::cpp(LIBRARY))?;
    Ok(MeshDistanceExact {
        value: ExactSquaredDistance::parse(&out.sqd)?,
        triangle_a: out.triangle_a,
        triangle_b: out.triangle_b,
        candidates: usize::try_from(out.candidates).unwrap_or(usize::MAX),
        float_squared: out.float_sqd,
    })
}

/// Exact distance between the convex hulls of `p` and `q` (0 when they intersect), by
/// `CGAL::Polytope_distance_d` with `Polytope_distance_d_traits_3<Epick, Gmpzf, double>`.
pub fn polytope_distance_exact(
    p: &[Point3<f64>],
    q: &[Point3<f64>],
) -> Result<PolytopeDistanceExact, BaselineError> {
    let out =
        ffi::cgal_polytope_sqd(&flatten(p), &flatten(q)).map_err(BaselineError::cpp(LIBRARY))?;
    Ok(PolytopeDistanceExact {
        value: ExactSquaredDistance::parse(&out.sqd)?,
        point_p: Point3::from(out.point_p),
        point_q: Point3::from(out.point_q),
    })
}

/// `q` rounded to the nearest double, ties to even, subnormals included (rug's
/// `Rational::to_f64` truncates instead).
pub fn round_to_f64(q: &Rational) -> f64 {
    let (mut f, dir) = Float::with_val_round(f64::MANTISSA_DIGITS, q, Round::Nearest);
    f.subnormalize_ieee_round(dir, Round::Nearest);
    f.to_f64()
}

/// `sqrt(q)` (q >= 0) rounded to the nearest double, ties to even: a high-precision estimate,
/// then exact comparisons of `q` with the squares of the neighbouring rounding midpoints.
pub fn sqrt_to_f64(q: &Rational) -> f64 {
    if q.cmp0() != Ordering::Greater {
        return 0.0;
    }
    let mut d = Float::with_val(SQRT_PREC, q).sqrt().to_f64();
    // Each step moves d by one ulp towards the correct result; the estimate is off by at most
    // one ulp, so two steps suffice (the cap only guards against a logic error).
    for _ in 0..4 {
        let lo = midpoint_sq(d, d.next_down());
        let hi = midpoint_sq(d, d.next_up());
        match (q.cmp(&lo), q.cmp(&hi)) {
            (Ordering::Less, _) => d = d.next_down(),
            (_, Ordering::Greater) => d = d.next_up(),
            (Ordering::Equal, _) => return even_of(d, d.next_down()),
            (_, Ordering::Equal) => return even_of(d, d.next_up()),
            _ => return d,
        }
    }
    d
}

/// Square of the exact midpoint of two doubles.
fn midpoint_sq(a: f64, b: f64) -> Rational {
    let m = (Rational::from_f64(a).unwrap_or_default() + Rational::from_f64(b).unwrap_or_default())
        / 2u32;
    Rational::from(&m * &m)
}

/// Of two adjacent doubles, the one with an even significand.
fn even_of(a: f64, b: f64) -> f64 {
    if a.to_bits() & 1 == 0 {
        a
    } else {
        b
    }
}
