//! Convex-hull lower bounds of revolved pieces, converged by a support-point
//! iteration on the hulls' Minkowski difference (Gilbert, Johnson and Keerthi 1988).
//!
//! A revolved segment is a frustum surface: it lies in the convex hull of its two boundary
//! circles. A revolved arc of sweep at most pi lies within its sagitta
//! `h = r (1 - cos(sweep / 2))` of its chord (in each meridian plane, so also in 3-D), hence
//! within `h` of its chord's frustum. For any unit direction `n`, the support function of
//! the hull of a few circles is the largest of theirs, `n . c + r |n - (n . k) k|` (centre
//! `c`, unit normal `k`), so every point pair is at least `-h_B(-n) - h_A(n) - h_a - h_b`
//! apart: a valid bound for every `n`, exact up to the sagittas when `n` is the direction
//! of the closest points of the two hulls. Unlike the disk bounds its error shrinks with the
//! square of the piece length (the sagitta), but it is useless when one piece wraps around
//! the other (a peg inside a ring: the hull contains the peg).
//!
//! **Direction.** The bound is only as good as `n`. The iteration keeps a simplex of up to
//! four points of the Minkowski difference `D = H_B - H_A` and its point `v` closest to the
//! origin; the support point `w` of `D` against `v` gives the bound `v . w / |v|` for the
//! direction `v / |v|` and a new simplex vertex. `|v|` is an upper bound of the hulls'
//! distance, so the iteration stops when the two meet within [`GAP_REL`], when the bound
//! reaches the caller's level, or after [`MAX_ITERATIONS`]. Whatever stops it, the largest
//! bound seen is returned: every one of them is valid. Three naive steps (the previous
//! direction rule, `n` from the last support points) left the bound short of the level in
//! 72% of the leaf pairs that then went to an exact solve (848 pairs, three model pairs at
//! eps 1e-4) that the converged bound prunes.

use crate::bvh::hull::{HullRef, ParallelHull, PieceHull};
use crate::bvh::patch::ProfileArc;
pub use crate::query::simplex::PointPair;
use crate::query::simplex::Simplex;
use crate::tolerances::{BOUND_SLACK, GAP_REL, WITNESS_GAP_REL};
use nalgebra::{Isometry3, Vector3};

/// Support points computed at most per bound. The hulls are smooth (circles) where the
/// iteration converges linearly; 24 steps reach [`GAP_REL`] on the measured leaf pairs,
/// and a bound stopped early stays valid.
pub const MAX_ITERATIONS: usize = 24;

/// Support points computed at most when the caller gives no level (`enough` infinite):
/// before any leaf pair has given an upper bound a node key only orders the search, and
/// converging every key of the descent to the first leaf doubled the node-bound time
/// (pawn-pawn at eps 1e-4: 63 -> 108 us per query with full convergence, 67 with 3,
/// 74 with 5, 82 with 8 steps; `query_cost --poses 100`). [`ParallelHull::bound`] and
/// [`hull_bound`] are not limited: a caller that wants the hulls' distance gets it.
pub const UNBOUNDED_ITERATIONS: usize = 3;

/// Convex-hull lower bound of two revolved pieces (module doc), starting from direction
/// `dir` (from A towards B; any nonzero vector is valid). `-inf` for an arc of sweep above
/// pi or a zero direction.
pub fn hull_bound(
    a: &ProfileArc,
    b: &ProfileArc,
    pos_ab: &Isometry3<f64>,
    dir: &Vector3<f64>,
) -> f64 {
    hull_bound_and_witness(a, b, pos_ab, dir, f64::INFINITY, true).0
}

/// [`hull_bound`], stopping as soon as the bound reaches `enough` (see
/// [`ParallelHull::bound_until`] for an infinite `enough`).
pub fn hull_bound_until(
    a: &ProfileArc,
    b: &ProfileArc,
    pos_ab: &Isometry3<f64>,
    dir: &Vector3<f64>,
    enough: f64,
) -> f64 {
    hull_bound_and_witness(a, b, pos_ab, dir, enough, false).0
}

