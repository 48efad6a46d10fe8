//! The point of the depth's lower bound for two posed solids: a point `x` whose signed
//! margins `s_A(x) + s_B(x)` (positive inside) sum to as much as a local ascent finds, and
//! the certified lower bound of the depth they give (module doc of
//! [`mod@crate::query::penetration`]).
//!
//! Everything is in A's frame; `pos_ab` places B there. A probe classifies `x` against both
//! approximating chains ([`point_in_profile_nearest`]) and returns each signed margin
//! (positive inside) with the nearest surface point. The ascent first maximises
//! `f(x) = min(s_A(x), s_B(x))` (the deepest common point), then the certificate
//! `s_A + s_B` from that point and from its two nearest surface points, with a few moves per
//! step: the midpoint of the two nearest surface points (the centre of the ball touching
//! both, exact for two spheres), a step along the weaker side's gradient (away from its
//! nearest point), and a step along the sum of both gradients; a step that gains nothing
//! halves the step length. A seed on a surface (the distance query's overlap point often is
//! one) has no gradient there; when the first ascent certifies nothing it starts again from
//! the deepest of a few points about the seed. [`Pair::certify_from`] climbs the certificate
//! from any seeds (the entry point adds the upper bound's last contact). Only the final
//! point's evaluation matters for the certificate.

use crate::bvh::containment::point_in_profile_nearest;
use crate::bvh::QueryTree;
use nalgebra::{Isometry3, Point2, Point3, Vector3};

/// Steps of one ascent (each evaluates three candidates, two tree descents each).
const MAX_STEPS: usize = 60;

/// Weight of the smaller clearance added to the sum in the second ascent (see
/// [`Pair::ascend`]): the maximiser of the weighted objective loses at most this share of
/// the smaller clearance from the best sum.
const BALANCE_SHARE: f64 = 1e-3;

/// Offsets, as shares of the smaller solid's size, of the points about the seed from which
/// an ascent that found no common point starts again ([`Pair::ascend`]).
const RETRY_SHARES: [f64; 2] = [1e-3, 1e-2];

/// One side of a probe: signed margin and nearest point of one solid's approximating
/// surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Side {
    /// Distance to the approximating surface, positive inside the approximating solid.
    pub signed_margin: f64,
    /// Nearest point of the approximating surface (A's frame).
    pub nearest: Point3<f64>,
}

impl Side {
    /// Unit direction in which the signed margin grows fastest at `x` (zero when `x` is on
    /// the surface).
    pub fn gradient(&self, x: &Point3<f64>) -> Vector3<f64> {
        let away = x - self.nearest;
        let len = away.norm();
        if !(len > 0.0 && len.is_finite()) {
            return Vector3::zeros();
        }
        away * (self.signed_margin.signum() / len)
    }
}

/// What the chains' signed margins may be off by: the trees' bounds `e_a`, `e_b` and the
/// pose's rounding `slack` ([`certified_margin`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Allowance {
    pub e_a: f64,
    pub e_b: f64,
    pub slack: f64,
}

/// A point classified against both solids.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Probe {
    /// The point (A's frame).
    pub x: Point3<f64>,
    pub a: Side,
    pub b: Side,
}

impl Probe {
    /// The smaller signed margin: the objective of the ascent.
    pub fn depth(&self) -> f64 {
        self.a.signed_margin.min(self.b.signed_margin)
    }

    /// The certified lower bound of the depth at `x` (module doc of
    /// [`mod@crate::query::penetration`]): the sum of the two true signed margins' certified
    /// lower bounds ([`certified_margin`] with the tree's bound and the rounding of `w`);
    /// `None` unless the sum is positive (then `x` is inside at least one true solid, deeper
    /// than it is outside the other).
    pub fn certified_bound(&self, w: &Allowance) -> Option<f64> {
        let (ca, cb) = self.certified_margins(w);
        let sum = ca + cb;
        (sum > 0.0).then_some(sum)
    }

    /// The two true signed margins' certified lower bounds ([`certified_margin`]).
    pub fn certified_margins(&self, w: &Allowance) -> (f64, f64) {
        (
            certified_margin(self.a.signed_margin, w.e_a, w.slack),
            certified_margin(self.b.signed_margin, w.e_b, w.slack),
        )
    }

    /// [`Probe::certified_bound`], 0 when there is none.
    pub fn bound(&self, w: &Allowance) -> f64 {
        self.certified_bound(w).unwrap_or(0.0)
    }
}

