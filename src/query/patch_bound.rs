//! Stage 1 of a leaf pair (issue 11, the cost model in [`super`]): a cheap lower bound
//! and a realised upper bound of the distance between two patches, before any degree-8
//! solve.
//!
//! **Lower bound.** A toroidal patch lies on the torus of its arc: every point is at
//! distance `r` (the arc's radius) from the major circle `M` traced by the arc's centre
//! (for a centre with `rho < 0` the circle of radius `|rho|` still holds every revolved
//! point within `r`, since `|rho_x - |c|| <= rho_x + |c|`). So each patch is inside the
//! solid torus `{x : dist(x, M) <= r}` and, by the triangle inequality as in
//! [`super::bounds`], `dist(patch A, patch B) >= dist(M_A, M_B) - r_A - r_B`. The bound is
//! tight whenever the two tori's closest points lie on the patches, which is the common
//! case for the leaf pair that holds the minimum (paper section 3: the distance of two
//! toroidal patches is `l - r1 - r2`, `l` a binormal length). Any patch pair also has the
//! solid-torus bound of the disks around its pieces; the larger of the two is returned.
//!
//! **Upper bound.** Two points that lie on the patches: the tori's closest points (or the
//! disks' major circles' closest points for cones) projected onto the patches in their
//! meridian planes, alternated once. Their distance is a true upper bound of the patch
//! distance whatever the projection does.
//!
//! Cost: one circle/circle minimum ([`crate::circle::min_distance`], under 1 us for circles
//! in general position) and a few planar closest-point evaluations.

use super::binormal_kernel::parallel_circle;
use super::bounds::{sphere_bound, torus_bound, BOUND_SLACK};
use super::line_field::{line_field_critical, line_field_levels};
use super::patch::{Core, Patch, ProfileArc};
use super::sweep::ParamCircle;
use super::tree::Disk;
use crate::circle::min_distance;
use nalgebra::{Isometry3, Point2, Point3, Vector2};

/// Bounds of one patch pair's distance (A's frame).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PatchBounds {
    /// A rigorous lower bound of the patch distance.
    pub lower: f64,
    /// The distance between `point_a` and `point_b`, two points on the patches.
    pub upper: f64,
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
}

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

/// The cheap lower bound of a patch pair alone: the bounding spheres of the disks around
/// the pieces (closed form), and, while that does not reach `prune_at`, the arcs' torus
/// bound (or the disks' solid-torus bound when a piece is straight).
pub fn patch_lower(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    prune_at: f64,
    memo: &mut CoreMemo,
) -> f64 {
    let (da, db) = (Disk::around(&a.arc), Disk::around(&b.arc));
    let spheres = sphere_bound(&da, &db, pos_ab);
    if spheres >= prune_at {
        return spheres;
    }
    match arc_tori(a, b, pos_ab, memo) {
        Some(t) => spheres.max(t.lower),
        None => {
            let disks = spheres.max(torus_bound(&da, &db, pos_ab));
            if disks >= prune_at {
                return disks;
            }
            arc_cone(a, b, pos_ab).map_or(disks, |t| disks.max(t.lower))
        }
    }
}

/// Stage-1 bounds of a patch pair (module doc).
pub fn patch_bounds(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    memo: &mut CoreMemo,
) -> PatchBounds {
    let (da, db) = (Disk::around(&a.arc), Disk::around(&b.arc));
    let spheres = sphere_bound(&da, &db, pos_ab);
    let (lower, start_a, start_b) = match arc_tori(a, b, pos_ab, memo) {
        Some(t) => (spheres.max(t.lower), t.near_a, t.near_b),
        None => {
            let disks = spheres.max(torus_bound(&da, &db, pos_ab));
            match arc_cone(a, b, pos_ab) {
                Some(t) => (disks.max(t.lower), t.near_a, t.near_b),
                None => {
                    // Two cones: start from the pieces' mid points (a realised pair only).
                    let mid = |p: &Patch| {
                        let m = p.arc.point_at(0.5);
                        Point3::new(m.x, 0.0, m.y)
                    };
                    (disks, mid(a), pos_ab * mid(b))
                }
            }
        }
    };
    let (pa, pb) = realise(a, b, pos_ab, start_a, start_b);
    PatchBounds {
        lower,
        upper: (pa - pb).norm(),
        point_a: pa,
        point_b: pb,
    }
}

