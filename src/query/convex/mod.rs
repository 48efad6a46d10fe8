//! The convex fast path: the distance between two solids of revolution certified convex
//! ([`crate::bvh::convex`]) by GJK on the supports of their approximations' hulls
//! ([`gjk`]), instead of a traversal.
//!
//! **Three ways to a pair, one acceptance.** A ball against the other solid is a planar
//! question (`ball.rs`: the other's nearest surface point to the centre, in its meridian).
//! Otherwise GJK runs one step at a time; after its first step, and again when its simplex
//! shows a rim (every support point of a solid on one crease of its chain), the rim solver minimises the distance from the rim circle to the other
//! solid's surface over the azimuth ([`rim`]), where GJK would approximate the circle by
//! chords for a dozen iterations. Whatever proposes the witnesses (two points of the
//! approximating surfaces), the answer is accepted by the same test (`Bounds`): a lower
//! bound of `d(H_A, H_B)`, GJK's or the hulls' separation along the witnesses' direction
//! from both exact supports (any direction gives one), within the requested width of the
//! witnesses' distance, and the interval within the allowed width.
//!
//! **Certified interval.** Let `H_A`, `H_B` be the hulls of the approximating surfaces and
//! `h_A`, `h_B` their two-sided Hausdorff bounds to the true solids
//! ([`crate::bvh::convex::ConvexHullData::error`]: the tree's eps, the certificate's dent, the hull's rounding).
//! The distance between convex solids is that between the sets (0 when they meet), and it
//! moves by at most `h_A + h_B` from `H_A, H_B` to the true solids. So with GJK's bounds
//! `[l, u]` on `d(H_A, H_B)` the answer is `[max(0, l - w), u + w]`, `w = h_A + h_B` plus the
//! query's rounding slack and [`GJK_ROUNDING_REL`]. Overlap is reported only with a point of
//! both hulls that the tree's containment test puts inside both true solids with a margin
//! above eps and slack ([`crate::bvh::containment`]).
//!
//! **Witnesses and value (GJK's).** GJK's closest points are convex combinations of support points,
//! inside curved hulls by up to the gap `u - l`. Each is moved to the nearest point of its
//! approximating surface ([`witness`]), within the tree's eps of the true surface; the value
//! is their distance. Both points lie in the hulls, so `l <= d(H_A, H_B) <=` value, and the
//! value exceeds the approximations' distance by at most `value - l <= 2 (u - l) +` the
//! certificates' dents ([`witness`] module doc). GJK therefore runs to a gap of half the
//! requested width (less the dents), and the path declines when `value - l` exceeds the
//! width: the value is then within `eps_a + eps_b + width` of the truth, as a traversal's.
//! The interval is widened to hold the value (raising an upper bound or lowering a lower one
//! keeps it valid).
//!
//! **Width.** The interval must fit the requested width, or the narrowest interval a
//! traversal at tolerance 0 reaches, `2 w` plus [`SETTLE_REL`] of the scale, whichever is
//! wider (the trees' eps limit a traversal the same way); GJK's gap is at most half of what
//! the widening leaves of it, which also covers the witnesses' moves. When it cannot get
//! there, or when the hulls meet without a certified common point, the path declines and the
//! query traverses.
//!
//! **What it may call.** The convexity certificates, hull supports, nearest points and
//! containment tests of [`crate::bvh`]; it answers with the query's
//! [`crate::query::Certified`] (A's frame). Never the other paths or the front door.

mod ball;
pub mod gjk;
pub mod rim;
#[cfg(test)]
mod tests;
pub mod witness;

use crate::bvh::containment::point_in_solid;
use crate::bvh::convex::ConvexHullData;
use crate::bvh::offset_solid::Core;
use crate::bvh::QueryTree;
use crate::query::certified::{Certified, TraversalStats};
use crate::tolerances::SETTLE_REL;
use gjk::{Gjk, Status};
use nalgebra::{Isometry3, Point3, Vector3};
use witness::nearest_surface_point;

/// Rounding of GJK's arithmetic (support lifts, barycentric combinations, dot products of
/// points of the configuration's size), relative to the configuration scale: a few hundred
/// ulps, with margin.
pub const GJK_ROUNDING_REL: f64 = 1e-13;

/// How many times GJK resumes, each with a quarter of its last gap, when the witnesses moved
/// to the surfaces leave the value or the interval outside the width: GJK converges to
/// rounding in a few dozen iterations on smooth sets, and two resumes cover a gap 16 times
/// narrower; beyond that the query traverses.
const GJK_RESUMES: usize = 2;

