//! Whether a profile is a simple curve: no two parts of the chain (closed, for an open
//! profile, by the axis segment between its ends) cross, touch or fold back onto each other.
//! Revolving a self-intersecting chain does not bound a solid.
//!
//! The test is certified in both directions up to [`SELF_TOUCH_REL`] of the profile's size:
//! every part of a piece is bracketed by the convex hull of its Bezier control points
//! (rational spans with positive weights keep that property), so
//! * two parts whose control boxes are farther apart than the tolerance cannot meet;
//! * two neighbouring parts that share a joint `J` meet only at `J` when the directions from
//!   `J` to their control points fill two disjoint angular sectors (each part lies in its
//!   sector's cone with apex `J`);
//! * one span cannot cross itself when the edges of its control polygon all point into one
//!   open half-plane: its derivative is a positive combination of those edges (Floater's
//!   derivative formula for rational Bezier curves), so the span is monotone along that
//!   half-plane's normal.
//!
//! Parts that none of these settles are halved (de Casteljau on the homogeneous points) until
//! they are smaller than the tolerance; two such parts that still touch are reported, with
//! the pieces they belong to and the point.

use crate::nurbs::{halve_homogeneous, Aabb2, NurbsCurve};
use nalgebra::{Point2, Vector2};

/// Two parts of a profile that come closer than this fraction of its size (bounding-box
/// diagonal) count as meeting: the same tolerance at which two piece ends count as joined
/// ([`super::JOIN_TOLERANCE_REL`]).
pub const SELF_TOUCH_REL: f64 = super::JOIN_TOLERANCE_REL;

/// Smallest angle (radians) between the sectors of two neighbouring parts, and the margin of
/// the half-plane test on one span's control polygon: directions closer than this are
/// treated as the same (angles are computed to ~1e-16 rad).
const SECTOR_MARGIN: f64 = 1e-12;

/// Subdivision depth at which a span's own monotonicity test gives up (a part `2^-60` of a
/// span is below any tolerance).
const MAX_SELF_DEPTH: u32 = 60;

/// Where a chain meets itself: the indices of the two parts (a piece index, or `None` for
/// the axis segment closing an open profile) and a point of the meeting.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Crossing {
    pub first: Option<usize>,
    pub second: Option<usize>,
    pub point: Point2<f64>,
}

/// A Bezier part of the chain: homogeneous control points and the piece it came from.
#[derive(Clone)]
struct Part {
    piece: Option<usize>,
    homogeneous: Vec<[f64; 3]>,
}

impl Part {
    fn points(&self) -> impl Iterator<Item = Point2<f64>> + '_ {
        self.homogeneous
            .iter()
            .map(|h| Point2::new(h[0] / h[2], h[1] / h[2]))
    }

    fn start(&self) -> Point2<f64> {
        let h = self.homogeneous[0];
        Point2::new(h[0] / h[2], h[1] / h[2])
    }

    fn end(&self) -> Point2<f64> {
        let h = self.homogeneous[self.homogeneous.len() - 1];
        Point2::new(h[0] / h[2], h[1] / h[2])
    }

    /// Distance between the part's ends: a lower bound on its length.
    fn chord(&self) -> f64 {
        (self.end() - self.start()).norm()
    }

    fn bbox(&self) -> Aabb2 {
        let mut pts = self.points();
        let first = pts.next().expect("a part has control points");
        pts.fold(
            Aabb2 {
                min: first,
                max: first,
            },
            Aabb2::including,
        )
    }

    /// The two halves at the middle parameter (de Casteljau on homogeneous points).
    fn halves(&self) -> (Part, Part) {
        let (left, right) = halve_homogeneous(&self.homogeneous);
        let part = |homogeneous| Part {
            piece: self.piece,
            homogeneous,
        };
        (part(left), part(right))
    }
}

/// The first place where the chain of `pieces` meets itself, or `None` for a simple curve.
/// `closing_axis`: the profile is open with both ends on the axis, closed by the axis segment
/// from its end back to its start; otherwise the chain is a closed loop.
pub fn first_crossing(pieces: &[NurbsCurve], closing_axis: bool, size: f64) -> Option<Crossing> {
    let tol = SELF_TOUCH_REL * size;
    let mut parts: Vec<Part> = pieces
        .iter()
        .enumerate()
        .flat_map(|(k, c)| {
            c.bezier_spans().into_iter().map(move |s| Part {
                piece: Some(k),
                homogeneous: s.homogeneous,
            })
        })
        .collect();
    if closing_axis {
        let (end, start) = (parts[parts.len() - 1].end(), parts[0].start());
        if (end - start).norm() > tol {
            parts.push(Part {
                piece: None,
                homogeneous: vec![[end.x, end.y, 1.0], [start.x, start.y, 1.0]],
            });
        }
    }
    let n = parts.len();
    let checker = Checker { tol };
    // Chord lengths along the chain, for the separation of two parts along it.
    let mut along = vec![0.0];
    for p in &parts {
        along.push(along[along.len() - 1] + p.chord());
    }
    let perimeter = along[n];
    for (i, p) in parts.iter().enumerate() {
        if let Some(c) = checker.within_span(p, 0) {
            return Some(c);
        }
        for (j, q) in parts.iter().enumerate().skip(i + 1) {
            // Consecutive parts share a joint; the chain is a loop (closed, or closed by the
            // axis), so the last part also joins the first.
            let joined = j == i + 1 || (i == 0 && j == n - 1 && n > 2);
            // Parts between i and j, either way around the loop.
            let between = (along[j] - along[i + 1]).min(perimeter - along[j + 1] + along[i]);
            let found = if !joined && between <= 2.0 * tol {
                // Separated along the chain by less than the tolerance: they meet by
                // continuity (the parts between are tested themselves).
                None
            } else if !joined {
                checker.apart(p, q)
            } else if j == i + 1 {
                checker.neighbours(p, q, 0)
            } else {
                checker.neighbours(q, p, 0)
            };
            if found.is_some() {
                return found;
            }
        }
    }
    None
}

