//! OpenCASCADE 7.6 (Debian's `libocct-*-dev` 7.6.3) as a reference on the true curved
//! surfaces: each profile is revolved into a B-rep solid (`BRepPrimAPI_MakeRevol`; a torus
//! exactly with `BRepPrimAPI_MakeTorus`), and the distance is `BRepExtrema_DistShapeShape`
//! with `Extrema_ExtFlag_MIN` (`cpp/src/occt_shim.cc`, `docs/verification.md` section 4).
//!
//! What OCCT's answer is, read from its sources (`BRepExtrema_DistShapeShape.cxx`,
//! `BRepExtrema_ExtFF.cxx`, 7.6):
//! * **numerical, not certified**: the minimum over pairs of sub-shapes (vertices, edges,
//!   faces) whose bounding boxes can beat the best so far; face-face pairs go through
//!   `Extrema_GenExtSS` (a sampling grid, then Newton), so a minimum between grid samples can be
//!   missed. The value is the distance between two points OCCT evaluated on the surfaces, so it
//!   is never below the surfaces' distance by more than rounding: a miss makes it too *high*.
//! * candidates closer than the *deflection* ([`OCCT_DEFLECTION`], OCCT's default
//!   `Precision::Confusion()`) count as equal, and the parametric tolerance of the extrema is
//!   the surfaces' resolution of that length; this is the tolerance we hold OCCT to
//!   ([`OCCT_TOLERANCE`]).
//! * **solids**: before the boundary distance, each vertex of one solid is classified against
//!   the other (`BRepClass3d_SolidClassifier`, tolerance 1e-3); a vertex *inside* gives
//!   `InnerSolution()` and distance 0. Otherwise the answer is the distance between the
//!   boundaries, so a solid nested inside the other with its few vertices within 1e-3 of the
//!   other's boundary is reported at its surface distance (revdist reports the solids' 0).
//!   [`OcctSolid::distance`] runs this same test in the shim with classifiers built once per
//!   solid (OCCT rebuilds both on every call, most of a query's time on these models) and
//!   hands BRepExtrema the shells; [`OcctSolid::distance_uncached`] is OCCT's own call.
//!
//! Without OCCT installed, `verify` still builds (`cfg(revdist_occt)` unset by `build.rs`) and
//! every function here returns [`BaselineError::Missing`].

use super::BaselineError;
use nalgebra::{Isometry3, Point3};
use revdist::profile::{Profile, ProfileKind};
use std::time::Duration;
#[cfg(revdist_occt)]
use std::time::Instant;

#[cfg(revdist_occt)]
use super::occt_ffi::ffi;
#[cfg(revdist_occt)]
use super::pose_rows;

const LIBRARY: &str = "OCCT";

/// BRepExtrema's deflection: OCCT's `Precision::Confusion()` = 1e-7 (its default, in
/// `BRepExtrema_DistShapeShape`'s constructors), the length below which OCCT treats two
/// distances or points as equal.
pub const OCCT_DEFLECTION: f64 = 1e-7;

/// The accuracy we hold OCCT's distance to: its deflection [`OCCT_DEFLECTION`]. OCCT states no
/// error bound for `BRepExtrema_DistShapeShape`; its extrema converge to the parametric
/// resolution of `Precision::Confusion()` (`BRepExtrema_ExtFF::Initialize`), and a distance
/// within the deflection of a better one is not pursued (`DistanceMapMap`).
pub const OCCT_TOLERANCE: f64 = OCCT_DEFLECTION;

/// Relative tolerance for recognising a profile as one full circle (then the solid is made as
/// an exact torus). Rational quadratic arcs evaluate on their circle to a few ulps of the
/// radius; 1e-12 is 1e4 ulps and still far below any deliberate deviation.
pub const CIRCLE_REL: f64 = 1e-12;

/// Samples per piece for [`circle_of`].
const CIRCLE_SAMPLES: usize = 64;

/// Hint printed when OCCT was not found at build time.
pub const MISSING: &str = "OCCT missing: run scripts/deps.sh (apt-get install \
                           libocct-modeling-algorithms-dev libocct-visualization-dev), then \
                           rebuild verify";

/// OCCT's version (`OCC_VERSION_COMPLETE` of the headers built against), or
/// [`BaselineError::Missing`].
pub fn version() -> Result<String, BaselineError> {
    #[cfg(revdist_occt)]
    {
        Ok(ffi::occt_version())
    }
    #[cfg(not(revdist_occt))]
    {
        Err(missing())
    }
}

