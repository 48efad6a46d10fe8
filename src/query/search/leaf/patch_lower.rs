//! Stage 1 of a leaf pair, the lower half: a cheap lower bound of the distance between two
//! patches before any degree-8 solve, with the points near the closest pair that start the
//! realised upper bound of [`super::patch_upper`].
//!
//! **Lower bound.** A toroidal patch lies on the torus of its arc: every point is at
//! distance `r` (the arc's radius) from the major circle `M` traced by the arc's centre
//! (for a centre with `rho < 0` the circle of radius `|rho|` still holds every revolved
//! point within `r`, since `|rho_x - |c|| <= rho_x + |c|`). So each patch is inside the
//! solid torus `{x : dist(x, M) <= r}` and, by the triangle inequality as in
//! [`crate::query::bound::node_pair`], `dist(patch A, patch B) >= dist(M_A, M_B) - r_A - r_B`. The bound is
//! tight whenever the two tori's closest points lie on the patches, which is the common
//! case for the leaf pair that holds the minimum (paper section 3: the distance of two
//! toroidal patches is `l - r1 - r2`, `l` a binormal length). Any patch pair also has the
//! solid-torus bound of the disks around its pieces; the larger of the two is returned.
//!
//! Cost: one circle/circle minimum ([`mod@crate::circle::min_distance`], under 1 us for circles
//! in general position) and a few planar closest-point evaluations.

use crate::bvh::hull::PieceHull;
use crate::bvh::patch::{Patch, ProfileArc};
use crate::circle::min_distance;
use crate::query::angles::common_normals::{as_circle3, parallel_circle};
use crate::query::angles::meridian_line::{line_field_critical, line_field_levels, FieldAngles};
use crate::query::angles::radial_field::ParamCircle;
use crate::query::bound::hull_bound::{hull_bound_and_witness, PointPair};
use crate::query::bound::node_pair::{
    axis_direction, shell_bound, slab_bound_in, sphere_bound, torus_bound,
};
use crate::tolerances::BOUND_SLACK;
use nalgebra::{Isometry3, Point2, Point3, Vector2, Vector3};

/// Memo of circle/circle minima within one query (one pose): neighbouring pieces of one
/// arc, and every piece of an exact torus or sphere, share their major circle, so a leaf
/// pair's patch pairs often ask for the same circle pair. Keyed by the bits of both arcs'
/// centres; a handful of entries, searched linearly.
#[derive(Debug, Default)]
pub struct CoreMemo {
    entries: Vec<([u64; 4], CircleMin)>,
}

/// Closest points of two major circles (A's frame) and their distance.
#[derive(Debug, Clone, Copy)]
struct CircleMin {
    distance: f64,
    point_a: Point3<f64>,
    point_b: Point3<f64>,
}

/// Largest number of entries kept in a [`CoreMemo`] (older ones are replaced).
const CORE_MEMO_SIZE: usize = 16;

impl CoreMemo {
    fn get(&mut self, ca: Point2<f64>, cb: Point2<f64>, pos_ab: &Isometry3<f64>) -> CircleMin {
        let key = [
            ca.x.to_bits(),
            ca.y.to_bits(),
            cb.x.to_bits(),
            cb.y.to_bits(),
        ];
        if let Some((_, m)) = self.entries.iter().find(|(k, _)| *k == key) {
            return *m;
        }
        let ma = parallel_circle(ca.x, ca.y, &Isometry3::identity());
        let mb = parallel_circle(cb.x, cb.y, pos_ab);
        let md = min_distance(&ma, &mb);
        let m = CircleMin {
            distance: md.distance,
            point_a: md.point_a,
            point_b: md.point_b,
        };
        if self.entries.len() >= CORE_MEMO_SIZE {
            self.entries.remove(0);
        }
        self.entries.push((key, m));
        m
    }
}

/// The cheap lower bound of a patch pair, with the start of a realised pair when the bound
/// was computed in full.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchLower {
    /// A rigorous lower bound of the patch distance.
    pub lower: f64,
    /// Points near the closest pair (A's frame), from which [`super::patch_upper::realised`] projects onto the
    /// patches; `None` when the bound stopped early at the caller's pruning level.
    pub(super) near: Option<PointPair>,
    /// The pieces' hulls' nearest points
    /// ([`crate::bvh::hull::ParallelHull::bound_and_witness`]), a second start for [`super::patch_upper::realised`]
    /// (the only good one for two cones).
    pub(super) hull_near: Option<PointPair>,
}

impl PatchLower {
    /// Direction from A's near point to B's (A's frame), a separating direction for
    /// [`crate::query::bound::hull_bound::hull_bound`] (the hulls' nearest points' when the hull iteration
    /// found them); `None` when the bound stopped early.
    pub fn direction(&self) -> Option<Vector3<f64>> {
        self.hull_near
            .filter(|(a, b)| a != b)
            .or(self.near)
            .map(|(a, b)| b - a)
    }
}

