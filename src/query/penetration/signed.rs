//! The public entry points: [`penetration`] (the certified interval of the translational
//! penetration depth) and [`signed_distance`] (the distance when apart, minus the depth
//! when overlapping), with the signed distance's gradient where it is one.

use super::ball_depth::detected_ball_lower;
use super::deepest::{Allowance, Pair};
use super::separate::Search;
use super::translation_cover::{translation_cover_lower, CoverSpec};
use crate::query::front::distance::{
    check_query, distance, query_slack, Distance, QueryError, QueryOptions, Tolerance,
};
use crate::query::front::gradient::Gradient;
use crate::query::search::Budget;
use crate::solid::Solid;
use nalgebra::{Point3, Vector3};
use std::time::Instant;

/// Share of the trees' eps below which the deepest-point ascent stops refining: the lower
/// bound `2 rho` is then within a few percent of the trees' own error `2 e` of what the
/// local maximum gives.
const ASCENT_STEP_SHARE: f64 = 0.02;

/// Depth relative to which an interval counts as narrow for the gradient (the interval
/// is narrow when `upper - lower <= max(2 (eps_a + eps_b), NARROW_REL * upper)`).
pub const NARROW_REL: f64 = 0.05;

/// Resolution of a ball's covering ([`super::ball_depth`]) as a share of the interval's
/// width asked: the covering's bound then falls short of the ball's exact depth by about a
/// quarter of the width, the trees' bounds aside.
const BALL_RESOLUTION_SHARE: f64 = 0.25;

/// Smallest resolution of a ball's covering, as a share of `eps_a + eps_b` (a width of 0
/// asked: the covering stops at its cell budget instead).
const BALL_RESOLUTION_FLOOR: f64 = 0.05;

/// Share of the width asked below the upper bound that the covering of translations
/// certifies (a little inside the width, so that the interval meets it after rounding).
const COVER_GOAL_SHARE: f64 = 0.9;

/// Counters of one penetration query.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct PenetrationStats {
    /// Points classified: against both solids by the deepest-point ascent, against one by a
    /// ball's covering.
    pub probes: usize,
    /// Cells of the covering of translations ([`super::translation_cover`]), 0 when the
    /// interval met the width asked without it.
    pub cover_cells: usize,
    /// Distance queries, the first (at the given pose) included.
    pub distance_queries: usize,
    /// The time budget ran out before the interval met the requested width.
    pub budget_exhausted: bool,
}

/// The certificate of a penetration depth's lower bound (module doc of
/// [`mod@crate::query::penetration`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum LowerCertificate {
    /// No positive lower bound was certified (`lower` is 0).
    None,
    /// The signed margins of `point` ([`super::deepest`]).
    Point,
    /// The covering of a detected ball's ways out, the ball centred at `point`
    /// ([`super::ball_depth`]).
    BallCovering,
    /// The covering of the translations shorter than `lower` by Lipschitz balls of
    /// several points' margins ([`super::translation_cover`]); `point`'s own certificate
    /// is the ball about no translation.
    TranslationCovering,
}

/// The certified interval of the penetration depth (module doc of
/// [`mod@crate::query::penetration`]). Points and directions are in the world frame.
#[derive(Debug, Clone, PartialEq)]
pub struct Penetration {
    /// Certified lower bound: the sum of the true signed margins of a point (positive
    /// inside; the point inside at least one solid), 0 when no positive sum was certified,
    /// e.g. for solids apart or touching within the trees' accuracy.
    pub lower: f64,
    /// Certified upper bound: B moved by `s * direction`, any `s > upper`, is apart from A.
    pub upper: f64,
    /// Unit translation of B that achieves `upper` (zero when the solids are apart).
    pub direction: Vector3<f64>,
    /// The point of `lower`'s certificate, when there is one: the point whose signed
    /// margins give it, or the centre of the ball whose covering gives it (when a covering
    /// of translations raised `lower`, the point of its ball about no translation).
    pub point: Option<Point3<f64>>,
    /// Which certificate gives `lower`.
    pub certificate: LowerCertificate,
    /// The point of B (at its pose) that touches A last along `direction`: the contact of
    /// the separating translation, used by the gradient.
    pub contact_b: Option<Point3<f64>>,
    /// `upper - lower <= max(2 (eps_a + eps_b), NARROW_REL * upper)`: narrow enough for
    /// [`SignedDistance::gradient`].
    pub narrow: bool,
    pub stats: PenetrationStats,
}

/// The signed distance: the distance when apart, `-PD` when overlapping, as a certified
/// interval, with the distance query and (unless certified apart) the penetration query
/// it came from.
#[derive(Debug, Clone, PartialEq)]
pub struct SignedDistance {
    pub lower: f64,
    pub upper: f64,
    pub distance: Distance,
    pub penetration: Option<Penetration>,
}