/// The pieces' hull bound and the hulls' nearest points ([`ParallelHull::bound_and_witness`]);
/// `-inf` and `None` for an arc of sweep above pi.
pub fn hull_bound_and_witness(
    a: &ProfileArc,
    b: &ProfileArc,
    pos_ab: &Isometry3<f64>,
    dir: &Vector3<f64>,
    enough: f64,
    converge: bool,
) -> (f64, Option<PointPair>) {
    match (PieceHull::of_piece(a), PieceHull::of_piece(b)) {
        (Some(ha), Some(hb)) => ha.bound_and_witness(&hb, pos_ab, dir, enough, converge),
        _ => (f64::NEG_INFINITY, None),
    }
}

impl HullRef<'_> {
    /// [`ParallelHull::bound_capped`] of this hull (frame A) against `other` (placed by
    /// `pos_ab`).
    pub fn bound_capped(
        &self,
        other: &HullRef<'_>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        enough: f64,
        cap: usize,
    ) -> f64 {
        match (*self, *other) {
            (HullRef::Node(a), HullRef::Node(b)) => a.bound_capped(b, pos_ab, dir, enough, cap),
            (HullRef::Node(a), HullRef::Upper(b)) => a.bound_capped(b, pos_ab, dir, enough, cap),
            (HullRef::Upper(a), HullRef::Node(b)) => a.bound_capped(b, pos_ab, dir, enough, cap),
            (HullRef::Upper(a), HullRef::Upper(b)) => a.bound_capped(b, pos_ab, dir, enough, cap),
        }
    }
}

impl<const N: usize> ParallelHull<N> {
    /// Lower bound of the distance between this set (frame A) and `other` (placed by
    /// `pos_ab`), starting from direction `dir` (module doc), iterated until it converges to
    /// the hulls' distance (or [`MAX_ITERATIONS`]).
    pub fn bound<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
    ) -> f64 {
        self.bound_and_witness(other, pos_ab, dir, f64::INFINITY, true)
            .0
    }

    /// [`ParallelHull::bound`], stopping as soon as the bound reaches `enough` or shows it
    /// out of reach; an infinite `enough` means no level (the bound only orders a search):
    /// then after at most [`UNBOUNDED_ITERATIONS`] support points.
    pub fn bound_until<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        enough: f64,
    ) -> f64 {
        let cap = if enough.is_finite() {
            MAX_ITERATIONS
        } else {
            UNBOUNDED_ITERATIONS
        };
        self.bound_capped(other, pos_ab, dir, enough, cap)
    }

    /// [`ParallelHull::bound_until`] after at most `cap` support points.
    pub fn bound_capped<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        enough: f64,
        cap: usize,
    ) -> f64 {
        self.separation(other, pos_ab, dir, Stop::bound(enough, cap))
            .0
    }

    /// [`ParallelHull::bound_until`] with the hulls' nearest points found by the
    /// iteration (A's frame; `None` when the hulls overlap): a start for a realised pair of
    /// the pieces (two cones have no closed-form nearest points). With `converge`
    /// the iteration runs on to the hulls' distance whatever `enough` (unless the bound
    /// reaches it): the nearest points are wanted, not only the bound.
    pub fn bound_and_witness<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        enough: f64,
        converge: bool,
    ) -> (f64, Option<PointPair>) {
        let cap = if converge || enough.is_finite() {
            MAX_ITERATIONS
        } else {
            UNBOUNDED_ITERATIONS
        };
        let stop = Stop {
            give_up: !converge,
            witness: true,
            ..Stop::bound(enough, cap)
        };
        self.separation(other, pos_ab, dir, stop)
    }

    /// The bound of [`ParallelHull::bound_and_witness`] with the hulls' nearest points to
    /// [`WITNESS_GAP_REL`]: iterated until the bound reaches `enough` or is within that
    /// fraction of the hulls' distance, never given up below `enough`. The points start a
    /// realised pair of the pieces, which projection and polishing refine further.
    pub fn nearest_points<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        enough: f64,
    ) -> (f64, Option<PointPair>) {
        let stop = Stop {
            give_up: false,
            gap: WITNESS_GAP_REL,
            witness: true,
            ..Stop::bound(enough, MAX_ITERATIONS)
        };
        self.separation(other, pos_ab, dir, stop)
    }

    /// [`hull_separation`] with the hulls' growth and the rounding slack subtracted.
    fn separation<const M: usize>(
        &self,
        other: &ParallelHull<M>,
        pos_ab: &Isometry3<f64>,
        dir: &Vector3<f64>,
        stop: Stop,
    ) -> (f64, Option<PointPair>) {
        let t = pos_ab.translation.vector;
        let scale = 1.0 + t.norm() + self.size() + other.size();
        let slack = self.grow + other.grow + BOUND_SLACK * scale;
        let stop = Stop {
            enough: stop.enough + slack,
            ..stop
        };
        let (lower, witness) = hull_separation(self, other, pos_ab, dir, &stop);
        (lower - slack, witness)
    }
}

