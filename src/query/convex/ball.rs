//! A ball against a convex solid of revolution: a planar question instead of GJK.
//!
//! The point of a surface of revolution nearest to a point `c` lies in `c`'s meridian
//! half-plane, at the point of the planar chain nearest to `c`'s meridian coordinates
//! `(rho, z)` ([`crate::bvh::convex::nearest`]: a descent of the tree's disks). For a ball
//! (a tree detected as the offset of a point, [`crate::bvh::offset_solid`]) of centre `c`
//! and radius `r` outside the other solid, that point `q` and the ball's surface point
//! towards it are the closest pair, at distance `|q - c| - r`.
//!
//! **Certificate.** Nothing above is trusted: the answer is checked as GJK's is
//! (`Bounds` in [`super`]). The lower bound is the hulls' separation along the unit direction
//! `d` from the ball's centre to `q`, from both solids' exact supports (as a GJK probe's:
//! `min over H_B of d . x - max over H_A of d . x`, any `d` gives one); the witnesses are
//! `q` lifted to its azimuth (on the other's approximating surface) and the nearest point of
//! the ball's approximating surface to `c + r d` (its own tree's chain); their distance is
//! the value. When the centre is inside the other solid, or the ball overlaps it, the value
//! exceeds the separation by more than the width and GJK takes over.

use super::witness::nearest_surface_point;
use super::{Answer, Bounds, Method};
use crate::bvh::offset_solid::Core;
use crate::bvh::QueryTree;
use nalgebra::{Isometry3, Point3, Vector3};

/// The answer when `ta` or `tb` is a ball and the planar pair fits (`Bounds` in [`super`]); `None`
/// otherwise (GJK runs). `support_a`, `support_b` are the hulls' supports in A's frame.
pub(super) fn ball_distance(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    bounds: &Bounds,
    support_a: impl Fn(&Vector3<f64>) -> Point3<f64>,
    support_b: impl Fn(&Vector3<f64>) -> Point3<f64>,
) -> Option<Answer> {
    let ball = |t: &QueryTree| match t.offset {
        Some(o) => match o.core {
            Core::Point { z } => Some((Point3::new(0.0, 0.0, z), o.radius)),
            Core::Segment { .. } | Core::Circle { .. } => None,
        },
        None => None,
    };
    // Witnesses (A's frame): the other solid's nearest surface point to the centre, and the
    // ball's surface point towards it.
    let (point_a, point_b) = if let Some((c, r)) = ball(ta) {
        let c_in_b = pos_ab.inverse_transform_point(&c);
        let q = pos_ab
            * nearest_surface_point(tb, &c_in_b, &pos_ab.inverse_transform_vector(&-c.coords));
        let d = (q - c).try_normalize(0.0)?;
        (nearest_surface_point(ta, &(c + d * r), &d), q)
    } else {
        let (c, r) = ball(tb)?;
        let c_in_a = pos_ab * c;
        let q = nearest_surface_point(ta, &c_in_a, &pos_ab.translation.vector);
        let d = (c_in_a - q).try_normalize(0.0)?;
        let on_ball = pos_ab.inverse_transform_point(&(c_in_a - d * r));
        let toward = pos_ab.inverse_transform_vector(&-d);
        (q, pos_ab * nearest_surface_point(tb, &on_ball, &toward))
    };
    // The separation of the hulls along the pair's direction (A towards B).
    let d = (point_b - point_a).try_normalize(0.0)?;
    let lower = d.dot(&(support_b(&-d) - support_a(&d)));
    bounds.finish(point_a, point_b, lower, f64::INFINITY, 0, Method::Ball)
}
