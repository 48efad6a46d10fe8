//! The one query entry point, `Pair.distance`, behind both of the package's: `revdist.distance`
//! (independent poses, spread over the cores with rayon) and `revdist.Pair` (a motion:
//! consecutive poses warm-start each other through a `QueryCache`). Both release the GIL for
//! the whole batch.
//!
//! Each pose is measured by `revdist::query::try_distance` (`try_distance_cached` for a
//! `Pair`) with A at `pose_a` and B at the pose, exactly the command line's batch query
//! (`revdist distance --batch`, which places A at the identity), so that the answers are
//! the same bits. With `signed`, by `revdist::query::signed_distance` (always cold), the
//! batch's `"signed": true`: the distance of the same query plus the penetration depth's
//! certified interval and the signed distance's gradient.

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use nalgebra::{Isometry3, Point3};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyReadonlyArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use rayon::prelude::*;
use revdist::query::{
    signed_distance, try_distance, try_distance_cached, width_limit, Distance, QueryCache,
    QueryOptions, SignedDistance,
};
use revdist::request::query_options;
use revdist::solid::Solid;

use crate::errors::value_error;
use crate::poses::{self, Poses};
use crate::solid::PySolid;

/// Names of `revdist::query::WidthLimit`, indexed by the codes of the
/// `width_limit_code` array (the command line's `"width_limit"` strings).
pub const WIDTH_LIMIT_NAMES: [&str; 4] = ["met", "budget", "rounding", "leaves"];

/// One pose's answer, compact (what the arrays hold), or the pose's error.
type Answer = Result<Row, String>;

/// The fields of a `Distance` the result arrays hold.
struct Row {
    value: f64,
    lower: f64,
    upper: f64,
    point_a: [f64; 3],
    point_b: [f64; 3],
    /// The distance's derivatives with respect to B's translation and rotation about its
    /// origin ([`Distance::gradient`]); NaN unless the solids are certified apart.
    gradient_translation: [f64; 3],
    gradient_rotation: [f64; 3],
    /// node pairs, leaf bounds, leaf tests, subdivided pairs.
    counters: [u64; 4],
    overlap: bool,
    budget_exhausted: bool,
    closed_form: bool,
    /// Index into [`WIDTH_LIMIT_NAMES`].
    width_limit: u8,
    /// With `signed`: the signed distance and the penetration depth.
    signed: Option<SignedRow>,
}

/// The fields of a `SignedDistance` the result arrays hold (`docs/cli.md`, `--signed`).
struct SignedRow {
    /// The signed distance's certified interval.
    lower: f64,
    upper: f64,
    /// The penetration depth's certified interval and the unit translation of B achieving
    /// its upper bound: `[0, 0]` and zeros when the solids are certified apart (their depth
    /// is 0), as `revdist::query::penetration` answers.
    pd_lower: f64,
    pd_upper: f64,
    pd_direction: [f64; 3],
}

impl SignedRow {
    fn new(s: &SignedDistance) -> SignedRow {
        let (pd_lower, pd_upper, pd_direction) = match &s.penetration {
            Some(p) => (p.lower, p.upper, p.direction.into()),
            None => (0.0, 0.0, [0.0; 3]),
        };
        SignedRow {
            lower: s.lower,
            upper: s.upper,
            pd_lower,
            pd_upper,
            pd_direction,
        }
    }
}

impl Row {
    fn new(d: &Distance, origin_b: &Point3<f64>, width_limit: u8) -> Row {
        let g = d.gradient(origin_b);
        let nan = [f64::NAN; 3];
        Row {
            gradient_translation: g.map_or(nan, |g| g.translation.into()),
            gradient_rotation: g.map_or(nan, |g| g.rotation.into()),
            value: d.value,
            lower: d.lower,
            upper: d.upper,
            point_a: [d.point_a.x, d.point_a.y, d.point_a.z],
            point_b: [d.point_b.x, d.point_b.y, d.point_b.z],
            counters: [
                d.stats.node_pairs as u64,
                d.stats.leaf_bounds as u64,
                d.stats.leaf_tests as u64,
                d.stats.subdivided_pairs as u64,
            ],
            overlap: d.overlap,
            budget_exhausted: d.stats.budget_exhausted,
            closed_form: d.stats.closed_forms > 0,
            width_limit,
            signed: None,
        }
    }

