//! Point-in-solid tests: a point is inside a solid of revolution when its meridian
//! coordinates `(rho, z)` lie inside the profile region, which is the area inside a closed
//! profile loop, or for an open-on-axis profile the area enclosed by the chain and the axis
//! segment joining its ends (solids, not surfaces: a query between overlapping or nested solids answers 0).
//!
//! The test is a winding number of the approximating chain (arcs and segments), with the
//! closing axis segment for open profiles. Its `margin` is the distance of the point from
//! the chain; when `margin > eps` of the tree the classification holds for the original
//! profile too (the original curve stays within eps of the chain, so it cannot pass
//! between the point and the chain).

use super::descent::{self, DiskVisitor, Visit};
use super::patch::ProfileArc;
use super::tree::QueryTree;
use crate::nearest::NearestPoint;
use crate::num::cross2;
use crate::profile::ProfileKind;
use crate::tolerances::AXIS_NUDGE;
use nalgebra::{Point2, Point3};
use std::f64::consts::TAU;
use std::ops::Range;

/// Sweep (radians) above which an arc's bulge side is read from its midpoint (sagitta at
/// least `r (1 - cos 0.5) ~ 0.12 r`, far above rounding); below it, from its centre.
const MID_SIDE_SWEEP: f64 = 1.0;

/// Classification of a point against a profile region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Inside {
    pub inside: bool,
    /// Distance from the point to the approximating boundary chain.
    pub margin: f64,
}

/// Signed angle swept by `piece` as seen from `x`.
fn swept_angle(piece: &ProfileArc, x: Point2<f64>) -> f64 {
    let (a, b) = (piece.start() - x, piece.end() - x);
    let chord = cross2(a, b).atan2(a.dot(&b));
    match *piece {
        ProfileArc::Segment { .. } => chord,
        ProfileArc::Arc {
            center,
            radius,
            sweep,
            ..
        } => {
            // The loop "arc, then chord back" winds once around points of the circular
            // segment between them: inside the circle and on the arc's side of the chord.
            let inside_circle = (x - center).norm() < radius;
            let (s, e) = (piece.start(), piece.end());
            // Side of the chord the arc bulges to: the midpoint's side for arcs that turn
            // enough for the midpoint to stand clear of the chord; for flatter arcs (whose
            // sagitta may be below rounding) the side opposite the centre, which is then far
            // from the chord (a minor arc bulges away from its centre).
            let side_mid = if sweep.abs() >= MID_SIDE_SWEEP {
                cross2(e - s, piece.point_at(0.5) - s)
            } else {
                -cross2(e - s, center - s)
            };
            let side_x = cross2(e - s, x - s);
            let in_segment = inside_circle && side_mid * side_x > 0.0;
            let full = sweep.abs() >= TAU - 1e-12;
            if full {
                return if inside_circle {
                    sweep.signum() * TAU
                } else {
                    0.0
                };
            }
            if in_segment {
                chord + sweep.signum() * TAU
            } else {
                chord
            }
        }
    }
}

/// Classifies the meridian point `m` (rho >= 0) against the tree's profile region.
///
/// With the tree's chain index ([`QueryTree::node_ends`]) whole subtrees are skipped: the
/// pieces under a node and the chord between their first and last points form a closed
/// loop inside the node's disk, so for a point outside the disk the pieces sweep exactly the
/// chord's angle; and their distance to the point is at least its distance to the disk.
/// Without the index every piece is visited.
pub fn point_in_profile(tree: &QueryTree, m: Point2<f64>) -> Inside {
    point_in_profile_capped(tree, m, f64::INFINITY)
}

/// [`point_in_profile`] with the margin capped at `cap`: the classification is the same,
/// the margin is `min(distance to the chain, cap)`.
///
/// The descent starts as if a piece `cap` away had already been seen, so a subtree whose
/// disk lies `cap` or more from the point (and does not hold it) contributes its chord's
/// angle without being opened. Callers that only compare the margin with a threshold below
/// `cap` get the same answer as from the exact margin; the saving is largest for points far
/// from the profile or deep inside it, for which many pieces are about equally near and the
/// exact margin opens most of the tree (measured: ~24,000 instructions a call on the M_t
/// frame at eps 1e-6, `certify_overlap`'s samples; see `docs/performance.md`).
pub fn point_in_profile_capped(tree: &QueryTree, m: Point2<f64>, cap: f64) -> Inside {
    classify(tree, m, cap).0
}

