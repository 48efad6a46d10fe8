//! `revdist distance`: minimum distance between two posed solids of revolution, one query
//! from the command line or a batch of JSON lines.
//!
//! Solid A sits at the identity; `pose_b` places B in A's frame: a point `x` of B's own
//! frame is at `R x + t`, `R` the unit quaternion `rotation` (w first), `t` the
//! `translation`. Output points are in A's frame.

pub(crate) mod batch;
pub(crate) mod signed;

use std::collections::HashMap;
use std::sync::{Arc, Mutex, OnceLock};

use nalgebra::{Isometry3, Vector3};
use revdist::query::{
    signed_distance, try_distance, width_limit, Distance, QueryOptions, SignedDistance,
};
use revdist::request::{
    build_solid, check_eps, check_tolerance, pose_from_quaternion, query_options, DEFAULT_EPS,
};
use revdist::solid::Solid;
use serde::{Deserialize, Serialize};

use crate::input::load_profile;
use crate::CmdResult;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Solid A: built-in model name or profile file (at the identity pose).
    a: Option<String>,
    /// Solid B: built-in model name or profile file (placed by --pose-b).
    b: Option<String>,
    /// Pose of B in A's frame as JSON: {"translation": [x,y,z], "rotation": [w,x,y,z]}.
    #[arg(long)]
    pose_b: Option<String>,
    /// Approximation bound of the biarc trees.
    #[arg(long, default_value_t = DEFAULT_EPS)]
    eps: f64,
    /// Target width of the certified interval (upper - lower); default: the trees' own
    /// accuracy, eps_A + eps_B. 0 runs until nothing can be narrowed.
    #[arg(long)]
    tolerance: Option<f64>,
    /// Refine the witness points on the exact NURBS surfaces.
    #[arg(long)]
    refine: bool,
    /// Anytime budget: stop after this many node pairs with the bounds reached.
    #[arg(long)]
    max_node_pairs: Option<usize>,
    /// Anytime budget: stop after this many milliseconds with the bounds reached.
    #[arg(long)]
    max_time_ms: Option<f64>,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Batch mode: read JSON lines {"a", "b", "pose_b", "eps", "tolerance", "refine",
    /// "signed"} from
    /// this file ("-" for stdin) and write exactly one JSON line per input line, in order,
    /// each with its "line" number; exit status 1 when some line failed.
    #[arg(long, conflicts_with_all = ["a", "b", "pose_b"])]
    batch: Option<String>,
    /// Batch mode: worker threads (default: every core).
    #[arg(long, requires = "batch")]
    threads: Option<usize>,
    /// Add each query's wall time in microseconds ("time_us") to its output.
    #[arg(long)]
    timings: bool,
    /// Signed distance: for solids not certified apart, also bound the translational
    /// penetration depth ("penetration": lower, upper, direction, point) and give
    /// "signed_distance": {lower, upper} (the distance when apart, minus the depth when
    /// overlapping). The budget and --tolerance apply to the depth's interval.
    #[arg(long)]
    signed: bool,
}

/// Pose as written in JSON.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct PoseJson {
    #[serde(default)]
    translation: Option<[f64; 3]>,
    #[serde(default)]
    rotation: Option<[f64; 4]>,
}

/// One batch request.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    a: String,
    b: String,
    #[serde(default)]
    pose_b: Option<PoseJson>,
    #[serde(default)]
    eps: Option<f64>,
    #[serde(default)]
    tolerance: Option<f64>,
    #[serde(default)]
    refine: Option<bool>,
    #[serde(default)]
    signed: Option<bool>,
}

/// One result line.
#[derive(Debug, Serialize)]
pub(crate) struct Output {
    /// Input line (batch mode, 1-based).
    #[serde(skip_serializing_if = "Option::is_none")]
    line: Option<usize>,
    distance: f64,
    lower: f64,
    upper: f64,
    point_a: [f64; 3],
    point_b: [f64; 3],
    overlap: bool,
    node_pairs: usize,
    leaf_bounds: usize,
    leaf_tests: usize,
    subdivided_pairs: usize,
    budget_exhausted: bool,
    /// Answered by the closed form for two balls or solid tori (no traversal).
    closed_form: bool,
    /// What limited `upper - lower`: `met` (the requested width), `budget`, `rounding`
    /// (the slack at this configuration's scale) or `leaves` (the trees' own accuracy).
    width_limit: &'static str,
    /// Wall time of the query in microseconds (`--timings`).
    #[serde(skip_serializing_if = "Option::is_none")]
    time_us: Option<f64>,
    /// Derivatives of the distance with respect to B's pose (`Distance::gradient`):
    /// present only when the solids are certified apart; with `--signed`, of the signed
    /// distance (`SignedDistance::gradient`), also when they overlap with a narrow depth
    /// interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    gradient: Option<GradientJson>,
    /// `--signed`: the signed distance's certified interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    signed_distance: Option<signed::IntervalJson>,
    /// `--signed`, solids not certified apart: the penetration depth's interval.
    #[serde(skip_serializing_if = "Option::is_none")]
    penetration: Option<signed::PenetrationJson>,
}

