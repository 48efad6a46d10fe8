//! `verify toi`: certified time of impact (`revdist::toi`) against the independent oracle
//! along the motion ([`check`]), over the built-in models (the paper's five, their freeform
//! variants, the analytic solids) and frames of M_t, for the motion families of
//! [`motions`].

pub mod check;
pub mod motions;

use crate::oracle::{self, PlanarIndex};
use crate::timing::thread_cpu;
use check::{Breach, Scene};
use motions::{random_motion, Extent, Family, MotionCase};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use revdist::toi::{time_of_impact, Motion, ToiOptions, ToiOutcome};
use std::collections::BTreeMap;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

/// Tree eps the campaign draws from by default: the three of the time-of-impact targets
/// (docs/verification.md, section 7).
pub const DEFAULT_EPS: [f64; 3] = [1e-2, 1e-3, 1e-4];
/// Frames of M_t in the pool.
pub const MORPH_FRAMES: [&str; 4] = ["morph@0", "morph@0.35", "morph@0.7", "morph@1"];

/// Campaign settings.
#[derive(Debug, Clone)]
pub struct Options {
    pub count: usize,
    pub seed: u64,
    pub eps: Vec<f64>,
    /// Run the cases whose index is `i` modulo `n`.
    pub shard: Option<(usize, usize)>,
    /// Worker threads (0: every core).
    pub threads: usize,
}

/// One shape of the pool at every eps of the campaign.
struct Shape {
    name: String,
    index: PlanarIndex,
    solids: Vec<Solid>,
    extent: Extent,
}

fn build_shape(name: &str, eps: &[f64]) -> Result<Shape, String> {
    let p = Arc::new(revdist::models::model(name).map_err(|e| e.to_string())?);
    let solids = eps
        .iter()
        .map(|&e| Solid::from_profile(Arc::clone(&p), e).map_err(|x| format!("{name}: {x}")))
        .collect::<Result<Vec<_>, _>>()?;
    // Placement only (not a check): the root disk (rho, z) of the coarsest tree, revolved,
    // lies in the ball about (0, 0, z) of radius |rho| + r.
    let root = &solids[0].tree.nodes[solids[0].tree.root as usize].bound;
    let extent = Extent {
        centre: nalgebra::Point3::new(0.0, 0.0, root.center.y),
        radius: root.center.x.abs() + root.radius,
    };
    Ok(Shape {
        name: name.to_string(),
        index: oracle::index(&p),
        solids,
        extent,
    })
}

/// Runs `f`, returning its result and the calling thread's CPU time it took (the wall time
/// when the thread clock is unavailable).
fn cpu_timed<T>(f: impl FnOnce() -> T) -> (T, Duration) {
    let (wall, cpu) = (Instant::now(), thread_cpu());
    let r = f();
    let time = match (cpu, thread_cpu()) {
        (Some(a), Some(b)) => b.saturating_sub(a),
        _ => wall.elapsed(),
    };
    (r, time)
}

/// Outcome counts and failures of a campaign.
#[derive(Debug, Default)]
pub struct Report {
    pub cases: usize,
    pub outcomes: BTreeMap<(&'static str, &'static str), usize>,
    pub queries: usize,
    pub oracle_calls: usize,
    /// Sampled times decided by the oracle's bounding spheres alone ([`check::Calls`]).
    pub sphere_decided: usize,
    /// Oracle calls decided by the oracle's grid (no local minimisation).
    pub grid_decided: usize,
    pub failures: Vec<String>,
    /// Sum of the searches' thread CPU times.
    pub toi_time: Duration,
    /// Each search's thread CPU time by (family, eps).
    pub times: BTreeMap<(&'static str, u64), Vec<Duration>>,
    /// Thread CPU time of the oracle's checks (all threads).
    pub oracle_time: Duration,
    /// The [`SLOWEST`] slowest searches: time, and the case as `describe` writes it.
    pub slowest: Vec<(Duration, String)>,
    pub wall: Duration,
    /// Building the trees and oracle indexes (part of `wall`).
    pub build: Duration,
}

/// How many of the slowest searches the report names.
pub const SLOWEST: usize = 5;

/// Median, p90, p99 and largest of `v` in milliseconds (nearest rank).
fn quantiles_ms(v: &[Duration]) -> [f64; 4] {
    let mut ms: Vec<f64> = v.iter().map(|d| d.as_secs_f64() * 1e3).collect();
    ms.sort_by(f64::total_cmp);
    let at = |q: f64| {
        if ms.is_empty() {
            f64::NAN
        } else {
            ms[((q * ms.len() as f64).ceil() as usize).clamp(1, ms.len()) - 1]
        }
    };
    [at(0.5), at(0.9), at(0.99), at(1.0)]
}

impl Report {
    pub fn summary(&self) -> String {
        let mut s = format!(
            "verify toi: {} motions, {} failures; {} distance queries ({:.1} per motion, {:.3} s CPU in the searches), {} oracle calls ({:.1} s CPU; {} decided by the oracle's grid) and {} sampled times decided by bounding spheres, {:.1} s wall ({:.1} s building the shapes)\n",
            self.cases,
            self.failures.len(),
            self.queries,
            self.queries as f64 / self.cases.max(1) as f64,
            self.toi_time.as_secs_f64(),
            self.oracle_calls,
            self.oracle_time.as_secs_f64(),
            self.grid_decided,
            self.sphere_decided,
            self.wall.as_secs_f64(),
            self.build.as_secs_f64()
        );
        for ((family, outcome), n) in &self.outcomes {
            s += &format!("  {family:<15} {outcome:<10} {n}\n");
        }
        s += &self.times_table();
        for (time, case) in &self.slowest {
            s += &format!("slow {:.3} ms: {case}\n", time.as_secs_f64() * 1e3);
        }
        for f in self.failures.iter().take(20) {
            s += &format!("FAIL {f}\n");
        }
        s
    }