/// [`point_in_profile`] with the point of the approximating chain nearest to `m` (at
/// distance `margin`): the classification, the margin and the foot of the margin come from
/// one descent. The foot gives the direction in which the margin grows fastest, which the
/// penetration depth's deepest-point search follows ([`mod@crate::query::penetration`]).
pub fn point_in_profile_nearest(tree: &QueryTree, m: Point2<f64>) -> (Inside, Point2<f64>) {
    classify(tree, m, f64::INFINITY)
}

/// Classification, capped margin and the nearest chain point seen (`m` itself when no
/// piece is nearer than `cap`).
fn classify(tree: &QueryTree, m: Point2<f64>, cap: f64) -> (Inside, Point2<f64>) {
    let mut total = 0.0;
    let mut margin = cap;
    let mut nearest = m;
    // A point on the axis is classified like its neighbours at small rho > 0 (the axis
    // closure of an open profile is interior to the solid, not boundary).
    let w = Point2::new(m.x.max(AXIS_NUDGE * (1.0 + m.coords.norm())), m.y);
    if tree.node_ends.is_empty() {
        for p in &tree.chain {
            total += swept_angle(p, w);
            let (d, q) = p.nearest(m);
            if d < margin {
                (margin, nearest) = (d, q);
            }
        }
    } else {
        let mut winding = Winding {
            w,
            m,
            total,
            margin,
            nearest,
        };
        descent::descend(tree, &mut winding);
        (total, margin, nearest) = (winding.total, winding.margin, winding.nearest);
    }
    if tree.kind == ProfileKind::OpenOnAxis {
        if let (Some(first), Some(last)) = (tree.chain.first(), tree.chain.last()) {
            let closing = ProfileArc::Segment {
                start: last.end(),
                end: first.start(),
            };
            total += swept_angle(&closing, w);
        }
    }
    let inside = Inside {
        inside: (total / TAU).round() != 0.0,
        margin,
    };
    (inside, nearest)
}

/// The winding angle of the chain about `w` and the smallest distance from `m` to it, with
/// where, summed and kept over a descent (see [`point_in_profile`]).
struct Winding {
    w: Point2<f64>,
    m: Point2<f64>,
    total: f64,
    margin: f64,
    nearest: Point2<f64>,
}

impl DiskVisitor for Winding {
    /// A subtree whose disk holds neither `w` nor a point nearer to `m` than the margin adds
    /// its chord's angle (the pieces under it run from the node's first end to its last).
    fn visit_node(&mut self, tree: &QueryTree, id: u32) -> Visit {
        let Some([s, e]) = tree.node_ends[id as usize] else {
            return Visit::Skip;
        };
        let n = &tree.nodes[id as usize];
        let (c, r) = (n.bound.center, n.bound.radius);
        if (self.w - c).norm() > r && (self.m - c).norm() - r >= self.margin {
            let (a, b) = (s - self.w, e - self.w);
            self.total += cross2(a, b).atan2(a.dot(&b));
            return Visit::Skip;
        }
        Visit::Open
    }

    fn visit_leaf(&mut self, tree: &QueryTree, pieces: Range<usize>) {
        for p in &tree.chain[pieces] {
            self.total += swept_angle(p, self.w);
            let (d, q) = p.nearest(self.m);
            if d < self.margin {
                (self.margin, self.nearest) = (d, q);
            }
        }
    }

    /// Nearer child first: its margin prunes more of the other.
    fn order(&self, tree: &QueryTree, id: u32) -> [u32; 2] {
        tree.children_nearer_first(id, self.m)
    }
}

