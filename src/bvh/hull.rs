//! Convex hulls of revolved pieces: the set within `grow` of the convex hull of a few
//! parallels (circles about the axis, given by meridian points), built from a piece's or a
//! biarc's chords grown by their sagittas (paper 4.1's fat biarcs), and the unions over
//! spirals the upper level of the tree stores.
//!
//! A revolved segment is a frustum surface: it lies in the convex hull of its two boundary
//! circles. A revolved arc of sweep at most pi lies within its sagitta
//! `h = r (1 - cos(sweep / 2))` of its chord (in each meridian plane, so also in 3-D), hence
//! within `h` of its chord's frustum. The support function of the hull of a few circles in a
//! unit direction `n` is the largest of theirs, `n . c + r |n - (n . k) k|` (centre `c`, unit
//! normal `k`). This module holds the shapes and their support function; the lower bound
//! between two hulls, iterated on their Minkowski difference, is
//! [`mod@crate::query::bound::hull_bound`].

use super::patch::ProfileArc;
use crate::num::norm2;
use crate::tolerances::ROTATION_ROUNDING;
use nalgebra::{Point2, Point3, Vector2, Vector3};

/// Chords per arc in [`PieceHull::of_piece`]: each halving of the chords quarters the
/// sagitta the bound loses (an arc of sweep 0.1 rad and radius 0.4 loses 5e-4 with one
/// chord, 8e-6 with eight), at the cost of more parallels in the support function. The
/// leaf arcs' sagittas (3e-4 to 4e-3 at eps 1e-4) kept the stage-1 bounds of the leaf
/// pairs near contact about 1e-3 below their distance. Measured (`query_cost --poses
/// 100`, eps 1e-4, cup-bottle): exact patch solves per query 1.4 (one chord) -> 0.8 (four
/// or eight), 114 us (four) -> 108 us (eight) -> 117 us (sixteen). Node hulls keep one
/// chord per arc ([`ParallelHull::of_pieces`]): the query tree stores them.
pub const ARC_CHORDS: usize = 8;

/// The hull of one piece ([`PieceHull::of_piece`]): up to [`ARC_CHORDS`] chords.
pub type PieceHull = ParallelHull<{ ARC_CHORDS + 1 }>;

/// The hull of a query-tree node ([`ParallelHull::of_pieces`]).
pub type NodeHull = ParallelHull<NODE_POINTS>;

/// Parallels of a node hull: one chord per arc of the node's biarc. Two or four chords per
/// arc (5 or 9 parallels) left node pairs, leaf pairs and query times unchanged
/// (`query_cost --poses 100`, eps 1e-4) at up to three times the hull memory.
pub const NODE_POINTS: usize = 3;

/// Parallels of an upper-level hull ([`UpperHull`]): the 2-D convex hull of the meridian
/// points of the spirals below a node over several spirals, when it has at most this many
/// vertices (no hull otherwise).
pub const UPPER_POINTS: usize = 8;

/// The hull of a node over several spirals ([`ParallelHull::union_of`]).
pub type UpperHull = ParallelHull<UPPER_POINTS>;

/// A node's hull, of either size: a fat biarc's ([`NodeHull`]) or a union over spirals
/// ([`UpperHull`]).
#[derive(Debug, Clone, Copy)]
pub enum HullRef<'a> {
    Node(&'a NodeHull),
    Upper(&'a UpperHull),
}

impl HullRef<'_> {
    /// [`ParallelHull::union_of`] of two node hulls.
    pub fn union(&self, other: &HullRef<'_>) -> Option<UpperHull> {
        match (*self, *other) {
            (HullRef::Node(a), HullRef::Node(b)) => UpperHull::union_of(a, b),
            (HullRef::Node(a), HullRef::Upper(b)) => UpperHull::union_of(a, b),
            (HullRef::Upper(a), HullRef::Node(b)) => UpperHull::union_of(a, b),
            (HullRef::Upper(a), HullRef::Upper(b)) => UpperHull::union_of(a, b),
        }
    }

    /// The hull's meridian points and growth (tests).
    #[cfg(test)]
    pub(crate) fn points_and_grow_for_tests(&self) -> (Vec<Point2<f64>>, f64) {
        match *self {
            HullRef::Node(h) => (h.points_for_tests(), h.grow),
            HullRef::Upper(h) => (h.points_for_tests(), h.grow),
        }
    }
}