/// The cheap lower bound of a patch pair alone: the bounding spheres of the disks around
/// the pieces and the spherical-shell bound of arcs centred near the axis (closed form),
/// and, while that does not reach `prune_at`, the arcs' torus bound (or the disks'
/// solid-torus bound and the torus/cone bound when a piece is straight), and then the
/// pieces' convex-hull bound ([`mod@crate::query::bound::hull_bound`]) iterated from the direction of the near
/// points (it separates short pieces whose tori overlap), whose nearest points
/// are a second start for [`super::patch_upper::realised`]. Two cones have no near points of their own: the
/// hull iteration gives both.
///
/// `precision` is the caller's: where the hulls lie within it of the pieces (their chords'
/// sagittas, `grow`) and are apart, the hull bound and the hulls' nearest points stand in
/// for the tori's bound and near points (0 never skips them).
pub fn patch_lower(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    prune_at: f64,
    precision: f64,
    memo: &mut CoreMemo,
) -> PatchLower {
    let pruned = |lower| PatchLower {
        lower,
        near: None,
        hull_near: None,
    };
    let (da, db) = (a.arc.bounding_disk(), b.arc.bounding_disk());
    let spheres = sphere_bound(&da, &db, pos_ab)
        .max(shell_bound(&a.arc, &b.arc, pos_ab))
        .max(slab_bound_in(&a.arc, &b.arc, &da, &db, pos_ab));
    if spheres >= prune_at {
        return pruned(spheres);
    }
    // With a pruning level, the pieces' hull bound first: it prunes most pairs that the
    // closed forms leave, before any circle/circle minimum or circle/cone solve (stage-1
    // time -10 to -15%, `query_cost --poses 100`, eps 1e-4).
    let hulls = PieceHull::of_piece(&a.arc).zip(PieceHull::of_piece(&b.arc));
    let mut early = None;
    if let (true, Some((ha, hb))) = (prune_at.is_finite(), &hulls) {
        let dir = axis_direction(&da, &db, pos_ab);
        // The hulls' nearest points are wanted when they will stand in for the tori's
        // (hulls within `precision` of the pieces) or when nothing else gives near points
        // (two cones): the iteration then runs on below the level instead of giving up. For
        // two cones this replaces a second iteration from the mid points (8.6% of the query
        // time on pawn-pawn and table-lightmill at eps 1e-4); for fine hulls it replaces the
        // tori, whose near points on the cup's waist started realised pairs too far from the
        // minimum (exact patch solves per query, eps 1e-4: cup-bottle 0.4 -> 0.2).
        let fine = ha.grow + hb.grow <= precision;
        let two_cones = matches!(
            (a.arc, b.arc),
            (ProfileArc::Segment { .. }, ProfileArc::Segment { .. })
        );
        let (hull, witness) = if fine || two_cones {
            ha.nearest_points(hb, pos_ab, &dir, prune_at)
        } else {
            ha.bound_and_witness(hb, pos_ab, &dir, prune_at, false)
        };
        if hull >= prune_at {
            return pruned(hull);
        }
        if let (true, true, Some(w)) = (fine, hull > 0.0, witness) {
            return PatchLower {
                lower: spheres.max(hull),
                near: Some(w),
                hull_near: None,
            };
        }
        early = Some((hull, witness));
    }
    let (lower, near_a, near_b) = match arc_tori(a, b, pos_ab, memo) {
        // An arc of large radius lies on a fat torus; its disk's solid torus is thinner
        // when the piece is short (leaves are cut to [`crate::bvh::tree::MAX_LEAF_RADIUS_REL`]).
        Some(t)
            if t.lower.max(spheres) < prune_at && t.lower.max(spheres) <= da.radius + db.radius =>
        {
            let disks = torus_bound(&da, &db, pos_ab);
            (spheres.max(t.lower).max(disks), t.near_a, t.near_b)
        }
        Some(t) => (spheres.max(t.lower), t.near_a, t.near_b),
        None => {
            let disks = spheres.max(torus_bound(&da, &db, pos_ab));
            if disks >= prune_at {
                return pruned(disks);
            }
            match arc_cone(a, b, pos_ab) {
                Some(t) => (disks.max(t.lower), t.near_a, t.near_b),
                // Two cones: the frusta's hull bound (exact up to rounding for frusta on
                // each other's convex side) and its nearest points as the realised start;
                // the pieces' mid points when the hulls overlap.
                None => {
                    let mut starts = match early {
                        Some((hull, hull_near)) => PatchLower {
                            lower: hull,
                            near: Some((mid_point(a), pos_ab * mid_point(b))),
                            hull_near,
                        },
                        None => mid_and_hull_starts(a, b, pos_ab, prune_at, true),
                    };
                    starts.lower = disks.max(starts.lower);
                    if starts.lower >= prune_at {
                        return pruned(starts.lower);
                    }
                    return starts;
                }
            }
        }
    };
    // The hull bound (unless computed above, with a level): tight where the tori overlap
    // but the short pieces themselves are well apart (second order in the piece length);
    // without a level, iterated from the near points' direction.
    let (lower, hull_near) = if let Some((hull, witness)) = early {
        (lower.max(hull), witness)
    } else if let (true, Some((ha, hb))) = (lower < prune_at, &hulls) {
        let (hull, witness) = ha.bound_and_witness(hb, pos_ab, &(near_b - near_a), prune_at, false);
        (lower.max(hull), witness)
    } else {
        (lower, None)
    };
    PatchLower {
        lower,
        near: Some((near_a, near_b)),
        hull_near,
    }
}

