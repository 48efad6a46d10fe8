//! `verify penetration`: the certified penetration depth and signed distance
//! (`revdist::query::penetration`) against independent references on the exact profiles
//! ([`oracle`]).
//!
//! Cases, seeded per index: a ball against a pool shape (exact depth, [`oracle::ball_depth`]),
//! shallow contacts of two pool shapes (B pushed into A by 1e-4 to 1e-2 of the sizes from a
//! touching pose) and deep overlaps (2 to 50 % of the sizes). Touching poses are found by
//! bisection on revdist's own certified verdict (placement only; no check relies on it).
//!
//! Checks of every overlapping answer (`lower <= upper` always):
//! * **exact** (balls): `lower <= PD <= upper` within the reference's tolerance.
//! * **upper**: B moved by `upper` (plus `1e-9` of the scene) along `direction` is not found
//!   overlapping by the full oracle (a boundary sample of one solid inside the other).
//! * **lower vs the oracle's separating translation**: `lower <= s`, `s` the shortest
//!   separating length the oracle finds along revdist's direction and along its own (the
//!   translation moving B's nearest exact surface point onto A's at the oracle's best
//!   common point), confirmed apart by the full oracle.
//! * **upper vs the oracle's point bound**: `upper >= c_A(x) + c_B(x)` at the best point the
//!   oracle finds on the exact profiles (signed clearances, a positive sum; inside both or
//!   not, [`oracle::common_point_bound`]).
//!
//! The tolerance of every comparison is `1e-9` of the scene (`1 + |t| + sizes`): the
//! oracle's own realised distances are within a few ulps of its exact closest points and
//! its marching stops at `1e-12` of the size.

pub mod oracle;

use crate::oracle::PlanarIndex;
use crate::random_profiles::random_profile;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::models::primitives::{arc, deg};
use revdist::profile::Profile;
use revdist::query::{distance, signed_distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Campaign settings.
#[derive(Debug, Clone)]
pub struct Options {
    pub count: usize,
    pub seed: u64,
    pub eps: Vec<f64>,
    pub threads: usize,
    pub out: std::path::PathBuf,
    /// Run the oracle's separation and common-point checks on every `oracle_every`-th
    /// case (they cost tens of milliseconds); the exact and self checks run on all.
    pub oracle_every: usize,
    /// Run only these case indices (each seeded as in the full campaign) instead of
    /// `0..count`: reproduces chosen cases of a campaign.
    pub cases: Vec<usize>,
}

/// What kind of case.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    Ball,
    Shallow,
    Deep,
}

impl Kind {
    fn name(self) -> &'static str {
        match self {
            Kind::Ball => "ball",
            Kind::Shallow => "shallow",
            Kind::Deep => "deep",
        }
    }
}

/// One case's outcome.
#[derive(Debug, Clone)]
pub struct Outcome {
    pub index: usize,
    pub kind: Kind,
    pub a: String,
    pub b: String,
    pub eps: f64,
    pub pose_b: Isometry3<f64>,
    /// Depth B was pushed in by (ball cases: the exact depth).
    pub push: f64,
    pub overlap: bool,
    pub lower: f64,
    pub upper: f64,
    pub exact: Option<f64>,
    /// Which certificate gave `lower` (empty when not overlapping).
    pub certificate: String,
    pub oracle_lower: Option<f64>,
    pub oracle_upper: Option<f64>,
    pub time_signed_us: f64,
    pub time_distance_us: f64,
    pub size: f64,
    pub violations: Vec<String>,
}

/// A ball of radius `r` centred on its frame's origin (an exact half circle).
pub fn ball_profile(r: f64) -> Profile {
    let c = arc([0.0, 0.0], r, deg(-90.0), deg(90.0)).expect("valid half circle");
    Profile::new("ball", vec![c]).expect("valid ball")
}

/// Centre of a shape's root disk on its axis (its own frame) and its radius.
pub fn bounding_ball(s: &Solid) -> (Point3<f64>, f64) {
    let root = &s.tree.nodes[s.tree.root as usize].bound;
    (
        Point3::new(0.0, 0.0, root.center.y),
        root.center.x.abs() + root.radius,
    )
}

/// B's pose with rotation `rot` whose bounding centre sits at A's plus `s u`.
pub fn pose_along(
    a: &Solid,
    b: &Solid,
    rot: UnitQuaternion<f64>,
    u: &Vector3<f64>,
    s: f64,
) -> Isometry3<f64> {
    let (ca, _) = bounding_ball(a);
    let (cb, _) = bounding_ball(b);
    let t = ca.coords - rot * cb.coords + u * s;
    Isometry3::from_parts(Translation3::from(t), rot)
}