impl SignedDistance {
    /// The gradient with respect to B's pose (world frame; B's frame origin at `origin_b`).
    ///
    /// Apart: the distance's gradient ([`Distance::gradient`]). Overlapping, with a narrow
    /// interval: moving B by `v` changes the depth by `-direction . v` to first order where
    /// the minimal separating translation is unique and parallel to its contact normal
    /// (`PD(v) = min |t - v|` over separating `t`), so the signed distance's derivative is
    /// `direction` in translation and `(contact_b - origin_b) x direction` in a rotation
    /// vector about B's origin (the contact point moving with B). Where several
    /// translations are minimal the depth has no gradient and this is one of its one-sided
    /// derivatives; the direction is that of the upper bound's translation, whose angle to
    /// the minimal one shrinks with the interval's width. `None` when the interval is not
    /// narrow or the solids touch within the trees' accuracy.
    pub fn gradient(&self, origin_b: &Point3<f64>) -> Option<Gradient> {
        if self.distance.lower > 0.0 {
            return self.distance.gradient(origin_b);
        }
        let p = self.penetration.as_ref()?;
        if !p.narrow || p.lower.is_nan() || p.lower <= 0.0 {
            return None;
        }
        let contact = p.contact_b?;
        let u = p.direction;
        Some(Gradient {
            normal: u,
            translation: u,
            rotation: (contact - origin_b).cross(&u),
        })
    }
}

/// The penetration depth of A and B ([`penetration`] after a distance query `d` of the
/// same pair that did not certify them apart).
fn penetration_after(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    d: &Distance,
    started: Instant,
) -> Penetration {
    let pos_ab = a.relative_pose(b);
    let slack = query_slack(&a.tree, &b.tree, &pos_ab);
    let (e_a, e_b) = (a.tree.eps, b.tree.eps);
    let eps_sum = a.tree.target_eps + b.tree.target_eps;
    let deadline = opts.budget.max_time.map(|t| started + t);
    let to_local = a.pose.inverse();
    // The distance's overlap point, or the middle of its witnesses when undecided.
    let seed = to_local * nalgebra::center(&d.point_a, &d.point_b);
    let mut pair = Pair::new(&a.tree, &b.tree, pos_ab);
    let step_tol = (ASCENT_STEP_SHARE * (e_a + e_b)).max(slack);
    let allowance = Allowance { e_a, e_b, slack };
    let deepest = pair.ascend(seed, step_tol, &allowance);
    let certified = deepest.certified_bound(&allowance);
    let lower = certified.unwrap_or(0.0);

    let width = match opts.tolerance {
        Tolerance::Trees => 2.0 * eps_sum,
        Tolerance::Absolute(t) => t.max(0.0),
    };
    let mut dist_opts = *opts;
    dist_opts.refine = false;
    dist_opts.budget = Budget {
        max_time: None,
        ..opts.budget
    };
    let mut search = Search::new(a, b, dist_opts, deadline, lower + width);
    search.offer_bounding_balls();
    // A ball against any solid: the covering of the ball's ways out (`ball_depth.rs`),
    // resolved to a quarter of the width asked, within the bounding balls' bound.
    let resolution = (BALL_RESOLUTION_SHARE * width).max(BALL_RESOLUTION_FLOOR * eps_sum);
    let ball = detected_ball_lower(
        &a.tree,
        &b.tree,
        &pos_ab,
        search.best_upper(),
        resolution,
        slack,
    );
    let mut point = certified.map(|_| deepest.x);
    let mut certificate = if certified.is_some() {
        LowerCertificate::Point
    } else {
        LowerCertificate::None
    };
    let mut lower = lower;
    let mut ball_cells = 0;
    if let Some((depth, centre)) = ball {
        ball_cells = depth.cells;
        if depth.lower > lower {
            (lower, point) = (depth.lower, Some(centre));
            certificate = LowerCertificate::BallCovering;
        }
    }
    search.goal = lower + width;
    // First the translation moving B's nearest surface point onto A's (exact for two
    // balls), then the margins' own gradients, then the two axes.
    let push = deepest.a.nearest - deepest.b.nearest;
    if certified.is_none() {
        // Touching within the trees' accuracy: the point sits on the surfaces, where the
        // nearest points give no direction; B away from A along the margins' differences.
        let (ga, gb) = pair.margin_gradients(deepest.x, eps_sum.max(slack));
        search.along(gb - ga, 0.0);
    }
    search.along(push, push.norm());
    let (ga, gb) = (
        deepest.a.gradient(&deepest.x),
        deepest.b.gradient(&deepest.x),
    );
    let axis_b = pos_ab.rotation * Vector3::z();
    for u in [gb, -ga, Vector3::z(), -Vector3::z(), axis_b, -axis_b] {
        search.along(u, lower.max(0.5 * push.norm()));
    }
    let best = search.best.expect("the bounding balls always give a bound");
    let mut anchors: Vec<Point3<f64>> = point.into_iter().collect();
    if best.upper - lower > width {
        // The separating translation's last contact: B's point there lies inside A about
        // as deep as the translation is long, often in another overlap region than the
        // distance query's point. The sum climbs from it, from the point of A it reaches
        // and from their middle.
        if let Some(c) = best.contact_b {
            let t = best.translation;
            let seeds = [c, c + 0.5 * t, c + t];
            let climbed = pair
                .certify_from(&seeds, 0.25 * t.norm(), step_tol, &allowance, f64::INFINITY)
                .expect("three seeds");
            if let Some(b) = climbed.certified_bound(&allowance) {
                anchors.push(climbed.x);
                if b > lower {
                    (lower, point) = (b, Some(climbed.x));
                    certificate = LowerCertificate::Point;
                }
            }
        }
    }
    let mut cover_cells = 0;
    if best.upper - lower > width.max(NARROW_REL * best.upper) && !anchors.is_empty() {
        // Not narrow: several contact regions, each blocking some of the ways out. A
        // covering of the translations shorter than the upper bound by the sums' Lipschitz
        // balls (`translation_cover.rs`), within COVER_GOAL_SHARE of the width asked.
        let covered = translation_cover_lower(
            &a.tree,
            &b.tree,
            &pos_ab,
            &CoverSpec {
                from: lower,
                goal: best.upper - COVER_GOAL_SHARE * width,
                // Resolved to a quarter of the narrow width (module doc of `translation_cover`:
                // the cells needed grow as the square of depth over resolution).
                resolution: resolution.max(BALL_RESOLUTION_SHARE * NARROW_REL * best.upper),
                anchors: &anchors,
                step_tol,
                deadline,
            },
        );
        cover_cells = covered.cells;
        pair.probes += covered.probes;
        if covered.lower > lower {
            lower = covered.lower;
            certificate = LowerCertificate::TranslationCovering;
        }
    }
    let upper = best.upper.max(lower);
    let len = best.translation.norm();
    let direction = if len > 0.0 {
        a.pose.rotation * (best.translation / len)
    } else {
        Vector3::zeros()
    };
    Penetration {
        lower,
        upper,
        direction,
        point: point.map(|x| a.pose * x),
        certificate,
        contact_b: best.contact_b.map(|p| a.pose * p),
        narrow: upper - lower <= (2.0 * eps_sum).max(NARROW_REL * upper),
        stats: PenetrationStats {
            probes: pair.probes + ball_cells,
            cover_cells,
            distance_queries: 1 + search.queries,
            budget_exhausted: search.budget_exhausted || d.stats.budget_exhausted,
        },
    }
}

