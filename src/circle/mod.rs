//! Circles in 3-D: point/circle distance, all binormal lines of two circles and their minimum
//! distance (paper section 3.2 and Appendix A).
//!
//! A binormal of circles A and B is a segment A(phi) B(theta) perpendicular to both circles:
//! (A - B) . A' = 0 and (A - B) . B' = 0 (the critical points of |A - B|^2 on the torus of
//! parameter pairs). They are found from a degree-8 polynomial in the half-angle of one circle
//! ([`poly8`]), solved by the even-root-preserving Bernstein solver of [`crate::poly`], then
//! polished by 2-D Newton on the geometric equations and de-duplicated ([`binormal`]).
//! Parallel planes are solved in closed form ([`parallel`]); continua of binormals (coaxial,
//! meridian, point on axis, Villarceau) are reported explicitly, never as garbage.

pub mod binormal;
mod certified;
mod descent;
mod frame;
pub mod min_distance;
pub mod parallel;
pub mod point;
pub mod poly8;

use nalgebra::{Isometry3, Point3, Unit, Vector3};

pub use binormal::binormals;
pub use min_distance::{min_distance, min_distance_value};
pub use point::{point_circle_distance, PointCircleDistance};

/// Two directions are treated as parallel when the sine of their angle is below this:
/// the closed-form parallel-plane solution is then exact up to `sin * radius`, i.e. within
/// double rounding of the configuration scale.
pub const PARALLEL_SIN_TOL: f64 = 1e-14;

/// Relative tolerance (of the configuration scale) under which two distances are a tie, a
/// point is on an axis, or a distance function is constant. It is the accuracy the solver
/// guarantees (1e-12 relative, checked against exact arithmetic by `verify circles`), so ties below it cannot be resolved anyway.
pub const TIE_REL_TOL: f64 = 1e-12;

/// Errors from building circles.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CircleError {
    #[error("circle radius must be finite and >= 0, got {0}")]
    BadRadius(f64),
    #[error("circle normal must be finite and non-zero")]
    BadNormal,
    #[error("circle centre must be finite")]
    BadCenter,
    #[error("circle u-axis must be finite and not parallel to the normal")]
    BadUAxis,
    #[error(
        "angle interval must be finite with length in [0, 2 pi], got start {start}, length {len}"
    )]
    BadInterval { start: f64, len: f64 },
}

/// A circle in 3-D: `center + radius (cos theta u_axis + sin theta v_axis)` with
/// `v_axis = normal x u_axis`. Radius 0 is a point and is supported everywhere.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Circle3 {
    pub center: Point3<f64>,
    pub normal: Unit<Vector3<f64>>,
    pub radius: f64,
    /// Direction of angle 0 (unit, perpendicular to `normal`).
    pub u_axis: Unit<Vector3<f64>>,
}

impl Circle3 {
    /// A circle with a canonical angle origin (the coordinate axis least aligned with the
    /// normal, projected into the plane).
    pub fn new(
        center: Point3<f64>,
        normal: Vector3<f64>,
        radius: f64,
    ) -> Result<Self, CircleError> {
        let n = check_normal(normal)?;
        let (ax, ay, az) = (n.x.abs(), n.y.abs(), n.z.abs());
        let e = if ax <= ay && ax <= az {
            Vector3::x()
        } else if ay <= az {
            Vector3::y()
        } else {
            Vector3::z()
        };
        Self::with_u_axis(center, n.into_inner(), e, radius)
    }

    /// A circle whose angle 0 points along `u_axis` projected into the circle's plane.
    pub fn with_u_axis(
        center: Point3<f64>,
        normal: Vector3<f64>,
        u_axis: Vector3<f64>,
        radius: f64,
    ) -> Result<Self, CircleError> {
        if !center.coords.iter().all(|c| c.is_finite()) {
            return Err(CircleError::BadCenter);
        }
        if !(radius.is_finite() && radius >= 0.0) {
            return Err(CircleError::BadRadius(radius));
        }
        let n = check_normal(normal)?;
        if !u_axis.iter().all(|c| c.is_finite()) {
            return Err(CircleError::BadUAxis);
        }
        let u = u_axis - n.into_inner() * n.dot(&u_axis);
        let un = u.norm();
        // `un` is finite here; reject a u axis (nearly) parallel to the normal.
        if un <= 1e-12 * u_axis.norm() || un == 0.0 {
            return Err(CircleError::BadUAxis);
        }
        Ok(Self {
            center,
            normal: n,
            radius,
            u_axis: Unit::new_unchecked(u / un),
        })
    }

