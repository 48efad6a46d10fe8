//! The nearest point of a tree's planar chain to a meridian point, for the convex fast path
//! ([`crate::query::convex`]): its witnesses and its ball path ask it once or twice per
//! query, so each piece's angular range is kept as the unit directions of its ends
//! ([`MeridianPiece`], built once per tree) and tested with cross products, where
//! [`ProfileArc`'s nearest point](crate::nearest::NearestPoint) computes an `atan2` and the ends' `sin` and `cos` per arc.
//!
//! The answer is a point of the piece: a point of the arc's circle whose direction from
//! the centre passes the range test (rounding of the test moves the boundary by a few ulps
//! of the direction, so the foot is on the arc up to that), or an end point. Which of two
//! nearly equidistant pieces wins may differ from the scan of [`ProfileArc`'s nearest point](crate::nearest::NearestPoint)
//! by rounding; either is a point of the approximating surface.

use crate::bvh::{descent, ProfileArc, QueryTree};
use crate::nearest::NearestPoint;
use crate::num::cross2;
use nalgebra::{Point2, Vector2};

/// A piece of the chain with what its nearest point needs precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MeridianPiece {
    Segment {
        start: Point2<f64>,
        /// `end - start`.
        along: Vector2<f64>,
        /// `1 / |end - start|^2` (0 for a point).
        inv_len2: f64,
    },
    /// A circular arc running counter-clockwise from `from` to `to` (unit directions from
    /// the centre), whichever way the piece runs; `wide` when it turns more than a half turn.
    Arc {
        center: Point2<f64>,
        radius: f64,
        from: Vector2<f64>,
        to: Vector2<f64>,
        wide: bool,
        start: Point2<f64>,
        end: Point2<f64>,
    },
}

impl MeridianPiece {
    /// The piece of `arc`.
    pub fn of(arc: &ProfileArc) -> MeridianPiece {
        match *arc {
            ProfileArc::Segment { start, end } => {
                let along = end - start;
                let l2 = along.norm_squared();
                MeridianPiece::Segment {
                    start,
                    along,
                    inv_len2: if l2 > 0.0 { 1.0 / l2 } else { 0.0 },
                }
            }
            ProfileArc::Arc { center, radius, .. } => {
                let (lo, span) = arc.ascending_angles().expect("an arc");
                let dir = |phi: f64| Vector2::new(phi.cos(), phi.sin());
                MeridianPiece::Arc {
                    center,
                    radius,
                    from: dir(lo),
                    to: dir(lo + span),
                    wide: span > std::f64::consts::PI,
                    start: arc.start(),
                    end: arc.end(),
                }
            }
        }
    }
}

impl NearestPoint for MeridianPiece {
    /// Distance from `m` to the piece and the piece's point at that distance.
    #[inline]
    fn nearest(&self, m: Point2<f64>) -> (f64, Point2<f64>) {
        match *self {
            MeridianPiece::Segment {
                start,
                along,
                inv_len2,
            } => {
                let t = ((m - start).dot(&along) * inv_len2).clamp(0.0, 1.0);
                let p = start + along * t;
                ((m - p).norm(), p)
            }
            MeridianPiece::Arc {
                center,
                radius,
                from,
                to,
                wide,
                start,
                end,
            } => {
                let d = m - center;
                let n2 = d.norm_squared();
                let (after_from, before_to) = (cross2(from, d) >= 0.0, cross2(d, to) >= 0.0);
                let in_range = if wide {
                    after_from || before_to
                } else {
                    after_from && before_to
                };
                if n2 > 0.0 && in_range {
                    let n = n2.sqrt();
                    return ((n - radius).abs(), center + d * (radius / n));
                }
                let (da, db) = ((m - start).norm_squared(), (m - end).norm_squared());
                if da <= db {
                    (da.sqrt(), start)
                } else {
                    (db.sqrt(), end)
                }
            }
        }
    }
}

/// The pieces of `tree.patches`, in their order.
pub fn meridian_pieces(tree: &QueryTree) -> Vec<MeridianPiece> {
    tree.patches
        .iter()
        .map(|p| MeridianPiece::of(&p.arc))
        .collect()
}

/// The point of the tree's chain nearest to the meridian point `m` and its distance, from
/// the tree's [`meridian_pieces`] ([`crate::bvh::descent::nearest_chain_point`]).
pub fn nearest_chain_point(
    tree: &QueryTree,
    pieces: &[MeridianPiece],
    m: Point2<f64>,
) -> Option<(f64, Point2<f64>)> {
    descent::nearest_chain_point(tree, pieces, m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use crate::solid::Solid;
    use crate::test_rng::SplitMix64;
    use std::f64::consts::PI;
    use std::sync::Arc;

    /// Each piece's nearest point agrees with `ProfileArc`'s `nearest` (the `atan2`
    /// form), arcs of either orientation, narrow and wide, and segments.
    #[test]
    fn pieces_agree_with_the_angle_form() {
        let mut rng = SplitMix64(11);
        let arcs = [
            ProfileArc::Arc {
                center: Point2::new(0.3, -0.2),
                radius: 0.7,
                phi_start: 2.5,
                sweep: -1.1,
            },
            ProfileArc::Arc {
                center: Point2::new(0.0, 0.5),
                radius: 0.5,
                phi_start: -0.5 * PI,
                sweep: PI,
            },
            ProfileArc::Arc {
                center: Point2::new(1.0, 1.0),
                radius: 0.25,
                phi_start: 0.3,
                sweep: 4.5,
            },
            ProfileArc::Segment {
                start: Point2::new(0.1, 0.2),
                end: Point2::new(0.9, -0.4),
            },
        ];
        for arc in &arcs {
            let piece = MeridianPiece::of(arc);
            for _ in 0..2000 {
                let m = Point2::new(rng.next_f64() * 3.0 - 1.0, rng.next_f64() * 3.0 - 1.0);
                let (d, p) = piece.nearest(m);
                let (d0, _) = arc.nearest(m);
                assert!((d - d0).abs() <= 1e-12, "{arc:?} {m:?}: {d} vs {d0}");
                assert!(((m - p).norm() - d).abs() <= 1e-14, "{arc:?} {m:?}");
            }
        }
    }

    /// The descent finds the same distance as a scan of every piece.
    #[test]
    fn descent_agrees_with_a_scan() {
        let mut rng = SplitMix64(7);
        for (name, eps) in [("capsule", 1e-4), ("pawn", 1e-4), ("cone", 1e-3)] {
            let s = Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap();
            let pieces = meridian_pieces(&s.tree);
            for _ in 0..300 {
                let m = Point2::new(rng.next_f64() * 2.0, rng.next_f64() * 4.0 - 1.0);
                let (d, _) = nearest_chain_point(&s.tree, &pieces, m).unwrap();
                let scan = s
                    .tree
                    .patches
                    .iter()
                    .map(|p| p.arc.nearest(m).0)
                    .fold(f64::INFINITY, f64::min);
                assert!((d - scan).abs() <= 1e-12 * (1.0 + scan), "{name} {m:?}");
            }
        }
    }
}
