//! Certified time of impact by conservative advancement (Johnson and Cohen 1997; Son et al.
//! 2020, section 3, give the certified lower bound each step uses).
//!
//! Invariant: the solids are certified apart — every lower bound of their distance above the
//! contact distance `D` — for all `t in [0, t_lower)`. A query at `t_lower` with lower bound
//! `l > D` (after subtracting the motion's rounding, [`MOTION_ROUNDING_REL`]) extends it by
//! `(l - D) / L`, `L` the speed bound of [`super::speed`]: `d(s) >= l - L (s - t_lower) > D`
//! there. When the step would pass 1 the solids stay apart on `[0, 1]`.
//!
//! Near a contact the steps shrink; when one falls below the time tolerance, or the lower
//! bound does not clear `D` even at the query's narrowest interval, the advancement has
//! *stalled*. Then the last query's witnesses are carried along the motions and tested for
//! a contact certificate ([`super::contact`]: points certified inside the true solids, a few
//! microseconds a test) at evenly spaced, then doubling times after `t_lower`; the first
//! time certified becomes `t_upper`, bisected towards `t_lower`. Only when no carried point
//! certifies one do probes at `t_lower + h` (h doubling from the time tolerance) look for a
//! time whose *upper* bound is `<= D` at tolerance 0 (for `D = 0`: a certified overlap); the
//! first one found becomes `t_upper` and a bisection towards `t_lower` moves it down while it
//! keeps finding certified contacts. The first contact time lies in `[t_lower, t_upper]`. When no
//! probe certifies a contact (grazing at the query's accuracy, or a budget ran out) the
//! answer is [`ToiOutcome::Undecided`]: apart before `t_lower`, nothing certified after.
//!
//! **How wide the interval is** (nothing above depends on it; it is what the trees allow).
//! Let `e_A`, `e_B` be the trees' bounds and `g(t)` the distance of the approximating
//! surfaces. The trees describe every pair of solids whose boundaries lie within `e_A`, `e_B`
//! of the approximating ones, so the true distance may be anything in `[g - e_A - e_B,
//! g + e_A + e_B]`: apart is certifiable only while `g > D + e_A + e_B`, contact only once
//! `g <= D - e_A - e_B` (for `D = 0`: the approximating regions overlap by more than
//! `e_A + e_B`, [`super::contact`]). Between the two, a band `2 (e_A + e_B)` wide in `g`,
//! no search from these trees can certify either; if `g` closes at speed `c` the interval
//! of *any* certified search is `2 (e_A + e_B) / c` wide in the worst case (leaves at their
//! bound), which is `2 eps / c` only when each tree's bound is `eps / 2`. This search adds
//! to the band: the advancement stops while the query's lower bound is within
//! `(e_A + e_B) / 4` of `D` ([`EARLY_STALL_DIVISOR`]) and its queries near `D` are asked
//! for half the remaining gap ([`GAP_TOLERANCE_SHARE`]), so `t_lower` is where the distance
//! is at most `D + (e_A + e_B) / 4` plus the query's own interval; the carried witnesses
//! certify `t_upper` once a point of their segment clears both eps, later than the first
//! overlap when the witness segment is not along the deepest direction; the bisection
//! stops at the time tolerance. `figures/toi_bench.md` measures the width in units of
//! `2 eps / closing speed`.

use super::contact::{CertifiedContact, ContactTest, Witness};
use super::motion::{Motion, MotionError, MOTION_ROUNDING_REL};
use super::speed::speed_bound;
use crate::query::{
    try_distance_cached, Distance, QueryCache, QueryError, QueryOptions, Tolerance, TraversalStats,
};
use crate::solid::Solid;

/// Relative shortening of each advancement step: the step `(l - D) / L` is computed with
/// three roundings (subtraction, division, the product with this factor), each at most a
/// unit roundoff `1.1e-16` relative; `1e-12` covers them with a wide margin. The sum
/// `t + step` is then moved down by two ulps (`below`) to cover its own rounding.
pub const STEP_SHRINK_REL: f64 = 1e-12;