/// How the convex path reached its answer: diagnostics for its tests and studies, not part
/// of the answer.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Trace {
    /// GJK's simplex updates (0 for the ball path).
    pub iterations: usize,
    /// Which step found the witnesses.
    pub method: Method,
}

/// The path's answer (A's frame) and how it was reached.
type Answer = (Certified, Trace);

/// The counters of an answer of this path.
fn path_stats() -> TraversalStats {
    TraversalStats {
        convex_paths: 1,
        ..TraversalStats::default()
    }
}

/// Which step of the convex path found the answer's witnesses.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// A ball against the other solid in the meridian plane (`ball.rs`).
    Ball,
    /// A rim circle's point nearest to the other solid ([`rim`]).
    Rim,
    /// GJK's closest points moved to the surfaces ([`witness`]), or GJK's overlap.
    Gjk,
}

/// The distance between the convex solids of trees `ta` (at the identity) and `tb` (at
/// `pos_ab`), certified in A's frame, with interval width at most `requested_width` or the
/// traversal's floor (module doc); `None` when the path declines.
pub fn convex_distance(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    slack: f64,
    requested_width: f64,
) -> Option<Certified> {
    convex_distance_traced(ta, tb, pos_ab, slack, requested_width).map(|(answer, _)| answer)
}

/// [`convex_distance`] with how it reached its answer.
pub fn convex_distance_traced(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    slack: f64,
    requested_width: f64,
) -> Option<Answer> {
    let (ca, cb) = (ta.convex.as_ref()?, tb.convex.as_ref()?);
    let scale = 1.0 + pos_ab.translation.vector.norm() + ca.support.extent + cb.support.extent;
    let widen = ca.error + cb.error + slack + GJK_ROUNDING_REL * scale;
    let allowed = requested_width.max(width_floor(ta, tb, pos_ab, slack)?);
    let center = |t: &QueryTree| {
        t.nodes.get(t.root as usize).map_or(Point3::origin(), |n| {
            Point3::new(0.0, 0.0, n.bound.center.y)
        })
    };
    let centers = [center(ta), pos_ab * center(tb)];
    // GJK starts along the closest points of the two core segments on the axes (where the
    // solids are widest): the exact direction for capsules and balls, a good one for other
    // solids of revolution near touching.
    let axis = |c: &ConvexHullData, pose: &Isometry3<f64>| {
        [0, 1].map(|k| pose * Point3::new(0.0, 0.0, c.support.core[k]))
    };
    let initial = closest_between_segments(axis(ca, &Isometry3::identity()), axis(cb, pos_ab))
        .filter(|v| v.norm_squared() > 0.0)
        .unwrap_or(centers[0] - centers[1]);
    let rotation = pos_ab.rotation.to_rotation_matrix();
    let shift = pos_ab.translation.vector;
    let rounding = GJK_ROUNDING_REL * scale;
    let dents = ca.certificate.dent + cb.certificate.dent;
    // The gap GJK must reach (module doc, "Witnesses"): what the widening leaves of the
    // allowed width, and the value's error within the requested width; the moves to the
    // surfaces usually shorten the pair (they remove the depths behind the supporting
    // planes), else GJK resumes with a quarter of the gap.
    let mut target_gap = (allowed - 2.0 * widen).min(requested_width - dents + rounding);
    let support_a = |d: &Vector3<f64>| ca.support.support(d);
    let support_b = |d: &Vector3<f64>| {
        rotation * cb.support.support(&rotation.inverse_transform_vector(d)) + shift
    };
    let bounds = Bounds {
        widen,
        requested_width,
        rounding,
        allowed,
    };
    let ball = |t: &QueryTree| matches!(t.offset, Some(o) if matches!(o.core, Core::Point { .. }));
    if ball(ta) || ball(tb) {
        if let Some(answer) = ball::ball_distance(ta, tb, pos_ab, &bounds, support_a, support_b) {
            return Some(answer);
        }
    }
    let mut g = Gjk::new(support_a, support_b, initial, 1e-14 * scale);
    let mut resumes = 0;
    let mut rim_tries = 0;
    let any_creases = !ca.creases.is_empty() || !cb.creases.is_empty();
    loop {
        g.probe();
        let gap = g.gap();
        // The rim solver: after GJK's first step (a crease or, for capsule-like solids, a
        // guess), then whenever a solid's simplex points all lie on one crease.
        let first = g.iterations() == 1;
        if (first || any_creases) && rim_tries < RIM_TRIES && gap > target_gap && g.lower() > 0.0 {
            let creases = [&ca.creases[..], &cb.creases[..]];
            // A single support point off the creases is a guess worth trying only where GJK
            // started along the exact direction: solids whose widest points span a segment
            // of the axis (capsules; the start is the closest points of those segments).
            let guesses = [ca, cb].map(|c| c.support.core[1] > c.support.core[0]);
            let rims = rims(creases, guesses, pos_ab, g.support_points(), first);
            if rims.iter().any(Option::is_some) {
                rim_tries += 1;
                // Start from the azimuths of GJK's closest points.
                let r = g.result();
                let local_b = pos_ab.inverse_transform_point(&r.point_b);
                let azimuths = [r.point_a.y.atan2(r.point_a.x), local_b.y.atan2(local_b.x)];
                let found = [0, 1].map(|k| {
                    rims[k].map(|(meridian, crease)| RimStart {
                        meridian,
                        theta: azimuths[k],
                        crease,
                    })
                });
                if let Some(answer) =
                    bounds.answer_from_rims(ta, tb, pos_ab, found, &support_a, &support_b, &r)
                {
                    return Some(answer);
                }
            }
        }
        if gap <= target_gap {
            if let Some(answer) = bounds.answer(ta, tb, pos_ab, &g.result()) {
                return Some(answer);
            }
            // The witnesses moved to the surfaces leave the value or the interval outside
            // the width: go on to a quarter of the gap.
            if resumes == GJK_RESUMES || gap.is_nan() || gap <= 0.0 {
                return None;
            }
            resumes += 1;
            target_gap = 0.25 * gap;
        }
        match g.advance() {
            Status::Running => {}
            Status::Intersect => {
                return certified_overlap(ta, tb, pos_ab, slack, &g.result(), centers)
            }
            Status::Stalled => return bounds.answer(ta, tb, pos_ab, &g.result()),
        }
    }
}