/// When a hull iteration ([`hull_separation`]) stops.
#[derive(Debug, Clone, Copy)]
struct Stop {
    /// Stop once the bound reaches this.
    enough: f64,
    /// Support points at most.
    cap: usize,
    /// Stop once `enough` is out of reach (a point of the Minkowski difference is nearer).
    give_up: bool,
    /// Converged once the bound is within this fraction of the hulls' distance.
    gap: f64,
    /// The nearest points are wanted: the simplex is updated after the last support point.
    witness: bool,
}

impl Stop {
    /// A bound alone, to `enough`, after at most `cap` support points.
    fn bound(enough: f64, cap: usize) -> Stop {
        Stop {
            enough,
            cap,
            give_up: true,
            gap: GAP_REL,
            witness: false,
        }
    }
}

/// A lower bound of the distance between the hulls of `a` (frame A) and `b` (placed by
/// `pos_ab`), iterated from direction `dir` until it reaches `stop.enough`, converges (to
/// `stop.gap`), or has computed `stop.cap` support points (module doc); with
/// `stop.give_up`, also once `enough` is out of reach.
fn hull_separation<const N: usize, const M: usize>(
    a: &ParallelHull<N>,
    b: &ParallelHull<M>,
    pos_ab: &Isometry3<f64>,
    dir: &Vector3<f64>,
    stop: &Stop,
) -> (f64, Option<PointPair>) {
    let Stop {
        enough,
        cap,
        give_up,
        gap,
        witness,
    } = *stop;
    // The rotation as a matrix once: each step rotates a direction and a point (a matrix
    // product is cheaper than the quaternion's).
    let rot_ab = pos_ab.rotation.to_rotation_matrix();
    let t = pos_ab.translation.vector;
    // For unit `n`: the bound `-h_B(-n) - h_A(n)` and the point of D = B - A that attains
    // min n . z (A's frame).
    let lowest = |n: &Vector3<f64>| {
        let (va, pa) = a.support(n);
        let (vb, qb) = b.support(&-rot_ab.inverse_transform_vector(n));
        let qb = rot_ab * qb + t;
        let lower = -(vb - n.dot(&t)) - va;
        (lower, qb - pa, (pa, qb))
    };
    let mut v = *dir;
    let mut simplex = Simplex::default();
    let mut best = f64::NEG_INFINITY;
    for step in 0..cap {
        let vn = v.norm();
        if vn == 0.0 || !vn.is_finite() {
            // The origin is in the simplex: the hulls overlap (or the start was void).
            break;
        }
        let n = v / vn;
        let (lower, w, pair) = lowest(&n);
        best = best.max(lower);
        // Past the first step `v` is a point of D, so `|v|` bounds the hulls' distance from
        // above: below a finite `enough`, no direction can prove `enough`.
        let hopeless = give_up && enough.is_finite() && vn < enough;
        let converged = step > 0 && (hopeless || vn - lower <= gap * vn);
        // Without the nearest points, the simplex step after the last support point is
        // wasted (one step of a node key over spirals is most of its cost).
        if best >= enough || converged || (step + 1 == cap && !witness) {
            break;
        }
        if !simplex.push(w, pair) {
            break;
        }
        v = simplex.closest_to_origin();
    }
    (best, simplex.witness())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bvh::hull::{NodeHull, UpperHull, ARC_CHORDS};
    use crate::test_rng::Lcg;
    use crate::tolerances::ROTATION_ROUNDING;
    use nalgebra::{Point2, Point3};
    use nalgebra::{Translation3, UnitQuaternion};

    /// The bound of one fixed direction `n` (unit, A towards B), without iteration.
    fn bound_along(a: &PieceHull, b: &PieceHull, pos_ab: &Isometry3<f64>, n: &Vector3<f64>) -> f64 {
        let (va, _) = a.support(n);
        let (vb, _) = b.support(&(pos_ab.rotation.inverse() * -n));
        -(vb - n.dot(&pos_ab.translation.vector)) - va - a.grow - b.grow
    }

    /// The union hull's support function is the larger of the two hulls' in every direction
    /// (the 2-D convex hull's right chain keeps every point a support can pick), for random
    /// node hulls of arcs and segments, some reaching the axis; growth the larger of two.
    #[test]
    fn union_hull_supports_both() {
        let mut s = Lcg(11);
        let mut unions = 0;
        for _ in 0..3000 {
            let piece = |s: &mut Lcg| {
                let start = Point2::new(
                    if s.f() < 0.2 { 0.0 } else { 2.0 * s.f() },
                    2.0 * s.f() - 1.0,
                );
                if s.f() < 0.4 {
                    ProfileArc::Segment {
                        start,
                        end: Point2::new(2.0 * s.f(), 2.0 * s.f() - 1.0),
                    }
                } else {
                    ProfileArc::Arc {
                        center: Point2::new(1.0 + s.f(), s.f()),
                        radius: 0.1 + 0.5 * s.f(),
                        phi_start: 6.0 * s.f(),
                        sweep: (2.0 * s.f() - 1.0) * 2.5,
                    }
                }
            };
            let (Some(a), Some(b)) = (
                NodeHull::of_pieces(&[piece(&mut s)], 0.01 * s.f()),
                NodeHull::of_pieces(&[piece(&mut s)], 0.01 * s.f()),
            ) else {
                continue;
            };
            let Some(u) = UpperHull::union_of(&a, &b) else {
                continue;
            };
            unions += 1;
            assert_eq!(u.grow, a.grow.max(b.grow));
            for _ in 0..20 {
                let n = Vector3::new(2.0 * s.f() - 1.0, 2.0 * s.f() - 1.0, 2.0 * s.f() - 1.0);
                let both = a.support(&n).0.max(b.support(&n).0);
                let got = u.support(&n).0;
                assert!(
                    (got - both).abs() <= 1e-12 * (1.0 + both.abs()),
                    "{got} vs {both}"
                );
            }
        }
        assert!(unions > 2000, "{unions}");
    }

    /// An arc's chord points (placed by rotation, [`PieceHull::of_piece`]) lie on the arc
    /// within the rounding the hull grows by, at their equally spaced angles.
    #[test]
    fn chord_points_lie_on_the_arc() {
        let mut s = Lcg(5);
        for _ in 0..2000 {
            let (center, radius) = (
                Point2::new(4.0 * s.f() - 1.0, 4.0 * s.f() - 2.0),
                1e-3 + 3.0 * s.f(),
            );
            let (phi_start, sweep) = (
                20.0 * s.f() - 10.0,
                (2.0 * s.f() - 1.0) * std::f64::consts::PI,
            );
            let arc = ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            };
            let h = PieceHull::of_piece(&arc).unwrap();
            let pts = h.points_for_tests();
            assert_eq!(pts.len(), ARC_CHORDS + 1);
            let allowance = ROTATION_ROUNDING * ARC_CHORDS as f64 * (radius + center.coords.norm());
            for (k, p) in pts.iter().enumerate() {
                let exact = arc.point_at(k as f64 / ARC_CHORDS as f64);
                assert!(
                    (p - exact).norm() <= allowance,
                    "{k}: {} > {allowance}",
                    (p - exact).norm()
                );
            }
        }
    }

    /// The iterated bound reaches the best of 20,000 directions spread over the sphere, from a
    /// start pointing away from B, for random chords and arcs: it converges to the hulls'
    /// distance. Three naive steps of the former rule fail this (case 0: 2.068 against
    /// 2.141).
    #[test]
    fn iteration_reaches_the_best_direction() {
        let dirs: Vec<Vector3<f64>> = (0..20_000)
            .map(|i| {
                let z = 1.0 - 2.0 * (i as f64 + 0.5) / 20_000.0;
                let phi = i as f64 * 2.399_963_229_728_653;
                let r = (1.0 - z * z).sqrt();
                Vector3::new(r * phi.cos(), r * phi.sin(), z)
            })
            .collect();
        let mut s = Lcg(41);
        let mut f = move || s.f();
        let mut separated = 0;
        for case in 0..120 {
            let mut piece = |k: usize| -> ProfileArc {
                if k.is_multiple_of(2) {
                    ProfileArc::Segment {
                        start: Point2::new(0.05 + f(), f() - 0.5),
                        end: Point2::new(0.05 + f(), f() - 0.5),
                    }
                } else {
                    ProfileArc::Arc {
                        center: Point2::new(0.6 + f(), f() - 0.5),
                        radius: 0.1 + 0.4 * f(),
                        phi_start: 6.0 * f(),
                        sweep: 2.0 * f() - 1.0,
                    }
                }
            };
            let (a, b) = (piece(case), piece(case / 2));
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(f(), f(), f()) * 3.0);
            let t = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 5.0;
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            let (ha, hb) = (
                PieceHull::of_piece(&a).unwrap(),
                PieceHull::of_piece(&b).unwrap(),
            );
            let best = dirs
                .iter()
                .map(|n| bound_along(&ha, &hb, &pos, n))
                .fold(f64::NEG_INFINITY, f64::max);
            if best <= 0.0 {
                continue;
            }
            separated += 1;
            // A start pointing away from B.
            let start = -(pos * Point3::origin() - Point3::origin());
            let iterated = ha.bound(&hb, &pos, &start);
            // The iteration stops within GAP_REL (1e-6) of its upper estimate, the hulls'
            // distance, which is at least the best sampled direction's bound (at most ~6
            // here); its validity is `bounds::tests::hull_bound_is_valid_for_every_direction`.
            assert!(
                iterated >= best - 1e-5,
                "case {case}: iterated {iterated} < best direction {best}"
            );
            // The witness points lie in their hulls (no direction's support is exceeded)
            // and are as far apart as the converged bound says (before the sagittas).
            let (lower, witness) = ha.bound_and_witness(&hb, &pos, &start, f64::INFINITY, true);
            let (p, q) = witness.expect("separated hulls have nearest points");
            let separation = lower + ha.grow + hb.grow;
            assert!(
                (q - p).norm() - separation <= 1e-5,
                "case {case}: {} vs {separation}",
                (q - p).norm()
            );
            let q_b = pos.inverse_transform_point(&q);
            for n in dirs.iter().step_by(97) {
                assert!(
                    n.dot(&p.coords) <= ha.support(n).0 + 1e-12,
                    "case {case}: p outside A"
                );
                assert!(
                    n.dot(&q_b.coords) <= hb.support(n).0 + 1e-12,
                    "case {case}: q outside B"
                );
            }
        }
        assert!(separated > 40, "{separated} separated cases");
    }
}