/// The advancement tries the carried contact certificate ([`super::contact`]) once, as soon
/// as its lower bound is within `(e_A + e_B) / 4` of the contact distance (the trees' eps),
/// after one query at tolerance 0 and its step: from there the steps would shrink
/// geometrically towards the time tolerance, more of them the coarser the trees. When no
/// contact is certified the advancement goes on as before.
pub const EARLY_STALL_DIVISOR: f64 = 4.0;

/// Near a contact the advancement asks each query for an interval no wider than this share
/// of the previous query's upper bound minus `D` (when that is narrower than the caller's
/// tolerance): a lower bound within half the remaining gap keeps each step at least half the
/// step the exact distance would allow, where a lower bound a whole tree eps below the
/// distance makes the steps shrink towards nothing while the solids are still that far
/// apart (grazing passes, and the last steps before a contact). Only the work per query
/// changes; every step still uses the query's certified lower bound.
pub const GAP_TOLERANCE_SHARE: f64 = 0.5;

/// Default time tolerance: the advancement stalls below steps of this length, and the
/// bisection stops when `t_upper - t_lower` is below it.
pub const DEFAULT_TIME_TOLERANCE: f64 = 1e-6;

/// Default cap on the number of distance queries of one time-of-impact search.
pub const DEFAULT_MAX_QUERIES: usize = 2000;

/// What the caller asks of a time-of-impact search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ToiOptions {
    /// Contact distance `D >= 0`: the solids "touch" when their distance is `<= D`.
    pub contact_distance: f64,
    /// Options of every distance query of the advancement; probes near a contact run with
    /// [`Tolerance::Absolute`]`(0)` (the narrowest interval the trees allow).
    pub query: QueryOptions,
    /// Steps below this stall the advancement; the bisection of `t_upper` stops below it.
    pub time_tolerance: f64,
    /// Cap on the number of distance queries (then [`ToiOutcome::Undecided`]).
    pub max_queries: usize,
}

impl Default for ToiOptions {
    fn default() -> Self {
        ToiOptions {
            contact_distance: 0.0,
            query: QueryOptions::default(),
            time_tolerance: DEFAULT_TIME_TOLERANCE,
            max_queries: DEFAULT_MAX_QUERIES,
        }
    }
}

/// Why a time-of-impact search cannot run.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ToiError {
    #[error("contact distance must be a finite number >= 0, got {0}")]
    ContactDistance(f64),
    #[error("time tolerance must be a finite number > 0, got {0}")]
    TimeTolerance(f64),
    #[error("max_queries must be at least 1")]
    MaxQueries,
    #[error("motion of solid {which}: {source}")]
    Motion {
        which: &'static str,
        source: MotionError,
    },
    #[error("distance query at t = {t}: {source}")]
    Query { t: f64, source: QueryError },
}

/// How the search ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ToiOutcome {
    /// Apart on `[0, t_lower)`, distance `<= D` at `t_upper`.
    Contact,
    /// Distance `> D` on all of `[0, 1]`.
    Apart,
    /// Apart on `[0, t_lower)`; no contact certified after it (grazing within the query's
    /// accuracy, or the query cap was reached).
    Undecided,
}

impl ToiOutcome {
    pub fn name(self) -> &'static str {
        match self {
            ToiOutcome::Contact => "contact",
            ToiOutcome::Apart => "apart",
            ToiOutcome::Undecided => "undecided",
        }
    }
}

/// The answer of [`time_of_impact`].
#[derive(Debug, Clone, PartialEq)]
pub struct TimeOfImpact {
    pub outcome: ToiOutcome,
    /// Certified apart (distance `> D`) for every `t < t_lower` in `[0, 1]` (`1` for
    /// [`ToiOutcome::Apart`], where `t = 1` is apart too).
    pub t_lower: f64,
    /// A time with distance certified `<= D` at the poses the motions compute for it,
    /// [`Motion::pose_at`] (only for [`ToiOutcome::Contact`]; see [`MOTION_ROUNDING_REL`]
    /// for how far those are from the exact motion).
    pub t_upper: Option<f64>,
    /// The distance query at `t_upper` (world frame; its witness points), for a contact.
    pub contact: Option<Distance>,
    /// Distance queries run (advancement steps, probes and bisection).
    pub queries: usize,
    /// Queries of the advancement alone.
    pub steps: usize,
    /// Contact certificates tried from carried witnesses ([`super::contact`]; not queries).
    pub certificates: usize,
    /// The speed bound `L` at `t = 0` ([`super::speed`]).
    pub speed_bound: f64,
    /// Traversal counters summed over every query.
    pub stats: TraversalStats,
}