/// How many times a query tries the rim solver ([`rim`]); each try is a few nearest-point
/// descents, about one or two GJK iterations.
const RIM_TRIES: usize = 2;

/// The rim solver stops when its predicted improvement is below this fraction of the
/// requested width (the value's error then hardly eats into the width).
const RIM_TOLERANCE: f64 = 0.01;

/// Rims in GJK's simplex: a solid all of whose support points in the simplex have the
/// same meridian point, one of its `creases` (a rim circle, [`rim`]) or, after GJK's first
/// step and where `guesses` allows, any point (its parallel circle), gives that meridian
/// point (its own frame) and whether it is a crease.
fn rims(
    creases: [&[nalgebra::Point2<f64>]; 2],
    guesses: [bool; 2],
    pos_ab: &Isometry3<f64>,
    supports: impl Iterator<Item = (Point3<f64>, Point3<f64>)>,
    first_step: bool,
) -> [Option<((f64, f64), bool)>; 2] {
    let meridian = |p: &Point3<f64>| ((p.x * p.x + p.y * p.y).sqrt(), p.z);
    // Distinct hull vertices of a chain are far further apart than this; two support points
    // this close in the meridian are the same vertex lifted to two azimuths (a near-miss
    // would only give a worse start: the rim's points are surface points all the same).
    let same = |m: (f64, f64), n: (f64, f64)| (m.0 - n.0).abs() + (m.1 - n.1).abs() <= 1e-9;
    let mut first: Option<[(f64, f64); 2]> = None;
    let mut rim = [true; 2];
    for (a, b) in supports {
        let m = [meridian(&a), meridian(&pos_ab.inverse_transform_point(&b))];
        match first {
            None => first = Some(m),
            Some(f) => {
                for k in 0..2 {
                    rim[k] &= same(m[k], f[k]);
                }
            }
        }
    }
    let Some(firsts) = first else {
        return [None, None];
    };
    let crease = |k: usize| {
        let m = firsts[k];
        creases[k]
            .iter()
            .any(|c| (c.x - m.0).abs() + (c.y - m.1).abs() <= 1e-9)
    };
    [0, 1].map(|k| {
        let on_crease = crease(k);
        (rim[k] && (on_crease || (first_step && guesses[k]))).then_some((firsts[k], on_crease))
    })
}

/// Where the rim solver starts on one solid ([`rims`]): the meridian point, the azimuth of
/// GJK's closest point, whether the point is a crease.
#[derive(Debug, Clone, Copy)]
struct RimStart {
    meridian: (f64, f64),
    theta: f64,
    crease: bool,
}