/// CPU time consumed so far by the calling thread (`CLOCK_THREAD_CPUTIME_ID`, through the OCCT
/// shim), or `None` without OCCT or when the clock is unavailable. Used to time revdist's
/// queries on the same footing as OCCT's.
pub fn thread_cpu_time() -> Option<Duration> {
    #[cfg(revdist_occt)]
    {
        Duration::try_from_secs_f64(ffi::occt_thread_cpu_seconds()).ok()
    }
    #[cfg(not(revdist_occt))]
    {
        None
    }
}

#[cfg(not(revdist_occt))]
fn missing() -> BaselineError {
    BaselineError::Missing {
        library: LIBRARY,
        hint: MISSING,
    }
}

/// How a solid was made.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Construction {
    /// `BRepPrimAPI_MakeRevol` of the profile's face.
    Revolved,
    /// `BRepPrimAPI_MakeTorus(major, minor)` centred at height `centre_z`.
    Torus {
        major: f64,
        minor: f64,
        centre_z: f64,
    },
}

/// A validated OCCT solid (checked once with `BRepCheck_Analyzer`, oriented outwards).
pub struct OcctSolid {
    #[cfg(revdist_occt)]
    inner: cxx::UniquePtr<ffi::OcctSolid>,
    construction: Construction,
    build_time: Duration,
}

impl std::fmt::Debug for OcctSolid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("OcctSolid")
            .field("construction", &self.construction)
            .field("build_time", &self.build_time)
            .finish()
    }
}

/// `BRepExtrema_DistShapeShape`'s answer, in A's frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OcctDistance {
    /// OCCT's minimum distance (0 with [`OcctDistance::inner`]).
    pub distance: f64,
    /// `InnerSolution()`: a vertex of one solid lies inside the other.
    pub inner: bool,
    /// `NbSolution()`.
    pub solutions: u32,
    /// The first solution's points on A and on B.
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Wall-clock time of the call (construction of the algorithm included).
    pub time: Duration,
    /// CPU time of the calling thread in `BRepExtrema_DistShapeShape` (not inflated by other
    /// processes sharing the cores).
    pub cpu_time: Duration,
}

// SAFETY: an `OcctSolid` owns its shape's topology and geometry exclusively (OCCT's handles are
// reference counted atomically; nothing else holds them), so moving it to another thread is
// sound. It is not `Sync`: concurrent queries on one shape have not been audited, and the
// cross-check builds one copy per thread.
#[cfg(revdist_occt)]
unsafe impl Send for ffi::OcctSolid {}

impl OcctSolid {
    /// The solid of `profile`: an exact torus when the profile is one full circle
    /// ([`circle_of`]), otherwise the revolution of its face.
    pub fn from_profile(profile: &Profile) -> Result<Self, BaselineError> {
        match circle_of(profile) {
            Some((rho, z, r)) => Self::torus(rho, r, z),
            None => Self::revolved(profile),
        }
    }

    /// The revolution of the profile's face (closed by the axis when the profile is open):
    /// each piece a `Geom_BSplineCurve` in the XZ plane, rational where the piece is.
    pub fn revolved(profile: &Profile) -> Result<Self, BaselineError> {
        #[cfg(revdist_occt)]
        {
            let curves: Vec<ffi::OcctCurve> = profile
                .pieces()
                .iter()
                .map(|c| ffi::OcctCurve {
                    degree: c.degree() as u32,
                    knots: c.knots().to_vec(),
                    points: c.points().iter().flat_map(|p| [p.x, p.y]).collect(),
                    weights: c.weights().map(<[f64]>::to_vec).unwrap_or_default(),
                })
                .collect();
            let start = Instant::now();
            let inner = ffi::occt_revolve(&curves, profile.kind() == ProfileKind::OpenOnAxis)
                .map_err(|e| BaselineError::Cpp {
                    library: LIBRARY,
                    message: format!("profile '{}': {}", profile.name(), e.what()),
                })?;
            Ok(OcctSolid {
                inner,
                construction: Construction::Revolved,
                build_time: start.elapsed(),
            })
        }
        #[cfg(not(revdist_occt))]
        {
            let _ = profile;
            Err(missing())
        }
    }

    /// The solid torus of radii `major > minor > 0` about Z, centred at height `centre_z`.
    pub fn torus(major: f64, minor: f64, centre_z: f64) -> Result<Self, BaselineError> {
        #[cfg(revdist_occt)]
        {
            let start = Instant::now();
            let inner =
                ffi::occt_torus(major, minor, centre_z).map_err(BaselineError::cpp(LIBRARY))?;
            Ok(OcctSolid {
                inner,
                construction: Construction::Torus {
                    major,
                    minor,
                    centre_z,
                },
                build_time: start.elapsed(),
            })
        }
        #[cfg(not(revdist_occt))]
        {
            let _ = (major, minor, centre_z);
            Err(missing())
        }
    }