/// The touching length along `u` by bisection on revdist's certified verdict (placement
/// only), from the bounding balls' sum. B at `pose_along(a, b, rot, u, touching_length(..))`
/// is certified apart from A; moved from there by `-p u`, its penetration depth is at most
/// `p` (moving it back separates it).
pub fn touching_length(a: &Solid, b: &Solid, rot: UnitQuaternion<f64>, u: &Vector3<f64>) -> f64 {
    let opts = QueryOptions::default();
    let (_, ra) = bounding_ball(a);
    let (_, rb) = bounding_ball(b);
    let (mut lo, mut hi) = (0.0, ra + rb + 1e-6);
    for _ in 0..40 {
        let mid = 0.5 * (lo + hi);
        let d = distance(a, &b.with_pose(pose_along(a, b, rot, u, mid)), &opts);
        if d.lower > 0.0 {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

fn rotation(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    let q = rng.quaternion();
    UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]))
}

/// A shape the cases draw from: its profile, the oracle's index of it and its size.
struct Shape {
    name: String,
    profile: Arc<Profile>,
    index: PlanarIndex,
    size: f64,
}

/// Random profiles in the pool.
const RANDOM_PROFILES: usize = 24;

/// The pool: every built-in model (the paper's, freeform, analytic, M_t at 0.5) and
/// seeded random profiles of three sizes.
fn build_pool(seed: u64) -> Vec<Shape> {
    let mut shapes = Vec::new();
    let mut push = |name: String, p: Profile| {
        let index = crate::oracle::index(&p);
        shapes.push(Shape {
            name,
            size: index.geom.size,
            profile: Arc::new(p),
            index,
        });
    };
    for name in revdist::models::model_names() {
        push(
            name.to_string(),
            revdist::models::model(name).expect("built-in"),
        );
    }
    push(
        "morph@0.5".into(),
        revdist::models::model("morph@0.5").expect("M_t"),
    );
    let mut rng = SplitMix64(seed ^ 0x0DE9_7A7E_5EED);
    for k in 0..RANDOM_PROFILES {
        let name = format!("rand-s{seed}-{k}");
        let size = [0.5, 1.0, 2.0][k % 3];
        let (p, _) = random_profile(&mut rng, &name, size);
        push(name, p);
    }
    shapes
}

/// Solids of the pool at each eps, built once.
struct Built {
    shapes: Vec<Shape>,
    solids: Vec<Vec<Solid>>,
}

