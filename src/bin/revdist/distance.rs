//! `revdist distance`: minimum distance between two posed solids of revolution, one query
//! from the command line or a batch of JSON lines.
//!
//! Solid A sits at the identity; `pose_b` places B in A's frame: a point `x` of B's own
//! frame is at `R x + t`, `R` the unit quaternion `rotation` (w first), `t` the
//! `translation`. Output points are in A's frame.

use std::collections::HashMap;
use std::io::{BufRead, Write};
use std::sync::Arc;

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use revdist::query::{try_distance, Budget, Distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use serde::{Deserialize, Serialize};

use crate::input::load_profile;
use crate::CmdResult;

/// Default approximation bound of the biarc trees.
const DEFAULT_EPS: f64 = 1e-4;
/// A quaternion whose norm differs from 1 by more than this is rejected (it is not a
/// rotation written with ~7 significant digits); closer ones are normalised.
const UNIT_QUATERNION_SLACK: f64 = 1e-6;

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
    /// Batch mode: read JSON lines {"a", "b", "pose_b", "eps"} from this file ("-" for
    /// stdin) and write one JSON result per line.
    #[arg(long, conflicts_with_all = ["a", "b", "pose_b"])]
    batch: Option<String>,
}

/// Pose as written in JSON.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct PoseJson {
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
}

/// One result line.
#[derive(Debug, Serialize)]
struct Output {
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
}

impl From<&Distance> for Output {
    fn from(d: &Distance) -> Self {
        Output {
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
        }
    }
}

fn pose_from_json(p: &PoseJson) -> Result<Isometry3<f64>, String> {
    let t = p.translation.unwrap_or([0.0; 3]);
    if t.iter().any(|v| !v.is_finite()) {
        return Err(format!("translation {t:?} is not finite"));
    }
    let r = p.rotation.unwrap_or([1.0, 0.0, 0.0, 0.0]);
    let q = Quaternion::new(r[0], r[1], r[2], r[3]);
    let n = q.norm();
    if !n.is_finite() || (n - 1.0).abs() > UNIT_QUATERNION_SLACK {
        return Err(format!(
            "rotation {r:?} is not a unit quaternion [w, x, y, z] (norm {n})"
        ));
    }
    Ok(Isometry3::from_parts(
        Translation3::from(Vector3::from(t)),
        UnitQuaternion::from_quaternion(q),
    ))
}

fn parse_pose(s: &str) -> Result<Isometry3<f64>, String> {
    let p: PoseJson = serde_json::from_str(s).map_err(|e| format!("--pose-b: {e}"))?;
    pose_from_json(&p).map_err(|e| format!("--pose-b: {e}"))
}

fn check_eps(eps: f64) -> Result<(), String> {
    if eps.is_finite() && eps > 0.0 {
        Ok(())
    } else {
        Err(format!("eps must be a positive number, got {eps}"))
    }
}

fn check_tolerance(t: f64) -> Result<(), String> {
    if t.is_finite() && t >= 0.0 {
        Ok(())
    } else {
        Err(format!("tolerance must be a non-negative number, got {t}"))
    }
}

/// Solids built so far, by (profile spec, eps bits).
#[derive(Default)]
struct SolidCache {
    solids: HashMap<(String, u64), Solid>,
}

impl SolidCache {
    fn get(&mut self, spec: &str, eps: f64) -> Result<Solid, String> {
        let key = (spec.to_string(), eps.to_bits());
        if let Some(s) = self.solids.get(&key) {
            return Ok(s.clone());
        }
        let profile = load_profile(spec).map_err(|e| e.to_string())?;
        let solid = Solid::from_profile(Arc::new(profile), eps)
            .map_err(|e| format!("'{spec}' at eps {eps}: {e}"))?;
        self.solids.insert(key, solid.clone());
        Ok(solid)
    }
}