    pub fn construction(&self) -> Construction {
        self.construction
    }

    /// Construction and validation time.
    pub fn build_time(&self) -> Duration {
        self.build_time
    }

    /// Numbers of faces, edges and vertices of the B-rep.
    pub fn topology(&self) -> [u32; 3] {
        #[cfg(revdist_occt)]
        {
            let v = ffi::occt_topology(&self.inner);
            [v[0], v[1], v[2]]
        }
        #[cfg(not(revdist_occt))]
        {
            [0; 3]
        }
    }

    /// Distance between `self` at the identity and `other` placed by `pose_b`, with
    /// `Extrema_ExtFlag_MIN` and the deflection [`OCCT_DEFLECTION`]. OCCT's inner-solution
    /// test runs in the shim with classifiers kept in the solids (built on first use), and
    /// BRepExtrema gets the shells: the same answer as [`OcctSolid::distance_uncached`], which
    /// rebuilds both classifiers on every call (`verify/tests/occt.rs` compares them).
    pub fn distance(
        &self,
        other: &OcctSolid,
        pose_b: &Isometry3<f64>,
    ) -> Result<OcctDistance, BaselineError> {
        self.distance_with(other, pose_b, true)
    }

    /// `BRepExtrema_DistShapeShape` on the two solids as OCCT does it, classification included.
    pub fn distance_uncached(
        &self,
        other: &OcctSolid,
        pose_b: &Isometry3<f64>,
    ) -> Result<OcctDistance, BaselineError> {
        self.distance_with(other, pose_b, false)
    }

    fn distance_with(
        &self,
        other: &OcctSolid,
        pose_b: &Isometry3<f64>,
        cached: bool,
    ) -> Result<OcctDistance, BaselineError> {
        #[cfg(revdist_occt)]
        {
            let start = Instant::now();
            let out = ffi::occt_distance(
                &self.inner,
                &other.inner,
                &pose_rows(pose_b),
                OCCT_DEFLECTION,
                cached,
            )
            .map_err(BaselineError::cpp(LIBRARY))?;
            let time = start.elapsed();
            if !out.distance.is_finite() || out.distance < 0.0 {
                return Err(BaselineError::Cpp {
                    library: LIBRARY,
                    message: format!(
                        "distance {} is not a finite non-negative number",
                        out.distance
                    ),
                });
            }
            Ok(OcctDistance {
                distance: out.distance,
                inner: out.inner,
                solutions: out.solutions,
                point_a: Point3::from(out.point_a),
                point_b: Point3::from(out.point_b),
                time,
                cpu_time: Duration::try_from_secs_f64(out.cpu_seconds).unwrap_or_default(),
            })
        }
        #[cfg(not(revdist_occt))]
        {
            let _ = (other, pose_b, cached);
            Err(missing())
        }
    }
}

/// `(rho_c, z_c, r)` when `profile` is a closed chain whose every sample lies on one circle of
/// centre `(rho_c, z_c)` and radius `r` within [`CIRCLE_REL`] (the circle through three of the
/// samples; the chain is closed and in `rho > 0` by [`Profile`]'s validation): the solid is then
/// a torus. This only chooses OCCT's exact construction; any other profile is revolved.
pub fn circle_of(profile: &Profile) -> Option<(f64, f64, f64)> {
    if profile.kind() != ProfileKind::Closed {
        return None;
    }
    let s = profile.sample(CIRCLE_SAMPLES);
    let n = s.len();
    let (a, b, c) = (s[0], s[n / 3], s[2 * n / 3]);
    // Circumcentre of a, b, c.
    let (ab, ac) = (b - a, c - a);
    let d = 2.0 * (ab.x * ac.y - ab.y * ac.x);
    if d.abs() <= f64::EPSILON * ab.norm() * ac.norm() {
        return None;
    }
    let (ab2, ac2) = (ab.norm_squared(), ac.norm_squared());
    let centre =
        a + nalgebra::Vector2::new((ac.y * ab2 - ab.y * ac2) / d, (ab.x * ac2 - ac.x * ab2) / d);
    let r = (a - centre).norm();
    let on_circle = s
        .iter()
        .all(|p| ((p - centre).norm() - r).abs() <= CIRCLE_REL * r);
    (on_circle && centre.x > r).then_some((centre.x, centre.y, r))
}