fn run_case(index: usize, built: &Built, opts: &Options) -> Option<Outcome> {
    let mut rng = SplitMix64(opts.seed ^ (index as u64).wrapping_mul(0x9E37_79B9_7F4A_7C15));
    let kind = match rng.below(10) {
        0..=2 => Kind::Ball,
        3..=6 => Kind::Shallow,
        _ => Kind::Deep,
    };
    let e = rng.below(opts.eps.len());
    let eps = opts.eps[e];
    let ia = rng.below(built.shapes.len());
    let a_shape = &built.shapes[ia];
    let a = built.solids[e][ia].clone();
    let size_a = a_shape.size;
    let (b, b_index, b_name, size_b, ball_r) = if kind == Kind::Ball {
        let r = rng.range(0.05, 0.4) * size_a;
        let p = ball_profile(r);
        let index = crate::oracle::index(&p);
        let s = Solid::from_profile(Arc::new(p), eps).ok()?;
        (s, Some(index), format!("ball{r:.4}"), 2.0 * r, Some(r))
    } else {
        let ib = rng.below(built.shapes.len());
        let s = built.solids[e][ib].clone();
        (
            s,
            None,
            built.shapes[ib].name.clone(),
            built.shapes[ib].size,
            None,
        )
    };
    let b_idx = b_index.as_ref().unwrap_or_else(|| {
        &built.shapes[built.shapes.iter().position(|s| s.name == b_name).unwrap()].index
    });
    let rot = rotation(&mut rng);
    let u = rng.direction();
    let touch = touching_length(&a, &b, rot, &u);
    let scale = size_a.min(size_b);
    let push = match kind {
        Kind::Ball | Kind::Shallow => rng.log_range(1e-4, 1e-2) * scale,
        Kind::Deep => rng.range(0.02, 0.5) * scale,
    };
    let pose_b = pose_along(&a, &b, rot, &u, touch - push);
    let b = b.with_pose(pose_b);
    let qopts = QueryOptions::default();
    let started = Instant::now();
    let sd = signed_distance(&a, &b, &qopts).ok()?;
    let time_signed_us = started.elapsed().as_secs_f64() * 1e6;
    let started = Instant::now();
    let _ = distance(&a, &b, &qopts);
    let time_distance_us = started.elapsed().as_secs_f64() * 1e6;
    let scene = 1.0 + pose_b.translation.vector.norm() + size_a + size_b;
    let tol = 1e-9 * scene;
    let mut out = Outcome {
        index,
        kind,
        a: a_shape.name.clone(),
        b: b_name,
        eps,
        pose_b,
        push,
        overlap: sd.penetration.is_some(),
        lower: sd.lower,
        upper: sd.upper,
        exact: None,
        certificate: String::new(),
        oracle_lower: None,
        oracle_upper: None,
        time_signed_us,
        time_distance_us,
        size: size_a.max(size_b),
        violations: Vec::new(),
    };
    if sd.lower.is_nan() || sd.upper.is_nan() || sd.lower > sd.upper {
        out.violations.push(format!(
            "signed interval [{}, {}] empty",
            sd.lower, sd.upper
        ));
    }
    let Some(p) = &sd.penetration else {
        return Some(out);
    };
    (out.lower, out.upper) = (p.lower, p.upper);
    out.certificate = p.certificate.name().to_string();
    if p.lower.is_nan() || p.upper.is_nan() || p.lower > p.upper {
        out.violations
            .push(format!("depth interval [{}, {}] empty", p.lower, p.upper));
    }
    if let Some(r) = ball_r {
        // The ball's centre is B's origin.
        let exact = oracle::ball_depth(
            &a_shape.index,
            &Point3::from(pose_b.translation.vector),
            r,
            size_a,
        );
        out.exact = Some(exact);
        if p.lower > exact + tol || p.upper < exact - tol {
            out.violations.push(format!(
                "exact depth {exact} outside [{}, {}]",
                p.lower, p.upper
            ));
        }
    }
    if index.is_multiple_of(opts.oracle_every.max(1)) {
        let ia_idx = &a_shape.index;
        // Upper: B moved just past `upper` along `direction` is not overlapping.
        if p.direction.norm() > 0.0 {
            let t = p.direction * (p.upper + tol);
            if oracle::apart_at(ia_idx, b_idx, &pose_b, &t) == Some(false) {
                out.violations.push(format!(
                    "oracle finds overlap past upper {} along {:?}",
                    p.upper, p.direction
                ));
            }
        }
        // The oracle's point bound: upper >= c_A + c_B (signed clearances).
        let seeds: Vec<Point3<f64>> = p.point.into_iter().collect();
        let seeds = if seeds.is_empty() {
            vec![nalgebra::center(&sd.distance.point_a, &sd.distance.point_b)]
        } else {
            seeds
        };
        let reach = 0.5 * out.size;
        let lo = oracle::common_point_bound(ia_idx, b_idx, &pose_b, &seeds, reach, 200, &mut rng);
        out.oracle_lower = Some(lo);
        if p.upper < lo - tol {
            out.violations.push(format!(
                "upper {} below the oracle's common-point bound {lo}",
                p.upper
            ));
        }
        // The oracle's separating translations: lower <= s.
        let mut best: Option<f64> = None;
        if p.direction.norm() > 0.0 {
            if let Some(s) = oracle::separating_length(
                ia_idx,
                b_idx,
                &pose_b,
                &p.direction,
                p.upper.max(tol) * 1.01,
                14,
            ) {
                best = Some(s);
            }
        }
        if let Some(s) = best {
            out.oracle_upper = Some(s);
            if p.lower > s + tol {
                out.violations.push(format!(
                    "lower {} above the oracle's separating length {s}",
                    p.lower
                ));
            }
        }
    }
    Some(out)
}

/// Summary of a campaign.
#[derive(Debug, Default)]
pub struct Summary {
    pub cases: usize,
    pub overlapping: usize,
    pub violations: usize,
    pub oracle_checked: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    v[v.len() / 2]
}

