//! Why a certified interval is wider than the caller asked, when it is.
//!
//! A query stops when `upper - lower` is within the requested width ([`Tolerance`]), or at
//! the narrowest interval it can certify, whichever is wider. Three things bound that
//! narrowest interval: the anytime budget; the rounding slack added on both sides
//! ([`query_slack`], which grows with the configuration's scale: solids `1e8` across keep
//! intervals of ~`1e-3`); and the leaves' own accuracy (a leaf pair's distance is known to
//! within `2 (e_a + e_b)`, `e` the leaves' Hausdorff bounds, which may exceed the requested
//! `eps_a + eps_b` when the closest leaves are near their bound). [`width_limit`] says which
//! one held an answer back, so that a caller never meets a wide interval unexplained.

use super::distance::{query_slack, Distance, QueryOptions};
use crate::solid::Solid;

/// Why `upper - lower` is what it is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WidthLimit {
    /// Within the requested width.
    Met,
    /// The anytime budget ran out first.
    Budget,
    /// The rounding slack at this configuration's scale alone is wider than requested.
    Rounding,
    /// The closest leaves' own accuracy: their certified interval is the narrowest the trees
    /// allow (build the trees with a smaller eps for a narrower one).
    Leaves,
}

impl WidthLimit {
    /// A short name (`met`, `budget`, `rounding`, `leaves`) for reports and JSON.
    pub fn name(self) -> &'static str {
        match self {
            WidthLimit::Met => "met",
            WidthLimit::Budget => "budget",
            WidthLimit::Rounding => "rounding",
            WidthLimit::Leaves => "leaves",
        }
    }
}

/// What limited the width of `d`, the answer of a query between `a` and `b` with `opts`.
pub fn width_limit(a: &Solid, b: &Solid, opts: &QueryOptions, d: &Distance) -> WidthLimit {
    let width = opts.tolerance.width(a.tree.target_eps, b.tree.target_eps);
    if d.upper - d.lower <= width {
        return WidthLimit::Met;
    }
    if d.stats.budget_exhausted {
        return WidthLimit::Budget;
    }
    // Without the slack on both sides, would the interval have met the width?
    let slack = query_slack(&a.tree, &b.tree, &a.relative_pose(b));
    if d.upper - d.lower - 2.0 * slack <= width {
        WidthLimit::Rounding
    } else {
        WidthLimit::Leaves
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use crate::profile::Profile;
    use nalgebra::{Isometry3, Point2};
    use std::sync::Arc;

    fn solid(p: Profile, eps: f64) -> Solid {
        Solid::from_profile(Arc::new(p), eps).unwrap()
    }

    #[test]
    fn a_default_query_meets_its_width() {
        let a = solid(model("pawn").unwrap(), 1e-4);
        let b = solid(model("cup").unwrap(), 1e-4).with_pose(Isometry3::translation(1.4, 0.0, 0.1));
        let opts = QueryOptions::default();
        let d = crate::query::distance(&a, &b, &opts);
        assert_eq!(width_limit(&a, &b, &opts, &d), WidthLimit::Met);
    }

    /// A disk 1e8 across and 1 thick next to a unit sphere: the rounding slack at that scale
    /// (~2e-3) is far above the requested 3e-4, and the answer says so.
    #[test]
    fn a_mixed_scale_pair_is_limited_by_rounding() {
        let (r, h) = (1e8, 1.0);
        let pts = [(0.0, 0.0), (r, 0.0), (r, h), (0.0, h)];
        let pieces = pts
            .windows(2)
            .map(|w| {
                crate::nurbs::NurbsCurve::line(
                    Point2::new(w[0].0, w[0].1),
                    Point2::new(w[1].0, w[1].1),
                )
                .unwrap()
            })
            .collect();
        let disk = solid(Profile::new("disk", pieces).unwrap(), 2e-4);
        let sphere =
            solid(model("sphere").unwrap(), 1e-4).with_pose(Isometry3::translation(0.0, 0.0, 1.5));
        let opts = QueryOptions::default();
        let d = crate::query::distance(&disk, &sphere, &opts);
        assert!(
            d.upper - d.lower
                > opts
                    .tolerance
                    .width(disk.tree.target_eps, sphere.tree.target_eps)
        );
        assert_eq!(width_limit(&disk, &sphere, &opts, &d), WidthLimit::Rounding);
    }
}
