//! A tree node from its two arcs: the node's disk and chord-distance bound, the arcs that
//! replace a piece too short to fit, the slots of nodes not built yet, and the arc geometry
//! they need (point-segment distance, farthest point, reach of a tangent, exact boxes).

use super::{Arc, BiarcNode, NO_CHILD};
use crate::biarc::bound::ulp_slack;
use crate::biarc::disk::Disk;
use crate::num::cross2;
use crate::nurbs::Aabb2;
use nalgebra::{Point2, Vector2};

/// A slot for a node that is not built yet (overwritten before the tree is used).
pub(super) fn placeholder() -> BiarcNode {
    let p = Point2::origin();
    let arc = Arc {
        start: p,
        end: p,
        start_tangent: Vector2::x(),
        curvature: 0.0,
        sweep: 0.0,
        length: 0.0,
    };
    BiarcNode {
        arcs: [arc; 2],
        eps: f64::INFINITY,
        disk: Disk {
            center: p,
            radius: f64::INFINITY,
        },
        chord_distance: f64::INFINITY,
        t0: 0.0,
        t1: 0.0,
        spiral: 0,
        first_child: NO_CHILD,
        depth: 0,
    }
}

/// The chord node's two segments `a -> m -> b` and its bound, for a curve piece within
/// `deviation` of the segment `ab` ([`PieceCurve::hull_deviation`]). `m` is the chord's
/// midpoint. When the chord is too short for a midpoint distinct from its ends (a piece that
/// returns to its start: a fin, a micro-spiral), `m` moves off `a` by `step`, the larger of
/// the deviation and a rounding-sized length, and the bound grows to `step + |b - a|`: every
/// curve point is within `deviation + |b - a|` of `a`, a point of the segments, and every
/// point of the segments is within `step + |b - a|` of `a` or `b`, curve points.
pub(super) fn chord_arcs(a: Point2<f64>, b: Point2<f64>, deviation: f64) -> ([Arc; 2], f64) {
    let mid = nalgebra::center(&a, &b);
    let (m, bound) = if mid != a && mid != b {
        (mid, deviation)
    } else {
        let step = deviation.max(ulp_slack(a.coords.amax().max(1.0)));
        (a + Vector2::new(0.0, step), step + (b - a).norm())
    };
    // Distinct end points, each pair: `m` differs from `a` and `b` in both branches.
    let segment = |p: Point2<f64>, q: Point2<f64>| {
        Arc::from_point_tangent_point(p, q - p, q).expect("a segment between distinct points")
    };
    ([segment(a, m), segment(m, b)], bound)
}

/// Node data for arcs whose curve piece is within `eps` of them as revolved: disk around the
/// chord midpoint and the chord-distance bound. The disk contains each arc, hence by
/// convexity its chord.
pub(super) fn make_node(arcs: [Arc; 2], eps: f64, spiral: u32, depth: u32) -> BiarcNode {
    let [a0, a1] = arcs;
    let (a, b) = (a0.start, a1.end);
    let m = nalgebra::center(&a, &b);
    let radius = max_distance(&a0, m).max(max_distance(&a1, m)) + eps;
    // Every point X of arc i is within sagitta_i of the chord of arc i, whose points are within
    // max(dist(start_i), dist(end_i)) of segment AB (distance to a convex set is convex).
    let j = a0.end;
    let chord_distance = a0.sagitta().max(a1.sagitta()) + segment_distance(j, a, b) + eps;
    let mut n = placeholder();
    n.arcs = arcs;
    n.eps = eps;
    n.disk = Disk { center: m, radius };
    n.chord_distance = chord_distance;
    n.spiral = spiral;
    n.depth = depth;
    n
}

pub(super) fn segment_distance(p: Point2<f64>, a: Point2<f64>, b: Point2<f64>) -> f64 {
    let d = b - a;
    let l2 = d.norm_squared();
    if l2 == 0.0 {
        return (p - a).norm();
    }
    let u = ((p - a).dot(&d) / l2).clamp(0.0, 1.0);
    (p - (a + d * u)).norm()
}

/// Arc length from `arc.start` to the point where the tangent turns to direction `dir`, if
/// that happens within the arc.
fn reach(arc: &Arc, dir: Vector2<f64>) -> Option<f64> {
    if arc.sweep == 0.0 {
        return None;
    }
    let t = arc.start_tangent;
    let mut d = cross2(t, dir).atan2(t.dot(&dir));
    if arc.sweep < 0.0 {
        d = -d;
    }
    if d < 0.0 {
        d += 2.0 * std::f64::consts::PI;
    }
    (d <= arc.sweep.abs()).then(|| arc.length * d / arc.sweep.abs())
}

/// Largest distance from `p` to points of the arc (end points, or the farthest circle point
/// when the arc contains it). The farthest point has its tangent perpendicular to `X - p`,
/// i.e. its outward radius along `c - p` reversed; computed without the (possibly huge) centre.
fn max_distance(arc: &Arc, p: Point2<f64>) -> f64 {
    let ends = (arc.start - p).norm().max((arc.end - p).norm());
    if arc.is_segment() {
        return ends;
    }
    let k = arc.curvature;
    let n = Vector2::new(-arc.start_tangent.y, arc.start_tangent.x);
    // k (c - p) = k (start - p) + n; the far point lies at direction -(c - p) from c... i.e.
    // the outward normal there is (c - p)/|c - p| reversed: far point = c + r (c - p)/|c - p|.
    let kc = (arc.start - p) * k + n;
    let len = kc.norm();
    if len == 0.0 {
        return ends; // p is the centre: every point is at distance r, the ends give it
    }
    // outward unit normal u at the far point = (c - p)/|c - p| = kc/len * sign(k); the tangent
    // there is rot90(u) * sign(k) (for a CCW arc the tangent is the outward normal turned left).
    let u = kc / len * k.signum();
    let tangent = Vector2::new(-u.y, u.x) * k.signum();
    match reach(arc, tangent) {
        Some(_) => ends.max((len + 1.0) / k.abs()),
        None => ends,
    }
}

/// Exact axis-aligned box of an arc.
pub(super) fn arc_aabb(arc: &Arc) -> Aabb2 {
    let mut bb = Aabb2 {
        min: arc.start,
        max: arc.start,
    }
    .including(arc.end);
    for dir in [Vector2::x(), -Vector2::x(), Vector2::y(), -Vector2::y()] {
        if let Some(s) = reach(arc, dir) {
            bb = bb.including(arc.point_at(s));
        }
    }
    bb
}
