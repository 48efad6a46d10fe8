//! One query checked against the oracle: the tree build and the query with panics caught,
//! the oracle's bounds tightened by the query's witnesses, the checks, and the same query
//! warm-started from a nearby pose's best leaf pair (the frame coherence motion sequences
//! use; its violations are marked "warm start").

use super::cases::Case;
use super::panics::panic_message;
use super::pool::Shape;
use super::pose_spec::PoseSpec;
use super::tree_cache::TreeCache;
use crate::oracle::{self, check, refine_hint, surface_distance, CheckInput, OracleOptions};
use crate::oracle::{OracleResult, PlanarIndex};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::profile::Profile;
use revdist::query::{
    distance, distance_cached, query_slack, Distance, QueryCache, QueryOptions, Tolerance,
};
use revdist::solid::Solid;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// Outcome of one case.
#[derive(Debug, Clone)]
pub struct CaseResult {
    pub case: Case,
    pub answer: Option<Distance>,
    pub oracle: Option<OracleResult>,
    pub violations: Vec<oracle::Violation>,
    /// Tree construction failed (message).
    pub build_error: Option<String>,
    pub query_time: Duration,
    pub oracle_time: Duration,
    /// The query's witnesses led the oracle to a smaller realised distance.
    pub hint_improved: Option<f64>,
    /// Time spent placing the pose (quick oracle runs).
    pub place_time: Duration,
    /// The query (or the tree build) panicked: message and location.
    pub panic: Option<String>,
}

impl CaseResult {
    /// A violation, a tree-build error or a panic.
    pub fn failed(&self) -> bool {
        !self.violations.is_empty() || self.build_error.is_some() || self.panic.is_some()
    }
}

/// The pose a case's warm-started query is primed from, as the frame before it in a
/// motion: B moved by a small deterministic step (0.5% of the configuration scale along a
/// fixed direction, 0.03 rad about a fixed axis), which usually changes the best leaf pair
/// near contact but not by much.
fn warm_prime_pose(pose: &Isometry3<f64>) -> Isometry3<f64> {
    let scale = 1.0 + pose.translation.vector.norm();
    let step = Vector3::new(0.6, -0.48, 0.64) * (0.005 * scale);
    let turn = UnitQuaternion::from_scaled_axis(Vector3::new(0.02, 0.01, -0.02));
    Isometry3::from_parts(
        Translation3::from(pose.translation.vector + step),
        turn * pose.rotation,
    )
}

/// The violations (marked "warm start") of the case's query between `sa` and the posed `sb`
/// warm-started ([`distance_cached`]) from the best leaf pair of a query with `sb` at
/// [`warm_prime_pose`]: frame coherence, the start motion sequences use. `inp` holds the
/// case's checks, with the cold answer.
fn warm_violations(
    inp: &CheckInput<'_>,
    sa: &Solid,
    sb: &Solid,
    qopts: &QueryOptions,
) -> Vec<oracle::Violation> {
    let mut cache = QueryCache::default();
    distance_cached(
        sa,
        &sb.with_pose(warm_prime_pose(&sb.pose)),
        qopts,
        &mut cache,
    );
    let warm = distance_cached(sa, sb, qopts, &mut cache);
    check(&CheckInput { d: &warm, ..*inp })
        .into_iter()
        .map(|v| oracle::Violation {
            detail: format!("warm start: {}", v.detail),
            ..v
        })
        .collect()
}

/// The checks' input for the answer `d` between `sa` (at the identity) and the posed `sb`,
/// against the oracle's `o` on the planar indices `a` and `b`.
fn check_input<'a>(
    d: &'a Distance,
    sa: &'a Solid,
    sb: &'a Solid,
    qopts: &QueryOptions,
    o: &'a OracleResult,
    a: &'a PlanarIndex,
    b: &'a PlanarIndex,
) -> CheckInput<'a> {
    CheckInput {
        d,
        pose_a: &sa.pose,
        pose_b: &sb.pose,
        eps_a: sa.tree.eps,
        eps_b: sb.tree.eps,
        tolerance: qopts
            .tolerance
            .width(sa.tree.target_eps, sb.tree.target_eps),
        declared_slack: query_slack(&sa.tree, &sb.tree, &sa.relative_pose(sb)),
        oracle: o,
        a,
        b,
    }
}

