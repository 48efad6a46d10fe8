//! The stages of one penetration query after a distance query that did not certify the
//! solids apart (module doc of [`mod@crate::query::penetration`]): the deepest point's
//! bound, a detected ball's covering, the upper bound's search, the climb from its last
//! contact and, while the interval is not narrow, the covering of translations.

use super::ball_depth::detected_ball_lower;
use super::deepest::{Allowance, Pair, Probe};
use super::separate::{Search, Separation, CAPPED_DIRECTION_QUERIES};
use super::signed::{LowerCertificate, Penetration, PenetrationStats, NARROW_REL};
use super::translation_cover::{translation_cover_lower, CoverSpec, Covered};
use crate::query::front::distance::{query_slack, Distance, QueryOptions, Tolerance};
use crate::query::search::Budget;
use crate::solid::Solid;
use nalgebra::{Isometry3, Point3, Vector3};
use std::time::Instant;

/// Share of the trees' eps below which the deepest-point ascent stops refining: the lower
/// bound `2 rho` is then within a few percent of the trees' own error `2 e` of what the
/// local maximum gives.
const ASCENT_STEP_SHARE: f64 = 0.02;

/// Resolution of a ball's covering ([`super::ball_depth`]) as a share of the interval's
/// width asked: the covering's bound then falls short of the ball's exact depth by about a
/// quarter of the width, the trees' bounds aside.
const BALL_RESOLUTION_SHARE: f64 = 0.25;

/// Smallest resolution of a ball's covering, as a share of `eps_a + eps_b` (a width of 0
/// asked: the covering stops at its cell budget instead).
const BALL_RESOLUTION_FLOOR: f64 = 0.05;

/// First step along a ball's way out past an answer that is not separated, as a share of
/// its length: the way out leaves within a little of the capped cell, often at a grazing
/// angle to the level set, so a short step (not the search's usual half length) finds the
/// translation where it separates. 5 % on the paper's models: the one ball case left wide
/// got its upper bound from 0.276 (half a length) to 0.2006 (0.2060 with 2 %) for a lower
/// bound of 0.1908.
const BALL_WAY_OUT_STEP: f64 = 0.05;

/// Share of the narrow width (`max(width asked, NARROW_REL * upper)`) below the upper bound
/// that the covering of translations certifies: a little inside it, so that the interval is
/// narrow after rounding. Past it the shells nearest the depth need cells as small as their
/// margins, and the covering's resolution (a quarter of the narrow width) cannot pay for them.
const COVER_GOAL_SHARE: f64 = 0.9;

/// The lower bound so far and what certifies it.
#[derive(Debug, Clone, Copy)]
struct LowerSoFar {
    value: f64,
    point: Option<Point3<f64>>,
    certificate: LowerCertificate,
}

impl LowerSoFar {
    /// Takes `value` when it is higher, with its certificate and, when given, its point.
    fn raise(&mut self, value: f64, certificate: LowerCertificate, point: Option<Point3<f64>>) {
        if value > self.value {
            self.value = value;
            self.certificate = certificate;
            if point.is_some() {
                self.point = point;
            }
        }
    }
}

/// What every stage of one penetration query shares: the pair in A's frame, the allowances
/// of its certificates and the width asked.
struct Stages<'s> {
    a: &'s Solid,
    b: &'s Solid,
    pos_ab: Isometry3<f64>,
    slack: f64,
    eps_sum: f64,
    allowance: Allowance,
    step_tol: f64,
    /// `upper - lower` asked of the interval.
    width: f64,
    deadline: Option<Instant>,
}