/// `Distance::gradient` as written in JSON (A's frame).
#[derive(Debug, Serialize)]
pub(crate) struct GradientJson {
    /// Unit normal (point_b - point_a) / |point_b - point_a|.
    pub(crate) normal: [f64; 3],
    /// d distance / d translation of B.
    pub(crate) translation: [f64; 3],
    /// d distance / d rotation vector of B about its frame origin.
    pub(crate) rotation: [f64; 3],
}

impl Output {
    /// Adds the gradient with respect to B's pose, B's frame origin at `origin_b`.
    pub(crate) fn with_gradient(mut self, d: &Distance, origin_b: &Vector3<f64>) -> Self {
        self.gradient = d
            .gradient(&nalgebra::Point3::from(*origin_b))
            .map(|g| GradientJson {
                normal: g.normal.into(),
                translation: g.translation.into(),
                rotation: g.rotation.into(),
            });
        self
    }
}

impl From<&Distance> for Output {
    fn from(d: &Distance) -> Self {
        Output {
            line: None,
            distance: d.value,
            lower: d.lower,
            upper: d.upper,
            point_a: [d.point_a.x, d.point_a.y, d.point_a.z],
            point_b: [d.point_b.x, d.point_b.y, d.point_b.z],
            overlap: d.overlap,
            node_pairs: d.stats.node_pairs,
            leaf_bounds: d.stats.leaf_bounds,
            leaf_tests: d.stats.leaf_tests,
            subdivided_pairs: d.stats.subdivided_pairs,
            budget_exhausted: d.stats.budget_exhausted,
            closed_form: d.stats.closed_forms > 0,
            width_limit: "met",
            time_us: None,
            gradient: None,
            signed_distance: None,
            penetration: None,
        }
    }
}

pub(crate) fn pose_from_json(p: &PoseJson) -> Result<Isometry3<f64>, String> {
    pose_from_quaternion(
        p.translation.unwrap_or([0.0; 3]),
        p.rotation.unwrap_or([1.0, 0.0, 0.0, 0.0]),
    )
    .map_err(|e| e.to_string())
}

fn parse_pose(s: &str) -> Result<Isometry3<f64>, String> {
    parse_pose_flag("--pose-b", s)
}

/// A pose given on the command line as JSON; errors name the flag.
pub(crate) fn parse_pose_flag(flag: &str, s: &str) -> Result<Isometry3<f64>, String> {
    let p: PoseJson = serde_json::from_str(s).map_err(|e| format!("{flag}: {e}"))?;
    pose_from_json(&p).map_err(|e| format!("{flag}: {e}"))
}

/// A solid built once for every query that names it.
type SharedSolid = Arc<OnceLock<Result<Solid, String>>>;

/// Solids built so far, by (profile spec, eps bits); shared by the batch's workers, each
/// shape built once (a second worker asking for it waits for the first).
#[derive(Default)]
pub(crate) struct SolidCache {
    solids: Mutex<HashMap<(String, u64), SharedSolid>>,
}

impl SolidCache {
    pub(crate) fn get(&self, spec: &str, eps: f64) -> Result<Solid, String> {
        let slot = {
            let mut solids = self.solids.lock().unwrap_or_else(|e| e.into_inner());
            Arc::clone(solids.entry((spec.to_string(), eps.to_bits())).or_default())
        };
        slot.get_or_init(|| {
            let profile = load_profile(spec).map_err(|e| e.to_string())?;
            build_solid(spec, profile, eps).map_err(|e| e.to_string())
        })
        .clone()
    }
}

