//! `revdist toi`: certified time of impact of two solids moving from start to end poses
//! over `t in [0, 1]` (`revdist::toi`: interpolated motion, conservative advancement).
//!
//! Poses are written as for `revdist distance` (A's start pose defaults to the identity,
//! a missing end pose to the start pose: that solid does not move). Points are in the
//! world frame, the frame the poses are given in.
//!
//! `--batch FILE`: JSON lines `{"a", "b", "pose_a", "pose_a_end", "pose_b", "pose_b_end",
//! "eps", "contact_distance"}` (`a`, `b`, `pose_b` required), one output line per input line:
//! the `--json` object with `"line": N`, or `{"line": N, "error": ...}`; the pipeline, exit
//! codes and `--threads` are those of `revdist distance --batch`.

use nalgebra::Isometry3;
use revdist::query::{Budget, QueryOptions};
use revdist::toi::{
    time_of_impact, Motion, TimeOfImpact, ToiOptions, ToiOutcome, DEFAULT_MAX_QUERIES,
    DEFAULT_TIME_TOLERANCE,
};
use serde::Serialize;

use crate::distance::batch;
use crate::distance::{parse_pose_flag, pose_from_json, PoseJson, SolidCache};
use crate::CmdResult;
use revdist::request::{check_eps, DEFAULT_EPS};
use serde::Deserialize;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Solid A: built-in model name or profile file.
    #[arg(required_unless_present = "batch")]
    a: Option<String>,
    /// Solid B: built-in model name or profile file.
    #[arg(required_unless_present = "batch")]
    b: Option<String>,
    /// Start pose of B as JSON: {"translation": [x,y,z], "rotation": [w,x,y,z]}.
    #[arg(long, required_unless_present = "batch")]
    pose_b: Option<String>,
    /// End pose of B (default: the start pose).
    #[arg(long)]
    pose_b_end: Option<String>,
    /// Start pose of A (default: the identity).
    #[arg(long)]
    pose_a: Option<String>,
    /// End pose of A (default: its start pose).
    #[arg(long)]
    pose_a_end: Option<String>,
    /// Approximation bound of the biarc trees.
    #[arg(long, default_value_t = DEFAULT_EPS)]
    eps: f64,
    /// Contact distance D >= 0: the solids touch when their distance is <= D.
    #[arg(long, default_value_t = 0.0)]
    contact_distance: f64,
    /// Steps of the advancement below this stall it; the bisection of t_upper stops below it.
    #[arg(long, default_value_t = DEFAULT_TIME_TOLERANCE)]
    time_tolerance: f64,
    /// Cap on the number of distance queries (then "undecided").
    #[arg(long, default_value_t = DEFAULT_MAX_QUERIES)]
    max_queries: usize,
    /// Print one JSON object instead of text.
    #[arg(long)]
    json: bool,
    /// Batch mode: read JSON lines {"a", "b", "pose_a", "pose_a_end", "pose_b",
    /// "pose_b_end", "eps", "contact_distance"} from this file ("-" for stdin) and write
    /// exactly one JSON line per input line, in order, each with its "line" number; exit
    /// status 1 when some line failed.
    #[arg(long, conflicts_with_all = ["a", "b", "pose_b", "pose_a", "pose_a_end", "pose_b_end"])]
    batch: Option<String>,
    /// Batch mode: worker threads (default: every core).
    #[arg(long, requires = "batch")]
    threads: Option<usize>,
    /// Batch mode: add each search's wall time in microseconds ("time_us") to its output.
    #[arg(long, requires = "batch")]
    timings: bool,
}

/// One batch request.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct Request {
    a: String,
    b: String,
    #[serde(default)]
    pose_a: Option<PoseJson>,
    #[serde(default)]
    pose_a_end: Option<PoseJson>,
    pose_b: PoseJson,
    #[serde(default)]
    pose_b_end: Option<PoseJson>,
    #[serde(default)]
    eps: Option<f64>,
    #[serde(default)]
    contact_distance: Option<f64>,
}

#[derive(Debug, Serialize)]
struct Output {
    /// Input line (batch mode, 1-based).
    #[serde(skip_serializing_if = "Option::is_none")]
    line: Option<usize>,
    /// "contact", "apart" (on all of [0, 1]) or "undecided".
    outcome: &'static str,
    /// Certified apart (distance > D) for every t < t_lower.
    t_lower: f64,
    /// Distance certified <= D at this time (contact only).
    t_upper: Option<f64>,
    /// Witness points at t_upper (world frame) and the distance interval there.
    point_a: Option<[f64; 3]>,
    point_b: Option<[f64; 3]>,
    lower_at_upper: Option<f64>,
    upper_at_upper: Option<f64>,
    overlap_at_upper: Option<bool>,
    /// Distance queries spent, and those of the advancement alone.
    queries: usize,
    advancement_queries: usize,
    /// Contact certificates tried from carried witnesses (not queries).
    certificates: usize,
    /// The proved bound on the rate of change of the distance at t = 0.
    speed_bound: f64,
    /// Wall time of the search in microseconds (always for one search; `--timings` in a batch).
    #[serde(skip_serializing_if = "Option::is_none")]
    time_us: Option<f64>,
}

impl Output {
    fn new(r: &TimeOfImpact, time_us: Option<f64>) -> Output {
        let c = r.contact.as_ref();
        Output {
            line: None,
            outcome: r.outcome.name(),
            t_lower: r.t_lower,
            t_upper: r.t_upper,
            point_a: c.map(|d| d.point_a.coords.into()),
            point_b: c.map(|d| d.point_b.coords.into()),
            lower_at_upper: c.map(|d| d.lower),
            upper_at_upper: c.map(|d| d.upper),
            overlap_at_upper: c.map(|d| d.overlap),
            queries: r.queries,
            advancement_queries: r.steps,
            certificates: r.certificates,
            speed_bound: r.speed_bound,
            time_us,
        }
    }
}