/// A set lying within `grow` of the convex hull of up to `N` parallels (circles about the
/// axis, given by their meridian points `(rho, z)`): a revolved piece's chords
/// ([`PieceHull`]), a revolved biarc's two chords ([`NodeHull`]), with their sagittas and
/// any further bound added to `grow` ([`crate::query::bound::hull_bound::hull_bound`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParallelHull<const N: usize = 3> {
    points: [Point2<f64>; N],
    len: usize,
    /// Distance by which the set may leave the hull.
    pub grow: f64,
}

impl PieceHull {
    /// The hull of a piece's chords: a segment's two ends, an arc cut into
    /// [`ARC_CHORDS`] equal sub-arcs, grown by a sub-arc's sagitta (`None` for an arc of
    /// sweep above pi, which may leave its chord's frustum by more than its sagitta).
    pub fn of_piece(p: &ProfileArc) -> Option<PieceHull> {
        PieceHull::of_chords(p, ARC_CHORDS)
    }
}

impl<const N: usize> ParallelHull<N> {
    /// The hull of consecutive pieces (at most two, joined end to start), `(N - 1) / 2`
    /// chords each, grown by the larger of their chords' sagittas plus `extra` (a node's fat
    /// biarc, paper 4.1; [`NodeHull`] keeps the query tree small).
    pub fn of_pieces(pieces: &[ProfileArc], extra: f64) -> Option<ParallelHull<N>> {
        let parts = (N - 1) / 2;
        let mut h = ParallelHull::<N>::of_chords(pieces.first()?, parts)?;
        if let Some(second) = pieces.get(1) {
            let h2 = ParallelHull::<N>::of_chords(second, parts)?;
            let start = h.len;
            for (k, m) in h2.points[1..h2.len].iter().enumerate() {
                h.points[start + k] = *m;
            }
            h.len += h2.len - 1;
            // The second chord starts at the first one's end within rounding; its own
            // start is counted as well by growing with the gap.
            h.grow = h.grow.max(h2.grow) + (second.start() - pieces[0].end()).norm();
        }
        h.grow += extra;
        Some(h)
    }

    /// The hull of the union of two hulls: the support function of a union is the larger
    /// of the two, and `n_z z + |rho| |n_xy|` is linear in `(|rho|, z)`, so the vertices of
    /// the 2-D convex hull of both sets' meridian points `(|rho|, z)` give the same support
    /// function; grown by the larger growth. `None` when that hull has more than `N`
    /// vertices.
    pub fn union_of<const A: usize, const B: usize>(
        a: &ParallelHull<A>,
        b: &ParallelHull<B>,
    ) -> Option<ParallelHull<N>> {
        let mut pts: Vec<Point2<f64>> = a.points[..a.len]
            .iter()
            .chain(&b.points[..b.len])
            .map(|m| Point2::new(m.x.abs(), m.y))
            .collect();
        let vertices = right_chain(&convex_hull_2d(&mut pts));
        if vertices.len() > N || vertices.is_empty() {
            return None;
        }
        let mut points = [vertices[0]; N];
        points[..vertices.len()].copy_from_slice(&vertices);
        Some(ParallelHull {
            points,
            len: vertices.len(),
            grow: a.grow.max(b.grow),
        })
    }

