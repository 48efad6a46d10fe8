//! A rigorous lower bound of the distance between two patches by subdivision, for the patch
//! pairs whose exact kernel had to fall back to a sampled scan (continua of binormals,
//! intersecting major circles, degenerate line fields): a sampled value is a distance
//! between two real surface points, hence a valid *upper* bound, but it may miss the
//! minimum, so it must never resolve a *lower* bound (a lower bound must be provably at most the true distance: lower bounds are true
//! lower bounds).
//!
//! **Method.** Best-first branch and bound over pairs of sub-pieces `(a[s0, s1], b[u0, u1])`.
//! Each sub-piece lies in a disk of the meridian half-plane ([`ProfileArc::bounding_disk`]: the chord's
//! Thales disk for sweeps up to pi), and the revolved sub-surfaces lie in the solid tori of
//! those disks, whose distance is bounded below by [`torus_bound`] (proof in
//! [`crate::query::bound::node_pair`]). The sub-piece pairs always cover both patches, so the smallest key
//! among the pairs still queued is a lower bound of the patch distance at every step; the
//! search pops that smallest key and splits the larger of its two pieces in halves.
//!
//! A sub-piece pair on a sphere (or close to one) also has the spherical-shell bound of
//! [`shell_bound`], exact for a ball touching a surface along a circle. Given a separating
//! direction (the caller's near points), every cell also gets the convex-hull bound of
//! [`crate::query::bound::hull_bound::hull_bound`]: chord frusta minus sagittas, whose error shrinks with the square of the
//! sub-piece length where the disk bounds' shrinks linearly; the torus bound (a circle/circle
//! minimum) is then computed only for cells the closed forms leave below the target.
//!
//! **Stopping.** It returns 0 at once when the upper bound is within `precision` of 0 (a
//! distance is never negative). It stops when the smallest key is within `precision` of a known upper bound
//! (the kernel's sampled value), or when the popped pair is finer than `precision` (its
//! disks' radii sum to at most `precision / 2`, so its key is within `precision` of the
//! distance between its pieces), or after `max_pairs` bounds. In every case the returned
//! value is the smallest queued key: valid however early the search stops, only less tight.

use crate::bvh::patch::ProfileArc;
use crate::query::bound::hull_bound::hull_bound_until;
use crate::query::bound::node_pair::{shell_bound, slab_bound_in, torus_bound};
use nalgebra::{Isometry3, Vector3};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Torus bounds computed per certified patch pair at most: about 2-5 ms at ~1.2 us each. The
/// fallback is rare (degenerate poses), and a bound cut short stays valid, only looser.
pub const CERTIFY_MAX_PAIRS: usize = 4096;

/// One queued pair of pieces (`T`: sub-piece ranges here, sector indices in
/// [`super::sectors`]) with its lower bound and the sum of their radii.
#[derive(Debug, Clone, Copy)]
pub(super) struct Cell<T> {
    pub key: f64,
    pub a: T,
    pub b: T,
    pub radii: f64,
}

impl<T> PartialEq for Cell<T> {
    fn eq(&self, o: &Self) -> bool {
        self.key == o.key
    }
}
impl<T> Eq for Cell<T> {}
impl<T> PartialOrd for Cell<T> {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl<T> Ord for Cell<T> {
    /// Smallest key first (BinaryHeap is a max-heap).
    fn cmp(&self, o: &Self) -> Ordering {
        o.key.total_cmp(&self.key)
    }
}

/// A piece split so that no part sweeps more than a quarter turn (so that its disk is the
/// chord's Thales disk, not the full circle).
pub(super) fn initial_ranges(p: &ProfileArc) -> Vec<(f64, f64)> {
    let n = match *p {
        ProfileArc::Arc { sweep, .. } => {
            (sweep.abs() / std::f64::consts::FRAC_PI_2).ceil() as usize
        }
        ProfileArc::Segment { .. } => 1,
    }
    .max(1);
    (0..n)
        .map(|i| (i as f64 / n as f64, (i + 1) as f64 / n as f64))
        .collect()
}

/// Rigorous lower bound of the distance between the revolved pieces `a` (frame A) and `b`
/// (placed by `pos_ab`), searched to `precision` below `upper` (module doc); `dir`, when
/// given, is the first direction of the cells' hull bounds (any direction is valid).
pub fn patch_lower_bound(
    a: &ProfileArc,
    b: &ProfileArc,
    pos_ab: &Isometry3<f64>,
    upper: f64,
    precision: f64,
    max_pairs: usize,
    dir: Option<&Vector3<f64>>,
) -> f64 {
    // A distance is at least 0, which already meets the stopping rule when `upper` is within
    // `precision` of 0: coincident or touching patches (a solid and its copy offset by 1e-9)
    // used to split until `max_pairs`, 2-5 ms per patch pair, for a bound no better than 0.
    if upper <= precision {
        return upper.min(0.0);
    }
    let cell = |ra: (f64, f64), rb: (f64, f64), parent: f64| {
        let (sa, sb) = (a.sub_piece(ra.0, ra.1), b.sub_piece(rb.0, rb.1));
        let (da, db) = (sa.bounding_disk(), sb.bounding_disk());
        let shell = shell_bound(&sa, &sb, pos_ab).max(slab_bound_in(&sa, &sb, &da, &db, pos_ab));
        let hull = dir.map_or(f64::NEG_INFINITY, |n| {
            hull_bound_until(&sa, &sb, pos_ab, n, upper)
        });
        let mut key = parent.max(shell).max(hull);
        // The torus bound (a circle/circle minimum, the expensive part) only where the
        // closed forms do not already reach the search's target.
        if key < upper - precision {
            key = key.max(torus_bound(&da, &db, pos_ab));
        }
        Cell {
            key,
            a: ra,
            b: rb,
            radii: da.radius + db.radius,
        }
    };
    let mut heap = BinaryHeap::new();
    for ra in initial_ranges(a) {
        for rb in initial_ranges(b) {
            heap.push(cell(ra, rb, f64::NEG_INFINITY));
        }
    }
    let mut computed = heap.len();
    while let Some(c) = heap.pop() {
        let fine = c.radii <= 0.5 * precision;
        if c.key >= upper - precision || fine || computed >= max_pairs {
            return c.key.min(upper);
        }
        let len = |r: (f64, f64), p: &ProfileArc| (r.1 - r.0) * p.length();
        let halves = |r: (f64, f64)| {
            let m = 0.5 * (r.0 + r.1);
            [(r.0, m), (m, r.1)]
        };
        if len(c.a, a) >= len(c.b, b) {
            for ra in halves(c.a) {
                heap.push(cell(ra, c.b, c.key));
            }
        } else {
            for rb in halves(c.b) {
                heap.push(cell(c.a, rb, c.key));
            }
        }
        computed += 2;
    }
    upper
}

#[cfg(test)]
mod tests {
    use super::super::sectors::sector_lower_bound;
    use super::*;
    use crate::nearest::NearestPoint;
    use crate::test_rng::Lcg;
    use nalgebra::{Point2, Translation3, UnitQuaternion, Vector3};