struct Checker {
    tol: f64,
}

impl Checker {
    /// Two parts that are not neighbours in the chain: a meeting point, if any.
    fn apart(&self, a: &Part, b: &Part) -> Option<Crossing> {
        let (ba, bb) = (a.bbox(), b.bbox());
        let gap = Vector2::new(
            (ba.min.x - bb.max.x).max(bb.min.x - ba.max.x),
            (ba.min.y - bb.max.y).max(bb.min.y - ba.max.y),
        );
        if gap.x > self.tol
            || gap.y > self.tol
            || separated_across_chord(a, b, self.tol)
            || separated_across_chord(b, a, self.tol)
        {
            return None;
        }
        let (da, db) = (ba.diagonal(), bb.diagonal());
        if da <= self.tol && db <= self.tol {
            return Some(Crossing {
                first: a.piece,
                second: b.piece,
                point: a.start(),
            });
        }
        if da >= db {
            let (a1, a2) = a.halves();
            self.apart(&a1, b).or_else(|| self.apart(&a2, b))
        } else {
            let (b1, b2) = b.halves();
            self.apart(a, &b1).or_else(|| self.apart(a, &b2))
        }
    }

    /// `a` followed by `b`, joined where `a` ends: they may meet only there.
    fn neighbours(&self, a: &Part, b: &Part, depth: u32) -> Option<Crossing> {
        let joint = a.end();
        let skip = self.tol;
        let sector_a = sector(a.points().map(|p| p - joint), skip);
        let sector_b = sector(b.points().map(|p| p - joint), skip);
        if let (Some(sa), Some(sb)) = (sector_a, sector_b) {
            if sectors_disjoint(sa, sb) {
                return None;
            }
        }
        // Parts within the tolerance of their joint meet by continuity; a fold-back (both
        // leaving the joint the same way) is found between the larger parts further out,
        // which the recursion below tests as parts apart.
        let small = a.bbox().diagonal() <= self.tol && b.bbox().diagonal() <= self.tol;
        if small || depth >= MAX_SELF_DEPTH {
            return None;
        }
        let (a1, a2) = a.halves();
        let (b1, b2) = b.halves();
        // Parts separated along the chain by less than the tolerance meet by continuity,
        // not by touching: only farther ones are tested (a chord is no longer than its arc,
        // and a loop inside the parts between is found by their own tests).
        let (gap_a2, gap_b1) = (a2.chord(), b1.chord());
        let far = |gap: f64| gap > 2.0 * self.tol;
        self.neighbours(&a2, &b1, depth + 1)
            .or_else(|| far(gap_a2).then(|| self.apart(&a1, &b1)).flatten())
            .or_else(|| far(gap_a2 + gap_b1).then(|| self.apart(&a1, &b2)).flatten())
            .or_else(|| far(gap_b1).then(|| self.apart(&a2, &b2)).flatten())
    }

    /// One span against itself: monotone along some direction, or halved.
    fn within_span(&self, part: &Part, depth: u32) -> Option<Crossing> {
        let pts: Vec<Point2<f64>> = part.points().collect();
        let edges = pts.windows(2).map(|w| w[1] - w[0]);
        if sector(edges, 0.0).is_some() || part.bbox().diagonal() <= self.tol {
            return None;
        }
        if depth >= MAX_SELF_DEPTH {
            return Some(Crossing {
                first: part.piece,
                second: part.piece,
                point: pts[0],
            });
        }
        let (l, r) = part.halves();
        self.within_span(&l, depth + 1)
            .or_else(|| self.within_span(&r, depth + 1))
            .or_else(|| self.neighbours(&l, &r, depth + 1))
    }
}

