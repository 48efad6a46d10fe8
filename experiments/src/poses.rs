//! Seeded poses of solid B near solid A at a chosen gap, for timing queries near contact
//! (the regime where a distance query does real work).

use crate::SplitMix;
use nalgebra::{Isometry3, Translation3, Vector3};
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;

/// Bisection steps when sliding B towards A to reach the requested gap: the slide range
/// halves each step, so 60 steps reach double precision on any range below 1e15.
const PLACEMENT_STEPS: usize = 60;

/// Relative accuracy at which a placed gap is accepted.
const GAP_ACCEPT_REL: f64 = 0.05;

/// A pose of `b` (relative to `a`, which sits at the identity) with a random rotation and a
/// random approach direction, slid along that direction until the certified distance is
/// within [`GAP_ACCEPT_REL`] of `gap` (the query's own value is used to place it; timing
/// does not depend on how exactly the gap is hit). `centres` are the mid-height axis points
/// `z` of both solids; `reach` bounds the sum of both solids' radii about them.
pub fn pose_at_gap(
    a: &Solid,
    b: &Solid,
    centres: (f64, f64),
    reach: f64,
    gap: f64,
    rng: &mut SplitMix,
) -> Option<Isometry3<f64>> {
    let rot = rng.rotation();
    let dir = rng.unit_vector();
    let at = |s: f64| {
        let t =
            Vector3::new(0.0, 0.0, centres.0) + dir * s - rot * Vector3::new(0.0, 0.0, centres.1);
        Isometry3::from_parts(Translation3::from(t), rot)
    };
    let opts = QueryOptions::default();
    let gap_of = |s: f64| {
        let d = distance(a, &b.with_pose(at(s)), &opts);
        if d.overlap {
            -1.0
        } else {
            d.value
        }
    };
    // Distance is 0 (or overlap) at s = 0 only if the axis points overlap; search from the
    // far side, where the solids are certainly apart.
    let (mut lo, mut hi) = (0.0, reach + 2.0 * gap + 1.0);
    if gap_of(hi) < gap {
        return None;
    }
    for _ in 0..PLACEMENT_STEPS {
        let mid = 0.5 * (lo + hi);
        let g = gap_of(mid);
        if (g - gap).abs() <= GAP_ACCEPT_REL * gap {
            return Some(at(mid));
        }
        if g < gap {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    None
}

/// Log-uniform gap in `[lo, hi]`.
pub fn log_uniform(rng: &mut SplitMix, lo: f64, hi: f64) -> f64 {
    (lo.ln() + (hi.ln() - lo.ln()) * rng.next_f64()).exp()
}