/// The arcs' torus bound and the tori's closest points (A's frame).
struct ArcTori {
    lower: f64,
    /// Point of A's torus closest to B's torus (on the common normal), and vice versa.
    near_a: Point3<f64>,
    near_b: Point3<f64>,
}

fn arc_tori(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>, memo: &mut CoreMemo) -> Option<ArcTori> {
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

/// A toroidal patch against a cone patch (either order): the torus lies within `r` of
/// its major circle `M`, the cone patch on the revolved full line of its segment (both
/// mirror branches), so `dist >= min over M of dist(., cone) - r`. Along `M` the distance to
/// the cone is `min(|F_+|, |F_-|)`, `F_s = s n_rho rho + n_z z - c` ([`super::line_field`]):
/// zero where `M` crosses the cone (level angles), else smallest at a critical angle. Both
/// sets of angles are roots of polynomials whose solver keeps every root, so no minimum is
/// lost. `None` unless exactly one piece is straight.
fn arc_cone(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> Option<ArcTori> {
    let (torus, cone, pos_ct, swapped) = match (a.arc, b.arc) {
        (ProfileArc::Arc { .. }, ProfileArc::Segment { .. }) => (a, b, pos_ab.inverse(), false),
        (ProfileArc::Segment { .. }, ProfileArc::Arc { .. }) => (b, a, *pos_ab, true),
        _ => return None,
    };
    let ProfileArc::Arc { center, radius, .. } = torus.arc else {
        return None;
    };
    let Core::Line { n, c } = cone.core() else {
        return None;
    };
    // The major circle of the torus in the cone's frame.
    let major = ParamCircle::parallel(center.x, center.y, &pos_ct);
    let (dist, theta) = circle_cone_distance(&major, n, c);
    let scale = 1.0
        + center.x.abs()
        + center.y.abs()
        + radius
        + pos_ct.translation.vector.norm()
        + cone.arc.start().coords.norm()
        + cone.arc.end().coords.norm();
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

/// `min over theta of dist(circle(theta), cone)` (circle in the cone's frame, the cone the
/// revolved full line `n . (rho, z) = c`), with an angle where it is attained.
fn circle_cone_distance(circle: &ParamCircle, n: Vector2<f64>, c: f64) -> (f64, f64) {
    let field = |theta: f64| {
        let p = circle.point(theta);
        let rho = p.x.hypot(p.y);
        let f_plus = n.x * rho + n.y * p.z - c;
        let f_minus = -n.x * rho + n.y * p.z - c;
        f_plus.abs().min(f_minus.abs())
    };
    let mut angles = Vec::with_capacity(16);
    if !line_field_levels(circle, n, c, &mut angles) {
        return (0.0, 0.0); // the circle lies on the cone
    }
    if let Some(&theta) = angles.first() {
        return (0.0, theta); // the circle crosses the cone
    }
    if !line_field_critical(circle, n, &mut angles) {
        return (field(0.0), 0.0); // constant along the circle
    }
    angles
        .iter()
        .map(|&t| (field(t), t))
        .fold((field(0.0), 0.0), |m, x| if x.0 < m.0 { x } else { m })
}

/// Two points on the patches near `xa` (A's frame, near A) and `xb` (A's frame, near B):
/// each projected onto its patch, then each patch's point projected against the other's,
/// keeping the closest of the realised pairs.
fn realise(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    xa: Point3<f64>,
    xb: Point3<f64>,
) -> (Point3<f64>, Point3<f64>) {
    let on_a = |x: &Point3<f64>| a.point_distance(x).1;
    let on_b = |x: &Point3<f64>| pos_ab * b.point_distance(&pos_ab.inverse_transform_point(x)).1;
    let pa = on_a(&xa);
    let pb = on_b(&xb);
    let mut best = (pa, pb, (pa - pb).norm());
    let qb = on_b(&pa);
    let d = (pa - qb).norm();
    if d < best.2 {
        best = (pa, qb, d);
    }
    let qa = on_a(&pb);
    let d = (qa - pb).norm();
    if d < best.2 {
        best = (qa, pb, d);
    }
    (best.0, best.1)
}