/// What an answer must meet (module doc, "Width").
struct Bounds {
    /// The hulls' errors, the slack and GJK's rounding.
    widen: f64,
    requested_width: f64,
    rounding: f64,
    /// The widest interval allowed.
    allowed: f64,
}

impl Bounds {
    /// The answer with witnesses `point_a`, `point_b` on the approximating surfaces, a
    /// lower bound `lower` of the hulls' distance and an upper bound `upper` of it, when it
    /// fits.
    fn finish(
        &self,
        point_a: Point3<f64>,
        point_b: Point3<f64>,
        lower_hulls: f64,
        upper_hulls: f64,
        iterations: usize,
        method: Method,
    ) -> Option<Answer> {
        let value = (point_a - point_b).norm();
        // `value` is a distance between points of the approximating solids, which lie in the
        // hulls: `lower <= d(H_A, H_B) <= value`. It exceeds the approximations' distance by
        // at most `value - lower`, which must fit the requested width (up to rounding) for
        // the value to be within `eps_a + eps_b + width` of the truth.
        let fits = value - lower_hulls <= self.requested_width + self.rounding;
        // Any number above an upper bound is one; any number below a lower bound is one.
        let lower = (lower_hulls - self.widen).max(0.0).min(value);
        let upper = (upper_hulls.min(value) + self.widen).max(value);
        (fits && upper - lower <= self.allowed).then_some((
            Certified {
                value,
                lower,
                upper,
                point_a,
                point_b,
                overlap: false,
                stats: path_stats(),
            },
            Trace { iterations, method },
        ))
    }

    /// The answer from a rim of A or B ([`rims`], [`rim`]): the rim point nearest to the
    /// other solid's surface and that surface point, bounded below by the hulls' separation
    /// along the pair (both supports) and by GJK's bound.
    #[allow(clippy::too_many_arguments)]
    fn answer_from_rims(
        &self,
        ta: &QueryTree,
        tb: &QueryTree,
        pos_ab: &Isometry3<f64>,
        found: [Option<RimStart>; 2],
        support_a: &impl Fn(&Vector3<f64>) -> Point3<f64>,
        support_b: &impl Fn(&Vector3<f64>) -> Point3<f64>,
        r: &gjk::GjkResult,
    ) -> Option<Answer> {
        let rim = |k: usize| {
            found[k].map(
                |RimStart {
                     meridian,
                     theta,
                     crease,
                 }| rim::Rim {
                    meridian,
                    theta,
                    // A crease is worth the secant's few steps; a single support point's
                    // parallel circle (a smooth part) only a guess.
                    evaluations: if crease {
                        rim::MAX_EVALUATIONS
                    } else {
                        rim::GUESS_EVALUATIONS
                    },
                    pose: if k == 0 { pos_ab.inverse() } else { *pos_ab },
                    other: if k == 0 { tb } else { ta },
                },
            )
        };
        let rims = [rim(0), rim(1)];
        let tolerance = RIM_TOLERANCE * self.requested_width.max(self.rounding);
        rim::first_accepted(&rims, tolerance, |k, x, q| {
            let (point_a, point_b) = if k == 0 {
                (x, pos_ab * q)
            } else {
                (q, pos_ab * x)
            };
            let d = (point_b - point_a).try_normalize(0.0)?;
            let along = d.dot(&(support_b(&-d) - support_a(&d)));
            self.finish(
                point_a,
                point_b,
                r.lower.max(along),
                r.upper,
                r.iterations,
                Method::Rim,
            )
        })
    }

    /// The answer from GJK's state `r`, when the witnesses moved to the surfaces fit.
    fn answer(
        &self,
        ta: &QueryTree,
        tb: &QueryTree,
        pos_ab: &Isometry3<f64>,
        r: &gjk::GjkResult,
    ) -> Option<Answer> {
        let (point_a, point_b) = surface_witnesses(ta, tb, pos_ab, r);
        self.finish(
            point_a,
            point_b,
            r.lower,
            r.upper,
            r.iterations,
            Method::Gjk,
        )
    }
}