/// Runs the campaign, writes `cases.csv` and `summary.txt` under `opts.out`, prints the
/// summary; returns it.
pub fn run(opts: &Options) -> std::io::Result<Summary> {
    let shapes = build_pool(opts.seed);
    let solids = opts
        .eps
        .iter()
        .map(|&e| {
            shapes
                .iter()
                .map(|s| Solid::from_profile(Arc::clone(&s.profile), e).expect("pool shape builds"))
                .collect()
        })
        .collect();
    let built = Built { shapes, solids };
    let next = AtomicUsize::new(0);
    let results = Mutex::new(Vec::new());
    let threads = if opts.threads == 0 {
        std::thread::available_parallelism().map_or(1, |n| n.get())
    } else {
        opts.threads
    };
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let k = next.fetch_add(1, Ordering::Relaxed);
                let index = if opts.cases.is_empty() {
                    (k < opts.count).then_some(k)
                } else {
                    opts.cases.get(k).copied()
                };
                let Some(index) = index else { break };
                if let Some(o) = run_case(index, &built, opts) {
                    results.lock().unwrap().push(o);
                }
            });
        }
    });
    let mut results = results.into_inner().unwrap();
    results.sort_by_key(|o| o.index);
    std::fs::create_dir_all(&opts.out)?;
    let mut csv = String::from("index,kind,a,b,eps,push,overlap,lower,upper,exact,certificate,oracle_lower,oracle_upper,size,time_signed_us,time_distance_us,violations\n");
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:e}"));
    for o in &results {
        csv += &format!(
            "{},{},{},{},{:e},{:e},{},{:e},{:e},{},{},{},{},{:e},{:.1},{:.1},\"{}\"\n",
            o.index,
            o.kind.name(),
            o.a,
            o.b,
            o.eps,
            o.push,
            o.overlap,
            o.lower,
            o.upper,
            opt(o.exact),
            o.certificate,
            opt(o.oracle_lower),
            opt(o.oracle_upper),
            o.size,
            o.time_signed_us,
            o.time_distance_us,
            o.violations.join("; ")
        );
    }
    std::fs::write(opts.out.join("cases.csv"), csv)?;
    let mut summary = Summary {
        cases: results.len(),
        ..Summary::default()
    };
    let mut text = String::new();
    for o in &results {
        summary.overlapping += o.overlap as usize;
        summary.violations += o.violations.len();
        summary.oracle_checked += o.oracle_lower.is_some() as usize;
        for v in &o.violations {
            text += &format!(
                "VIOLATION case {} ({} {} vs {}, eps {:e}, pose t {:?} q {:?}): {v}\n",
                o.index,
                o.kind.name(),
                o.a,
                o.b,
                o.eps,
                o.pose_b.translation.vector.as_slice(),
                o.pose_b.rotation.coords.as_slice()
            );
        }
    }
    for kind in [Kind::Ball, Kind::Shallow, Kind::Deep] {
        let of: Vec<&Outcome> = results
            .iter()
            .filter(|o| o.kind == kind && o.overlap)
            .collect();
        if of.is_empty() {
            // A `--cases` run may hold no case of this kind: no line of medians of nothing.
            continue;
        }
        let target_met = of
            .iter()
            .filter(|o| {
                let pd = o.exact.unwrap_or(o.upper);
                o.upper - o.lower <= (4.0 * o.eps).max(0.05 * pd)
            })
            .count();
        let widths: Vec<f64> = of.iter().map(|o| (o.upper - o.lower) / o.eps).collect();
        let ratios: Vec<f64> = of
            .iter()
            .map(|o| o.time_signed_us / o.time_distance_us)
            .collect();
        let times: Vec<f64> = of.iter().map(|o| o.time_signed_us).collect();
        text += &format!(
            "{:8} overlapping {:6}  width <= max(2 (eps_a + eps_b), 5% PD): {:6} ({:.1} %)  median width / eps {:.3}  median time {:.0} us  median time / distance time {:.2}\n",
            kind.name(),
            of.len(),
            target_met,
            100.0 * target_met as f64 / of.len().max(1) as f64,
            median(widths),
            median(times),
            median(ratios),
        );
    }
    let mut by_certificate = std::collections::BTreeMap::<&str, usize>::new();
    for o in results.iter().filter(|o| o.overlap) {
        *by_certificate.entry(o.certificate.as_str()).or_default() += 1;
    }
    text += &format!("lower bound by: {by_certificate:?}\n");
    text += &format!(
        "cases {}  overlapping {}  oracle-checked {}  violations {}\n",
        summary.cases, summary.overlapping, summary.oracle_checked, summary.violations
    );
    print!("{text}");
    std::fs::write(opts.out.join("summary.txt"), text)?;
    Ok(summary)
}