/// A lower bound of the true solid's signed margin at a point (positive inside) from the
/// approximating chain's signed margin `m`, the tree's bound `e` and the rounding `slack`.
/// A point more than `e + slack` inside the chain is inside the true solid with a clearance
/// of at least `m - e - slack` ([`crate::bvh::containment`]: the true profile cannot pass
/// between the point and the chain); any other point is within `|m| + e + slack` of the
/// true surface (which lies within `e` of the chain), so its signed margin is at least
/// minus that.
pub fn certified_margin(m: f64, e: f64, slack: f64) -> f64 {
    if m > e + slack {
        m - e - slack
    } else {
        -(m.abs() + e + slack)
    }
}

/// Signed margin and nearest surface point of `x` (the tree's own frame).
fn side(tree: &QueryTree, x: &Point3<f64>) -> Side {
    let rho = x.x.hypot(x.y);
    let (c, q) = point_in_profile_nearest(tree, Point2::new(rho, x.z));
    // The nearest surface point lies in x's meridian half-plane; on the axis any
    // half-plane serves.
    let (cos, sin) = if rho > 0.0 {
        (x.x / rho, x.y / rho)
    } else {
        (1.0, 0.0)
    };
    Side {
        signed_margin: if c.inside { c.margin } else { -c.margin },
        nearest: Point3::new(q.x * cos, q.x * sin, q.y),
    }
}

/// Two trees in A's frame, ready to probe points.
pub struct Pair<'a> {
    pub ta: &'a QueryTree,
    pub tb: &'a QueryTree,
    pub pos_ab: Isometry3<f64>,
    pos_ba: Isometry3<f64>,
    /// Probes evaluated so far.
    pub probes: usize,
}

impl<'a> Pair<'a> {
    pub fn new(ta: &'a QueryTree, tb: &'a QueryTree, pos_ab: Isometry3<f64>) -> Self {
        Pair {
            ta,
            tb,
            pos_ab,
            pos_ba: pos_ab.inverse(),
            probes: 0,
        }
    }

    /// Radius of the smaller root disk: the scale of the smaller solid.
    fn scale(&self) -> f64 {
        let r = |t: &QueryTree| t.nodes[t.root as usize].bound.radius;
        r(self.ta).min(r(self.tb))
    }

    /// Classifies `x` (A's frame) against both solids.
    pub fn probe(&mut self, x: Point3<f64>) -> Probe {
        self.probes += 1;
        let a = side(self.ta, &x);
        let b_local = side(self.tb, &(self.pos_ba * x));
        let b = Side {
            signed_margin: b_local.signed_margin,
            nearest: self.pos_ab * b_local.nearest,
        };
        Probe { x, a, b }
    }

    /// Central differences of both signed margins about `x` at spacing `h`: the margins'
    /// gradients where `x` lies on or next to a surface, whose nearest point then gives none
    /// ([`Side::gradient`]). Each unit length or zero.
    pub fn margin_gradients(&mut self, x: Point3<f64>, h: f64) -> (Vector3<f64>, Vector3<f64>) {
        let (mut ga, mut gb) = (Vector3::zeros(), Vector3::zeros());
        for k in 0..3 {
            let d = Vector3::ith(k, h);
            let (p, m) = (self.probe(x + d), self.probe(x - d));
            ga[k] = p.a.signed_margin - m.a.signed_margin;
            gb[k] = p.b.signed_margin - m.b.signed_margin;
        }
        let unit = |g: Vector3<f64>| {
            let n = g.norm();
            if n > 0.0 && n.is_finite() {
                g / n
            } else {
                Vector3::zeros()
            }
        };
        (unit(ga), unit(gb))
    }

    /// The point with the best certificate an ascent from `seed` finds: first the smaller
    /// margin is raised (which brings the point inside both solids, to the centre of the
    /// largest ball touching both surfaces), then the sum of the margins (the certificate,
    /// [`Probe::certified_bound`] with the allowance `w`) with the sum kept
    /// positive. The sum is flat along the segment between two nearest points (two balls),
    /// so a small share of the smaller clearance is added to keep the point off the
    /// surfaces. Stops when the step falls below `step_tol`.
    pub fn ascend(&mut self, seed: Point3<f64>, step_tol: f64, w: &Allowance) -> Probe {
        let mut first = self.climb(seed, step_tol, Probe::depth);
        if first.certified_bound(w).is_none() {
            // A seed on a surface (the distance query's overlap point often is one) has no
            // gradient there: start again from the deepest of a few points about it.
            let scale = self.scale();
            let mut start = first;
            for share in RETRY_SHARES {
                for d in [
                    Vector3::x(),
                    -Vector3::x(),
                    Vector3::y(),
                    -Vector3::y(),
                    Vector3::z(),
                    -Vector3::z(),
                ] {
                    let p = self.probe(seed + d * (share * scale));
                    if p.depth() > start.depth() {
                        start = p;
                    }
                }
            }
            if start.x != first.x {
                let retry = self.climb(start.x, step_tol, Probe::depth);
                if retry.depth() > first.depth() {
                    first = retry;
                }
            }
        }
        // The sum also climbs from the two nearest surface points: a surface point of one
        // solid deep in the other certifies its depth there, and the best certificate of a
        // corner pressed into a face lies on the face's normal through the corner, outside
        // the corner's solid, where no ascent inside both arrives.
        let reach = first.depth().abs();
        let seeds = [first.x, first.a.nearest, first.b.nearest];
        let climbed = self
            .certify_from(&seeds, reach, step_tol, w, f64::INFINITY)
            .expect("three seeds");
        if climbed.bound(w) > first.bound(w) {
            climbed
        } else {
            first
        }
    }

