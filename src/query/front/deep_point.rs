//! Branch and bound for a point of one approximating surface deeper than a threshold inside
//! the other solid (the overlap certificate of [`super::overlap`]), over both directions at
//! once: B's surface in A and A's surface in B.
//!
//! **Regions.** A region is a revolution-angle interval `[t0, t1]` times a meridian set: a
//! node's disk (centre `c`, radius `r`) or a sub-arc `[s0, s1]` of one patch (its points lie
//! within half its length of the midpoint, `point_at` being proportional to arc length).
//! Lifted, the region lies in the ball about the meridian centre lifted at the middle angle,
//! of radius `R = r + 2 (|c.x| + r) sin(h / 2)`, `h` the interval's half width: a point at
//! angle `t` is at most the chord `2 rho sin(|t - t_mid| / 2)` from its lift at `t_mid`.
//!
//! **Bound.** The signed depth in the outer solid is 1-Lipschitz, so no point of the region
//! is deeper than `depth(X) + R`, `X` the ball's centre. The depth of `X` is capped
//! ([`signed_depth_capped`], [`region_depth`]): a capped depth is a lower bound inside and
//! an upper bound outside. Outside, the bound stays an upper bound; inside, a cap above the
//! threshold keeps `min(depth, cap) + R` above the threshold, so such a region is never
//! dropped (it is only visited later than its true bound would put it). Regions whose bound is at most the threshold hold no certificate and are
//! dropped; the others are split (the larger of the meridian and angular radii halves) and
//! visited deepest first, by `depth(X) + R / 2` ([`PRIORITY_RADIUS_WEIGHT`]), so a deep
//! overlap is reached before the shallow band around a contact is refined.
//!
//! **Certificate.** Only a point of an approximating surface certifies: the centre of a
//! sub-arc region, lifted, deeper than the threshold, or, for a node region whose centre is
//! deeper than the threshold plus its radius (every point of it is then deeper than the
//! threshold), a patch midpoint under the node lifted at the middle angle, its depth
//! measured again. Node centres themselves only guide.
//!
//! **Completeness.** If some surface point is deeper than `threshold + delta`, every region
//! of radius below `delta / 2` around it has a centre deeper than the threshold, and no
//! region holding it is dropped; the search finds a certificate before it has refined every
//! region of the surface to that size. Around a touching contact (no overlap) the bounds
//! stay above the threshold down to regions of about the threshold's size, so the search
//! runs until its evaluation budget is spent and reports [`DeepPoint::Undecided`].

use crate::bvh::containment::signed_depth_capped;
use crate::bvh::patch::{e_rho, lift};
use crate::bvh::QueryTree;
use nalgebra::{Isometry3, Point2, Point3};
use std::cell::Cell;
use std::cmp::Ordering;
use std::collections::BinaryHeap;
use std::f64::consts::TAU;

/// Largest region radius a centre's depth is capped at, as a fraction of the outer root
/// disk's radius ([`region_depth`]).
const CAP_FRACTION: f64 = 0.25;

/// Weight of a region's radius in its visiting priority, `depth(centre) + w R`: regions are
/// dropped by their bound (`w = 1`), but visited deeper centres first, which reaches an
/// overlap before every wide region around the contact is refined. Three corner crossings
/// the campaign found needed 201, 707 and 1,715 evaluations at `w = 1`, and 123, 365 and 783
/// at 0.5; at 0.25 the third never finished (a shallow lens held the search).
const PRIORITY_RADIUS_WEIGHT: f64 = 0.5;

/// Angle intervals the search starts from, per direction (30 degrees each).
const START_INTERVALS: usize = 12;

/// One direction of the search: points of `inner`'s approximating surface (mapped to
/// `outer`'s frame by `pos`) deeper than `threshold` in `outer`.
#[derive(Clone, Copy)]
pub struct Direction<'a> {
    pub outer: &'a QueryTree,
    pub inner: &'a QueryTree,
    pub pos: &'a Isometry3<f64>,
    pub threshold: f64,
}

/// What the search concluded.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DeepPoint {
    /// A surface point of direction `dir`'s inner solid deeper than its threshold, in the
    /// outer solid's frame.
    Found { dir: usize, point: Point3<f64> },
    /// No surface point of either direction is deeper than its threshold.
    Absent,
    /// The evaluation budget ran out first.
    Undecided,
}

#[derive(Debug, Clone, Copy)]
enum Meridian {
    Node(u32),
    Piece { patch: u32, s0: f64, s1: f64 },
}

#[derive(Debug, Clone, Copy)]
struct Region {
    /// Visiting order, largest first ([`PRIORITY_RADIUS_WEIGHT`]); the region's bound is
    /// above the threshold (else it was dropped).
    priority: f64,
    dir: usize,
    set: Meridian,
    t0: f64,
    t1: f64,
}