/// Starts for a realised pair of two pieces without near points of their own (two cones):
/// the pieces' mid points, and the hulls' nearest points from the hull iteration started
/// along them ([`hull_bound_and_witness`] with `enough` and `converge`), whose bound is
/// `lower`.
pub(super) fn mid_and_hull_starts(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    enough: f64,
    converge: bool,
) -> PatchLower {
    let (mid_a, mid_b) = (mid_point(a), pos_ab * mid_point(b));
    let (lower, hull_near) =
        hull_bound_and_witness(&a.arc, &b.arc, pos_ab, &(mid_b - mid_a), enough, converge);
    PatchLower {
        lower,
        near: Some((mid_a, mid_b)),
        hull_near,
    }
}

/// The mid point of a patch's piece at revolution angle 0 (the patch's frame).
pub(super) fn mid_point(p: &Patch) -> Point3<f64> {
    let m = p.arc.point_at(0.5);
    Point3::new(m.x, 0.0, m.y)
}

/// The arcs' torus bound and the tori's closest points (A's frame).
pub(super) struct ArcTori {
    pub(super) lower: f64,
    /// Point of A's torus closest to B's torus (on the common normal), and vice versa.
    pub(super) near_a: Point3<f64>,
    pub(super) near_b: Point3<f64>,
}

pub(super) fn arc_tori(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    memo: &mut CoreMemo,
) -> Option<ArcTori> {
    let (
        ProfileArc::Arc {
            center: ca,
            radius: ra,
            ..
        },
        ProfileArc::Arc {
            center: cb,
            radius: rb,
            ..
        },
    ) = (a.arc, b.arc)
    else {
        return None;
    };
    let md = memo.get(ca, cb, pos_ab);
    let scale = 1.0
        + ca.y.abs()
        + cb.y.abs()
        + ca.x.abs()
        + cb.x.abs()
        + ra
        + rb
        + pos_ab.translation.vector.norm();
    let lower = md.distance - ra - rb - BOUND_SLACK * scale;
    let w = md.point_b - md.point_a;
    let n = w.norm();
    let u = if n > 0.0 {
        w / n
    } else {
        nalgebra::Vector3::z()
    };
    Some(ArcTori {
        lower,
        near_a: md.point_a + u * ra,
        near_b: md.point_b - u * rb,
    })
}