    /// The row of a signed query: its distance's fields, the signed distance's gradient
    /// ([`SignedDistance::gradient`]: the distance's when apart, the depth's where its
    /// interval is narrow, else NaN) and the depth, as the command line's `--signed`.
    fn from_signed(s: &SignedDistance, origin_b: &Point3<f64>, width_limit: u8) -> Row {
        let mut row = Row::new(&s.distance, origin_b, width_limit);
        let g = s.gradient(origin_b);
        let nan = [f64::NAN; 3];
        row.gradient_translation = g.map_or(nan, |g| g.translation.into());
        row.gradient_rotation = g.map_or(nan, |g| g.rotation.into());
        row.signed = Some(SignedRow::new(s));
        row
    }
}

/// What a call asks, checked: the poses of A (one, or one per pose of B) and of B, and the
/// query options.
struct Call {
    poses_a: Vec<Isometry3<f64>>,
    poses_b: Poses,
    opts: QueryOptions,
    /// Signed distances and penetration depths (cold queries).
    signed: bool,
}

impl Call {
    fn new(
        poses_b: &PyReadonlyArrayDyn<'_, f64>,
        pose_a: Option<&PyReadonlyArrayDyn<'_, f64>>,
        tolerance: Option<f64>,
        max_time_ms: Option<f64>,
        max_node_pairs: Option<usize>,
        refine: bool,
        signed: bool,
    ) -> PyResult<Call> {
        let opts = query_options(
            tolerance,
            max_node_pairs,
            ("max_time_ms", max_time_ms),
            refine,
        )
        .map_err(value_error)?;
        let poses_b = poses::read("poses", poses_b)?;
        let poses_a = match pose_a {
            None => vec![Isometry3::identity()],
            Some(p) => poses::read("pose_a", p)?.poses,
        };
        if poses_a.len() != 1 && poses_a.len() != poses_b.poses.len() {
            return Err(value_error(format!(
                "pose_a holds {} poses and poses {}: give one pose_a or one per pose",
                poses_a.len(),
                poses_b.poses.len()
            )));
        }
        Ok(Call {
            poses_a,
            poses_b,
            opts,
            signed,
        })
    }

    fn pose_a(&self, i: usize) -> Isometry3<f64> {
        self.poses_a[if self.poses_a.len() == 1 { 0 } else { i }]
    }
}

/// The query of pose `i` on `pair`, copies of the two solids whose poses are set here (the
/// same as `Solid::with_pose`, without touching the shared trees' reference counts), with or
/// without a warm start; a signed query is always cold (the warm start is not used or
/// changed).
fn answer(
    pair: &mut (Solid, Solid),
    call: &Call,
    i: usize,
    cache: Option<&mut QueryCache>,
) -> Answer {
    let (a, b) = pair;
    a.pose = call.pose_a(i);
    b.pose = call.poses_b.poses[i];
    let origin_b = Point3::from(b.pose.translation.vector);
    if call.signed {
        let s = signed_distance(a, b, &call.opts).map_err(|e| format!("poses[{i}]: {e}"))?;
        let limit = width_limit(a, b, &call.opts, &s.distance) as u8;
        return Ok(Row::from_signed(&s, &origin_b, limit));
    }
    let d = match cache {
        Some(cache) => try_distance_cached(a, b, &call.opts, cache),
        None => try_distance(a, b, &call.opts),
    }
    .map_err(|e| format!("poses[{i}]: {e}"))?;
    let limit = width_limit(a, b, &call.opts, &d) as u8;
    Ok(Row::new(&d, &origin_b, limit))
}