impl PartialEq for Region {
    fn eq(&self, o: &Self) -> bool {
        self.cmp(o) == Ordering::Equal
    }
}
impl Eq for Region {}
impl PartialOrd for Region {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Region {
    fn cmp(&self, o: &Self) -> Ordering {
        self.priority.total_cmp(&o.priority)
    }
}

/// Meridian centre and radius of a region's meridian set.
fn meridian_ball(inner: &QueryTree, set: Meridian) -> (Point2<f64>, f64) {
    match set {
        Meridian::Node(id) => {
            let b = &inner.nodes[id as usize].bound;
            (b.center, b.radius)
        }
        Meridian::Piece { patch, s0, s1 } => {
            let arc = &inner.patches[patch as usize].arc;
            (
                arc.point_at(0.5 * (s0 + s1)),
                0.5 * (s1 - s0) * arc.length(),
            )
        }
    }
}

/// A meridian point of the approximating chain under node `id`: the midpoint of the first
/// patch of its first leaf (inside the node's disk, which holds its pieces).
fn node_surface_point(inner: &QueryTree, id: u32) -> Point2<f64> {
    let mut n = &inner.nodes[id as usize];
    while !n.is_leaf() {
        n = &inner.nodes[n.children[0] as usize];
    }
    inner
        .patches
        .get(n.patch_start as usize)
        .filter(|_| n.patch_start < n.patch_end)
        .map_or(n.bound.center, |p| p.arc.point_at(0.5))
}

/// Angular radius of a region: how far its lift at any angle of `[t0, t1]` is from its lift
/// at the middle angle (module doc).
fn angular_radius(centre: Point2<f64>, r: f64, t0: f64, t1: f64) -> f64 {
    2.0 * (centre.x.abs() + r) * (0.25 * (t1 - t0)).sin()
}

/// Signed depth of a region's centre `x` in `outer`, capped at `radius + 2 threshold`
/// (module doc), the radius first limited to [`CAP_FRACTION`] of the outer root disk's
/// radius: a deep centre then no longer opens most of the outer tree (every piece is about
/// equally far from it). Only a centre farther outside than that first cap, of a region
/// wider than it (the top levels), is measured again with the full cap, which decides
/// whether the region is dropped.
fn region_depth(outer: &QueryTree, x: &Point3<f64>, radius: f64, threshold: f64) -> f64 {
    let size = outer
        .nodes
        .get(outer.root as usize)
        .map_or(0.0, |n| n.bound.radius);
    let limited = radius.min(CAP_FRACTION * size);
    let depth = signed_depth_capped(outer, x, limited + 2.0 * threshold);
    if limited < radius && depth <= -(limited + 2.0 * threshold) {
        signed_depth_capped(outer, x, radius + 2.0 * threshold)
    } else {
        depth
    }
}

/// Best-first search over both directions for a certificate, at most `budget` depth
/// evaluations.
pub fn deep_point(dirs: &[Direction<'_>], budget: usize) -> DeepPoint {
    let mut heap = BinaryHeap::new();
    let evaluations = Cell::new(0usize);
    // Bounds a region; a certificate when its centre is a surface point deep enough.
    let visit = |dir: usize, set: Meridian, t0: f64, t1: f64, heap: &mut BinaryHeap<_>| {
        let d = &dirs[dir];
        let (m, r) = meridian_ball(d.inner, set);
        let radius = r + angular_radius(m, r, t0, t1);
        let x = d.pos * lift(m, &e_rho(0.5 * (t0 + t1)));
        evaluations.set(evaluations.get() + 1);
        let depth = region_depth(d.outer, &x, radius, d.threshold);
        if matches!(set, Meridian::Piece { .. }) && depth > d.threshold {
            return Some(x);
        }
        // Every point of the region is deeper than the threshold: one surface point of it
        // certifies, without refining the region down to a sub-arc.
        if let Meridian::Node(id) = set {
            if depth - radius > d.threshold {
                let y = d.pos * lift(node_surface_point(d.inner, id), &e_rho(0.5 * (t0 + t1)));
                evaluations.set(evaluations.get() + 1);
                if signed_depth_capped(d.outer, &y, 2.0 * d.threshold) > d.threshold {
                    return Some(y);
                }
            }
        }
        let bound = depth + radius;
        if bound > d.threshold {
            heap.push(Region {
                priority: depth + PRIORITY_RADIUS_WEIGHT * radius,
                dir,
                set,
                t0,
                t1,
            });
        }
        None
    };
    for (dir, d) in dirs.iter().enumerate() {
        let root = Meridian::Node(d.inner.root);
        if d.inner.nodes.is_empty() {
            continue;
        }
        for k in 0..START_INTERVALS {
            let step = TAU / START_INTERVALS as f64;
            let (t0, t1) = (k as f64 * step, (k + 1) as f64 * step);
            if let Some(point) = visit(dir, root, t0, t1, &mut heap) {
                return DeepPoint::Found { dir, point };
            }
        }
    }
    while let Some(g) = heap.pop() {
        if evaluations.get() >= budget {
            return DeepPoint::Undecided;
        }
        let inner = dirs[g.dir].inner;
        let (m, r) = meridian_ball(inner, g.set);
        let tm = 0.5 * (g.t0 + g.t1);
        let split_angle = angular_radius(m, r, g.t0, g.t1) > r;
        let mut children: Vec<(Meridian, f64, f64)> = Vec::new();
        if split_angle {
            children.push((g.set, g.t0, tm));
            children.push((g.set, tm, g.t1));
        } else {
            match g.set {
                Meridian::Node(id) => {
                    let n = &inner.nodes[id as usize];
                    if n.is_leaf() {
                        children.extend((n.patch_start..n.patch_end).map(|patch| {
                            (
                                Meridian::Piece {
                                    patch,
                                    s0: 0.0,
                                    s1: 1.0,
                                },
                                g.t0,
                                g.t1,
                            )
                        }));
                    } else {
                        children.extend(n.children.map(|c| (Meridian::Node(c), g.t0, g.t1)));
                    }
                }
                Meridian::Piece { patch, s0, s1 } => {
                    let sm = 0.5 * (s0 + s1);
                    children.push((Meridian::Piece { patch, s0, s1: sm }, g.t0, g.t1));
                    children.push((Meridian::Piece { patch, s0: sm, s1 }, g.t0, g.t1));
                }
            }
        }
        for (set, t0, t1) in children {
            if let Some(point) = visit(g.dir, set, t0, t1, &mut heap) {
                return DeepPoint::Found { dir: g.dir, point };
            }
        }
    }
    DeepPoint::Absent
}