/// Largest float at least two ulps below a finite `x >= 0` (0 stays 0).
fn below(x: f64) -> f64 {
    if x <= 0.0 {
        0.0
    } else {
        f64::from_bits(x.to_bits().saturating_sub(2))
    }
}

/// Bound on the distance of any point of `s` from its frame origin: the root bounding
/// sphere of the tree about the local origin, grown by the tree's eps.
fn radius(s: &Solid) -> f64 {
    let t = &s.tree;
    t.nodes.get(t.root as usize).map_or(0.0, |n| {
        n.bound.center.coords.norm() + n.bound.radius + t.eps
    })
}

/// One query of the search. `lower` is a bound for the exact motion (the query's lower
/// bound at the computed poses minus the motion's rounding, [`MOTION_ROUNDING_REL`]);
/// `upper` is the query's upper bound at the computed poses `pose_at(t)`, which is what a
/// contact certifies: an overlap certificate (a point inside both solids) has no depth to
/// absorb the rounding, so the exact motion's distance there is only known to be within
/// `D` plus that rounding (below `1e-13` of the configuration's scale).
struct Probe {
    lower: f64,
    upper: f64,
    distance: Distance,
}

struct Search<'a> {
    a: &'a Solid,
    b: &'a Solid,
    ma: Motion,
    mb: Motion,
    ra: f64,
    rb: f64,
    opts: ToiOptions,
    cache: QueryCache,
    queries: usize,
    certificates: usize,
    stats: TraversalStats,
}

impl Search<'_> {
    /// A query at `t`: at tolerance 0 when `tight`, else at the caller's tolerance narrowed
    /// to half of `gap` (an estimate of the distance above `D`, see [`GAP_TOLERANCE_SHARE`]).
    fn probe(&mut self, t: f64, tight: bool, gap: f64) -> Result<Probe, ToiError> {
        let pa = self.ma.pose_at(t);
        let pb = self.mb.pose_at(t);
        let a = self.a.with_pose(pa);
        let b = self.b.with_pose(pb);
        let mut q = self.opts.query;
        let asked = q
            .tolerance
            .width(self.a.tree.target_eps, self.b.tree.target_eps);
        let near = GAP_TOLERANCE_SHARE * gap.max(0.0);
        if tight {
            q.tolerance = Tolerance::Absolute(0.0);
        } else if near < asked {
            q.tolerance = Tolerance::Absolute(near);
        }
        let d = try_distance_cached(&a, &b, &q, &mut self.cache)
            .map_err(|source| ToiError::Query { t, source })?;
        self.queries += 1;
        self.stats.add(&d.stats);
        let slack = MOTION_ROUNDING_REL
            * (2.0
                + pa.translation.vector.norm()
                + pb.translation.vector.norm()
                + self.ra
                + self.rb);
        Ok(Probe {
            lower: d.lower - slack,
            upper: d.upper,
            distance: d,
        })
    }

    fn budget_left(&self) -> bool {
        self.queries < self.opts.max_queries
    }
}

fn check(opts: &ToiOptions) -> Result<(), ToiError> {
    let d = opts.contact_distance;
    if !(d.is_finite() && d >= 0.0) {
        return Err(ToiError::ContactDistance(d));
    }
    let h = opts.time_tolerance;
    if !(h.is_finite() && h > 0.0) {
        return Err(ToiError::TimeTolerance(h));
    }
    if opts.max_queries == 0 {
        return Err(ToiError::MaxQueries);
    }
    Ok(())
}

