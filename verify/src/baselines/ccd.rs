//! libccd 2.1 convex baseline on convex point sets (each set stands for its convex hull, seen
//! through a support function), and distance through FCL's libccd-based GJK
//! (`fcl::detail::GJKDistance<double>`; libccd 2.1 has no distance call).
//!
//! All points are in one common (world) frame and so are the results. libccd's answers are
//! approximate: EPA/MPR stop at their tolerances (see [`CcdParams`]); GJK distance stops when an
//! iteration improves the distance by less than its tolerance, which does not bound the error
//! itself (FCL's documentation says so), so compare with a tolerance well above it.

use super::ffi;
use super::{flatten, BaselineError};
use nalgebra::{Point3, Vector3};

const LIBRARY: &str = "libccd";

/// Iteration cap for every libccd/GJK call. libccd's own default is unbounded
/// (`(unsigned long)-1`), which can hang on degenerate input.
pub const DEFAULT_MAX_ITERATIONS: u32 = 1000;

/// Default EPA/MPR/GJK tolerance (length units): libccd's 1e-4 default is far too coarse for a
/// reference; 1e-10 still converges in a few dozen iterations on polytopes.
pub const DEFAULT_TOLERANCE: f64 = 1e-10;

/// libccd's `ccd_t` parameters.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CcdParams {
    /// Iteration cap (GJK, EPA and MPR).
    pub max_iterations: u32,
    /// EPA stops when its lower and upper depth bounds are this close.
    pub epa_tolerance: f64,
    /// MPR stops when the portal is this close to the boundary.
    pub mpr_tolerance: f64,
    /// GJK stops when the distance improves by less than this.
    pub dist_tolerance: f64,
}

impl Default for CcdParams {
    fn default() -> Self {
        CcdParams {
            max_iterations: DEFAULT_MAX_ITERATIONS,
            epa_tolerance: DEFAULT_TOLERANCE,
            mpr_tolerance: DEFAULT_TOLERANCE,
            dist_tolerance: DEFAULT_TOLERANCE,
        }
    }
}

impl CcdParams {
    fn to_ffi(self) -> ffi::CcdParams {
        ffi::CcdParams {
            max_iterations: u64::from(self.max_iterations),
            epa_tolerance: self.epa_tolerance,
            mpr_tolerance: self.mpr_tolerance,
            dist_tolerance: self.dist_tolerance,
        }
    }
}

/// libccd's two algorithm families.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Algorithm {
    /// GJK (intersection) and GJK + EPA (penetration).
    Gjk,
    /// Minkowski portal refinement.
    Mpr,
}

/// Penetration of hull B into hull A: translating B by `depth * direction` brings the hulls
/// into touching contact (libccd's convention).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Penetration {
    /// Penetration depth (length units, >= 0).
    pub depth: f64,
    /// Unit direction (world frame).
    pub direction: Vector3<f64>,
    /// A contact position (world frame).
    pub position: Point3<f64>,
}

/// GJK distance result (world frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GjkDistance {
    /// Distance between the hulls; for [`gjk_signed_distance`] negative penetration depth when
    /// they overlap.
    pub distance: f64,
    /// Closest point on hull A.
    pub point_a: Point3<f64>,
    /// Closest point on hull B.
    pub point_b: Point3<f64>,
}

/// Whether the hulls of `a` and `b` intersect.
pub fn intersect(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
    algorithm: Algorithm,
    params: &CcdParams,
) -> Result<bool, BaselineError> {
    let (fa, fb, p) = (flatten(a), flatten(b), params.to_ffi());
    match algorithm {
        Algorithm::Gjk => ffi::ccd_gjk_intersect(&fa, &fb, &p),
        Algorithm::Mpr => ffi::ccd_mpr_intersect(&fa, &fb, &p),
    }
    .map_err(BaselineError::cpp(LIBRARY))
}

/// Penetration of B into A (`ccdGJKPenetration` or `ccdMPRPenetration`); `None` when the hulls
/// are separated.
pub fn penetration(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
    algorithm: Algorithm,
    params: &CcdParams,
) -> Result<Option<Penetration>, BaselineError> {
    let (fa, fb, p) = (flatten(a), flatten(b), params.to_ffi());
    let out = match algorithm {
        Algorithm::Gjk => ffi::ccd_gjk_penetration(&fa, &fb, &p),
        Algorithm::Mpr => ffi::ccd_mpr_penetration(&fa, &fb, &p),
    }
    .map_err(BaselineError::cpp(LIBRARY))?;
    Ok(out.intersect.then(|| Penetration {
        depth: out.depth,
        direction: Vector3::from(out.dir),
        position: Point3::from(out.pos),
    }))
}

/// `ccdGJKSeparate`: the minimal translation of B that separates the hulls; `None` when they
/// are already separated.
pub fn gjk_separate(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
    params: &CcdParams,
) -> Result<Option<Vector3<f64>>, BaselineError> {
    let out = ffi::ccd_gjk_separate(&flatten(a), &flatten(b), &params.to_ffi())
        .map_err(BaselineError::cpp(LIBRARY))?;
    Ok(out.intersect.then(|| Vector3::from(out.sep)))
}

/// Distance between the hulls by FCL's libccd GJK with the default cap and tolerance;
/// `None` when they overlap.
pub fn gjk_distance(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
) -> Result<Option<GjkDistance>, BaselineError> {
    gjk_distance_with(a, b, DEFAULT_MAX_ITERATIONS, DEFAULT_TOLERANCE)
}

/// [`gjk_distance`] with an explicit iteration cap and tolerance.
pub fn gjk_distance_with(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
    max_iterations: u32,
    tolerance: f64,
) -> Result<Option<GjkDistance>, BaselineError> {
    let out = ffi::ccd_gjk_distance(&flatten(a), &flatten(b), max_iterations, tolerance, false)
        .map_err(BaselineError::cpp("FCL GJK (libccd)"))?;
    Ok(out.separated.then(|| GjkDistance {
        distance: out.distance,
        point_a: Point3::from(out.point_a),
        point_b: Point3::from(out.point_b),
    }))
}

/// Signed distance (`GJKSignedDistance`): the distance when separated, minus the penetration
/// depth (GJK + EPA) when the hulls overlap.
pub fn gjk_signed_distance(
    a: &[Point3<f64>],
    b: &[Point3<f64>],
) -> Result<GjkDistance, BaselineError> {
    let out = ffi::ccd_gjk_distance(
        &flatten(a),
        &flatten(b),
        DEFAULT_MAX_ITERATIONS,
        DEFAULT_TOLERANCE,
        true,
    )
    .map_err(BaselineError::cpp("FCL GJK (libccd)"))?;
    Ok(GjkDistance {
        distance: out.distance,
        point_a: Point3::from(out.point_a),
        point_b: Point3::from(out.point_b),
    })
}