/// Options of a search with contact distance `d` (the defaults of the library otherwise).
fn search_options(d: f64, time_tolerance: f64, max_queries: usize) -> ToiOptions {
    ToiOptions {
        contact_distance: d,
        query: QueryOptions {
            budget: Budget::default(),
            ..QueryOptions::default()
        },
        time_tolerance,
        max_queries,
    }
}

/// One batch line's output: its result with its line number, or its error.
fn answer_line(
    number: usize,
    line: Result<&str, String>,
    args: &Args,
    cache: &SolidCache,
) -> Result<String, String> {
    let req: Request = serde_json::from_str(line?).map_err(|e| format!("bad request: {e}"))?;
    let eps = check_eps(req.eps.unwrap_or(args.eps)).map_err(|e| e.to_string())?;
    let pose = |name: &str, p: Option<&PoseJson>, default: Isometry3<f64>| {
        p.map_or(Ok(default), |p| {
            pose_from_json(p).map_err(|e| format!("{name}: {e}"))
        })
    };
    let a0 = pose("pose_a", req.pose_a.as_ref(), Isometry3::identity())?;
    let a1 = pose("pose_a_end", req.pose_a_end.as_ref(), a0)?;
    let b0 = pose("pose_b", Some(&req.pose_b), Isometry3::identity())?;
    let b1 = pose("pose_b_end", req.pose_b_end.as_ref(), b0)?;
    let ma = Motion::new(a0, a1).map_err(|e| format!("solid A: {e}"))?;
    let mb = Motion::new(b0, b1).map_err(|e| format!("solid B: {e}"))?;
    let opts = search_options(
        req.contact_distance.unwrap_or(args.contact_distance),
        args.time_tolerance,
        args.max_queries,
    );
    let sa = cache.get(&req.a, eps)?;
    let sb = cache.get(&req.b, eps)?;
    let started = std::time::Instant::now();
    let r = time_of_impact(&sa, &ma, &sb, &mb, &opts).map_err(|e| e.to_string())?;
    let time_us = started.elapsed().as_secs_f64() * 1e6;
    let mut out = Output::new(&r, args.timings.then_some(time_us));
    out.line = Some(number);
    serde_json::to_string(&out).map_err(|e| e.to_string())
}

fn pose(flag: &str, s: Option<&String>, default: Isometry3<f64>) -> Result<Isometry3<f64>, String> {
    s.map_or(Ok(default), |s| parse_pose_flag(flag, s))
}

pub fn run(args: Args) -> CmdResult {
    check_eps(args.eps)?;
    if let Some(path) = &args.batch {
        let threads = match args.threads {
            Some(0) => return Err("--threads must be at least 1".into()),
            Some(n) => n,
            None => std::thread::available_parallelism().map_or(1, |n| n.get()),
        };
        return batch::run(path, threads, &|number, line, cache| {
            answer_line(number, line, &args, cache)
        });
    }
    let (Some(a), Some(b), Some(pose_b)) = (&args.a, &args.b, &args.pose_b) else {
        return Err("give two solids A B and --pose-b, or --batch FILE".into());
    };
    let a0 = pose("--pose-a", args.pose_a.as_ref(), Isometry3::identity())?;
    let a1 = pose("--pose-a-end", args.pose_a_end.as_ref(), a0)?;
    let b0 = pose("--pose-b", Some(pose_b), Isometry3::identity())?;
    let b1 = pose("--pose-b-end", args.pose_b_end.as_ref(), b0)?;
    let ma = Motion::new(a0, a1).map_err(|e| format!("solid A: {e}"))?;
    let mb = Motion::new(b0, b1).map_err(|e| format!("solid B: {e}"))?;
    let opts = search_options(args.contact_distance, args.time_tolerance, args.max_queries);
    let cache = SolidCache::default();
    let sa = cache.get(a, args.eps)?;
    let sb = cache.get(b, args.eps)?;
    let started = std::time::Instant::now();
    let r = time_of_impact(&sa, &ma, &sb, &mb, &opts)?;
    let time_us = started.elapsed().as_secs_f64() * 1e6;
    let c = r.contact.as_ref();
    let out = Output::new(&r, Some(time_us));
    if args.json {
        println!("{}", serde_json::to_string(&out)?);
        return Ok(());
    }
    match r.outcome {
        ToiOutcome::Contact => {
            println!(
                "contact   t in [{:.12}, {:.12}]",
                r.t_lower,
                r.t_upper.unwrap_or(f64::NAN)
            );
            if let Some(d) = c {
                let p = |x: nalgebra::Point3<f64>| format!("{:.9} {:.9} {:.9}", x.x, x.y, x.z);
                println!("point_a   {}", p(d.point_a));
                println!("point_b   {}", p(d.point_b));
                println!("distance  [{:.6e}, {:.6e}] at t_upper", d.lower, d.upper);
            }
        }
        ToiOutcome::Apart => println!(
            "apart     distance > {} on all of [0, 1]",
            args.contact_distance
        ),
        ToiOutcome::Undecided => println!(
            "undecided apart before t = {:.12}; no contact certified after it",
            r.t_lower
        ),
    }
    println!(
        "queries   {} ({} advancing), speed bound {:.6e}, {:.1} us",
        r.queries, r.steps, r.speed_bound, time_us
    );
    Ok(())
}