pub fn run(args: Args) -> CmdResult {
    let opts = query_options(
        args.tolerance,
        args.max_node_pairs,
        ("--max-time-ms", args.max_time_ms),
        args.refine,
    )?;
    if let Some(path) = &args.batch {
        check_eps(args.eps)?;
        let threads = match args.threads {
            Some(0) => return Err("--threads must be at least 1".into()),
            Some(n) => n,
            None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        };
        let settings = batch::Settings {
            default_eps: args.eps,
            opts,
            timings: args.timings,
            signed: args.signed,
        };
        return batch::run(path, threads, &|number, line, cache| {
            answer_line(number, line, &settings, cache)
        });
    }
    let (Some(a), Some(b)) = (&args.a, &args.b) else {
        return Err("give two solids A B, or --batch FILE".into());
    };
    check_eps(args.eps)?;
    let pose = match &args.pose_b {
        Some(s) => parse_pose(s)?,
        None => Isometry3::identity(),
    };
    let cache = SolidCache::default();
    let sa = cache.get(a, args.eps)?;
    let sb = cache.get(b, args.eps)?.with_pose(pose);
    let started = std::time::Instant::now();
    let (d, sd) = query(&sa, &sb, &opts, args.signed)?;
    let time_us = started.elapsed().as_secs_f64() * 1e6;
    let limit = width_limit(&sa, &sb, &opts, &d).name();
    if args.json {
        let mut out = Output::from(&d).with_gradient(&d, &pose.translation.vector);
        if let Some(s) = &sd {
            out = out.with_signed(s, &pose.translation.vector);
        }
        out.width_limit = limit;
        out.time_us = args.timings.then_some(time_us);
        println!("{}", serde_json::to_string(&out)?);
    } else {
        println!("distance  {:.12e}", d.value);
        println!("interval  [{:.12e}, {:.12e}]", d.lower, d.upper);
        println!(
            "point_a   {:.9} {:.9} {:.9}",
            d.point_a.x, d.point_a.y, d.point_a.z
        );
        println!(
            "point_b   {:.9} {:.9} {:.9}",
            d.point_b.x, d.point_b.y, d.point_b.z
        );
        println!("overlap   {}", d.overlap);
        if let Some(s) = &sd {
            signed::print_text(s);
        }
        let gradient = match &sd {
            Some(s) => s.gradient(&pose.translation.vector.into()),
            None => d.gradient(&pose.translation.vector.into()),
        };
        if let Some(g) = gradient {
            let v = |x: nalgebra::Vector3<f64>| format!("{:.9} {:.9} {:.9}", x.x, x.y, x.z);
            println!("d/dt_B    {}", v(g.translation));
            println!("d/dr_B    {}", v(g.rotation));
        }
        if limit != "met" {
            println!("width     wider than asked: limited by {limit}");
        }
        if args.timings {
            println!("time      {time_us:.1} us");
        }
        if d.stats.closed_forms > 0 {
            println!("stats     closed form (two balls or solid tori: core distance minus radii)");
            return Ok(());
        }
        println!(
            "stats     {} node pairs, {} leaf pairs bounded, {} solved exactly ({} patch pairs){}",
            d.stats.node_pairs,
            d.stats.leaf_bounds,
            d.stats.leaf_tests,
            d.stats.patch_tests,
            if d.stats.budget_exhausted {
                " (budget exhausted)"
            } else {
                ""
            }
        );
    }
    Ok(())
}

/// A batch line's request to a query ready to run, or a per-line error message.
pub(crate) fn prepare_request(
    line: &str,
    settings: &batch::Settings,
    cache: &SolidCache,
) -> Result<(Solid, Solid, QueryOptions, bool), String> {
    let req: Request = serde_json::from_str(line).map_err(|e| format!("bad request: {e}"))?;
    let eps = check_eps(req.eps.unwrap_or(settings.default_eps)).map_err(|e| e.to_string())?;
    let mut opts = settings.opts;
    if let Some(t) = req.tolerance {
        opts.tolerance = check_tolerance(Some(t)).map_err(|e| e.to_string())?;
    }
    if let Some(r) = req.refine {
        opts.refine = r;
    }
    let signed = req.signed.unwrap_or(settings.signed);
    let pose = match &req.pose_b {
        Some(p) => pose_from_json(p).map_err(|e| format!("pose_b: {e}"))?,
        None => Isometry3::identity(),
    };
    let a = cache.get(&req.a, eps)?;
    let b = cache.get(&req.b, eps)?.with_pose(pose);
    Ok((a, b, opts, signed))
}

/// The distance, and with `signed` the signed distance (which holds the same distance).
fn query(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    signed: bool,
) -> Result<(Distance, Option<SignedDistance>), String> {
    if signed {
        let s = signed_distance(a, b, opts).map_err(|e| e.to_string())?;
        Ok((s.distance.clone(), Some(s)))
    } else {
        Ok((try_distance(a, b, opts).map_err(|e| e.to_string())?, None))
    }
}

/// One batch line's output: its result with its line number, or its error.
pub(crate) fn answer_line(
    number: usize,
    line: Result<&str, String>,
    settings: &batch::Settings,
    cache: &SolidCache,
) -> Result<String, String> {
    let (a, b, opts, signed) = prepare_request(line?, settings, cache)?;
    let started = std::time::Instant::now();
    let (d, sd) = query(&a, &b, &opts, signed)?;
    let time_us = started.elapsed().as_secs_f64() * 1e6;
    let mut out = Output::from(&d).with_gradient(&d, &b.pose.translation.vector);
    if let Some(s) = &sd {
        out = out.with_signed(s, &b.pose.translation.vector);
    }
    out.line = Some(number);
    out.width_limit = width_limit(&a, &b, &opts, &d).name();
    out.time_us = settings.timings.then_some(time_us);
    serde_json::to_string(&out).map_err(|e| e.to_string())
}