impl Stages<'_> {
    /// A ball against any solid: the covering of the ball's ways out (`ball_depth.rs`),
    /// resolved to [`Stages::ball_resolution`], within the upper bound known. Returns the
    /// points the covering classified and B's translation towards the cell that capped it.
    fn ball_lower(&self, upper: f64, lower: &mut LowerSoFar) -> (usize, Option<Vector3<f64>>) {
        let Some(ball) = detected_ball_lower(
            &self.a.tree,
            &self.b.tree,
            &self.pos_ab,
            upper,
            self.ball_resolution(),
            self.slack,
        ) else {
            return (0, None);
        };
        lower.raise(
            ball.depth.lower,
            LowerCertificate::BallCovering,
            Some(ball.centre),
        );
        (ball.depth.cells, ball.capped_translation)
    }

    /// The ball's covering was capped where no point held the ball in: B's translation `t`
    /// there is the ball's way out, within the covering's resolution of its exact depth.
    /// The cell's centre may still hold the ball in by up to the resolution and the trees'
    /// bounds, so the first query goes that much past it, and the steps are short
    /// ([`BALL_WAY_OUT_STEP`]).
    fn follow_ball_way_out(&self, search: &mut Search, t: Vector3<f64>) {
        let past = self.ball_resolution() + self.allowance.e_a + self.allowance.e_b;
        search.along_from(t, t.norm() + past, past.max(BALL_WAY_OUT_STEP * t.norm()));
    }

    /// The covering of translations was capped at B's translation `t`: where no point held
    /// B in (or the first cell left unexamined when its cells ran out), so a shorter way
    /// out may lie along it. A few more queries there
    /// ([`CAPPED_DIRECTION_QUERIES`]) while the interval is not narrow.
    fn follow_capped_cell(&self, search: &mut Search, t: Vector3<f64>, lower: f64, narrow: f64) {
        if search.best_upper() - lower > narrow {
            search.goal = lower + self.width;
            search.grant(CAPPED_DIRECTION_QUERIES);
            search.along(t, t.norm());
        }
    }

    /// A quarter of the width asked, never below a share of the trees' accuracy.
    fn ball_resolution(&self) -> f64 {
        (BALL_RESOLUTION_SHARE * self.width).max(BALL_RESOLUTION_FLOOR * self.eps_sum)
    }

    /// The upper bound's directions from the deepest point: the translation moving B's
    /// nearest surface point onto A's (exact for two balls), then the margins' own
    /// gradients, then the two axes; first, when nothing positive is certified, B away
    /// from A along the margins' differences.
    fn search_directions(
        &self,
        search: &mut Search,
        pair: &mut Pair,
        deepest: &Probe,
        certified: bool,
        lower: f64,
    ) {
        let push = deepest.a.nearest - deepest.b.nearest;
        if !certified {
            // Touching within the trees' accuracy: the point sits on the surfaces, where the
            // nearest points give no direction.
            let (ga, gb) = pair.margin_gradients(deepest.x, self.eps_sum.max(self.slack));
            search.along(gb - ga, 0.0);
        }
        search.along(push, push.norm());
        let (ga, gb) = (
            deepest.a.gradient(&deepest.x),
            deepest.b.gradient(&deepest.x),
        );
        let axis_b = self.pos_ab.rotation * Vector3::z();
        for u in [gb, -ga, Vector3::z(), -Vector3::z(), axis_b, -axis_b] {
            search.along(u, lower.max(0.5 * push.norm()));
        }
    }

    /// The separating translation's last contact: B's point there lies inside A about as
    /// deep as the translation is long, often in another overlap region than the distance
    /// query's point. The sum climbs from it, from the point of A it reaches and from their
    /// middle; a certified point found joins the anchors.
    fn climb_from_contact(
        &self,
        pair: &mut Pair,
        best: &Separation,
        lower: &mut LowerSoFar,
        anchors: &mut Vec<Point3<f64>>,
    ) {
        let Some(c) = best.contact_b else {
            return;
        };
        let t = best.translation;
        let seeds = [c, c + 0.5 * t, c + t];
        let climbed = pair
            .certify_from(
                &seeds,
                0.25 * t.norm(),
                self.step_tol,
                &self.allowance,
                f64::INFINITY,
            )
            .expect("three seeds");
        if let Some(bound) = climbed.certified_bound(&self.allowance) {
            anchors.push(climbed.x);
            lower.raise(bound, LowerCertificate::Point, Some(climbed.x));
        }
    }

    /// Several contact regions, each blocking some of the ways out: a covering of the
    /// translations shorter than `upper` by the sums' Lipschitz balls
    /// (`translation_cover.rs`), within COVER_GOAL_SHARE of `narrow_width`.
    fn cover_translations(
        &self,
        upper: f64,
        narrow_width: f64,
        anchors: &[Point3<f64>],
        lower: &mut LowerSoFar,
    ) -> Covered {
        let covered = translation_cover_lower(
            &self.a.tree,
            &self.b.tree,
            &self.pos_ab,
            &CoverSpec {
                from: lower.value,
                goal: upper - COVER_GOAL_SHARE * narrow_width,
                // Resolved to a quarter of the narrow width (module doc of `translation_cover`:
                // the cells needed grow as the square of depth over resolution).
                resolution: self
                    .ball_resolution()
                    .max(BALL_RESOLUTION_SHARE * narrow_width),
                anchors,
                step_tol: self.step_tol,
                deadline: self.deadline,
            },
        );
        lower.raise(covered.lower, LowerCertificate::TranslationCovering, None);
        covered
    }
}

