//! The deep interior of a solid: meridian points with a large clearance from the
//! approximating chain, and the ball or solid torus they span, inscribed in the true solid.
//! Computed once per tree, on first use ([`QueryTree::deep_interior`]).
//!
//! **Certification.** A meridian point `m` inside the approximating region with clearance
//! `c` from the approximating chain has the disk of radius `c` about it inside that region;
//! the true boundary lies within the tree's `eps` of the chain, so the disk of radius
//! `c - eps` lies in the true profile region. Revolved, the disk about `m = (rho, z)` is a
//! solid torus about the circle of radius `rho` at height `z` when `c <= rho`; when `c > rho`
//! it holds the ball about the axis point `(0, z)` of radius `sqrt(c^2 - rho^2)` (a meridian
//! point `(r, z')` of that ball has `(r - rho)^2 + (z' - z)^2 <= r^2 + (z' - z)^2 + rho^2 <=
//! c^2`, since `r, rho >= 0`). Either is an [`OffsetSolid`] whose `error` is the tree's eps:
//! the true solid contains its core's offset by `radius - error`, the only half of the
//! offset contract an inscribed solid keeps (it does not enclose the solid).

use super::containment::point_in_profile_capped;
use super::deep_interior::DeepInterior;
use super::offset_solid::{Core, OffsetSolid};
use super::QueryTree;
use nalgebra::Point2;

/// Interior points probed per axis of the profile's bounding box (a 12 x 12 grid).
const GRID: usize = 12;

/// Interior points with the largest clearance kept.
const KEPT: usize = 4;

/// Cap of the clearances the grid ranks, as a fraction of the root disk's radius: grid
/// points deeper than this are equally good (well inside the solid, far above any eps), and
/// their exact clearance would open most of the tree (every piece is about equally far from
/// a central point).
const CAP_FRACTION: f64 = 0.25;

impl QueryTree {
    /// Interior points of the solid with a large clearance, and the ball or solid torus
    /// they span (module doc), computed on first use (a 12 x 12 grid of point-in-profile
    /// tests) and kept in the tree.
    pub fn deep_interior(&self) -> &DeepInterior {
        self.deep_cache().get_or_init(|| probe(self))
    }
}

/// Probes `tree`'s profile region on a grid over its root disk's bounding box.
fn probe(tree: &QueryTree) -> DeepInterior {
    let points = deep_meridian_points(tree);
    let inscribed = points
        .first()
        .and_then(|&(m, c)| inscribed_offset(m, c, tree.eps));
    DeepInterior { points, inscribed }
}

fn deep_meridian_points(tree: &QueryTree) -> Vec<(Point2<f64>, f64)> {
    let Some(root) = tree.nodes.get(tree.root as usize) else {
        return Vec::new();
    };
    let (c, r) = (root.bound.center, root.bound.radius);
    let lo = Point2::new((c.x - r).max(0.0), c.y - r);
    let hi = Point2::new(c.x + r, c.y + r);
    let cap = CAP_FRACTION * r;
    let mut found: Vec<(Point2<f64>, f64)> = Vec::new();
    for i in 0..GRID {
        for j in 0..GRID {
            let fx = (i as f64 + 0.5) / GRID as f64;
            let fy = (j as f64 + 0.5) / GRID as f64;
            let m = Point2::new(lo.x + fx * (hi.x - lo.x), lo.y + fy * (hi.y - lo.y));
            let inside = point_in_profile_capped(tree, m, cap);
            if inside.inside {
                found.push((m, inside.margin));
            }
        }
    }
    let centre = Point2::new(c.x, c.y);
    found.sort_by(|x, y| {
        y.1.total_cmp(&x.1)
            .then((x.0 - centre).norm().total_cmp(&(y.0 - centre).norm()))
    });
    found.truncate(KEPT);
    found
}

/// The solid torus or ball spanned by the meridian disk of radius `clearance` about `m`
/// (module doc), `None` when nothing of it is certainly inside the true solid.
fn inscribed_offset(m: Point2<f64>, clearance: f64, eps: f64) -> Option<OffsetSolid> {
    let (core, radius) = if clearance > m.x {
        (
            Core::Point { z: m.y },
            (clearance * clearance - m.x * m.x).sqrt(),
        )
    } else {
        (Core::Circle { rho: m.x, z: m.y }, clearance)
    };
    (radius > eps && radius.is_finite()).then_some(OffsetSolid {
        core,
        radius,
        error: eps,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::containment::point_in_profile;
    use crate::models::model;
    use crate::solid::Solid;
    use std::sync::Arc;

    /// Every model's inscribed solid lies inside it: meridian points of the inscribed disk
    /// or ball, shrunk by the error, classify inside with the exact containment test.
    #[test]
    fn inscribed_solids_lie_inside() {
        let mut seen = 0;
        for name in [
            "pawn",
            "cup",
            "bottle",
            "ring",
            "sphere",
            "table",
            "morph@0.3",
        ] {
            let s = Solid::from_profile(Arc::new(model(name).unwrap()), 1e-3).unwrap();
            let deep = probe(&s.tree);
            let Some(o) = deep.inscribed else { continue };
            seen += 1;
            let r = o.radius - o.error;
            for k in 0..64 {
                let phi = k as f64 * std::f64::consts::TAU / 64.0;
                for f in [0.25, 0.7, 1.0] {
                    let (dr, dz) = (f * r * phi.cos(), f * r * phi.sin());
                    let m = match o.core {
                        Core::Point { z } => Point2::new(dr.abs(), z + dz),
                        Core::Circle { rho, z } => Point2::new(rho + dr, z + dz),
                        Core::Segment { .. } => unreachable!("inscribed solids are balls or tori"),
                    };
                    let c = point_in_profile(&s.tree, m);
                    assert!(c.inside, "{name}: {m:?} of {o:?} outside");
                }
            }
        }
        assert!(seen >= 5, "{seen}");
    }
}