pub fn run(args: Args) -> CmdResult {
    let tolerance = match args.tolerance {
        Some(t) => {
            check_tolerance(t)?;
            Tolerance::Absolute(t)
        }
        None => Tolerance::Trees,
    };
    let max_time = match args.max_time_ms {
        Some(ms) if ms.is_finite() && ms > 0.0 => {
            Some(std::time::Duration::from_secs_f64(ms / 1e3))
        }
        Some(ms) => return Err(format!("--max-time-ms must be a positive number, got {ms}").into()),
        None => None,
    };
    let opts = QueryOptions {
        tolerance,
        budget: Budget {
            max_node_pairs: args.max_node_pairs,
            max_time,
        },
        refine: args.refine,
        ..QueryOptions::default()
    };
    if let Some(path) = &args.batch {
        return run_batch(path, args.eps, &opts);
    }
    let (Some(a), Some(b)) = (&args.a, &args.b) else {
        return Err("give two solids A B, or --batch FILE".into());
    };
    check_eps(args.eps)?;
    let pose = match &args.pose_b {
        Some(s) => parse_pose(s)?,
        None => Isometry3::identity(),
    };
    let mut cache = SolidCache::default();
    let sa = cache.get(a, args.eps)?;
    let sb = cache.get(b, args.eps)?.with_pose(pose);
    let d = try_distance(&sa, &sb, &opts).map_err(|e| e.to_string())?;
    if args.json {
        println!("{}", serde_json::to_string(&Output::from(&d))?);
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

/// A parsed batch line: the two posed solids and the options of its query.
struct Prepared {
    a: Solid,
    b: Solid,
    opts: QueryOptions,
}

/// One batch line to a query ready to run, or a per-line error message.
fn prepare_line(
    line: &str,
    default_eps: f64,
    opts: &QueryOptions,
    cache: &mut SolidCache,
) -> Result<Prepared, String> {
    let req: Request = serde_json::from_str(line).map_err(|e| format!("bad request: {e}"))?;
    let eps = req.eps.unwrap_or(default_eps);
    check_eps(eps)?;
    let mut opts = *opts;
    if let Some(t) = req.tolerance {
        check_tolerance(t)?;
        opts.tolerance = Tolerance::Absolute(t);
    }
    if let Some(r) = req.refine {
        opts.refine = r;
    }
    let pose = match &req.pose_b {
        Some(p) => pose_from_json(p).map_err(|e| format!("pose_b: {e}"))?,
        None => Isometry3::identity(),
    };
    let a = cache.get(&req.a, eps)?;
    let b = cache.get(&req.b, eps)?.with_pose(pose);
    Ok(Prepared { a, b, opts })
}

/// Lines read, prepared (trees built once per shape and eps, in order) and then queried in
/// parallel per chunk; results are written in input order.
const BATCH_CHUNK: usize = 1024;

fn run_batch(path: &str, default_eps: f64, opts: &QueryOptions) -> CmdResult {
    check_eps(default_eps)?;
    let reader: Box<dyn BufRead> = if path == "-" {
        Box::new(std::io::stdin().lock())
    } else {
        let f = std::fs::File::open(path).map_err(|e| format!("cannot open '{path}': {e}"))?;
        Box::new(std::io::BufReader::new(f))
    };
    let mut cache = SolidCache::default();
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    let mut chunk: Vec<(usize, Result<Prepared, String>)> = Vec::with_capacity(BATCH_CHUNK);
    let mut flush = |chunk: &mut Vec<(usize, Result<Prepared, String>)>| -> CmdResult {
        let results: Vec<String> = chunk
            .par_iter()
            .map(|(i, p)| {
                let r = p
                    .as_ref()
                    .map_err(Clone::clone)
                    .and_then(|p| try_distance(&p.a, &p.b, &p.opts).map_err(|e| e.to_string()));
                match r {
                    Ok(d) => serde_json::to_string(&Output::from(&d)).unwrap_or_default(),
                    Err(e) => serde_json::json!({ "line": i + 1, "error": e }).to_string(),
                }
            })
            .collect();
        for text in results {
            writeln!(out, "{text}")?;
        }
        chunk.clear();
        Ok(())
    };
    for (i, line) in reader.lines().enumerate() {
        let line = line.map_err(|e| format!("reading '{path}': {e}"))?;
        if line.trim().is_empty() {
            continue;
        }
        chunk.push((i, prepare_line(&line, default_eps, opts, &mut cache)));
        if chunk.len() >= BATCH_CHUNK {
            flush(&mut chunk)?;
        }
    }
    flush(&mut chunk)
}
