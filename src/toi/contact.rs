//! A cheap certificate of contact at a time `t`: points certified inside the true solids,
//! found from the witnesses of an earlier query and carried along the motions, instead of
//! a distance query at tolerance 0.
//!
//! **The argument** (the overlap certificate of `query/front/overlap.rs`, with the
//! motion's rounding added). Let `e_X` be tree X's bound (X's true boundary lies within
//! `e_X` of its approximating boundary, both ways) and `margin_X(y)` the distance of a point
//! `y` of X's frame from X's approximating chain, revolved ([`point_in_solid_capped`]: the
//! winding number of the chain in the meridian plane; the distance to a surface of revolution
//! is the distance in the point's meridian half-plane). If `y` is inside X's approximating
//! region with `margin_X(y) > e_X`, the ball of radius `margin_X(y) - e_X` about `y` is inside
//! true X.
//!
//! The world point `x` is mapped to X's frame by the computed pose `pose_at(t)^-1`. Two
//! roundings separate the computed local point from the local point under the *exact*
//! motion: the motion's ([`MOTION_ROUNDING_REL`] of `1 + |p(t)| + r`, the same slack
//! [`super::advance`] subtracts from lower bounds) and applying the pose (the query's rounding
//! slack, [`query_slack`]). With `s` their sum, `margin_X(y) > e_X + s` puts `x` inside true X
//! at the exact pose. Then:
//!
//! * `D = 0`: one point `x` inside both true solids: they overlap, distance 0. Or a point `y`
//!   within `e_B` of B's true boundary (a point of B's approximating surface, as the query's
//!   witnesses are, carried rigidly with B) inside A with `margin_A(y) > e_A + e_B + 2 s`:
//!   the ball of radius `e_B` about it holds a point of B's true boundary and lies inside
//!   true A, so the solids overlap (the first certificate of
//!   `query/front/overlap.rs`; the same with A and B swapped).
//! * `D > 0`: `x_a` inside true A, `x_b` inside true B: `d(A, B) <= |x_a - x_b|`, so
//!   `|x_a - x_b| + s <= D` certifies `d <= D` (`s` covers the rounding of the difference,
//!   far below the pose slack).
//!
//! The winding number's rounding only matters within a few ulps of the chain; every margin
//! compared here is above `e_X`, far from it.
//!
//! **Where the points come from.** A query at `t0` near contact gives witness points `w_a` on
//! A's approximating surface and `w_b` on B's, `n = w_b - w_a`. They are fixed in their
//! solids' frames and carried to `t` by the motions (`P_a(t)`, `P_b(t)`); the candidates are
//! points of the segment `P_a P_b` (inside both once the material points have crossed) and,
//! for `D > 0`, `P_a` pushed into A and `P_b` into B along the carried `n`. A failed
//! candidate certifies nothing (the search then falls back to distance queries).

use super::motion::{Motion, MOTION_ROUNDING_REL};
use crate::bvh::containment::point_in_solid_capped;
use crate::query::{query_slack, Distance};
use crate::solid::Solid;
use nalgebra::{Isometry3, Point3, Vector3};

/// Margins are computed up to this many times the threshold they are compared with (any cap
/// above the threshold gives the same comparison; see [`point_in_solid_capped`]).
const CAP_OVER_THRESHOLD: f64 = 2.0;

/// Fractions of the segment `P_a -> P_b` tried as a point inside both solids, besides the
/// one that balances the two thresholds ([`ContactTest::certify`]).
const SEGMENT_FRACTIONS: [f64; 3] = [0.5, 0.25, 0.75];

/// How far (in thresholds) the `D > 0` candidates are pushed into their solids.
const PUSH_OVER_THRESHOLD: f64 = 2.0;

/// The witness pair of a query, fixed in the solids' frames.
#[derive(Debug, Clone, Copy)]
pub struct Witness {
    /// `w_a` in A's frame, `w_b` in B's frame.
    local_a: Point3<f64>,
    local_b: Point3<f64>,
    /// `n = w_b - w_a` (unnormalised) in A's and in B's frame.
    normal_in_a: Vector3<f64>,
    normal_in_b: Vector3<f64>,
}

impl Witness {
    /// The witnesses of `d`, a query at the poses `pa`, `pb` (world frame).
    pub fn new(d: &Distance, pa: &Isometry3<f64>, pb: &Isometry3<f64>) -> Witness {
        let n = d.point_b - d.point_a;
        Witness {
            local_a: pa.inverse_transform_point(&d.point_a),
            local_b: pb.inverse_transform_point(&d.point_b),
            normal_in_a: pa.inverse_transform_vector(&n),
            normal_in_b: pb.inverse_transform_vector(&n),
        }
    }
}