    /// Search times (thread CPU, ms) per eps over all families, then per family and eps.
    pub fn times_table(&self) -> String {
        let mut s = String::from(
            "search time, thread CPU ms:\n  family          eps      searches  median     p90      p99      max\n",
        );
        let mut by_eps: BTreeMap<u64, Vec<Duration>> = BTreeMap::new();
        for ((_, e), v) in &self.times {
            by_eps.entry(*e).or_default().extend(v);
        }
        let row = |name: &str, e: u64, v: &[Duration]| {
            let [m, p90, p99, max] = quantiles_ms(v);
            format!(
                "  {name:<15} {:<8.0e} {:>8}  {m:<8.3} {p90:<8.3} {p99:<8.3} {max:.3}\n",
                f64::from_bits(e),
                v.len()
            )
        };
        for (e, v) in &by_eps {
            s += &row("all", *e, v);
        }
        for ((family, e), v) in &self.times {
            s += &row(family, *e, v);
        }
        s
    }
}

fn describe(i: usize, sa: &Shape, sb: &Shape, eps: f64, case: &MotionCase, what: &str) -> String {
    let pose = |p: &nalgebra::Isometry3<f64>| {
        let t = p.translation.vector;
        let q = p.rotation.into_inner();
        format!(
            "{{\"translation\":[{:e},{:e},{:e}],\"rotation\":[{:e},{:e},{:e},{:e}]}}",
            t.x, t.y, t.z, q.w, q.i, q.j, q.k
        )
    };
    format!(
        "case {i} ({}): {} {} --eps {eps} --contact-distance {} --pose-a '{}' --pose-a-end '{}' --pose-b '{}' --pose-b-end '{}': {what}",
        case.family.name(),
        sa.name,
        sb.name,
        case.contact_distance,
        pose(&case.a[0]),
        pose(&case.a[1]),
        pose(&case.b[0]),
        pose(&case.b[1])
    )
}

/// What one case did.
struct CaseResult {
    family: Family,
    eps: f64,
    outcome: &'static str,
    queries: usize,
    calls: check::Calls,
    /// The search's thread CPU time.
    time: Duration,
    /// The checks' thread CPU time.
    oracle_time: Duration,
    /// The case with the search's answer, as [`describe`] writes it.
    description: String,
}

/// Runs case `i` and checks it.
fn run_case(
    i: usize,
    opts: &Options,
    shapes: &[Shape],
    failures: &Mutex<Vec<String>>,
) -> CaseResult {
    let mut rng = SplitMix64(opts.seed ^ 0x7011_0032).fork(i as u64);
    let (ia, ib) = (rng.int(0, shapes.len() - 1), rng.int(0, shapes.len() - 1));
    let ie = rng.int(0, opts.eps.len() - 1);
    let family = Family::ALL[i % Family::ALL.len()];
    let (sa, sb) = (&shapes[ia], &shapes[ib]);
    let case = random_motion(&mut rng, family, &sa.extent, &sb.extent);
    let result = |outcome, queries, calls, time, oracle_time, what: &str| CaseResult {
        family,
        eps: opts.eps[ie],
        outcome,
        queries,
        calls,
        time,
        oracle_time,
        description: describe(i, sa, sb, opts.eps[ie], &case, what),
    };
    let fail = |what: String| {
        let msg = describe(i, sa, sb, opts.eps[ie], &case, &what);
        failures.lock().unwrap_or_else(|e| e.into_inner()).push(msg);
    };
    let (ma, mb) = match (
        Motion::new(case.a[0], case.a[1]),
        Motion::new(case.b[0], case.b[1]),
    ) {
        (Ok(a), Ok(b)) => (a, b),
        (Err(e), _) | (_, Err(e)) => {
            fail(format!("motion rejected: {e}"));
            return result(
                "error",
                0,
                check::Calls::default(),
                Duration::ZERO,
                Duration::ZERO,
                "motion rejected",
            );
        }
    };
    let topts = ToiOptions {
        contact_distance: case.contact_distance,
        ..ToiOptions::default()
    };
    let (r, time) = cpu_timed(|| time_of_impact(&sa.solids[ie], &ma, &sb.solids[ie], &mb, &topts));
    let r = match r {
        Ok(r) => r,
        Err(e) => {
            fail(format!("error: {e}"));
            return result(
                "error",
                0,
                check::Calls::default(),
                time,
                Duration::ZERO,
                "query error",
            );
        }
    };
    let scene = Scene {
        a: &sa.index,
        b: &sb.index,
        pose_a: case.a,
        pose_b: case.b,
    };
    let mut breaches: Vec<Breach> = Vec::new();
    let d = case.contact_distance;
    let (calls, oracle_time) = cpu_timed(|| {
        let mut calls = match r.outcome {
            ToiOutcome::Apart => scene.check_apart(1.0, true, d, &mut breaches),
            _ => scene.check_apart(r.t_lower, false, d, &mut breaches),
        };
        if let (ToiOutcome::Contact, Some(tu)) = (r.outcome, r.t_upper) {
            if tu < r.t_lower {
                fail(format!("t_upper {tu} < t_lower {}", r.t_lower));
            }
            scene.check_contact(tu, d, &mut breaches);
            calls.oracle += 1;
        }
        calls
    });
    let n = breaches.len();
    if let Some(b) = breaches.first() {
        fail(format!(
            "{n} breaches; first: {} at t = {} (oracle [{}, {}], overlap {}; answer {} [{}, {:?}])",
            b.what,
            b.t,
            b.oracle_lower,
            b.oracle_upper,
            b.overlap,
            r.outcome.name(),
            r.t_lower,
            r.t_upper
        ));
    }
    let what = format!(
        "{} [{}, {:?}], {} queries, {} certificates",
        r.outcome.name(),
        r.t_lower,
        r.t_upper,
        r.queries,
        r.certificates
    );
    result(r.outcome.name(), r.queries, calls, time, oracle_time, &what)
}

/// The shapes of the campaign: every built-in model and [`MORPH_FRAMES`].
pub fn shape_names() -> Vec<String> {
    revdist::models::model_names()
        .iter()
        .map(|s| s.to_string())
        .chain(MORPH_FRAMES.iter().map(|s| s.to_string()))
        .collect()
}

/// Runs the campaign.
pub fn run(opts: &Options) -> Result<Report, String> {
    if opts.eps.is_empty() || opts.eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        return Err(format!("eps must be positive numbers, got {:?}", opts.eps));
    }
    if let Some((i, n)) = opts.shard {
        if n == 0 || i >= n {
            return Err(format!("shard {i}/{n}: need 0 <= I < N"));
        }
    }
    let wall = Instant::now();
    let shapes = shape_names()
        .iter()
        .map(|n| build_shape(n, &opts.eps))
        .collect::<Result<Vec<_>, _>>()?;
    let build = wall.elapsed();
    let cases: Vec<usize> = (0..opts.count)
        .filter(|i| opts.shard.is_none_or(|(s, n)| i % n == s))
        .collect();
    let threads = if opts.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        opts.threads
    };
    let next = AtomicUsize::new(0);
    let failures = Mutex::new(Vec::new());
    let report = Mutex::new(Report::default());
    std::thread::scope(|s| {
        for _ in 0..threads {
            s.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let Some(&i) = cases.get(k) else { break };
                let c = run_case(i, opts, &shapes, &failures);
                let mut r = report.lock().unwrap_or_else(|e| e.into_inner());
                r.cases += 1;
                *r.outcomes.entry((c.family.name(), c.outcome)).or_default() += 1;
                r.queries += c.queries;
                r.oracle_calls += c.calls.oracle;
                r.sphere_decided += c.calls.spheres;
                r.grid_decided += c.calls.grid;
                r.toi_time += c.time;
                r.oracle_time += c.oracle_time;
                if c.outcome != "error" {
                    r.times
                        .entry((c.family.name(), c.eps.to_bits()))
                        .or_default()
                        .push(c.time);
                    r.slowest.push((c.time, c.description));
                    r.slowest.sort_by_key(|s| std::cmp::Reverse(s.0));
                    r.slowest.truncate(SLOWEST);
                }
            });
        }
    });
    let mut r = report.into_inner().unwrap_or_else(|e| e.into_inner());
    r.failures = failures.into_inner().unwrap_or_else(|e| e.into_inner());
    r.wall = wall.elapsed();
    r.build = build;
    Ok(r)
}