/// Classifies a point given in the solid's local frame.
pub fn point_in_solid(tree: &QueryTree, x: &Point3<f64>) -> Inside {
    point_in_profile(tree, Point2::new(x.x.hypot(x.y), x.z))
}

/// [`point_in_solid`] with the margin capped at `cap` ([`point_in_profile_capped`]).
pub fn point_in_solid_capped(tree: &QueryTree, x: &Point3<f64>, cap: f64) -> Inside {
    point_in_profile_capped(tree, Point2::new(x.x.hypot(x.y), x.z), cap)
}

/// Signed depth of `x` (the solid's frame): the margin inside, minus it outside, capped at
/// `cap` on both sides ([`point_in_solid_capped`]), so a lower bound of the depth inside and
/// an upper bound outside.
pub fn signed_depth_capped(tree: &QueryTree, x: &Point3<f64>, cap: f64) -> f64 {
    let c = point_in_solid_capped(tree, x, cap);
    if c.inside {
        c.margin
    } else {
        -c.margin
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn sphere_and_ring_regions() {
        // Sphere of radius 1: half circle from the south pole to the north pole (open).
        let sphere = QueryTree::from_exact_pieces(
            &[ProfileArc::Arc {
                center: Point2::new(0.0, 0.0),
                radius: 1.0,
                phi_start: -PI / 2.0,
                sweep: PI,
            }],
            ProfileKind::OpenOnAxis,
            0.3,
            0.3,
        );
        for (m, inside) in [
            ((0.5, 0.5), true),
            ((0.0, 0.9), true),
            ((0.9, 0.9), false),
            ((2.0, 0.0), false),
            ((0.1, -0.99), true),
        ] {
            let r = point_in_profile(&sphere, Point2::new(m.0, m.1));
            assert_eq!(r.inside, inside, "{m:?}");
            let truth = (m.0 * m.0 + m.1 * m.1).sqrt();
            assert!((r.margin - (truth - 1.0).abs()).abs() < 1e-12);
        }
        // Ring: full circle of radius 0.3 around (1, 0), clockwise.
        let ring = QueryTree::from_exact_pieces(
            &[ProfileArc::Arc {
                center: Point2::new(1.0, 0.0),
                radius: 0.3,
                phi_start: 0.0,
                sweep: -2.0 * PI,
            }],
            ProfileKind::Closed,
            0.5,
            0.5,
        );
        assert!(point_in_profile(&ring, Point2::new(1.1, 0.1)).inside);
        assert!(!point_in_profile_capped(&ring, Point2::new(0.5, 0.0), 1e-3).inside);
        assert!(!point_in_profile(&ring, Point2::new(0.5, 0.0)).inside);
        assert!(!point_in_profile(&ring, Point2::new(1.0, 0.5)).inside);
    }

    /// The capped descent against the flat loop over every piece (the tree without its
    /// chain index): same classification, margin `min(exact, cap)`.
    #[test]
    fn capped_margin_matches_the_flat_loop() {
        use crate::test_rng::SplitMix64;
        let profile = crate::models::model("pawn_ff").unwrap();
        let bt = crate::biarc::BiarcTree::build(&profile, 1e-4).unwrap();
        let tree = QueryTree::from_biarc_tree(&bt, profile.kind());
        assert!(!tree.node_ends.is_empty());
        let mut flat = tree.clone();
        flat.node_ends.clear();
        let root = tree.nodes[tree.root as usize].bound;
        let mut rng = SplitMix64(91);
        for _ in 0..2000 {
            let m = Point2::new(
                rng.range(0.0, root.center.x + 1.5 * root.radius),
                rng.range(
                    root.center.y - 1.5 * root.radius,
                    root.center.y + 1.5 * root.radius,
                ),
            );
            let cap = 10f64.powf(rng.range(-6.0, 0.0));
            let (got, want) = (
                point_in_profile_capped(&tree, m, cap),
                point_in_profile(&flat, m),
            );
            assert_eq!(got.inside, want.inside, "{m:?}");
            assert_eq!(got.margin, want.margin.min(cap), "{m:?} cap {cap:e}");
        }
    }
}
