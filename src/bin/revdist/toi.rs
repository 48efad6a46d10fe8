//! `revdist toi`: certified time of impact of two solids moving from start to end poses
//! over `t in [0, 1]` (`revdist::toi`: interpolated motion, conservative advancement).
//!
//! Poses are written as for `revdist distance` (A's start pose defaults to the identity,
//! a missing end pose to the start pose: that solid does not move). Points are in the
//! world frame, the frame the poses are given in.

use nalgebra::Isometry3;
use revdist::query::{Budget, QueryOptions};
use revdist::toi::{
    time_of_impact, Motion, ToiOptions, ToiOutcome, DEFAULT_MAX_QUERIES, DEFAULT_TIME_TOLERANCE,
};
use serde::Serialize;

use crate::distance::{parse_pose_flag, SolidCache};
use crate::CmdResult;
use revdist::request::check_eps;

/// Default approximation bound of the biarc trees (as `revdist distance`).
const DEFAULT_EPS: f64 = 1e-4;

#[derive(Debug, clap::Args)]
pub struct Args {
    /// Solid A: built-in model name or profile file.
    a: String,
    /// Solid B: built-in model name or profile file.
    b: String,
    /// Start pose of B as JSON: {"translation": [x,y,z], "rotation": [w,x,y,z]}.
    #[arg(long)]
    pose_b: String,
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
}

#[derive(Debug, Serialize)]
struct Output {
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
    /// The proved bound on the rate of change of the distance at t = 0.
    speed_bound: f64,
    time_us: f64,
}

fn pose(flag: &str, s: Option<&String>, default: Isometry3<f64>) -> Result<Isometry3<f64>, String> {
    s.map_or(Ok(default), |s| parse_pose_flag(flag, s))
}

pub fn run(args: Args) -> CmdResult {
    check_eps(args.eps)?;
    let a0 = pose("--pose-a", args.pose_a.as_ref(), Isometry3::identity())?;
    let a1 = pose("--pose-a-end", args.pose_a_end.as_ref(), a0)?;
    let b0 = pose("--pose-b", Some(&args.pose_b), Isometry3::identity())?;
    let b1 = pose("--pose-b-end", args.pose_b_end.as_ref(), b0)?;
    let ma = Motion::new(a0, a1).map_err(|e| format!("solid A: {e}"))?;
    let mb = Motion::new(b0, b1).map_err(|e| format!("solid B: {e}"))?;
    let opts = ToiOptions {
        contact_distance: args.contact_distance,
        query: QueryOptions {
            budget: Budget::default(),
            ..QueryOptions::default()
        },
        time_tolerance: args.time_tolerance,
        max_queries: args.max_queries,
    };
    let cache = SolidCache::default();
    let sa = cache.get(&args.a, args.eps)?;
    let sb = cache.get(&args.b, args.eps)?;
    let started = std::time::Instant::now();
    let r = time_of_impact(&sa, &ma, &sb, &mb, &opts)?;
    let time_us = started.elapsed().as_secs_f64() * 1e6;
    let c = r.contact.as_ref();
    let out = Output {
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
        speed_bound: r.speed_bound,
        time_us,
    };
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