/// An answer for solids certified apart: depth 0.
fn apart() -> Penetration {
    Penetration {
        lower: 0.0,
        upper: 0.0,
        direction: Vector3::zeros(),
        point: None,
        certificate: LowerCertificate::None,
        contact_b: None,
        narrow: true,
        stats: PenetrationStats {
            distance_queries: 1,
            ..PenetrationStats::default()
        },
    }
}

/// Certified interval of the translational penetration depth of two posed solids
/// (module doc of [`mod@crate::query::penetration`]): `lower <= PD <= upper`.
///
/// `opts.tolerance` asks for `upper - lower` (the default, [`Tolerance::Trees`], for
/// `2 (eps_a + eps_b)`; the lower bound alone loses up to twice the larger leaf bound);
/// `opts.budget.max_time` bounds the whole query, `max_node_pairs` each distance query.
/// Solids certified apart have depth `[0, 0]`.
///
/// # Errors
/// [`QueryError`] for poses outside the representable range.
pub fn penetration(a: &Solid, b: &Solid, opts: &QueryOptions) -> Result<Penetration, QueryError> {
    Ok(signed_distance(a, b, opts)?
        .penetration
        .unwrap_or_else(apart))
}

/// Certified interval of the signed distance: `[lower, upper]` of the distance when the
/// solids are certified apart; `[-PD upper, -PD lower]` when they overlap; and
/// `[-PD upper, distance upper]` when they touch within the trees' accuracy.
///
/// # Errors
/// [`QueryError`] for poses outside the representable range.
pub fn signed_distance(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
) -> Result<SignedDistance, QueryError> {
    check_query(a, b)?;
    let started = Instant::now();
    let d = distance(a, b, opts);
    if d.lower > 0.0 {
        return Ok(SignedDistance {
            lower: d.lower,
            upper: d.upper,
            distance: d,
            penetration: None,
        });
    }
    let p = penetration_after(a, b, opts, &d, started);
    let overlap = d.overlap || p.lower > 0.0;
    Ok(SignedDistance {
        lower: -p.upper,
        upper: if overlap { -p.lower } else { d.upper },
        distance: d,
        penetration: Some(p),
    })
}
