//! The meridian polyline: the leaves' arcs replaced by segments ([`super::arc_chords`]), with
//! a per-segment bound on the distance to the profile curve.
//!
//! Every segment carries `leaf_eps` (its leaf's bound, arcs vs curve) and `deviation` (segment
//! vs its arc piece, two-sided). Three kinds of vertex moves keep the polyline a single chain
//! with exact poles, each adding its displacement `d` to the deviation of the segments at the
//! moved vertex (moving the end points of a segment by at most `d` moves each of its points,
//! an affine combination of the end points, by at most `d`):
//! - joins: an arc starts where the previous one ended up to rounding (a knot evaluated from
//!   two spans, pieces joined within the profile's join tolerance); the previous end is kept;
//! - closing a closed profile: the last arc's end is replaced by the first vertex;
//! - poles: a vertex with `rho <= POLE_SNAP_REL * size` (the ends of an open profile, which
//!   lie on the axis up to the join tolerance) or `rho < 0` gets `rho = 0`.
//!
//! Consecutive equal vertices are merged; the merged segment's bound stays in
//! [`Meridian::bound`] (its point is still a vertex of the polyline). Collinear vertices are
//! removed ([`COLLINEAR_REL`]).

use nalgebra::Point2;

use super::arc_chords::push_arc_segments;
use super::VertexPlacement;
use crate::biarc::BiarcTree;
use crate::profile::{ProfileKind, JOIN_TOLERANCE_REL};

/// Interior vertices at most this fraction of the profile size from the segment joining their
/// neighbours are removed (the biarcs of a straight piece are two collinear segments); the
/// distance is added to the merged segment's deviation (the Hausdorff distance between the
/// path `a v b` and the segment `a b` is at most the distance from `v` to `a b`).
pub const COLLINEAR_REL: f64 = 1e-12;

/// Vertices with `rho` below this fraction of the profile size are put on the axis. Equal to
/// the profile's join tolerance: open profiles end on the axis up to exactly that.
pub const POLE_SNAP_REL: f64 = JOIN_TOLERANCE_REL;

/// What the revolution contributes per unit of `rho`, and how the meridian budget is shared.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeridianBudget {
    /// Revolution error per unit `rho` (`tau` of the module doc of [`super`]).
    pub tau: f64,
    /// Total bound to meet at every segment, before rounding slack.
    pub budget: f64,
    /// Vertex placement.
    pub placement: VertexPlacement,
    /// Cap on segment lengths.
    pub max_edge: Option<f64>,
}

/// The meridian polyline of a profile and its certified bounds.
#[derive(Debug, Clone, PartialEq)]
pub struct Meridian {
    /// Vertices in profile order. For a closed profile the last segment joins the last vertex
    /// back to the first; for an open one the first and last vertices are poles (`rho = 0`).
    pub points: Vec<Point2<f64>>,
    /// Whether the polyline is a loop.
    pub closed: bool,
    /// Largest leaf bound over the segments.
    pub leaf_error: f64,
    /// Largest segment deviation (chord error plus vertex moves).
    pub deviation: f64,
    /// Largest `tau * rho` over the vertices.
    pub revolution_error: f64,
    /// Largest `leaf_eps + deviation + tau * rho_max` over the segments: the certified
    /// Hausdorff bound of the revolved mesh (module doc of [`super`]), without rounding slack.
    pub bound: f64,
}

impl Meridian {
    /// Number of segments.
    pub fn segments(&self) -> usize {
        if self.closed {
            self.points.len()
        } else {
            self.points.len().saturating_sub(1)
        }
    }
}

/// Builds the polyline of `tree`'s leaves for the given budget; `None` when some arc has no
/// budget left for its segments (`leaf_eps + tau * rho >= budget`).
///
/// Each arc takes the largest chord tolerance its place allows: with `rho_hi` an upper bound on
/// `rho` over the arc (`max(rho_start, rho_end) + sagitta`: an arc stays within its sagitta of
/// its chord), its segments stay below `rho_hi + tol`, so `leaf_eps + tol + tau (rho_hi + tol)
/// <= budget` gives `tol = (budget - leaf_eps - tau rho_hi) / (1 + tau)`.
pub fn build(
    tree: &BiarcTree,
    kind: ProfileKind,
    size: f64,
    b: &MeridianBudget,
) -> Option<Meridian> {
    let mut points: Vec<Point2<f64>> = Vec::new();
    let mut leaf_eps: Vec<f64> = Vec::new();
    let mut deviation: Vec<f64> = Vec::new();
    for leaf in tree.leaves() {
        for arc in leaf.revolved_arcs(tree.flat_radius()) {
            let rho_hi = arc.start.x.max(arc.end.x) + arc.sagitta();
            let tol = (b.budget - leaf.eps() - b.tau * rho_hi) / (1.0 + b.tau);
            if tol.is_nan() || tol <= 0.0 {
                return None;
            }
            let join = match points.last() {
                Some(last) => (arc.start - last).norm(),
                None => {
                    points.push(arc.start);
                    0.0
                }
            };
            let first = deviation.len();
            push_arc_segments(
                &arc,
                tol,
                b.placement,
                b.max_edge,
                &mut points,
                &mut deviation,
            );
            leaf_eps.resize(deviation.len(), leaf.eps());
            deviation[first] += join;
        }
    }
    if deviation.is_empty() {
        return None;
    }
    let closed = kind == ProfileKind::Closed;
    if closed {
        // The last vertex should be the first one: drop it, the last segment wraps around.
        let last = points.pop().expect("a segment has two end points");
        let n = deviation.len() - 1;
        deviation[n] += (last - points[0]).norm();
    }
    snap_poles(&mut points, &mut deviation, closed, POLE_SNAP_REL * size);
    let (points, leaf_eps, deviation) = merge_collinear(
        points,
        leaf_eps,
        deviation,
        COLLINEAR_REL * size,
        b.max_edge,
    );
    Some(finish(points, leaf_eps, deviation, closed, b.tau))
}