    /// Coincident patches (a piece against itself, offset by 1e-9) with an upper bound within
    /// the precision of 0 get the bound 0 at once, not after splitting to the budget: with a
    /// budget of one split the search itself could only return a torus key far below 0.
    #[test]
    fn coincident_patches_get_zero_at_once() {
        let arc = ProfileArc::Arc {
            center: Point2::new(1.0, 0.0),
            radius: 0.5,
            phi_start: -1.0,
            sweep: 2.0,
        };
        let pos = Isometry3::translation(1e-9, 0.0, 0.0);
        assert_eq!(
            patch_lower_bound(&arc, &arc, &pos, 1e-9, 1e-5, 2, None),
            0.0
        );
        // Above the precision the search runs (and stays a valid bound).
        let lb = patch_lower_bound(&arc, &arc, &pos, 1e-3, 1e-5, 2, None);
        assert!(lb < 0.0, "{lb}");
    }

    /// The bound never exceeds a dense sampling of the true distance (an upper estimate)
    /// and, with budget enough, comes within the precision of it; the same for the sector
    /// subdivision ([`super::super::sectors`]).
    #[test]
    fn bound_is_valid_and_tight() {
        let mut s = Lcg(11);
        let mut f = move || s.f();
        for case in 0..60 {
            let arc = |f: &mut dyn FnMut() -> f64| ProfileArc::Arc {
                center: Point2::new(0.6 + f(), f() - 0.5),
                radius: 0.1 + 0.4 * f(),
                phi_start: 6.0 * f(),
                sweep: 2.0 * f() - 1.0,
            };
            let seg = |f: &mut dyn FnMut() -> f64| ProfileArc::Segment {
                start: Point2::new(0.1 + f(), f()),
                end: Point2::new(0.1 + f(), f()),
            };
            let a = if case % 2 == 0 {
                arc(&mut f)
            } else {
                seg(&mut f)
            };
            let b = if case % 3 == 0 {
                seg(&mut f)
            } else {
                arc(&mut f)
            };
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(f(), f(), f()) * 3.0);
            let t = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 2.0;
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            // Dense sampling of A's surface, each sample measured exactly against B's
            // surface (planar distance in B's meridian plane): an upper estimate.
            let n = 400;
            let pos_ba = pos.inverse();
            let mut sampled = f64::INFINITY;
            for i in 0..=n {
                let m = a.point_at(i as f64 / n as f64);
                for k in 0..n {
                    let th = k as f64 * std::f64::consts::TAU / n as f64;
                    let x = pos_ba * nalgebra::Point3::new(m.x * th.cos(), m.x * th.sin(), m.y);
                    let d = b.nearest(Point2::new(x.x.hypot(x.y), x.z)).0;
                    sampled = sampled.min(d);
                }
            }
            let hint = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5);
            let profile = patch_lower_bound(&a, &b, &pos, sampled, 1e-3, 1 << 20, None);
            let sectors = sector_lower_bound(&a, &b, &pos, sampled, 1e-3, 1 << 20, Some(&hint));
            for (method, lb) in [("profile", profile), ("sectors", sectors)] {
                assert!(
                    lb <= sampled + 1e-12,
                    "case {case} ({method}): {lb} > sampled {sampled}"
                );
                // Sampling resolution: A's samples are at most 2 pi * 1.5 / 400 + 1.5 / 400
                // ~ 0.03 apart, so the sampled value is within that of the truth; the bound
                // must be within that plus its precision 1e-3.
                assert!(
                    lb >= sampled - 0.035,
                    "case {case} ({method}): {lb} far below {sampled}"
                );
            }
            // With budget enough both searches end within the precision below the truth (or
            // at the sampled value), and neither is above it: two independent methods agree.
            assert!(
                (profile - sectors).abs() <= 1e-3 + 1e-9,
                "case {case}: profile {profile} and sectors {sectors} disagree"
            );
        }
    }
}