/// The answers as numpy arrays in a dict (the Python layer wraps them in `DistanceResult`),
/// or the first pose's error as a `ValueError`. With `signed`, also `signed_lower`,
/// `signed_upper`, `pd_lower`, `pd_upper` and `pd_direction`.
fn arrays<'py>(
    py: Python<'py>,
    answers: Vec<Answer>,
    single: bool,
    signed: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let n = answers.len();
    let mut value = Vec::with_capacity(n);
    let mut lower = Vec::with_capacity(n);
    let mut upper = Vec::with_capacity(n);
    let mut point_a = Vec::with_capacity(3 * n);
    let mut point_b = Vec::with_capacity(3 * n);
    let mut grad_t = Vec::with_capacity(3 * n);
    let mut grad_r = Vec::with_capacity(3 * n);
    let mut overlap = Vec::with_capacity(n);
    let mut limit = Vec::with_capacity(n);
    let mut node_pairs = Vec::with_capacity(n);
    let mut leaf_bounds = Vec::with_capacity(n);
    let mut leaf_tests = Vec::with_capacity(n);
    let mut subdivided = Vec::with_capacity(n);
    let mut budget = Vec::with_capacity(n);
    let mut closed = Vec::with_capacity(n);
    let mut s_lower = Vec::with_capacity(n);
    let mut s_upper = Vec::with_capacity(n);
    let mut pd_lower = Vec::with_capacity(n);
    let mut pd_upper = Vec::with_capacity(n);
    let mut pd_direction = Vec::with_capacity(3 * n);
    for a in answers {
        let r = a.map_err(value_error)?;
        if let Some(s) = &r.signed {
            s_lower.push(s.lower);
            s_upper.push(s.upper);
            pd_lower.push(s.pd_lower);
            pd_upper.push(s.pd_upper);
            pd_direction.extend(s.pd_direction);
        }
        value.push(r.value);
        lower.push(r.lower);
        upper.push(r.upper);
        point_a.extend(r.point_a);
        point_b.extend(r.point_b);
        grad_t.extend(r.gradient_translation);
        grad_r.extend(r.gradient_rotation);
        overlap.push(r.overlap);
        limit.push(r.width_limit);
        node_pairs.push(r.counters[0]);
        leaf_bounds.push(r.counters[1]);
        leaf_tests.push(r.counters[2]);
        subdivided.push(r.counters[3]);
        budget.push(r.budget_exhausted);
        closed.push(r.closed_form);
    }
    let points = |v: Vec<f64>| Array2::from_shape_vec((n, 3), v).map_err(value_error);
    let out = PyDict::new(py);
    out.set_item("value", value.into_pyarray(py))?;
    out.set_item("lower", lower.into_pyarray(py))?;
    out.set_item("upper", upper.into_pyarray(py))?;
    out.set_item("point_a", points(point_a)?.into_pyarray(py))?;
    out.set_item("point_b", points(point_b)?.into_pyarray(py))?;
    out.set_item("gradient_translation", points(grad_t)?.into_pyarray(py))?;
    out.set_item("gradient_rotation", points(grad_r)?.into_pyarray(py))?;
    out.set_item("overlap", overlap.into_pyarray(py))?;
    out.set_item("width_limit_code", limit.into_pyarray(py))?;
    out.set_item("node_pairs", node_pairs.into_pyarray(py))?;
    out.set_item("leaf_bounds", leaf_bounds.into_pyarray(py))?;
    out.set_item("leaf_tests", leaf_tests.into_pyarray(py))?;
    out.set_item("subdivided_pairs", subdivided.into_pyarray(py))?;
    out.set_item("budget_exhausted", budget.into_pyarray(py))?;
    out.set_item("closed_form", closed.into_pyarray(py))?;
    if signed {
        out.set_item("signed_lower", s_lower.into_pyarray(py))?;
        out.set_item("signed_upper", s_upper.into_pyarray(py))?;
        out.set_item("pd_lower", pd_lower.into_pyarray(py))?;
        out.set_item("pd_upper", pd_upper.into_pyarray(py))?;
        out.set_item("pd_direction", points(pd_direction)?.into_pyarray(py))?;
    }
    out.set_item("single", single)?;
    Ok(out)
}

/// Rayon pools by thread count, built once each (a pool costs ~100 us to start).
fn pool(threads: usize) -> PyResult<Arc<rayon::ThreadPool>> {
    static POOLS: OnceLock<Mutex<HashMap<usize, Arc<rayon::ThreadPool>>>> = OnceLock::new();
    let mut pools = POOLS
        .get_or_init(Default::default)
        .lock()
        .unwrap_or_else(|e| e.into_inner());
    if let Some(p) = pools.get(&threads) {
        return Ok(Arc::clone(p));
    }
    let p = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .map_err(|e| value_error(format!("cannot start {threads} threads: {e}")))?;
    let p = Arc::new(p);
    pools.insert(threads, Arc::clone(&p));
    Ok(p)
}