/// Runs one case: tree, query, oracle, checks.
pub(super) fn run_case(case: Case, shapes: &[Shape], trees: &TreeCache) -> CaseResult {
    let mut res = CaseResult {
        case: case.clone(),
        answer: None,
        oracle: None,
        violations: Vec::new(),
        build_error: None,
        query_time: Duration::ZERO,
        oracle_time: Duration::ZERO,
        hint_improved: None,
        place_time: Duration::ZERO,
        panic: None,
    };
    let built = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        (
            trees.get(shapes, case.a, case.eps),
            trees.get(shapes, case.b, case.eps),
        )
    }));
    let built = match built {
        Ok(b) => b,
        Err(e) => {
            res.panic = Some(format!("tree build: {}", panic_message(e.as_ref())));
            return res;
        }
    };
    let (sa, sb) = match built {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            res.build_error = Some(e);
            return res;
        }
    };
    let pose_b = case.pose.isometry();
    let sb = sb.with_pose(pose_b);
    let t0 = Instant::now();
    let qopts = QueryOptions {
        tolerance: query_tolerance(case.tolerance),
        refine: case.refine,
        ..QueryOptions::default()
    };
    let answer =
        std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| distance(&sa, &sb, &qopts)));
    res.query_time = t0.elapsed();
    let d = match answer {
        Ok(d) => d,
        Err(e) => {
            res.panic = Some(panic_message(e.as_ref()));
            return res;
        }
    };
    let (ia, ib) = (&shapes[case.a].index, &shapes[case.b].index);
    let t1 = Instant::now();
    let mut o = surface_distance(ia, ib, &pose_b, &oracle_options(&d, ia, ib, &pose_b));
    // The query's witnesses as a hint: a realised pair from them can only tighten U.
    if d.point_a
        .coords
        .iter()
        .chain(d.point_b.coords.iter())
        .all(|v| v.is_finite())
    {
        let (h, pa, pb) = refine_hint(ia, ib, &pose_b, &d.point_a, &d.point_b);
        if h < o.upper * (1.0 - 1e-9) - 1e-12 {
            res.hint_improved = Some(o.upper - h);
            o.upper = h;
            o.point_a = pa;
            o.point_b = pb;
            o.lower = o.lower.min(h);
        }
    }
    res.oracle_time = t1.elapsed();
    let inp = check_input(&d, &sa, &sb, &qopts, &o, ia, ib);
    res.violations = check(&inp);
    let warm = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        warm_violations(&inp, &sa, &sb, &qopts)
    }));
    match warm {
        Ok(v) => res.violations.extend(v),
        Err(e) => res.panic = Some(format!("warm start: {}", panic_message(e.as_ref()))),
    }
    res.answer = Some(d);
    res.oracle = Some(o);
    res
}

/// The oracle's options for checking the answer `d`: thorough, with the lower estimate
/// wanted only up to what check b can use, the query's upper bound plus twice the scene's
/// round-off slack (`docs/verification.md`, "An oracle that finishes").
fn oracle_options(
    d: &Distance,
    a: &PlanarIndex,
    b: &PlanarIndex,
    pose_b: &Isometry3<f64>,
) -> OracleOptions {
    let slack = oracle::scene_slack(a, b, pose_b);
    OracleOptions {
        goal: d.upper + 2.0 * slack,
        ..OracleOptions::full()
    }
}

/// The query tolerance of a case: absolute when given, else the trees' accuracy.
fn query_tolerance(t: Option<f64>) -> Tolerance {
    t.map_or(Tolerance::Trees, Tolerance::Absolute)
}

/// A single query checked against the oracle (for the `verify oracle` command).
pub fn single(
    a: &Profile,
    b: &Profile,
    pose: &PoseSpec,
    eps: f64,
    tolerance: Option<f64>,
    refine: bool,
) -> Result<
    (
        Distance,
        OracleResult,
        Vec<oracle::Violation>,
        Duration,
        Duration,
    ),
    String,
> {
    let sa = Solid::from_profile(Arc::new(a.clone()), eps).map_err(|e| e.to_string())?;
    let sb = Solid::from_profile(Arc::new(b.clone()), eps)
        .map_err(|e| e.to_string())?
        .with_pose(pose.isometry());
    let qopts = QueryOptions {
        tolerance: query_tolerance(tolerance),
        refine,
        ..QueryOptions::default()
    };
    let t0 = Instant::now();
    let d = distance(&sa, &sb, &qopts);
    let tq = t0.elapsed();
    let (ia, ib) = (oracle::index(a), oracle::index(b));
    let t1 = Instant::now();
    let iso = pose.isometry();
    let mut o = surface_distance(&ia, &ib, &iso, &oracle_options(&d, &ia, &ib, &iso));
    let (h, pa, pb) = refine_hint(&ia, &ib, &iso, &d.point_a, &d.point_b);
    if h < o.upper {
        o.upper = h;
        o.point_a = pa;
        o.point_b = pb;
        o.lower = o.lower.min(h);
    }
    let to = t1.elapsed();
    let inp = check_input(&d, &sa, &sb, &qopts, &o, &ia, &ib);
    let mut v = check(&inp);
    v.extend(warm_violations(&inp, &sa, &sb, &qopts));
    Ok((d, o, v, tq, to))
}