    /// The hull of `parts` equal chords of a piece (one for a segment; `parts < N`), grown
    /// by the sagitta of one part.
    fn of_chords(p: &ProfileArc, parts: usize) -> Option<ParallelHull<N>> {
        debug_assert!(parts < N);
        let mut points = [p.end(); N];
        let (grow, len) = match *p {
            ProfileArc::Segment { start, .. } => {
                points[0] = start;
                (0.0, 2)
            }
            ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            } if sweep.abs() <= std::f64::consts::PI => {
                // The chord points by rotating the start's direction (two sine/cosine pairs
                // instead of one per point); the end is the piece's own.
                let step = sweep / parts as f64;
                let (sd, cd) = step.sin_cos();
                let (s0, c0) = phi_start.sin_cos();
                let mut u = Vector2::new(c0, s0);
                points[0] = center + radius * u;
                for m in points.iter_mut().take(parts).skip(1) {
                    u = Vector2::new(u.x * cd - u.y * sd, u.x * sd + u.y * cd);
                    *m = center + radius * u;
                }
                // r (1 - cos(s / 2)) of a part's sweep s, without cancellation, plus the
                // rotations' rounding: each of up to `parts` steps moves a point off the
                // arc by at most a few ulps of the radius (ROTATION_ROUNDING each).
                let q = (0.25 * step).sin();
                let rounding = ROTATION_ROUNDING * parts as f64 * (radius + center.coords.norm());
                (2.0 * radius * q * q + rounding, parts + 1)
            }
            ProfileArc::Arc { .. } => return None,
        };
        Some(ParallelHull { points, len, grow })
    }

    /// The hull's meridian points (tests).
    #[cfg(test)]
    pub(crate) fn points_for_tests(&self) -> Vec<Point2<f64>> {
        self.points[..self.len].to_vec()
    }

    /// Support value and a support point of the hull (own frame, axis z) in direction `n`:
    /// the largest `n_z z + |rho| |n_xy|` over the parallels, at the parallel's point along
    /// `n`'s horizontal part (its centre when `n` is vertical, also in the hull).
    pub(crate) fn support(&self, n: &Vector3<f64>) -> (f64, Point3<f64>) {
        let l = norm2(n.x, n.y);
        // The best parallel first, then its point (one division, not one per improvement).
        let mut best: Option<(f64, &Point2<f64>)> = None;
        for m in &self.points[..self.len] {
            let v = n.z * m.y + m.x.abs() * l;
            if v > best.map_or(f64::NEG_INFINITY, |b| b.0) {
                best = Some((v, m));
            }
        }
        let Some((v, m)) = best else {
            return (f64::NEG_INFINITY, Point3::origin());
        };
        let r = m.x.abs();
        let p = if l > 0.0 {
            Point3::new(n.x * r / l, n.y * r / l, m.y)
        } else {
            Point3::new(0.0, 0.0, m.y)
        };
        (v, p)
    }

    /// An upper bound of the hull's points' distance from the origin (the larger `|rho| +
    /// |z|`: no square roots), the scale of the rounding slack.
    pub(crate) fn size(&self) -> f64 {
        self.points[..self.len]
            .iter()
            .map(|m| m.x.abs() + m.y.abs())
            .fold(0.0, f64::max)
    }
}

/// The vertices of a convex polygon (counter-clockwise) that maximise some `l |rho| + n_z z`
/// with `l >= 0`, the only ones a support function of parallels can pick: those with an
/// adjacent edge whose outward normal `(dz, -drho)` points to `rho >= 0`.
fn right_chain(h: &[Point2<f64>]) -> Vec<Point2<f64>> {
    let m = h.len();
    if m < 3 {
        return h.to_vec();
    }
    let faces_right = |i: usize| h[(i + 1) % m].y - h[i].y >= 0.0;
    (0..m)
        .filter(|&i| faces_right((i + m - 1) % m) || faces_right(i))
        .map(|i| h[i])
        .collect()
}

/// Vertices of the convex hull of `pts` (Andrew's monotone chain; collinear points
/// dropped, a single point kept).
fn convex_hull_2d(pts: &mut [Point2<f64>]) -> Vec<Point2<f64>> {
    pts.sort_by(|p, q| p.x.total_cmp(&q.x).then(p.y.total_cmp(&q.y)));
    let turn = |o: &Point2<f64>, a: &Point2<f64>, b: &Point2<f64>| {
        (a.x - o.x) * (b.y - o.y) - (a.y - o.y) * (b.x - o.x)
    };
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(pts.len() + 1);
    // The lower chain left to right, then the upper chain right to left.
    let m = pts.len();
    for pass in 0..2 {
        let start = hull.len();
        for k in 0..m {
            let p = pts[if pass == 0 { k } else { m - 1 - k }];
            while hull.len() >= start + 2
                && turn(&hull[hull.len() - 2], &hull[hull.len() - 1], &p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    if hull.is_empty() {
        hull.extend(pts.first());
    }
    hull
}