/// The penetration depth of A and B ([`penetration`] after a distance query `d` of the
/// same pair that did not certify them apart): the deepest point's bound, a ball's
/// covering, the upper bound's search, the climb from its contact and, while the interval
/// is not narrow, the covering of translations (module doc of
/// [`mod@crate::query::penetration`]).
pub(super) fn penetration_after(
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
    let stages = Stages {
        a,
        b,
        pos_ab,
        slack,
        eps_sum,
        allowance: Allowance { e_a, e_b, slack },
        step_tol: (ASCENT_STEP_SHARE * (e_a + e_b)).max(slack),
        width: match opts.tolerance {
            Tolerance::Trees => 2.0 * eps_sum,
            Tolerance::Absolute(t) => t.max(0.0),
        },
        deadline,
    };
    let width = stages.width;
    // The distance's overlap point, or the middle of its witnesses when undecided.
    let seed = a.pose.inverse() * nalgebra::center(&d.point_a, &d.point_b);
    let mut pair = Pair::new(&a.tree, &b.tree, pos_ab);
    let deepest = pair.ascend(seed, stages.step_tol, &stages.allowance);
    let certified = deepest.certified_bound(&stages.allowance);
    let mut lower = LowerSoFar {
        value: certified.unwrap_or(0.0),
        point: certified.map(|_| deepest.x),
        certificate: if certified.is_some() {
            LowerCertificate::Point
        } else {
            LowerCertificate::None
        },
    };

    let mut dist_opts = *opts;
    dist_opts.refine = false;
    dist_opts.budget = Budget {
        max_time: None,
        ..opts.budget
    };
    let mut search = Search::new(a, b, dist_opts, deadline, lower.value + width);
    search.offer_bounding_balls();
    let (ball_cells, ball_way_out) = stages.ball_lower(search.best_upper(), &mut lower);
    search.goal = lower.value + width;
    if let Some(t) = ball_way_out {
        stages.follow_ball_way_out(&mut search, t);
    }
    stages.search_directions(
        &mut search,
        &mut pair,
        &deepest,
        certified.is_some(),
        lower.value,
    );
    let first = search.best.expect("the bounding balls always give a bound");
    let mut anchors: Vec<Point3<f64>> = lower.point.into_iter().collect();
    if first.upper - lower.value > width {
        stages.climb_from_contact(&mut pair, &first, &mut lower, &mut anchors);
    }
    let mut cover_cells = 0;
    let mut cover_timed_out = false;
    let narrow_width = width.max(NARROW_REL * first.upper);
    if first.upper - lower.value > narrow_width && !anchors.is_empty() {
        let covered = stages.cover_translations(first.upper, narrow_width, &anchors, &mut lower);
        cover_cells = covered.cells;
        cover_timed_out = covered.timed_out;
        pair.probes += covered.probes;
        if let Some(t) = covered.capped_at {
            stages.follow_capped_cell(&mut search, t, lower.value, narrow_width);
        }
    }
    let best = search.best.expect("the bounding balls always give a bound");
    let upper = best.upper.max(lower.value);
    let len = best.translation.norm();
    let direction = if len > 0.0 {
        a.pose.rotation * (best.translation / len)
    } else {
        Vector3::zeros()
    };
    Penetration {
        lower: lower.value,
        upper,
        direction,
        point: lower.point.map(|x| a.pose * x),
        certificate: lower.certificate,
        contact_b: best.contact_b.map(|p| a.pose * p),
        narrow: upper - lower.value <= (2.0 * eps_sum).max(NARROW_REL * upper),
        stats: PenetrationStats {
            probes: pair.probes + ball_cells,
            cover_cells,
            distance_queries: 1 + search.queries,
            budget_exhausted: search.budget_exhausted
                || cover_timed_out
                || d.stats.budget_exhausted,
        },
    }
}
