//! Upper bounds of the penetration depth: translations of B that a certified distance query
//! finds separated (module doc of [`mod@crate::query::penetration`]: a query answering
//! `d(A, B + t) >= L > 0` gives `PD <= |t| - L`).
//!
//! The search works in A's frame. Along a direction `u` it queries `B + t` at
//! `t = (s + margin) u`, `s` the estimated touching length: a separated answer with witness
//! normal `n` and gap `g` gives the touching translation `t - g n` and the next candidate
//! `(s' + margin) n`, `s'` that translation's component along `n` (a step in contact space
//! towards a translation parallel to its contact normal); an answer that is not separated
//! moves `t` further along `u`, each step three times the last and the first half the
//! estimate (so that a touching length 60 times the estimate, e.g. from a weak lower bound,
//! is reached within the direction's steps; the contact-space step then shortens an
//! overshoot). A direction is abandoned once its translations are no shorter than the best
//! upper bound so far.

use crate::query::front::distance::{distance, query_slack, Distance, QueryOptions};
use crate::query::search::Budget;
use crate::solid::Solid;
use nalgebra::{Isometry3, Point3, Translation3, Vector3};
use std::time::Instant;

/// Distance queries one penetration search may spend along the deepest point's
/// directions.
pub const MAX_QUERIES: usize = 16;

/// Further distance queries granted along the direction where the covering of translations
/// was capped ([`Search::grant`]).
pub const CAPPED_DIRECTION_QUERIES: usize = 4;

/// Steps along one direction.
const STEPS_PER_DIRECTION: usize = 6;

/// A certified separating translation.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Separation {
    /// Certified upper bound of the penetration depth: `|translation| - L + slack`.
    pub upper: f64,
    /// The translation of B queried (A's frame), as the difference of the two poses.
    pub translation: Vector3<f64>,
    /// B's witness point at the separated pose, moved back by the translation: the point
    /// of B (at its own pose, A's frame) that touches A last along `translation`. `None`
    /// for the bound from bounding spheres.
    pub contact_b: Option<Point3<f64>>,
}

/// The state of one search.
pub struct Search<'a> {
    /// A at the identity: the queries run in A's frame, so that `pos_ab` is exact.
    a0: Solid,
    b: &'a Solid,
    pos_ab: Isometry3<f64>,
    opts: QueryOptions,
    deadline: Option<Instant>,
    /// How far past an estimated touching translation a query is placed: above the width
    /// a separated query's interval can reach, so that its lower bound can clear 0.
    margin: f64,
    /// Stop once the best upper bound is within this of the lower bound.
    pub goal: f64,
    pub best: Option<Separation>,
    pub queries: usize,
    /// Queries allowed in all: [`MAX_QUERIES`], plus what [`Search::grant`] added.
    max_queries: usize,
    pub budget_exhausted: bool,
}

impl<'a> Search<'a> {
    pub fn new(
        a: &Solid,
        b: &'a Solid,
        opts: QueryOptions,
        deadline: Option<Instant>,
        goal: f64,
    ) -> Self {
        let pos_ab = a.relative_pose(b);
        let slack = query_slack(&a.tree, &b.tree, &pos_ab);
        let margin = a.tree.target_eps + b.tree.target_eps + 4.0 * slack;
        Search {
            a0: a.with_pose(Isometry3::identity()),
            b,
            pos_ab,
            opts,
            deadline,
            margin,
            goal,
            best: None,
            queries: 0,
            max_queries: MAX_QUERIES,
            budget_exhausted: false,
        }
    }

    /// The best certified upper bound so far (infinite before any).
    pub fn best_upper(&self) -> f64 {
        self.best.map_or(f64::INFINITY, |s| s.upper)
    }

    fn offer(&mut self, s: Separation) {
        if s.upper < self.best_upper() {
            self.best = Some(s);
        }
    }

    /// Whether the search is done: goal met, queries or time spent.
    pub fn done(&mut self) -> bool {
        if self.best_upper() <= self.goal {
            return true;
        }
        if self.queries >= self.max_queries {
            return true;
        }
        if self.deadline.is_some_and(|d| Instant::now() >= d) {
            self.budget_exhausted = true;
            return true;
        }
        false
    }

    /// Allows exactly `extra` more queries from now on (what was left unspent lapses).
    pub fn grant(&mut self, extra: usize) {
        self.max_queries = self.queries + extra;
    }

