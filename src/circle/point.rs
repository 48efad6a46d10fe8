//! Distance from a point to a circle: `d^2 = h^2 + (rho - r)^2` with h the height above the
//! plane and rho the distance to the axis (paper section 3: every normal of the circle meets
//! its axis).

use super::{Circle3, TIE_REL_TOL};
use nalgebra::Point3;

/// Result of [`point_circle_distance`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PointCircleDistance {
    pub distance: f64,
    /// A closest point on the circle.
    pub closest: Point3<f64>,
    /// Its angle on the circle.
    pub angle: f64,
    /// The point is on the circle's axis (within [`TIE_REL_TOL`] of the scale): every point
    /// of the circle is equally close and `closest` is only a representative.
    pub on_axis: bool,
}

/// Distance from `p` to `circle`, with a closest point and an on-axis flag.
pub fn point_circle_distance(p: &Point3<f64>, circle: &Circle3) -> PointCircleDistance {
    let d = p - circle.center;
    let u = circle.u_axis.into_inner();
    let v = circle.v_axis();
    let (x, y, h) = (d.dot(&u), d.dot(&v), d.dot(&circle.normal));
    let rho = x.hypot(y);
    let r = circle.radius;
    let scale = d.norm().max(r);
    let on_axis = rho <= TIE_REL_TOL * scale;
    let angle = if rho == 0.0 { 0.0 } else { y.atan2(x) };
    let distance = h.hypot(rho - r);
    PointCircleDistance {
        distance,
        closest: circle.point_at(angle),
        angle,
        on_axis: on_axis && r > 0.0,
    }
}