/// Certified time of impact of `a` moving by `ma` and `b` moving by `mb` over `[0, 1]`
/// (the solids' own poses are ignored). See the module doc for the method and
/// [`TimeOfImpact`] for what is certified.
pub fn time_of_impact(
    a: &Solid,
    ma: &Motion,
    b: &Solid,
    mb: &Motion,
    opts: &ToiOptions,
) -> Result<TimeOfImpact, ToiError> {
    check(opts)?;
    let mut s = Search {
        a,
        b,
        ma: *ma,
        mb: *mb,
        ra: radius(a),
        rb: radius(b),
        opts: *opts,
        cache: QueryCache::default(),
        queries: 0,
        certificates: 0,
        stats: TraversalStats::default(),
    };
    let dist = opts.contact_distance;
    let speed0 = speed_bound(ma, s.ra, mb, s.rb, 0.0);
    let answer =
        |s: &Search, outcome, t_lower, t_upper: Option<f64>, contact, steps| TimeOfImpact {
            outcome,
            t_lower,
            t_upper,
            contact,
            queries: s.queries,
            steps,
            certificates: s.certificates,
            speed_bound: speed0,
            stats: s.stats,
        };
    // Contact certified at `t` by probe `p` (its upper bound within the contact distance).
    let contact_at = |s: &Search, t: f64, p: Probe| {
        answer(
            s,
            ToiOutcome::Contact,
            t,
            Some(t),
            Some(p.distance),
            s.queries,
        )
    };
    // Advancement: apart on [0, t).
    let eps_sum = a.tree.eps + b.tree.eps;
    let contact_test = |s: &Search| ContactTest {
        a,
        b,
        ma,
        mb,
        ra: s.ra,
        rb: s.rb,
        contact_distance: dist,
    };
    let mut early_tried = false;
    let mut t = 0.0_f64;
    let mut witness: Witness;
    // The last query's upper bound minus D (the distance above D is at most this there).
    let mut gap = f64::INFINITY;
    loop {
        if !s.budget_left() {
            return Ok(answer(&s, ToiOutcome::Undecided, t, None, None, s.queries));
        }
        let mut p = s.probe(t, false, gap)?;
        gap = p.upper - dist;
        if p.upper <= dist {
            return Ok(contact_at(&s, t, p));
        }
        witness = Witness::new(&p.distance, &ma.pose_at(t), &mb.pose_at(t));
        let speed = speed_bound(ma, s.ra, mb, s.rb, t);
        let step = |p: &Probe| {
            if speed > 0.0 {
                (p.lower - dist) / speed * (1.0 - STEP_SHRINK_REL)
            } else {
                f64::INFINITY
            }
        };
        if (p.lower <= dist || step(&p) < opts.time_tolerance) && s.budget_left() {
            p = s.probe(t, true, gap)?;
            gap = p.upper - dist;
            if p.upper <= dist {
                return Ok(contact_at(&s, t, p));
            }
            witness = Witness::new(&p.distance, &ma.pose_at(t), &mb.pose_at(t));
        }
        if p.lower > dist {
            let h = step(&p);
            if t + h > 1.0 {
                // [t, 1] lies inside [t, t + h), where the bound holds.
                return Ok(answer(&s, ToiOutcome::Apart, 1.0, None, None, s.queries));
            }
            if h >= opts.time_tolerance {
                let mut next = below(t + h).max(t);
                if !early_tried && h * speed < eps_sum / EARLY_STALL_DIVISOR && s.budget_left() {
                    // Within a fraction of the trees' eps of D: the remaining steps would
                    // shrink geometrically. One query at tolerance 0 (its lower bound is
                    // close to the distance), its step, then the carried certificate.
                    early_tried = true;
                    let pt = s.probe(t, true, gap)?;
                    gap = pt.upper - dist;
                    if pt.upper <= dist {
                        return Ok(contact_at(&s, t, pt));
                    }
                    witness = Witness::new(&pt.distance, &ma.pose_at(t), &mb.pose_at(t));
                    if pt.lower > dist {
                        let ht = step(&pt);
                        if t + ht > 1.0 {
                            return Ok(answer(&s, ToiOutcome::Apart, 1.0, None, None, s.queries));
                        }
                        next = next.max(below(t + ht));
                    }
                    let test = contact_test(&s);
                    let even = eps_sum / speed;
                    if let Some((hi, c)) = carried_contact(
                        &test,
                        &witness,
                        next,
                        even,
                        opts.time_tolerance,
                        &mut s.certificates,
                    ) {
                        let steps = s.queries;
                        return Ok(answer(
                            &s,
                            ToiOutcome::Contact,
                            next,
                            Some(hi),
                            Some(contact_distance_of(&c)),
                            steps,
                        ));
                    }
                }
                t = next;
                continue;
            }
        }
        break;
    }
    let steps = s.queries;
    // Stalled at t: a contact certified from the carried witnesses first.
    let test = contact_test(&s);
    {
        let speed = speed_bound(ma, s.ra, mb, s.rb, t);
        let even = if speed > 0.0 {
            (a.tree.eps + b.tree.eps) / speed
        } else {
            1.0
        };
        if let Some((hi, c)) = carried_contact(
            &test,
            &witness,
            t,
            even,
            opts.time_tolerance,
            &mut s.certificates,
        ) {
            return Ok(answer(
                &s,
                ToiOutcome::Contact,
                t,
                Some(hi),
                Some(contact_distance_of(&c)),
                steps,
            ));
        }
    }
    // Then distance queries at tolerance 0 (their overlap certificates search both solids).
    let contact_probe = |s: &mut Search, at: f64| -> Result<Option<Distance>, ToiError> {
        let p = s.probe(at, true, 0.0)?;
        Ok((p.upper <= dist).then_some(p.distance))
    };
    let mut h = opts.time_tolerance;
    let mut before = t;
    let mut found: Option<(f64, Distance)> = None;
    while s.budget_left() {
        let probe_t = (t + h).min(1.0);
        if let Some(d) = contact_probe(&mut s, probe_t)? {
            found = Some((probe_t, d));
            break;
        }
        if probe_t >= 1.0 {
            break;
        }
        before = probe_t;
        h *= 2.0;
    }
    let Some((mut hi, mut hit)) = found else {
        return Ok(answer(&s, ToiOutcome::Undecided, t, None, None, steps));
    };
    // Move t_upper down towards t while contacts keep being certified.
    let mut lo = before;
    while hi - t > opts.time_tolerance && hi - lo > opts.time_tolerance && s.budget_left() {
        let mid = 0.5 * (lo + hi);
        match contact_probe(&mut s, mid)? {
            Some(d) => (hi, hit) = (mid, d),
            None => lo = mid,
        }
    }
    Ok(answer(
        &s,
        ToiOutcome::Contact,
        t,
        Some(hi),
        Some(hit),
        steps,
    ))
}