/// A toroidal patch against a cone patch (either order): the torus lies within `r` of its
/// major circle `M`, so `dist >= dist(M, cone patch) - r`, and `dist(M, cone patch)` is
/// computed exactly by [`circle_segment_distance`]. `None` unless exactly one piece is
/// straight.
fn arc_cone(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> Option<ArcTori> {
    let (torus, cone, pos_ct, swapped) = match (a.arc, b.arc) {
        (ProfileArc::Arc { .. }, ProfileArc::Segment { .. }) => (a, b, pos_ab.inverse(), false),
        (ProfileArc::Segment { .. }, ProfileArc::Arc { .. }) => (b, a, *pos_ab, true),
        _ => return None,
    };
    let ProfileArc::Arc { center, radius, .. } = torus.arc else {
        return None;
    };
    let ProfileArc::Segment { start, end } = cone.arc else {
        return None;
    };
    // The major circle of the torus in the cone's frame.
    let major = ParamCircle::parallel(center.x, center.y, &pos_ct);
    let found = circle_segment_distance(&major, start, end)?;
    let theta = found.theta;
    // Unresolved cone angles leave no lower bound here: the caller's volume bounds stand.
    let dist = if found.complete {
        found.distance
    } else {
        f64::NEG_INFINITY
    };
    let scale = 1.0
        + center.x.abs()
        + center.y.abs()
        + radius
        + pos_ct.translation.vector.norm()
        + start.coords.norm()
        + end.coords.norm();
    let lower = dist - radius - BOUND_SLACK * scale;
    // Realised start: the major circle's point, its closest point on the cone patch, and the
    // torus point towards it (cone's frame).
    let core = major.point(theta);
    let on_cone = cone.point_distance(&core).1;
    let w = on_cone - core;
    let wn = w.norm();
    let on_torus = if wn > 0.0 {
        core + w * (radius / wn)
    } else {
        core
    };
    // Points are in the cone's frame: A's when swapped, else B's.
    let (near_a, near_b) = if swapped {
        (on_cone, on_torus)
    } else {
        (pos_ab * on_torus, pos_ab * on_cone)
    };
    Some(ArcTori {
        lower,
        near_a,
        near_b,
    })
}

/// `min over theta of dist(circle(theta), S)` for the revolved segment `S` from `start` to
/// `end` (circle in S's frame), with an angle where it is attained; `None` for a degenerate
/// segment.
///
/// **Exactness.** `g(theta)` is the planar distance from the circle point's meridian
/// coordinates `(rho, z)` to the segment. At a local minimum of `g` the foot on the segment
/// is either interior, where `g = |F|`, `F = n . (rho, z) - c` the signed distance to the
/// segment's line, so the angle is a zero of `F` (a crossing: distance 0, up to the root's
/// rounding) or a critical angle of `F` ([`line_field_levels`], [`line_field_critical`];
/// the squared equations include both mirror branches and the circle's passages through
/// the axis, a superset);
/// or an end point, whose distance along the circle is bounded below by the circle/circle
/// minimum to that end's parallel ([`mod@crate::circle::min_distance`]). The minimum over
/// these candidates, keeping only interior candidates whose foot lies on the segment, is
/// the distance (each candidate is a realised value, and every local minimum is covered).
pub(super) fn circle_segment_distance(
    circle: &ParamCircle,
    start: Point2<f64>,
    end: Point2<f64>,
) -> Option<CircleSegment> {
    let dir = end - start;
    let len = dir.norm();
    if len == 0.0 || !len.is_finite() {
        return None;
    }
    let d = dir / len;
    let n = Vector2::new(-d.y, d.x);
    let c = n.dot(&start.coords);
    // Planar distance to the segment when the foot is interior, else None.
    let interior = |theta: f64| {
        let p = circle.point(theta);
        let q = Point2::new(p.x.hypot(p.y), p.z);
        let t = (q - start).dot(&d);
        (0.0..=len)
            .contains(&t)
            .then(|| (n.dot(&q.coords) - c).abs())
    };
    // End parallels.
    let mut best = (f64::INFINITY, 0.0);
    for e in [start, end] {
        let (dist, theta) = circle_parallel_distance(circle, e);
        if dist < best.0 {
            best = (dist, theta);
        }
    }
    // Level and critical angles of both mirror branches (a superset): each is measured
    // exactly where its foot is interior, so angles of the mirror branch are harmless.
    let mut angles = Vec::with_capacity(24);
    let levels = line_field_levels(circle, n, c, &mut angles);
    if levels == FieldAngles::Constant {
        // The circle lies on the extended cone: F is constant along it.
        angles.push(0.0);
    }
    let critical = line_field_critical(circle, n, &mut angles);
    if critical == FieldAngles::Constant {
        // F constant along the circle: every angle is critical.
        angles.push(0.0);
    }
    for &theta in &angles {
        if let Some(dist) = interior(theta) {
            if dist < best.0 {
                best = (dist, theta);
            }
        }
    }
    let complete = ![levels, critical].contains(&FieldAngles::Clustered);
    Some(CircleSegment {
        distance: best.0,
        theta: best.1,
        complete,
    })
}

/// What [`circle_segment_distance`] found.
pub(super) struct CircleSegment {
    /// The least candidate distance: always realised (an upper bound of the distance), and
    /// the distance itself when `complete`.
    pub distance: f64,
    /// An angle on the circle where `distance` is attained.
    pub theta: f64,
    /// Every candidate angle was isolated; `false` when the cone's angles came out as
    /// clusters (`angles::meridian_line`, "Clusters"), and then `distance` is no lower bound.
    pub complete: bool,
}

/// Minimum distance from a circle (a [`ParamCircle`] in the parallel's frame) to the
/// parallel of meridian point `e`, with an angle on the circle where it is attained.
fn circle_parallel_distance(circle: &ParamCircle, e: Point2<f64>) -> (f64, f64) {
    let parallel = parallel_circle(e.x, e.y, &Isometry3::identity());
    match as_circle3(circle) {
        Some(c3) => {
            let m = min_distance(&c3, &parallel);
            (m.distance, m.angle_a)
        }
        None => {
            let p = circle.o;
            let dist = (p.x.hypot(p.y) - e.x.abs()).hypot(p.z - e.y);
            (dist, 0.0)
        }
    }
}