    /// `normal x u_axis`: direction of angle pi/2.
    pub fn v_axis(&self) -> Vector3<f64> {
        self.normal.cross(&self.u_axis)
    }

    /// The point at angle `theta`.
    pub fn point_at(&self, theta: f64) -> Point3<f64> {
        let (s, c) = theta.sin_cos();
        self.center + self.radius * (c * self.u_axis.into_inner() + s * self.v_axis())
    }

    /// d/dtheta of [`Self::point_at`] (length = radius).
    pub fn tangent_at(&self, theta: f64) -> Vector3<f64> {
        let (s, c) = theta.sin_cos();
        self.radius * (-s * self.u_axis.into_inner() + c * self.v_axis())
    }

    /// Angle of the projection of `p` into the plane (0 when `p` is on the axis).
    pub fn angle_of(&self, p: &Point3<f64>) -> f64 {
        let d = p - self.center;
        let (x, y) = (d.dot(&self.u_axis), d.dot(&self.v_axis()));
        if x == 0.0 && y == 0.0 {
            0.0
        } else {
            y.atan2(x)
        }
    }

    /// The circle moved by a rigid motion (angles are preserved).
    pub fn transformed(&self, iso: &Isometry3<f64>) -> Circle3 {
        Circle3 {
            center: iso * self.center,
            normal: Unit::new_normalize(iso.rotation * self.normal.into_inner()),
            radius: self.radius,
            u_axis: Unit::new_normalize(iso.rotation * self.u_axis.into_inner()),
        }
    }

    /// The circle scaled by `s > 0` about the origin.
    pub fn scaled(&self, s: f64) -> Circle3 {
        Circle3 {
            center: Point3::from(self.center.coords * s),
            radius: self.radius * s,
            ..*self
        }
    }
}

fn check_normal(normal: Vector3<f64>) -> Result<Unit<Vector3<f64>>, CircleError> {
    let len = normal.norm();
    if !(len.is_finite() && len > 0.0) {
        return Err(CircleError::BadNormal);
    }
    Ok(Unit::new_unchecked(normal / len))
}

/// A counter-clockwise range of angles `[start, start + len]` (radians, len in [0, 2 pi]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleInterval {
    pub start: f64,
    pub len: f64,
}

impl AngleInterval {
    /// Validated interval.
    pub fn new(start: f64, len: f64) -> Result<Self, CircleError> {
        if !(start.is_finite() && len.is_finite() && (0.0..=std::f64::consts::TAU).contains(&len)) {
            return Err(CircleError::BadInterval { start, len });
        }
        Ok(Self { start, len })
    }

    /// The whole circle.
    pub fn full() -> Self {
        Self {
            start: 0.0,
            len: std::f64::consts::TAU,
        }
    }

    /// True when `theta` lies in the interval, with an angular slack `tol`.
    pub fn contains(&self, theta: f64, tol: f64) -> bool {
        if self.len >= std::f64::consts::TAU - tol {
            return true;
        }
        let rel = (theta - self.start).rem_euclid(std::f64::consts::TAU);
        rel <= self.len + tol || rel >= std::f64::consts::TAU - tol
    }
}

/// One binormal segment: angles on both circles, the two feet and the length.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Binormal {
    pub angle_a: f64,
    pub angle_b: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    pub distance: f64,
}

/// How the binormals or the closest pairs of two circles are arranged.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Multiplicity {
    /// Finitely many (the usual case); for a minimum: how many distinct closest pairs.
    #[default]
    Finite,
    /// A continuum: every point of circle A pairs with a partner (coaxial circles,
    /// Villarceau circles, concentric coplanar circles).
    ContinuumOnBoth,
    /// A continuum along circle B from one fixed point of A (that point is on B's axis:
    /// meridian circle, a point of A at B's centre with tangent along B's axis).
    ContinuumOnB,
    /// A continuum along circle A from one fixed point of B.
    ContinuumOnA,
}

/// All binormals of two circles (within the requested angle ranges).
#[derive(Debug, Clone, Copy, Default)]
pub struct Binormals {
    /// Isolated binormals (for a continuum: one representative of each family).
    pub items: crate::poly::FixedVec<Binormal, { binormal::MAX_BINORMALS }>,
    /// Whether a continuum of binormals exists (its representatives are in `items`).
    pub multiplicity: Multiplicity,
}

/// The minimum distance of two circles with one closest pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MinDistance {
    pub distance: f64,
    pub angle_a: f64,
    pub angle_b: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Number of distinct closest pairs found (ties within [`TIE_REL_TOL`]) when finite.
    pub closest_pairs: usize,
    /// A continuum of closest pairs, if any.
    pub multiplicity: Multiplicity,
}

#[cfg(test)]
mod tests;