/// Evenly spaced tries of the carried certificate before the steps start doubling: at a
/// stall the distance is within a few eps of contact, and a thin overlap window (a wall
/// crossed at an angle) can be shorter than a doubled step.
const EVEN_TRIES: usize = 64;

/// The first time after `t` at which the carried witnesses certify a contact
/// ([`super::contact`]): [`EVEN_TRIES`] steps of `even` (the time the distance needs to change
/// by the trees' eps at the speed bound), then doubling steps, then bisection down to `h`;
/// `None` when no time up to 1 certifies one.
fn carried_contact(
    test: &ContactTest,
    w: &Witness,
    t: f64,
    even: f64,
    h: f64,
    count: &mut usize,
) -> Option<(f64, CertifiedContact)> {
    let mut certify = |at: f64| {
        *count += 1;
        test.certify(at, w)
    };
    let (mut step, mut lo, mut tries) = (even.max(h), t, 0);
    let (mut hi, mut hit) = loop {
        let at = (lo + step).min(1.0);
        if let Some(c) = certify(at) {
            break (at, c);
        }
        if at >= 1.0 {
            return None;
        }
        lo = at;
        tries += 1;
        if tries >= EVEN_TRIES {
            step *= 2.0;
        }
    };
    while hi - lo > h && hi - t > h {
        let mid = 0.5 * (lo + hi);
        match certify(mid) {
            Some(c) => (hi, hit) = (mid, c),
            None => lo = mid,
        }
    }
    Some((hi, hit))
}

/// A carried certificate as the answer's contact query.
fn contact_distance_of(c: &CertifiedContact) -> Distance {
    Distance {
        value: c.upper,
        lower: 0.0,
        upper: c.upper,
        point_a: c.point_a,
        point_b: c.point_b,
        overlap: c.upper == 0.0,
        stats: TraversalStats::default(),
    }
}