/// Whether the control points of `b` lie beyond those of `a` by more than `tol` along the
/// normal of `a`'s chord (either side): long, nearly parallel parts are then apart without
/// subdividing until their axis-aligned boxes separate.
fn separated_across_chord(a: &Part, b: &Part, tol: f64) -> bool {
    let chord = a.end() - a.start();
    let length = chord.norm();
    if length.is_nan() || length <= 0.0 {
        return false;
    }
    let normal = Vector2::new(-chord.y, chord.x) / length;
    let range = |p: &Part| {
        p.points()
            .map(|q| normal.dot(&q.coords))
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), v| {
                (lo.min(v), hi.max(v))
            })
    };
    let ((a_lo, a_hi), (b_lo, b_hi)) = (range(a), range(b));
    b_lo - a_hi > tol || a_lo - b_hi > tol
}

/// The smallest angular sector `(start, width)` holding every direction of `vectors` longer
/// than `skip`, when it is narrower than a half-turn (by [`SECTOR_MARGIN`]); `None` when no
/// open half-plane holds them all, or when no vector is long enough (the part is a point at
/// this resolution: no direction settles anything).
fn sector(vectors: impl Iterator<Item = Vector2<f64>>, skip: f64) -> Option<(f64, f64)> {
    let mut angles: Vec<f64> = vectors
        .filter(|v| v.norm() > skip)
        .map(|v| v.y.atan2(v.x))
        .collect();
    if angles.is_empty() {
        return None;
    }
    angles.sort_by(f64::total_cmp);
    // The sector is the circle minus its largest gap between consecutive directions.
    let tau = std::f64::consts::TAU;
    let mut best = (angles[0] + tau - angles[angles.len() - 1], angles[0]);
    for w in angles.windows(2) {
        if w[1] - w[0] > best.0 {
            best = (w[1] - w[0], w[1]);
        }
    }
    let width = tau - best.0;
    (width < std::f64::consts::PI - SECTOR_MARGIN).then_some((best.1, width))
}

/// Whether two sectors `(start, width)` are apart by more than [`SECTOR_MARGIN`].
fn sectors_disjoint(a: (f64, f64), b: (f64, f64)) -> bool {
    let tau = std::f64::consts::TAU;
    // Start of b relative to the start of a, in [0, 2 pi).
    let rel = (b.0 - a.0).rem_euclid(tau);
    rel > a.1 + SECTOR_MARGIN && rel + b.1 < tau - SECTOR_MARGIN
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line(a: [f64; 2], b: [f64; 2]) -> NurbsCurve {
        NurbsCurve::line(Point2::new(a[0], a[1]), Point2::new(b[0], b[1])).unwrap()
    }

    fn polyline(pts: &[[f64; 2]]) -> Vec<NurbsCurve> {
        pts.windows(2).map(|w| line(w[0], w[1])).collect()
    }

    #[test]
    fn a_square_ring_is_simple_and_a_bow_tie_is_not() {
        let ring = polyline(&[[1., 0.], [2., 0.], [2., 1.], [1., 1.], [1., 0.]]);
        assert_eq!(first_crossing(&ring, false, 1.5), None);
        let bow = polyline(&[[1., 0.], [2., 1.], [2., 0.], [1., 1.], [1., 0.]]);
        let c = first_crossing(&bow, false, 1.5).expect("bow tie crosses");
        assert_eq!((c.first, c.second), (Some(0), Some(2)));
        assert!((c.point - Point2::new(1.5, 0.5)).norm() < 1e-8, "{c:?}");
    }

    #[test]
    fn a_fold_back_and_a_curve_along_the_axis_meet_themselves() {
        // Out along z = 0 and back over itself.
        let fold = polyline(&[[0., 0.], [1., 0.], [0.5, 0.], [0., 0.]]);
        assert!(first_crossing(&fold, true, 1.0).is_some());
        // The whole curve on the axis: it runs over the closing axis segment.
        let on_axis = polyline(&[[0., 0.], [0., 1.]]);
        let c = first_crossing(&on_axis, true, 1.0).unwrap();
        assert!(c.first.is_none() || c.second.is_none(), "{c:?}");
    }

    #[test]
    fn a_cubic_loop_within_one_span_is_found() {
        let loop_ = NurbsCurve::bezier(vec![
            Point2::new(1.0, 0.0),
            Point2::new(3.0, 2.0),
            Point2::new(1.0, 2.0),
            Point2::new(3.0, 0.0),
        ])
        .unwrap();
        let mut chain = vec![loop_];
        chain.extend(polyline(&[[3., 0.], [3., -1.], [1., -1.], [1., 0.]]));
        let c = first_crossing(&chain, false, 3.0).expect("the cubic loops");
        assert_eq!((c.first, c.second), (Some(0), Some(0)));
    }

    #[test]
    fn a_touch_within_the_tolerance_counts_and_a_gap_above_it_does_not() {
        // A notch whose tip comes within `gap` of the opposite wall.
        let notch = |gap: f64| {
            polyline(&[
                [1., 0.],
                [3., 0.],
                [3., 2.],
                [2., 2.],
                [2., 0.0 + gap],
                [1.5, 2.],
                [1., 2.],
                [1., 0.],
            ])
        };
        assert!(first_crossing(&notch(1e-12), false, 2.8).is_some());
        assert!(first_crossing(&notch(1e-6), false, 2.8).is_none());
    }
}