    /// The point with the best certificate ([`Probe::certified_bound`] with the allowance
    /// `w`) that ascents of the certified sum from `seeds` find, the first step of each the
    /// longer of `reach` and the seed's smaller margin. The sum is flat along the segment
    /// between two nearest points (two balls), so a small share of the smaller clearance is
    /// added to keep the point off the surfaces.
    /// Stops when the step falls below `step_tol`, or as soon as a certificate exceeds
    /// `enough` (infinite: never). `None` without seeds.
    pub fn certify_from(
        &mut self,
        seeds: &[Point3<f64>],
        reach: f64,
        step_tol: f64,
        w: &Allowance,
        enough: f64,
    ) -> Option<Probe> {
        let objective = |p: &Probe| {
            let (ca, cb) = p.certified_margins(w);
            if ca + cb > 0.0 {
                ca + cb + BALANCE_SHARE * ca.min(cb)
            } else {
                f64::NEG_INFINITY
            }
        };
        let bound = |p: &Probe| p.bound(w);
        let done = |p: &Probe| bound(p) > enough;
        let mut best: Option<Probe> = None;
        for &seed in seeds {
            let climbed = self.climb_from(seed, reach, step_tol, objective, done);
            if best.is_none_or(|b| bound(&climbed) > bound(&b)) {
                best = Some(climbed);
            }
            if best.as_ref().is_some_and(done) {
                break;
            }
        }
        best
    }

    /// Pattern ascent of `objective` from `seed`, the first step as long as the seed's
    /// smaller margin ([`Pair::climb_from`]).
    fn climb(
        &mut self,
        seed: Point3<f64>,
        step_tol: f64,
        objective: impl Fn(&Probe) -> f64,
    ) -> Probe {
        self.climb_from(seed, 0.0, step_tol, objective, |_| false)
    }

    /// Pattern ascent of `objective` from `seed` with the moves of the module doc; the first
    /// step is the longer of `reach` and the seed's smaller margin. Stops early at a point
    /// that is `done`.
    fn climb_from(
        &mut self,
        seed: Point3<f64>,
        reach: f64,
        step_tol: f64,
        objective: impl Fn(&Probe) -> f64,
        done: impl Fn(&Probe) -> bool,
    ) -> Probe {
        let mut best = self.probe(seed);
        let mut value = objective(&best);
        let mut h = best.depth().abs().max(reach).max(step_tol);
        for _ in 0..MAX_STEPS {
            if h < step_tol || done(&best) {
                break;
            }
            let x = best.x;
            let (ga, gb) = (best.a.gradient(&x), best.b.gradient(&x));
            let (sa, sb) = (best.a.signed_margin, best.b.signed_margin);
            let weak = if sa <= sb { ga } else { gb };
            // Balancing the two margins along the weaker gradient needs about half their
            // difference; at least the current step.
            let balance = (0.5 * (sa - sb).abs()).max(h);
            let sum = ga + gb;
            let mut candidates = vec![
                nalgebra::center(&best.a.nearest, &best.b.nearest),
                x + weak * balance,
                x + weak * h,
            ];
            if sum.norm() > 1e-12 {
                candidates.push(x + sum.normalize() * h);
            }
            let mut improved = false;
            for c in candidates {
                if !c.coords.iter().all(|v| v.is_finite()) {
                    continue;
                }
                let p = self.probe(c);
                let v = objective(&p);
                if v > value {
                    let moved = (p.x - best.x).norm();
                    (best, value) = (p, v);
                    h = moved.max(step_tol);
                    improved = true;
                }
            }
            if !improved {
                h *= 0.5;
            }
        }
        best
    }
}