/// The two solids, their motions and the contact distance of a search.
pub struct ContactTest<'a> {
    pub a: &'a Solid,
    pub b: &'a Solid,
    pub ma: &'a Motion,
    pub mb: &'a Motion,
    /// Bounds on the distance of any point of A (B) from its frame origin.
    pub ra: f64,
    pub rb: f64,
    pub contact_distance: f64,
}

/// A certified contact: the world points (equal for `D = 0`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CertifiedContact {
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Certified upper bound of the distance (`0` for a point inside both solids).
    pub upper: f64,
}

impl ContactTest<'_> {
    /// The rounding slack `s` of the module doc at the computed poses `pa`, `pb`.
    fn slack(&self, pa: &Isometry3<f64>, pb: &Isometry3<f64>) -> f64 {
        let motion = MOTION_ROUNDING_REL
            * (2.0
                + pa.translation.vector.norm()
                + pb.translation.vector.norm()
                + self.ra
                + self.rb);
        motion + query_slack(&self.a.tree, &self.b.tree, &(pa.inverse() * pb))
    }

    /// Whether the world point `x` is inside true X (posed at `pose`) by the module doc's
    /// argument.
    fn inside(solid: &Solid, pose: &Isometry3<f64>, x: &Point3<f64>, slack: f64) -> bool {
        Self::deep(solid, pose, x, solid.tree.eps + slack)
    }

    /// Whether the world point `x` is inside X's approximating region (X posed at `pose`)
    /// with margin above `threshold`.
    fn deep(solid: &Solid, pose: &Isometry3<f64>, x: &Point3<f64>, threshold: f64) -> bool {
        let y = pose.inverse_transform_point(x);
        let c = point_in_solid_capped(&solid.tree, &y, CAP_OVER_THRESHOLD * threshold);
        c.inside && c.margin > threshold
    }

    /// A certified contact at time `t` from the carried witnesses, or `None`.
    pub fn certify(&self, t: f64, w: &Witness) -> Option<CertifiedContact> {
        let pa = self.ma.pose_at(t);
        let pb = self.mb.pose_at(t);
        let slack = self.slack(&pa, &pb);
        let (xa, xb) = (pa * w.local_a, pb * w.local_b);
        let (ea, eb) = (self.a.tree.eps, self.b.tree.eps);
        // Surface points of one solid deep inside the other (once the witnesses crossed).
        let both = ea + eb + 2.0 * slack;
        for (x, inside_a) in [(xb, true), (xa, false)] {
            let deep = if inside_a {
                Self::deep(self.a, &pa, &x, both)
            } else {
                Self::deep(self.b, &pb, &x, both)
            };
            if deep {
                return Some(CertifiedContact {
                    point_a: x,
                    point_b: x,
                    upper: 0.0,
                });
            }
        }
        // The point of the segment whose distances to the two witnesses exceed each solid's
        // threshold by the same share, then fixed fractions.
        let balanced = (ea + slack) / (ea + eb + 2.0 * slack);
        for f in std::iter::once(balanced).chain(SEGMENT_FRACTIONS) {
            let x = xa + (xb - xa) * f;
            if Self::inside(self.a, &pa, &x, slack) && Self::inside(self.b, &pb, &x, slack) {
                return Some(CertifiedContact {
                    point_a: x,
                    point_b: x,
                    upper: 0.0,
                });
            }
        }
        let d = self.contact_distance;
        if d <= 0.0 {
            return None;
        }
        let push = |solid: &Solid, n: Vector3<f64>| {
            n.try_normalize(0.0)
                .map(|u| u * (PUSH_OVER_THRESHOLD * (solid.tree.eps + slack)))
        };
        let (na, nb) = (
            push(self.a, pa * w.normal_in_a)?,
            push(self.b, pb * w.normal_in_b)?,
        );
        let (ya, yb) = (xa - na, xb + nb);
        let upper = (yb - ya).norm() + slack;
        if upper <= d
            && Self::inside(self.a, &pa, &ya, slack)
            && Self::inside(self.b, &pb, &yb, slack)
        {
            return Some(CertifiedContact {
                point_a: ya,
                point_b: yb,
                upper,
            });
        }
        None
    }
}