/// A pair of solids, and the warm start of a motion through their poses
/// (`revdist::query::QueryCache`): the one query entry point of the extension. The Python
/// layer's `revdist.distance` asks a fresh pair for independent poses, `revdist.Pair` keeps
/// one for a motion; see their docstrings.
#[pyclass(name = "Pair", module = "revdist", frozen)]
pub struct PyPair {
    a: Solid,
    b: Solid,
    cache: Mutex<QueryCache>,
}

#[pymethods]
impl PyPair {
    #[new]
    fn new(a: &PySolid, b: &PySolid) -> Self {
        PyPair {
            a: a.solid.clone(),
            b: b.solid.clone(),
            cache: Mutex::new(QueryCache::default()),
        }
    }

    /// Distances at `poses`. With `warm`, in order, each warm-started by the previous one
    /// (and the first by the last pose of the previous warm call), on the calling thread;
    /// without, independent cold queries spread over `threads` (default every core). With
    /// `signed`, signed distances and penetration depths, each query cold (in order when
    /// `warm`, the warm start untouched). The GIL is released while the queries run.
    #[pyo3(signature = (poses, *, pose_a = None, tolerance = None, max_time_ms = None,
        max_node_pairs = None, refine = false, threads = None, warm = true, signed = false))]
    #[allow(clippy::too_many_arguments)]
    fn distance<'py>(
        &self,
        py: Python<'py>,
        poses: PyReadonlyArrayDyn<'py, f64>,
        pose_a: Option<PyReadonlyArrayDyn<'py, f64>>,
        tolerance: Option<f64>,
        max_time_ms: Option<f64>,
        max_node_pairs: Option<usize>,
        refine: bool,
        threads: Option<usize>,
        warm: bool,
        signed: bool,
    ) -> PyResult<Bound<'py, PyDict>> {
        let call = Call::new(
            &poses,
            pose_a.as_ref(),
            tolerance,
            max_time_ms,
            max_node_pairs,
            refine,
            signed,
        )?;
        let answers = if warm {
            if threads.is_some() {
                return Err(value_error(
                    "threads: a warm-started motion runs in order on the calling thread",
                ));
            }
            py.detach(|| self.in_order(&call))
        } else {
            self.spread(py, &call, threads)?
        };
        arrays(py, answers, call.poses_b.single, call.signed)
    }

    /// Forgets the warm start (the next query is cold).
    fn reset(&self) {
        *self.cache.lock().unwrap_or_else(|e| e.into_inner()) = QueryCache::default();
    }
}

impl PyPair {
    /// The poses in order, each warm-started by the previous one; stops at the first error.
    fn in_order(&self, call: &Call) -> Vec<Answer> {
        let mut cache = self.cache.lock().unwrap_or_else(|e| e.into_inner());
        let mut pair = (self.a.clone(), self.b.clone());
        let mut out = Vec::with_capacity(call.poses_b.poses.len());
        for i in 0..call.poses_b.poses.len() {
            let r = answer(&mut pair, call, i, Some(&mut cache));
            let failed = r.is_err();
            out.push(r);
            if failed {
                break;
            }
        }
        out
    }

    /// Independent cold queries, over the cores (one thread: on the caller's, so that
    /// concurrent single-threaded calls from several Python threads run side by side; more
    /// share a pool of that size).
    fn spread(&self, py: Python<'_>, call: &Call, threads: Option<usize>) -> PyResult<Vec<Answer>> {
        let pool = match threads {
            Some(0) => return Err(value_error("threads must be at least 1")),
            Some(1) => None,
            Some(t) => Some(pool(t)?),
            None => None,
        };
        let n = call.poses_b.poses.len();
        let fresh = || (self.a.clone(), self.b.clone());
        let one = |pair: &mut (Solid, Solid), i| answer(pair, call, i, None);
        let all = || -> Vec<Answer> { (0..n).into_par_iter().map_init(fresh, one).collect() };
        Ok(py.detach(|| match (&pool, threads) {
            (_, Some(1)) => {
                let mut pair = fresh();
                (0..n).map(|i| one(&mut pair, i)).collect()
            }
            (Some(p), _) => p.install(all),
            (None, _) => all(),
        }))
    }
}