    /// The bound from the solids' bounding balls (no query): A's approximating surface lies
    /// in the ball about `(0, 0, c_z)` of radius `|c_rho| + r` (its root disk revolved) and
    /// the true solid within the tree's bound `e` more; B's likewise. Moving B until the
    /// balls are apart separates the solids.
    pub fn offer_bounding_balls(&mut self) {
        let ball = |s: &Solid, pose: &Isometry3<f64>| {
            let root = &s.tree.nodes[s.tree.root as usize].bound;
            (
                pose * Point3::new(0.0, 0.0, root.center.y),
                root.center.x.abs() + root.radius + s.tree.eps,
            )
        };
        let (ca, ra) = ball(&self.a0, &Isometry3::identity());
        let (cb, rb) = ball(self.b, &self.pos_ab);
        let gap = cb - ca;
        let u = if gap.norm() > 0.0 {
            gap.normalize()
        } else {
            Vector3::z()
        };
        let slack = query_slack(&self.a0.tree, &self.b.tree, &self.pos_ab);
        // Balls apart once |cb + t - ca| > ra + rb; t along the centres' line.
        let need = (ra + rb - gap.norm()).max(0.0);
        let upper = need * (1.0 + 4.0 * f64::EPSILON) + slack;
        self.offer(Separation {
            upper,
            translation: u * upper,
            contact_b: None,
        });
    }

    /// Queries B moved by `t` (A's frame): the separated answer with the translation
    /// actually applied, or `None` when the answer does not certify separation.
    fn query_at(&mut self, t: &Vector3<f64>) -> (Option<Vector3<f64>>, Distance) {
        let moved = Isometry3::from_parts(
            Translation3::from(self.pos_ab.translation.vector + t),
            self.pos_ab.rotation,
        );
        let bt = self.b.with_pose(moved);
        let mut opts = self.opts;
        if let Some(d) = self.deadline {
            let left = d.saturating_duration_since(Instant::now());
            opts.budget = Budget {
                max_time: Some(opts.budget.max_time.map_or(left, |m| m.min(left))),
                ..opts.budget
            };
        }
        let d = distance(&self.a0, &bt, &opts);
        self.queries += 1;
        if d.lower.is_nan() || d.lower <= 0.0 || d.overlap || !d.lower.is_finite() {
            return (None, d);
        }
        // The translation between the two poses as queried, and the bound with the
        // rounding of its length.
        let dt = moved.translation.vector - self.pos_ab.translation.vector;
        let slack = query_slack(&self.a0.tree, &self.b.tree, &moved);
        let upper = (dt.norm() * (1.0 + 4.0 * f64::EPSILON) - d.lower + slack).max(0.0);
        self.offer(Separation {
            upper,
            translation: dt,
            contact_b: Some(d.point_b - dt),
        });
        (Some(dt), d)
    }

    /// Searches along the unit direction `u` from the estimated touching length `s0`, the
    /// first step past an answer that is not separated half that length.
    pub fn along(&mut self, u: Vector3<f64>, s0: f64) {
        self.along_from(u, s0, 0.5 * s0);
    }

    /// [`Search::along`] with the first step past an answer that is not separated `step`
    /// (at least the margin; each next step three times the last): short for a direction
    /// known to leave within a little of `s0`.
    pub fn along_from(&mut self, u: Vector3<f64>, s0: f64, step: f64) {
        if u.norm().is_nan() || u.norm() <= 0.0 || !s0.is_finite() {
            return;
        }
        let mut u = u.normalize();
        let mut s = s0.max(0.0);
        let mut grow = self.margin.max(step);
        for _ in 0..STEPS_PER_DIRECTION {
            if self.done() {
                return;
            }
            let t = u * (s + self.margin);
            // Longer than the best bound: a separated answer here cannot improve it.
            if t.norm() >= self.best_upper() + self.margin {
                return;
            }
            match self.query_at(&t) {
                (Some(dt), d) => {
                    let gap = d.point_b - d.point_a;
                    let len = gap.norm();
                    if !(len > 0.0 && len.is_finite()) {
                        return;
                    }
                    let n = gap / len;
                    let touch = dt - n * d.value;
                    let s_next = touch.dot(&n);
                    // The next candidate's bound would be about `s_next` plus the query's
                    // width; stop when that cannot beat the best by a useful amount.
                    if s_next <= 0.0 || s_next >= self.best_upper() - 0.1 * self.margin {
                        return;
                    }
                    (u, s) = (n, s_next);
                    grow = self.margin.max(0.5 * s);
                }
                (None, _) => {
                    s += grow;
                    grow *= 3.0;
                }
            }
        }
    }
}