/// GJK's closest points moved to the approximating surfaces ([`witness`]), B's in A's
/// frame; a point on the axis moves in the meridian towards the other solid. A single
/// support point is on its surface already ([`crate::bvh::convex::SupportTable`]: hull
/// vertices and arc points of the chain, lifted by the azimuth).
fn surface_witnesses(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    r: &gjk::GjkResult,
) -> (Point3<f64>, Point3<f64>) {
    let v = r.point_a - r.point_b;
    let point_a = if r.single_a {
        r.point_a
    } else {
        nearest_surface_point(ta, &r.point_a, &-v)
    };
    let point_b = if r.single_b {
        r.point_b
    } else {
        let local_b = pos_ab.inverse_transform_point(&r.point_b);
        pos_ab * nearest_surface_point(tb, &local_b, &pos_ab.inverse_transform_vector(&v))
    };
    (point_a, point_b)
}

/// `p - q` for the closest points `p` of segment `a` and `q` of segment `b`, either
/// possibly a point (Ericson, *Real-Time Collision Detection*, 5.1.9).
fn closest_between_segments(a: [Point3<f64>; 2], b: [Point3<f64>; 2]) -> Option<Vector3<f64>> {
    let (d1, d2, r) = (a[1] - a[0], b[1] - b[0], a[0] - b[0]);
    let (aa, ee, f) = (d1.norm_squared(), d2.norm_squared(), d2.dot(&r));
    let (s, t) = if aa == 0.0 && ee == 0.0 {
        (0.0, 0.0)
    } else if aa == 0.0 {
        (0.0, (f / ee).clamp(0.0, 1.0))
    } else {
        let c = d1.dot(&r);
        if ee == 0.0 {
            ((-c / aa).clamp(0.0, 1.0), 0.0)
        } else {
            let bb = d1.dot(&d2);
            let denom = aa * ee - bb * bb;
            let s = if denom > 0.0 {
                ((bb * f - c * ee) / denom).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let t = (bb * s + f) / ee;
            if t < 0.0 {
                ((-c / aa).clamp(0.0, 1.0), 0.0)
            } else if t > 1.0 {
                (((bb - c) / aa).clamp(0.0, 1.0), 1.0)
            } else {
                (s, t)
            }
        }
    };
    let v = (a[0] + d1 * s) - (b[0] + d2 * t);
    v.iter().all(|x| x.is_finite()).then_some(v)
}

/// The narrowest interval the path aims for (module doc): twice the widening by the hulls'
/// errors, the slack and GJK's rounding, plus [`SETTLE_REL`] of the configuration scale;
/// `None` unless both trees are certified convex.
pub fn width_floor(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    slack: f64,
) -> Option<f64> {
    let (ca, cb) = (ta.convex.as_ref()?, tb.convex.as_ref()?);
    let scale = 1.0 + pos_ab.translation.vector.norm() + ca.support.extent + cb.support.extent;
    let widen = ca.error + cb.error + slack + GJK_ROUNDING_REL * scale;
    Some(2.0 * widen + SETTLE_REL * scale)
}

/// Overlap when a point of both hulls is inside both true solids with a margin above the
/// trees' eps and the slack (the containment test, [`point_in_solid`]); `None` (decline)
/// otherwise. Candidates: GJK's common point (often on a flat face of one hull), then
/// points moved from it towards either solid's centre on its axis (inside that solid,
/// convexity) or their midpoint, by growing fractions, then points between the centres.
fn certified_overlap(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    slack: f64,
    r: &gjk::GjkResult,
    centers: [Point3<f64>; 2],
) -> Option<Answer> {
    let inside = |t: &QueryTree, p: &Point3<f64>| {
        let c = point_in_solid(t, p);
        c.inside && c.margin > t.eps + slack
    };
    let x = Point3::from((r.point_a.coords + r.point_b.coords) * 0.5);
    let on = |p: &Point3<f64>, q: &Point3<f64>, t: f64| Point3::from(p.coords.lerp(&q.coords, t));
    let middle = on(&centers[0], &centers[1], 0.5);
    let steps = [1e-6, 1e-3, 0.1, 0.5];
    let candidates = std::iter::once(x)
        .chain(steps.into_iter().flat_map(|t| {
            [
                on(&x, &centers[0], t),
                on(&x, &centers[1], t),
                on(&x, &middle, t),
            ]
        }))
        .chain((1..8).map(|k| on(&centers[0], &centers[1], k as f64 / 8.0)));
    let found = candidates
        .into_iter()
        .find(|p| inside(ta, p) && inside(tb, &pos_ab.inverse_transform_point(p)))?;
    Some((
        Certified::overlap_at(found, path_stats()),
        Trace {
            iterations: r.iterations,
            method: Method::Gjk,
        },
    ))
}
