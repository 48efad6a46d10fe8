//! Gauss-map restriction of the major-circle angles of two toroidal patches (paper
//! section 3.3).
//!
//! A common normal line of two toroidal patches is a binormal of their major circles
//! (section 3.2). Its direction `u` is a surface normal of both patches: with
//! `d(phi, theta) = cos phi e_rho(theta) + sin phi e_z` the unit vector from the major
//! circle to the profile point of arc angle `phi` at revolution angle `theta`, the line
//! through major-circle angle `theta_a` has `u = +-d_A(phi_a, theta_a)` for some `phi_a` in
//! A's arc range, and likewise for B. Taking the sign so that `u = d_A(phi_a, theta_a)`,
//! the condition on B reads `u . axis_B in S_B or -S_B` with `S_B = {sin psi : psi in B's
//! range}` (the Gauss image of a full revolution is a zone of latitudes about its axis).
//!
//! Writing `u` by latitude `lambda` and longitude: for arc angles with `cos phi >= 0`,
//! `lambda = phi` and the longitude is `theta_a`; for `cos phi <= 0`, `lambda = pi - phi`
//! and the longitude is `theta_a + pi`. With `axis_B = (k cos alpha, k sin alpha, a_z)` in
//! A's frame and `x = k cos(longitude - alpha)`,
//! `u . axis_B = h(lambda, x) = x cos lambda + a_z sin lambda`.
//! Because `cos lambda >= 0` on `[-pi/2, pi/2]`, both `max_lambda h` and `min_lambda h`
//! are non-decreasing in `x`, so the set of `x` for which `h` meets a target interval
//! `[w0, w1]` is exactly an interval `[x_lo, x_hi]` with
//! `x_lo = min_lambda (w0 - a_z sin lambda) / cos lambda` and
//! `x_hi = max_lambda (w1 - a_z sin lambda) / cos lambda`; each extremum is at an end of
//! the latitude range or where `sin lambda = a_z / w` (derivative
//! `(w sin lambda - a_z) / cos^2 lambda`). The longitudes with `k cos(. - alpha)` in that
//! interval are two arcs symmetric about `alpha`. The union over the (at most three)
//! constant-sign parts of A's range and the two target intervals is then covered by one
//! arc (the complement of the largest gap), which is what the circle solver takes.
//!
//! Every step widens outwards (arc ranges by the inclusive slack of the range test, the
//! cosine interval and the final arc by [`GAUSS_SLACK`]), so the restriction never loses a
//! binormal that the unrestricted computation would keep; tests check exactly that.

use crate::bvh::patch::{Patch, ProfileArc};
use crate::circle::AngleInterval;
use crate::tolerances::{ANGLE_SLACK, GAUSS_SLACK, MIN_AXIS_TILT};
use nalgebra::{Isometry3, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// At most two arcs of revolution angles (`None` in [`MajorRanges::Ranges`] = whole circle).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AngleArcs {
    arcs: [AngleInterval; 2],
    n: usize,
}

impl AngleArcs {
    /// The arcs.
    pub fn arcs(&self) -> &[AngleInterval] {
        &self.arcs[..self.n]
    }

    /// Total angle covered.
    pub fn total_len(&self) -> f64 {
        self.arcs().iter().map(|a| a.len).sum()
    }

    /// The smallest single arc covering both (for use as a filter).
    pub fn hull(&self) -> AngleInterval {
        if self.n == 1 {
            return self.arcs[0];
        }
        let [a, b] = self.arcs;
        // Either from a's start to b's end, or from b's start to a's end.
        let ab = (b.start - a.start).rem_euclid(TAU) + b.len;
        let ba = (a.start - b.start).rem_euclid(TAU) + a.len;
        let (start, len) = if ab <= ba {
            (a.start, ab)
        } else {
            (b.start, ba)
        };
        AngleInterval {
            start,
            len: len.min(TAU),
        }
    }

    /// Whether `theta` lies in one of the arcs (no extra slack: the arcs are widened).
    pub fn contains(&self, theta: f64) -> bool {
        self.arcs().iter().any(|a| a.contains(theta, 0.0))
    }
}