/// Puts vertices with `rho <= snap` (or negative) on the axis, charging the move to the
/// segments at the vertex.
fn snap_poles(points: &mut [Point2<f64>], deviation: &mut [f64], closed: bool, snap: f64) {
    let n = points.len();
    let segs = deviation.len();
    for i in 0..n {
        let rho = points[i].x;
        if rho == 0.0 || rho > snap {
            continue;
        }
        let moved = rho.abs();
        points[i].x = 0.0;
        // Segment i starts at vertex i; segment i - 1 (or the wrapping one) ends there.
        if i < segs {
            deviation[i] += moved;
        }
        if i > 0 {
            deviation[i - 1] += moved;
        } else if closed {
            deviation[segs - 1] += moved;
        }
    }
}

/// Removes interior vertices (not on the axis, not the first) lying within `tol` of the
/// segment joining their neighbours, unless that segment would exceed `max_edge`.
fn merge_collinear(
    points: Vec<Point2<f64>>,
    leaf_eps: Vec<f64>,
    deviation: Vec<f64>,
    tol: f64,
    max_edge: Option<f64>,
) -> (Vec<Point2<f64>>, Vec<f64>, Vec<f64>) {
    let n = points.len();
    let mut pts = Vec::with_capacity(n);
    let mut eps = Vec::with_capacity(leaf_eps.len());
    let mut dev = Vec::with_capacity(deviation.len());
    pts.push(points[0]);
    for (i, (&e, &d)) in leaf_eps.iter().zip(&deviation).enumerate() {
        let b = points[(i + 1) % n];
        let k = pts.len();
        if k >= 2 && i + 1 < n {
            let (a, v) = (pts[k - 2], pts[k - 1]);
            let off = segment_distance(v, a, b);
            let short = max_edge.is_none_or(|m| (b - a).norm() <= m);
            if v.x > 0.0 && off <= tol && short {
                pts[k - 1] = b;
                let j = eps.len() - 1;
                eps[j] = f64::max(eps[j], e);
                dev[j] = f64::max(dev[j], d) + off;
                continue;
            }
        }
        if i + 1 < n {
            pts.push(b);
        }
        eps.push(e);
        dev.push(d);
    }
    (pts, eps, dev)
}

/// Distance from `p` to the segment `ab`.
fn segment_distance(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    let u = if l2 > 0.0 {
        ((p - a).dot(&d) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (p - (a + d * u)).norm()
}

/// Merges consecutive equal vertices and computes the bounds.
fn finish(
    points: Vec<Point2<f64>>,
    leaf_eps: Vec<f64>,
    deviation: Vec<f64>,
    closed: bool,
    tau: f64,
) -> Meridian {
    let n = points.len();
    let mut out = Meridian {
        points: Vec::with_capacity(n),
        closed,
        leaf_error: 0.0,
        deviation: 0.0,
        revolution_error: 0.0,
        bound: 0.0,
    };
    for (i, (&e, &d)) in leaf_eps.iter().zip(&deviation).enumerate() {
        let (a, b) = (points[i], points[(i + 1) % n]);
        out.leaf_error = out.leaf_error.max(e);
        out.deviation = out.deviation.max(d);
        out.bound = out.bound.max(e + d + tau * a.x.max(b.x));
    }
    for (i, &p) in points.iter().enumerate() {
        out.revolution_error = out.revolution_error.max(tau * p.x);
        let is_last_of_loop = closed && i + 1 == n && p == points[0];
        if out.points.last() != Some(&p) && !is_last_of_loop {
            out.points.push(p);
        }
    }
    out
}
