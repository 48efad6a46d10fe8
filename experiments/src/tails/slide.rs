//! The geometry of placement: model extents, the surfaces' distance, and sliding B along a
//! path until that distance is the drawn gap (scan, then bisection).

use super::{ACCEPT_REL, BISECTION_STEPS, PLACE_WIDTH_REL, SCAN_STEPS};
use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion};
use revdist::profile::Profile;
use revdist::query::bound::node_pair::BoundKind;
use revdist::query::search::{traverse, TraversalOptions};
use revdist::query::Budget;
use revdist::solid::Solid;

/// The quaternion of a half turn about x: B upside down.
pub(super) fn flip() -> UnitQuaternion<f64> {
    UnitQuaternion::from_quaternion(Quaternion::new(0.0, 1.0, 0.0, 0.0))
}

/// (min, max) of a profile's z, and its largest radius.
pub(super) fn extent(p: &Profile) -> (f64, f64, f64) {
    let b = p.bounding_box();
    (b.min.y, b.max.y, b.max.x)
}

/// Bounds of the distance between the boundary surfaces of `a` (identity) and `b` at
/// `pose`, to a width of `width` (not the solids' distance: nested solids have a positive
/// surface distance).
pub(super) fn surface_gap(a: &Solid, b: &Solid, pose: &Isometry3<f64>, width: f64) -> (f64, f64) {
    let opts = TraversalOptions {
        tolerance: width,
        lower_floor: f64::NEG_INFINITY,
        budget: Budget::default(),
        bound: BoundKind::default(),
    };
    let s = traverse(&a.tree, &b.tree, pose, &opts, None);
    if s.surfaces_meet {
        (0.0, 0.0)
    } else {
        (s.lower, s.upper)
    }
}

/// Slides B along `at(s)` from `s0` (where the surfaces are more than `gap` apart) towards
/// `s1` until their distance is `gap` within [`ACCEPT_REL`]: a scan for the first point
/// below the gap, then bisection. `None` when the scan finds none or the bisection misses.
pub(super) fn slide(
    a: &Solid,
    b: &Solid,
    at: impl Fn(f64) -> Isometry3<f64>,
    (s0, s1): (f64, f64),
    gap: f64,
) -> Option<Isometry3<f64>> {
    let width = PLACE_WIDTH_REL * gap;
    let g = |s: f64| {
        let (lo, hi) = surface_gap(a, b, &at(s), width);
        0.5 * (lo + hi)
    };
    let accept = |v: f64| (v - gap).abs() <= ACCEPT_REL * gap;
    if g(s0) < gap {
        return None;
    }
    let mut far = s0;
    let mut near = None;
    for k in 1..=SCAN_STEPS {
        let s = s0 + (s1 - s0) * k as f64 / SCAN_STEPS as f64;
        let v = g(s);
        if accept(v) {
            return Some(at(s));
        }
        if v < gap {
            near = Some(s);
            break;
        }
        far = s;
    }
    let mut near = near?;
    for _ in 0..BISECTION_STEPS {
        let mid = 0.5 * (far + near);
        let v = g(mid);
        if accept(v) {
            return Some(at(mid));
        }
        if v < gap {
            near = mid;
        } else {
            far = mid;
        }
    }
    None
}

/// Coaxial placement: B (rotated by `rot`) on A's axis, translated by `s` along z.
pub(super) fn on_axis(rot: UnitQuaternion<f64>) -> impl Fn(f64) -> Isometry3<f64> {
    move |s| Isometry3::from_parts(Translation3::new(0.0, 0.0, s), rot)
}

/// B's z range once rotated by `rot` (identity or [`flip`]).
pub(super) fn z_range(p: &Profile, flipped: bool) -> (f64, f64) {
    let (lo, hi, _) = extent(p);
    if flipped {
        (-hi, -lo)
    } else {
        (lo, hi)
    }
}