/// Result of the restriction for one patch pair.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum MajorRanges {
    /// The Gauss images do not overlap: no interior common normal exists.
    Disjoint,
    /// Revolution angles on each major circle where a common normal may start
    /// (`None`: the whole circle).
    Ranges {
        a: Option<AngleArcs>,
        b: Option<AngleArcs>,
    },
}

/// Gauss-map restriction (paper 3.3) of the major-circle angles of toroidal patches `a`
/// (frame A) and `b` (placed by `pos_ab`). Straight pieces are not restricted.
pub fn major_angle_ranges(a: &Patch, b: &Patch, pos_ab: &Isometry3<f64>) -> MajorRanges {
    let axis_b_in_a = pos_ab.rotation * Vector3::z();
    let axis_a_in_b = pos_ab.rotation.inverse() * Vector3::z();
    let ra = side_range(&a.arc, &b.arc, &axis_b_in_a);
    let rb = side_range(&b.arc, &a.arc, &axis_a_in_b);
    match (ra, rb) {
        (Side::Empty, _) | (_, Side::Empty) => MajorRanges::Disjoint,
        (ra, rb) => MajorRanges::Ranges {
            a: ra.arcs(),
            b: rb.arcs(),
        },
    }
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Side {
    Empty,
    Full,
    Arcs(AngleArcs),
}

impl Side {
    fn arcs(self) -> Option<AngleArcs> {
        match self {
            Side::Arcs(r) => Some(r),
            _ => None,
        }
    }
}

/// Angle range `[lo, hi]` (real numbers, `hi - lo <= 2 pi`) of an arc, widened by the
/// inclusive slack of [`ProfileArc::arc_param`]; `None` for segments.
fn widened_phi_range(arc: &ProfileArc) -> Option<(f64, f64)> {
    let ProfileArc::Arc {
        phi_start,
        sweep,
        radius,
        ..
    } = *arc
    else {
        return None;
    };
    let slack = 2.0 * ANGLE_SLACK.max(1e-12 / radius.max(1e-300));
    let (lo, hi) = if sweep >= 0.0 {
        (phi_start, phi_start + sweep)
    } else {
        (phi_start + sweep, phi_start)
    };
    Some((lo - slack, hi + slack))
}

/// Range of `sin` over `[lo, hi]`.
fn sin_range(lo: f64, hi: f64) -> (f64, f64) {
    if hi - lo >= TAU {
        return (-1.0, 1.0);
    }
    let (s0, s1) = (lo.sin(), hi.sin());
    let mut r = (s0.min(s1), s0.max(s1));
    // Does [lo, hi] contain pi/2 + 2 pi k (max) or -pi/2 + 2 pi k (min)?
    let contains = |c: f64| (lo - c).div_euclid(TAU) != (hi - c).div_euclid(TAU) || lo == c;
    if contains(FRAC_PI_2) {
        r.1 = 1.0;
    }
    if contains(-FRAC_PI_2) {
        r.0 = -1.0;
    }
    r
}

/// Parts of `[lo, hi]` on which `cos` has one sign, as latitude ranges in
/// `[-pi/2, pi/2]` with the longitude shift (0 for `cos >= 0`, pi for `cos <= 0`).
fn latitude_parts(lo: f64, hi: f64) -> impl Iterator<Item = (f64, f64, f64)> {
    // Breakpoints at pi/2 + k pi inside (lo, hi): at most three parts for hi - lo <= 2 pi.
    let first_k = ((lo - FRAC_PI_2) / PI).floor() + 1.0;
    let mut cuts = [lo; 8];
    let mut n = 1;
    let mut k = first_k;
    while n < 7 {
        let c = FRAC_PI_2 + k * PI;
        if c >= hi {
            break;
        }
        if c > lo {
            cuts[n] = c;
            n += 1;
        }
        k += 1.0;
    }
    cuts[n] = hi;
    (0..n).map(move |i| {
        let (p, q) = (cuts[i], cuts[i + 1]);
        let mid = 0.5 * (p + q);
        let m = (mid / TAU).round() * TAU;
        if mid.cos() >= 0.0 {
            // lambda = phi - m
            let (l0, l1) = (p - m, q - m);
            (l0.max(-FRAC_PI_2), l1.min(FRAC_PI_2), 0.0)
        } else {
            // lambda = pi - phi (+ 2 pi j); centre the range in [-pi/2, pi/2].
            let (l0, l1) = (PI - q, PI - p);
            let j = (0.5 * (l0 + l1) / TAU).round() * TAU;
            ((l0 - j).max(-FRAC_PI_2), (l1 - j).min(FRAC_PI_2), PI)
        }
    })
}

/// `x` range (see module doc) for latitudes `[l0, l1]` and target `[w0, w1]` of
/// `h = x cos lambda + a_z sin lambda`; `None` when no `x` works.
fn x_interval(l0: f64, l1: f64, a_z: f64, w0: f64, w1: f64) -> Option<(f64, f64)> {
    // Candidate latitudes: the ends and the stationary points of each quotient.
    let extremum = |w: f64, pick_min: bool| -> f64 {
        let mut best = if pick_min {
            f64::INFINITY
        } else {
            f64::NEG_INFINITY
        };
        let mut consider = |lam: f64| {
            let (s, c) = lam.sin_cos();
            let num = w - a_z * s;
            let v = if c <= 1e-12 {
                // h does not depend on x here: the target is met for every x or never.
                let met = if pick_min { num <= 0.0 } else { num >= 0.0 };
                if met {
                    if pick_min {
                        f64::NEG_INFINITY
                    } else {
                        f64::INFINITY
                    }
                } else if pick_min {
                    f64::INFINITY
                } else {
                    f64::NEG_INFINITY
                }
            } else {
                num / c
            };
            best = if pick_min { best.min(v) } else { best.max(v) };
        };
        consider(l0);
        consider(l1);
        if w != 0.0 && (a_z / w).abs() <= 1.0 {
            let lam = (a_z / w).asin();
            if lam > l0 && lam < l1 {
                consider(lam);
            }
        }
        best
    };
    let x_lo = extremum(w0, true);
    let x_hi = extremum(w1, false);
    (x_lo <= x_hi).then_some((x_lo, x_hi))
}

/// Restricted revolution angles of `own` (its frame) for a common normal with `other`,
/// whose axis is `axis_other` in `own`'s frame.
fn side_range(own: &ProfileArc, other: &ProfileArc, axis_other: &Vector3<f64>) -> Side {
    let (Some((lo, hi)), Some((olo, ohi))) = (widened_phi_range(own), widened_phi_range(other))
    else {
        return Side::Full;
    };
    if let ProfileArc::Arc { center, .. } = own {
        if center.x == 0.0 {
            // The major circle is a point: no angle to restrict.
            return Side::Full;
        }
    }
    if hi - lo >= PI {
        // A range of half a turn or more (full circles, after widening) spans every
        // latitude of one meridian half: nothing to restrict, and it could have four
        // constant-sign parts.
        return Side::Full;
    }
    let (s0, s1) = sin_range(olo, ohi);
    let targets = [(s0, s1), (-s1, -s0)];
    let k = axis_other.x.hypot(axis_other.y);
    let a_z = axis_other.z;
    let alpha = axis_other.y.atan2(axis_other.x);
    // At most 2 parts (range below pi) x 2 targets x 2 arcs.
    let mut arcs: [(f64, f64); 12] = [(0.0, 0.0); 12];
    let mut n = 0;
    for (l0, l1, shift) in latitude_parts(lo, hi) {
        if l0 > l1 {
            continue;
        }
        for &(w0, w1) in &targets {
            let Some((x0, x1)) = x_interval(l0, l1, a_z, w0, w1) else {
                continue;
            };
            let slack = GAUSS_SLACK * (1.0 + k);
            let (x0, x1) = (x0 - slack, x1 + slack);
            if x0 > k || x1 < -k {
                continue;
            }
            if k < MIN_AXIS_TILT {
                return Side::Full;
            }
            // cos(longitude - alpha) in [c0, c1].
            let (c0, c1) = ((x0 / k).max(-1.0), (x1 / k).min(1.0));
            let (t_small, t_big) = (c1.acos(), c0.acos());
            let centre = alpha + shift;
            if t_small <= 0.0 {
                // One arc through `centre`.
                arcs[n] = (centre - t_big, 2.0 * t_big);
                n += 1;
            } else if t_big >= PI {
                // One arc through `centre + pi`.
                arcs[n] = (centre + t_small, TAU - 2.0 * t_small);
                n += 1;
            } else {
                arcs[n] = (centre + t_small, t_big - t_small);
                arcs[n + 1] = (centre - t_big, t_big - t_small);
                n += 2;
            }
        }
    }
    if n == 0 {
        return Side::Empty;
    }
    match covering_arcs(&mut arcs[..n]) {
        Some(cover) => Side::Arcs(cover),
        None => Side::Full,
    }
}

/// At most two arcs covering the given arcs `(start, len)`: the complement of the two
/// largest uncovered gaps, each arc widened by [`GAUSS_SLACK`]. `None` when the arcs (or
/// the widened result) cover the circle.
fn covering_arcs(arcs: &mut [(f64, f64)]) -> Option<AngleArcs> {
    for a in arcs.iter_mut() {
        if a.1 >= TAU {
            return None;
        }
        a.0 = a.0.rem_euclid(TAU);
    }
    arcs.sort_by(|x, y| x.0.total_cmp(&y.0));
    let first = arcs[0].0;
    // An arc running past `first + TAU` also covers `[first, end - TAU]`.
    let max_end = arcs
        .iter()
        .map(|a| a.0 + a.1)
        .fold(f64::NEG_INFINITY, f64::max);
    let mut reach = (first + arcs[0].1).max(max_end - TAU);
    // The two largest gaps (start, end), largest first.
    let mut gaps = [(0.0f64, 0.0f64); 2];
    let keep = |g: (f64, f64), gaps: &mut [(f64, f64); 2]| {
        let len = g.1 - g.0;
        if len > gaps[0].1 - gaps[0].0 {
            gaps[1] = gaps[0];
            gaps[0] = g;
        } else if len > gaps[1].1 - gaps[1].0 {
            gaps[1] = g;
        }
    };
    for &(s, l) in &arcs[1..] {
        if s > reach {
            keep((reach, s), &mut gaps);
        }
        reach = reach.max(s + l);
    }
    if first + TAU > reach {
        keep((reach, first + TAU), &mut gaps);
    }
    let widen = |start: f64, len: f64| {
        AngleInterval::new(start - GAUSS_SLACK, (len + 2.0 * GAUSS_SLACK).min(TAU)).ok()
    };
    let g0_len = gaps[0].1 - gaps[0].0;
    let g1_len = gaps[1].1 - gaps[1].0;
    if g0_len <= 2.0 * GAUSS_SLACK {
        return None;
    }
    if g1_len <= 2.0 * GAUSS_SLACK {
        // One gap: one arc from its end round to its start.
        let arc = widen(gaps[0].1, TAU - g0_len)?;
        return Some(AngleArcs {
            arcs: [arc; 2],
            n: 1,
        });
    }
    // Two gaps: the arcs between them.
    let (ga, gb) = (gaps[0], gaps[1]);
    let len_ab = (gb.0 - ga.1).rem_euclid(TAU);
    let len_ba = (ga.0 - gb.1).rem_euclid(TAU);
    Some(AngleArcs {
        arcs: [widen(ga.1, len_ab)?, widen(gb.1, len_ba)?],
        n: 2,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::circle::{binormals, Multiplicity};
    use crate::query::angles::common_normals::parallel_circle;
    use crate::test_rng::Lcg;
    use nalgebra::{Point2, Translation3, UnitQuaternion};

    /// A toroidal patch in the half-plane rho >= 0 with `|sweep| <= max_sweep`; the arc centre
    /// may lie left of the axis.
    fn random_torus(rng: &mut Lcg, max_sweep: f64) -> Patch {
        loop {
            let arc = ProfileArc::Arc {
                center: Point2::new(rng.f() * 1.2 - 0.2, rng.f() - 0.5),
                radius: 0.05 + rng.f() * 0.5,
                phi_start: rng.f() * TAU,
                sweep: (2.0 * rng.f() - 1.0) * max_sweep,
            };
            if arc.length() > 1e-4 && (0..=50).all(|i| arc.point_at(i as f64 / 50.0).x >= 0.0) {
                return Patch::new(arc);
            }
        }
    }

    fn random_pose(rng: &mut Lcg) -> Isometry3<f64> {
        let axis = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5);
        let t = Vector3::new(rng.f() - 0.5, rng.f() - 0.5, rng.f() - 0.5) * 3.0;
        Isometry3::from_parts(
            Translation3::from(t),
            UnitQuaternion::from_scaled_axis(axis * 6.0),
        )
    }

    /// Interior common normals of two patches found WITHOUT the restriction: binormals of
    /// the full major circles whose line meets both patches inside their arc ranges.
    fn unrestricted_normals(a: &Patch, b: &Patch, pos: &Isometry3<f64>) -> Option<Vec<(f64, f64)>> {
        let (
            crate::bvh::patch::Core::Circle {
                r_major: ra, z: za, ..
            },
            crate::bvh::patch::Core::Circle {
                r_major: rb, z: zb, ..
            },
        ) = (a.core(), b.core())
        else {
            return None;
        };
        let ma = parallel_circle(ra, za, &Isometry3::identity());
        let mb = parallel_circle(rb, zb, pos);
        let bn = binormals(&ma, &mb, None, None);
        if bn.multiplicity != Multiplicity::Finite {
            return None;
        }
        let pos_ba = pos.inverse();
        let mut out = Vec::new();
        for item in bn.items.iter() {
            let w = item.point_b - item.point_a;
            if w.norm() < 1e-9 {
                continue;
            }
            let dir = w.normalize();
            let (mut pa, mut pb) = (Vec::new(), Vec::new());
            a.points_on_normal_line(&item.point_a, &dir, &mut pa);
            b.points_on_normal_line(&(pos_ba * item.point_b), &(pos_ba.rotation * dir), &mut pb);
            if !pa.is_empty() && !pb.is_empty() {
                out.push((item.angle_a, item.angle_b));
            }
        }
        Some(out)
    }

    /// The restriction is conservative: every interior common normal of the unrestricted
    /// computation starts inside the restricted ranges on both major circles.
    #[test]
    fn restriction_keeps_every_interior_common_normal() {
        let mut rng = Lcg(2024);
        let mut found = 0;
        for max_sweep in [0.05, 0.5, 2.0, 6.0] {
            for i in 0..600 {
                let (a, b) = (
                    random_torus(&mut rng, max_sweep),
                    random_torus(&mut rng, max_sweep),
                );
                let pos = random_pose(&mut rng);
                let Some(normals) = unrestricted_normals(&a, &b, &pos) else {
                    continue;
                };
                let ranges = major_angle_ranges(&a, &b, &pos);
                for (ta, tb) in normals {
                    found += 1;
                    let MajorRanges::Ranges { a: ra, b: rb } = ranges else {
                        panic!("case {i} (sweep {max_sweep}): disjoint but normal at {ta}, {tb}: {a:?} {b:?} {pos:?}");
                    };
                    assert!(
                        ra.is_none_or(|r| r.contains(ta)),
                        "case {i} (sweep {max_sweep}): theta_a {ta} outside {ra:?}: {a:?} {b:?} {pos:?}"
                    );
                    assert!(
                        rb.is_none_or(|r| r.contains(tb)),
                        "case {i} (sweep {max_sweep}): theta_b {tb} outside {rb:?}: {a:?} {b:?} {pos:?}"
                    );
                }
            }
        }
        // The check is not vacuous: many normals were tested.
        assert!(found > 300, "only {found} interior normals");
    }

    /// Fraction of the major circle left to search (the driving side: the smaller of the
    /// two), averaged over random pairs with arcs of at most `max_sweep`.
    fn mean_searched_fraction(max_sweep: f64, n: usize) -> f64 {
        let mut rng = Lcg(99);
        let mut sum = 0.0;
        for _ in 0..n {
            let (a, b) = (
                random_torus(&mut rng, max_sweep),
                random_torus(&mut rng, max_sweep),
            );
            let pos = random_pose(&mut rng);
            sum += match major_angle_ranges(&a, &b, &pos) {
                MajorRanges::Disjoint => 0.0,
                MajorRanges::Ranges { a, b } => {
                    let f = |r: Option<AngleArcs>| r.map_or(1.0, |r| r.total_len() / TAU);
                    f(a).min(f(b))
                }
            };
        }
        sum / n as f64
    }

    /// On leaf-sized arcs the restriction removes most of the circle (paper 3.3), and less
    /// the wider the arcs.
    #[test]
    fn restriction_narrows_small_arcs() {
        let small = mean_searched_fraction(0.05, 2000);
        let medium = mean_searched_fraction(0.5, 2000);
        let large = mean_searched_fraction(6.0, 2000);
        eprintln!("searched fraction: sweep 0.05 {small:.3}, 0.5 {medium:.3}, 6 {large:.3}");
        assert!(small < 0.1, "{small}");
        assert!(small < medium && medium < large, "{small} {medium} {large}");
    }

    #[test]
    fn covering_arcs_handles_wrap_and_two_gaps() {
        // Two separate arcs: kept apart.
        let mut arcs = [(0.1, 0.2), (3.0, 0.3)];
        let c = covering_arcs(&mut arcs).unwrap();
        assert_eq!(c.arcs().len(), 2);
        assert!(c.contains(0.2) && c.contains(3.2) && !c.contains(1.5) && !c.contains(5.0));
        // An arc across 0 merged with one just after it; three pieces reduce to two arcs.
        let mut arcs = [(6.0, 0.5), (0.3, 0.2), (2.0, 0.1), (4.0, 0.1)];
        let c = covering_arcs(&mut arcs).unwrap();
        for t in [6.1, 0.1, 0.4, 2.05, 4.05] {
            assert!(c.contains(t), "{t} {c:?}");
        }
        assert!(c.total_len() < TAU - 1.0);
        // Covering everything.
        let mut arcs = [(0.0, 3.5), (3.0, 3.5)];
        assert!(covering_arcs(&mut arcs).is_none());
    }

    #[test]
    fn latitude_parts_split_at_the_poles() {
        // phi in [0.5, 2.5] crosses pi/2: a cos>=0 part [0.5, pi/2] and a cos<=0 part with
        // latitudes pi - phi in [pi - 2.5, pi/2], longitude shifted by pi.
        let parts: Vec<_> = latitude_parts(0.5, 2.5).collect();
        assert_eq!(parts.len(), 2);
        assert!((parts[0].0 - 0.5).abs() < 1e-15 && (parts[0].1 - FRAC_PI_2).abs() < 1e-15);
        assert_eq!(parts[0].2, 0.0);
        assert!((parts[1].0 - (PI - 2.5)).abs() < 1e-15 && (parts[1].1 - FRAC_PI_2).abs() < 1e-15);
        assert_eq!(parts[1].2, PI);
        // A full turn has three parts covering all latitudes.
        assert_eq!(latitude_parts(-1.0, -1.0 + TAU).count(), 3);
    }

    #[test]
    fn sin_range_covers_extrema() {
        assert_eq!(sin_range(0.0, 3.0).1, 1.0);
        assert_eq!(sin_range(3.0, 5.0).0, -1.0);
        let (lo, hi) = sin_range(0.1, 0.2);
        assert!((lo - 0.1f64.sin()).abs() < 1e-16 && (hi - 0.2f64.sin()).abs() < 1e-16);
        assert_eq!(sin_range(-10.0, -3.0), (-1.0, 1.0));
    }
}
