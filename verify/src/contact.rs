//! Contact poses: B placed so that a chosen point of its surface meets a chosen point of
//! A's at a chosen gap along A's normal, B's outward normal there turned against A's, and B
//! spun about that normal. The corner contacts of `verify queries` and the touching piece
//! pairs of `verify bounds` both place B this way.

use nalgebra::{Isometry3, Translation3, Unit, UnitQuaternion, Vector3};
use std::f64::consts::PI;

/// A rotation taking `from` to `to` (unit vectors), about some perpendicular axis when
/// they are opposite.
pub fn rotation_between(from: &Vector3<f64>, to: &Vector3<f64>) -> UnitQuaternion<f64> {
    UnitQuaternion::rotation_between(from, to).unwrap_or_else(|| {
        let axis = from.cross(&Vector3::x());
        let axis = if axis.norm() > 0.1 {
            axis
        } else {
            from.cross(&Vector3::y())
        };
        UnitQuaternion::from_axis_angle(&Unit::new_normalize(axis), PI)
    })
}

/// The pose of B (in A's frame) that puts B's point `pb` (outward unit normal `nb`, B's
/// frame) at `pa + gap na` (A's point and outward unit normal), `nb` turned to `-na`, then
/// turned by `spin` radians about `na`.
pub fn contact_pose(
    (pa, na): (Vector3<f64>, Vector3<f64>),
    (pb, nb): (Vector3<f64>, Vector3<f64>),
    gap: f64,
    spin: f64,
) -> Isometry3<f64> {
    let twist = UnitQuaternion::from_axis_angle(&Unit::new_normalize(na), spin);
    let rot = twist * rotation_between(&nb, &(-na));
    let t = pa + na * gap - rot * pb;
    Isometry3::from_parts(Translation3::from(t), rot)
}
