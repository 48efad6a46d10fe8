//! Penetration depth (`revdist::query::penetration`, docs/architecture.md "Signed distance
//! and penetration depth"): the certified interval's width against the depth and eps on the
//! paper's models, its time against a distance query of the same pair, pose and eps, and
//! coal 3's EPA depths of convex primitives against the interval.
//!
//! Cases, seeded: B placed along a random direction `u` with a random rotation at the
//! touching length (bisection on revdist's certified verdict, `verify::penetration`), then
//! pushed back by `p = level * size` (`size` the smaller profile diagonal; levels 1e-4 to
//! 0.3): B moved by `p u` is apart again, so `PD <= p`. Pairs: the 15 pairs of the paper's
//! five models, and a ball (radius 5-30 % of the model's size) against each model.
//!
//! The width target of the issue (docs/verification.md): on ball-against-solid and shallow
//! contacts (`p <= 1 %` of the size, so `PD <= 1 %`), `upper - lower <= max(2 (eps_a +
//! eps_b), 5 % of PD)`, judged here with PD replaced by its certified lower bound (a stricter
//! test). Each miss is attributed: the upper bound's search spent its distance queries
//! (`revdist::query::penetration::separate::MAX_QUERIES`), or it stopped with queries left
//! (no better translation found along its directions).
//!
//! Times are the thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`) of `signed_distance` (the
//! distance query at the pose included) and of `distance` at the same pose and options,
//! one query at a time; the summary gives medians and the median of the per-case ratio.
//!
//! coal: the convex models sphere, capsule, cylinder and cone (all 10 pairs) as coal's exact
//! primitives, through `coal_peer` (experiments/src/peers/coal.rs), with coal's default signed
//! distance request: EPA's penetration depth (closed forms for sphere and capsule pairs). Its
//! depth must lie in `[lower - tol, upper + tol]`, `tol = 1e-6 + 1e-9 * scene`: coal's EPA
//! tolerance (`EPA_DEFAULT_TOLERANCE`, "the precision on the estimated distance between two
//! geometries which are in collision") and the poses' rounding to the decimal text the program
//! reads. A depth outside is judged by the query oracle of `verify` on the exact profiles,
//! independent of `revdist::query`: below the interval, by the oracle's certified common point
//! (`c_A(x) + c_B(x) <= PD`, `verify::penetration::oracle::common_point_bound`); above it, by
//! the oracle's verdict that B moved by `upper` along revdist's direction is apart. A depth the
//! oracle shows to be wrong is coal's error (counted, with its size); any other depth outside
//! the interval is a violation (exit status 1).
//!
//! Usage: `penetration [--poses N] [--coal-poses N] [--eps E,...] [--seed S] [--paper]
//! [--out DIR]`; writes `DIR/penetration.csv`, `.md` and `.svg`.

use clap::Parser;
use experiments::cli::{Eps, Out, Paper, Seed};
use experiments::driver::{self, CheckFailed, DriverResult};
use experiments::peers::coal::CoalPeer;
use experiments::peers::convex::{primitive, CONVEX_MODELS};
use experiments::plot::{log_log_panels, Curve, Panel};
use experiments::shapes::{diagonal, profile, PAPER_MODELS};
use experiments::stats::{median, quantile};
use nalgebra::{Isometry3, UnitQuaternion};
use revdist::query::penetration::separate::MAX_QUERIES;
use revdist::query::{distance, signed_distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::sync::Arc;
use verify::oracle::PlanarIndex;
use verify::penetration::oracle::{apart_at, common_point_bound};
use verify::penetration::{ball_profile, pose_along, touching_length};
use verify::timing::thread_cpu_us;

/// Relative pushes `p / size` of the default run and of `--paper`.
const LEVELS: [f64; 6] = [1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3];
const DEFAULT_POSES: usize = 2;
const PAPER_POSES: usize = 20;
const DEFAULT_COAL_POSES: usize = 6;
const PAPER_COAL_POSES: usize = 100;
const DEFAULT_EPS: [f64; 2] = [1e-3, 1e-4];
/// `--paper`: the paper's three eps (`experiments::shapes::PAPER_EPS`).
const PAPER_EPS: [f64; 3] = experiments::shapes::PAPER_EPS;
const SEED: u64 = 40;
/// Share of the size up to which a contact is shallow (the 1 %).
const SHALLOW: f64 = 0.01;
/// The target's share of the depth.
const TARGET_REL: f64 = 0.05;
/// coal's `EPA_DEFAULT_TOLERANCE` (coal/narrowphase/narrowphase_defaults.h).
const COAL_EPA_TOLERANCE: f64 = 1e-6;

#[derive(Parser, Debug)]
#[command(about = "Penetration depth: interval width vs depth and eps, time, coal's EPA")]
struct Args {
    /// Poses per pair, eps and depth level [default: 2; --paper: 20, and eps 1e-5 too]
    #[arg(long)]
    poses: Option<usize>,
    /// Poses per convex pair and eps checked against coal's EPA [default: 6; --paper: 100]
    #[arg(long)]
    coal_poses: Option<usize>,
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    seed: Seed,
    #[command(flatten)]
    paper: Paper,
    #[command(flatten)]
    out: Out,
}

/// What kind of contact a case is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Class {
    /// A ball against a model.
    Ball,
    /// Two models, pushed by at most 1 % of the size.
    Shallow,
    /// Two models, pushed deeper.
    Deep,
    /// Two convex models, compared with coal.
    Convex,
}

impl Class {
    fn name(self) -> &'static str {
        match self {
            Class::Ball => "ball",
            Class::Shallow => "shallow",
            Class::Deep => "deep",
            Class::Convex => "convex",
        }
    }
    /// Whether the width target applies.
    fn targeted(self) -> bool {
        matches!(self, Class::Ball | Class::Shallow)
    }
}

/// One case's answer.
struct Row {
    pair: String,
    class: Class,
    eps: f64,
    level: f64,
    push: f64,
    size: f64,
    pose: Isometry3<f64>,
    /// The depth interval (NaN when the solids were certified apart).
    lower: f64,
    upper: f64,
    queries: usize,
    probes: usize,
    signed_us: f64,
    distance_us: f64,
    /// Unit translation of B achieving `upper`, and the common point giving `lower`.
    direction: nalgebra::Vector3<f64>,
    point: Option<nalgebra::Point3<f64>>,
    /// coal's depth (convex cases).
    coal_depth: Option<f64>,
    coal_us: Option<f64>,
    /// The oracle's verdict on a coal depth outside the interval.
    coal_verdict: Option<CoalVerdict>,
}

/// What the oracle says of coal's depth (convex cases).
#[derive(Debug, Clone, Copy, PartialEq)]
enum CoalVerdict {
    /// Within `[lower - tol, upper + tol]`.
    Inside,
    /// Below the oracle's certified common point bound (this value): coal's error.
    BelowCommonPoint(f64),
    /// Above a translation the oracle confirms separating: coal's error.
    AboveSeparation,
    /// Outside the interval and not refuted by the oracle: a violation.
    Unexplained,
}

impl Row {
    fn width(&self) -> f64 {
        self.upper - self.lower
    }
    fn target(&self) -> f64 {
        (4.0 * self.eps).max(TARGET_REL * self.lower)
    }
    fn met(&self) -> bool {
        self.width() <= self.target()
    }
    fn answered(&self) -> bool {
        self.lower.is_finite()
    }
    fn coal_tolerance(&self) -> f64 {
        let scene = 1.0 + self.pose.translation.vector.norm() + 2.0 * self.size;
        COAL_EPA_TOLERANCE + 1e-9 * scene
    }
    /// coal's depth outside the interval, by how much (0 inside).
    fn coal_excess(&self) -> Option<f64> {
        let c = self.coal_depth?;
        Some((self.lower - c).max(c - self.upper).max(0.0))
    }
    fn coal_outside(&self) -> bool {
        self.coal_excess()
            .is_some_and(|e| e > self.coal_tolerance())
    }
    fn coal_violates(&self) -> bool {
        self.coal_verdict == Some(CoalVerdict::Unexplained)
    }
    /// The oracle's tolerance (`verify penetration`'s): `1e-9` of the scene.
    fn oracle_tolerance(&self) -> f64 {
        1e-9 * (1.0 + self.pose.translation.vector.norm() + 2.0 * self.size)
    }
    /// Judges coal's depth against the interval and, outside it, the oracle on the exact
    /// profiles `ia`, `ib`.
    fn judge_coal(&self, ia: &PlanarIndex, ib: &PlanarIndex) -> Option<CoalVerdict> {
        let c = self.coal_depth?;
        if !self.coal_outside() {
            return Some(CoalVerdict::Inside);
        }
        let tol = self.oracle_tolerance();
        if c < self.lower {
            let seeds: Vec<_> = self.point.into_iter().collect();
            let mut rng = SplitMix64(self.pose.translation.vector.x.to_bits());
            let lo = common_point_bound(ia, ib, &self.pose, &seeds, 0.5 * self.size, 200, &mut rng);
            if c < lo - tol {
                return Some(CoalVerdict::BelowCommonPoint(lo));
            }
        } else if self.direction.norm() > 0.0 {
            let t = self.direction * (self.upper + tol);
            if apart_at(ia, ib, &self.pose, &t) == Some(true) {
                return Some(CoalVerdict::AboveSeparation);
            }
        }
        Some(CoalVerdict::Unexplained)
    }
}

/// A solid of the experiment: its name, solid at one eps and size.
struct Named {
    name: String,
    solid: Solid,
    size: f64,
}

fn model(name: &str, eps: f64) -> Result<Named, Box<dyn std::error::Error>> {
    let p = profile(name)?;
    let size = diagonal(&p);
    Ok(Named {
        name: name.to_owned(),
        solid: Solid::from_profile(Arc::new(p), eps)?,
        size,
    })
}

/// Places B against A (random rotation and direction), pushed in by `level * size`, and
/// answers the depth and the two timings.
fn case(a: &Named, b: &Named, class: Class, eps: f64, level: f64, rng: &mut SplitMix64) -> Row {
    let q = rng.quaternion();
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
    let u = rng.direction();
    let size = a.size.min(b.size);
    let push = level * size;
    let touch = touching_length(&a.solid, &b.solid, rot, &u);
    let pose = pose_along(&a.solid, &b.solid, rot, &u, touch - push);
    let bp = b.solid.with_pose(pose);
    let opts = QueryOptions::default();
    let t0 = thread_cpu_us();
    let s = signed_distance(&a.solid, &bp, &opts).expect("poses in range");
    let signed_us = thread_cpu_us() - t0;
    let t0 = thread_cpu_us();
    let d = distance(&a.solid, &bp, &opts);
    let distance_us = thread_cpu_us() - t0;
    std::hint::black_box(&d);
    let (lower, upper, queries, probes) = match &s.penetration {
        Some(p) => (p.lower, p.upper, p.stats.distance_queries, p.stats.probes),
        None => (f64::NAN, f64::NAN, 1, 0),
    };
    let (direction, point) = s
        .penetration
        .as_ref()
        .map_or((nalgebra::Vector3::zeros(), None), |p| {
            (p.direction, p.point)
        });
    let class = match class {
        Class::Shallow | Class::Deep if level <= SHALLOW => Class::Shallow,
        Class::Shallow | Class::Deep => Class::Deep,
        c => c,
    };
    Row {
        pair: format!("{}-{}", a.name, b.name),
        class,
        eps,
        level,
        push,
        size,
        pose,
        lower,
        upper,
        queries,
        probes,
        signed_us,
        distance_us,
        direction,
        point,
        coal_depth: None,
        coal_us: None,
        coal_verdict: None,
    }
}

/// The seed of one group of cases.
fn group_rng(seed: u64, parts: &[u64]) -> SplitMix64 {
    let mut h = seed ^ 0x5EED_DE97;
    for p in parts {
        h = (h ^ p).wrapping_mul(0x9E37_79B9_7F4A_7C15).rotate_left(29);
    }
    SplitMix64(h)
}

/// The paper's pairs and the balls against each paper model.
fn model_cases(
    eps_list: &[f64],
    poses: usize,
    seed: u64,
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    let mut rows = Vec::new();
    for (ie, &eps) in eps_list.iter().enumerate() {
        let models: Vec<Named> = PAPER_MODELS
            .iter()
            .map(|m| model(m, eps))
            .collect::<Result<_, _>>()?;
        for (i, a) in models.iter().enumerate() {
            for (j, b) in models.iter().enumerate().skip(i) {
                for (il, &level) in LEVELS.iter().enumerate() {
                    let mut rng = group_rng(seed, &[ie as u64, i as u64, j as u64, il as u64]);
                    for _ in 0..poses {
                        rows.push(case(a, b, Class::Deep, eps, level, &mut rng));
                    }
                }
            }
            for (il, &level) in LEVELS.iter().enumerate() {
                let mut rng = group_rng(seed, &[ie as u64, i as u64, 99, il as u64]);
                for _ in 0..poses {
                    let r = rng.range(0.05, 0.3) * a.size;
                    let ball = Named {
                        name: format!("ball{r:.3}"),
                        solid: Solid::from_profile(Arc::new(ball_profile(r)), eps)?,
                        size: 2.0 * r,
                    };
                    rows.push(case(a, &ball, Class::Ball, eps, level, &mut rng));
                }
            }
        }
        eprintln!(
            "penetration: eps {eps:e} done ({} cases so far)",
            rows.len()
        );
    }
    Ok(rows)
}

/// The convex pairs, answered by revdist and by coal's EPA on the same exact solids.
fn coal_cases(
    coal: &mut CoalPeer,
    eps_list: &[f64],
    poses: usize,
    seed: u64,
) -> Result<Vec<Row>, Box<dyn std::error::Error>> {
    let mut index = Vec::new();
    for name in CONVEX_MODELS {
        coal.primitive(name, &primitive(name).expect("convex model"))?;
        index.push(verify::oracle::index(&profile(name)?));
    }
    let mut rows = Vec::new();
    for (ie, &eps) in eps_list.iter().enumerate() {
        let models: Vec<Named> = CONVEX_MODELS
            .iter()
            .map(|m| model(m, eps))
            .collect::<Result<_, _>>()?;
        for (i, a) in models.iter().enumerate() {
            for (j, b) in models.iter().enumerate().skip(i) {
                let mut rng = group_rng(seed, &[ie as u64, i as u64, j as u64, 77]);
                let mut group: Vec<Row> = (0..poses)
                    .map(|_| {
                        let level = rng.log_range(1e-3, 0.3);
                        case(a, b, Class::Convex, eps, level, &mut rng)
                    })
                    .collect();
                let pose_list: Vec<Isometry3<f64>> = group.iter().map(|r| r.pose).collect();
                let answers = coal.signed_query(&a.name, &b.name, &pose_list)?;
                for (r, c) in group.iter_mut().zip(answers) {
                    r.coal_depth = Some((-c.distance).max(0.0));
                    r.coal_us = Some(c.us);
                    r.coal_verdict = r.judge_coal(&index[i], &index[j]);
                }
                rows.extend(group);
            }
        }
    }
    Ok(rows)
}

fn csv(rows: &[Row], preamble: String) -> String {
    let mut s = preamble;
    s += "pair,class,eps,level,push,size,lower,upper,width,target,met,distance_queries,probes,signed_us,distance_us,coal_depth,coal_us,coal_verdict,tx,ty,tz,qw,qx,qy,qz\n";
    let opt = |v: Option<f64>| v.map_or(String::new(), |x| format!("{x:.17e}"));
    for r in rows {
        let (t, q) = (r.pose.translation.vector, r.pose.rotation.quaternion());
        let _ = writeln!(
            s,
            "{},{},{:e},{:e},{:.17e},{:.6e},{:.17e},{:.17e},{:.6e},{:.6e},{},{},{},{:.1},{:.1},{},{},{},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e},{:.17e}",
            r.pair,
            r.class.name(),
            r.eps,
            r.level,
            r.push,
            r.size,
            r.lower,
            r.upper,
            r.width(),
            r.target(),
            r.met(),
            r.queries,
            r.probes,
            r.signed_us,
            r.distance_us,
            opt(r.coal_depth),
            opt(r.coal_us),
            match r.coal_verdict {
                None => "",
                Some(CoalVerdict::Inside) => "inside",
                Some(CoalVerdict::BelowCommonPoint(_)) => "coal below a certified common point",
                Some(CoalVerdict::AboveSeparation) => "coal above a confirmed separation",
                Some(CoalVerdict::Unexplained) => "unexplained",
            },
            t.x,
            t.y,
            t.z,
            q.w,
            q.i,
            q.j,
            q.k
        );
    }
    s
}

/// The summary's line of one class at one eps.
fn summary_line(class: Class, eps: f64, rows: &[&Row]) -> String {
    let answered: Vec<&&Row> = rows.iter().filter(|r| r.answered()).collect();
    let met = answered.iter().filter(|r| r.met()).count();
    let w_eps: Vec<f64> = answered.iter().map(|r| r.width() / r.eps).collect();
    let w_rel: Vec<f64> = answered
        .iter()
        .filter(|r| r.lower > 0.0)
        .map(|r| r.width() / r.lower)
        .collect();
    let signed: Vec<f64> = answered.iter().map(|r| r.signed_us).collect();
    let dist: Vec<f64> = answered.iter().map(|r| r.distance_us).collect();
    let ratio: Vec<f64> = answered
        .iter()
        .map(|r| r.signed_us / r.distance_us)
        .collect();
    let target = if class.targeted() {
        format!(
            "{met} / {} ({:.1} %)",
            answered.len(),
            100.0 * met as f64 / answered.len().max(1) as f64
        )
    } else {
        format!("({met} / {})", answered.len())
    };
    format!(
        "| {} | {eps:.0e} | {} | {} | {target} | {:.3} | {:.3} | {:.4} | {:.0} | {:.0} | {:.2} | {:.2} |\n",
        class.name(),
        rows.len(),
        answered.len(),
        median(&w_eps),
        quantile(&w_eps, 0.9),
        median(&w_rel),
        median(&signed),
        median(&dist),
        median(&ratio),
        quantile(&ratio, 0.9),
    )
}

/// Where the width of the targeted cases that miss it goes.
fn misses(rows: &[Row]) -> String {
    let missed: Vec<&Row> = rows
        .iter()
        .filter(|r| r.class.targeted() && r.answered() && !r.met())
        .collect();
    if missed.is_empty() {
        return "Every ball and shallow case met the width target.\n".into();
    }
    let spent = missed.iter().filter(|r| r.queries > MAX_QUERIES).count();
    let untouched = missed.iter().filter(|r| r.lower <= 0.0).count();
    let mut s = format!(
        "{} ball or shallow cases missed the width target: {spent} with the upper bound's \
         search out of distance queries ({MAX_QUERIES}), {} with queries left (no shorter \
         separating translation along its directions); {untouched} with no certified common \
         point (lower 0: touching within the trees' accuracy). The worst by width / target:\n\n\
         | pair | class | eps | push / size | lower | upper | width / target | queries |\n\
         |---|---|---|---|---|---|---|---|\n",
        missed.len(),
        missed.len() - spent,
    );
    let mut worst = missed.clone();
    worst.sort_by(|x, y| (y.width() / y.target()).total_cmp(&(x.width() / x.target())));
    for r in worst.iter().take(8) {
        let _ = writeln!(
            s,
            "| {} | {} | {:.0e} | {:.0e} | {:.6e} | {:.6e} | {:.2} | {} |",
            r.pair,
            r.class.name(),
            r.eps,
            r.level,
            r.lower,
            r.upper,
            r.width() / r.target(),
            r.queries
        );
    }
    s
}

fn coal_table(rows: &[Row], coal_version: &str) -> String {
    let convex: Vec<&Row> = rows.iter().filter(|r| r.coal_depth.is_some()).collect();
    if convex.is_empty() {
        return String::new();
    }
    let mut s = format!(
        "\n## coal {coal_version} EPA depths against the interval\n\n\
         coal's signed distance (default request: EPA, closed forms for sphere and capsule \
         pairs) on its exact primitives at the same poses; inside means `lower - tol <= coal \
         <= upper + tol`, `tol = {COAL_EPA_TOLERANCE:e} + 1e-9 scene` (coal's EPA tolerance). \
         A depth outside is judged by `verify`'s oracle on the exact profiles: *coal error* \
         when it is below a common point's certified bound `c_A + c_B` (or above a translation \
         the oracle confirms separating); *unexplained* (a violation) otherwise.\n\n\
         | pair | eps | cases | inside | coal error | unexplained | max excess | largest coal shortfall below c_A + c_B | median (coal - lower) / width | median coal us | median revdist signed us |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n"
    );
    let mut keys: Vec<(String, u64)> = Vec::new();
    for r in &convex {
        let k = (r.pair.clone(), r.eps.to_bits());
        if !keys.contains(&k) {
            keys.push(k);
        }
    }
    for (pair, eps) in keys {
        let g: Vec<&&Row> = convex
            .iter()
            .filter(|r| r.pair == pair && r.eps.to_bits() == eps && r.answered())
            .collect();
        let inside = g
            .iter()
            .filter(|r| r.coal_verdict == Some(CoalVerdict::Inside))
            .count();
        let unexplained = g.iter().filter(|r| r.coal_violates()).count();
        let shortfall = g
            .iter()
            .filter_map(|r| match r.coal_verdict {
                Some(CoalVerdict::BelowCommonPoint(lo)) => Some(lo - r.coal_depth?),
                _ => None,
            })
            .fold(0.0, f64::max);
        let excess = g.iter().filter_map(|r| r.coal_excess()).fold(0.0, f64::max);
        let pos: Vec<f64> = g
            .iter()
            .map(|r| {
                (r.coal_depth.unwrap_or(f64::NAN) - r.lower) / r.width().max(f64::MIN_POSITIVE)
            })
            .collect();
        let cu: Vec<f64> = g.iter().filter_map(|r| r.coal_us).collect();
        let su: Vec<f64> = g.iter().map(|r| r.signed_us).collect();
        let _ = writeln!(
            s,
            "| {pair} | {:.0e} | {} | {inside} | {} | {unexplained} | {excess:.2e} | {shortfall:.2e} | {:.3} | {:.2} | {:.0} |",
            f64::from_bits(eps),
            g.len(),
            g.len() - inside - unexplained,
            median(&pos),
            median(&cu),
            median(&su),
        );
    }
    s
}

/// Width against depth, one panel per eps: medians and 90th percentiles per depth level of
/// the ball cases and the model pairs, and the target.
fn draw(path: &std::path::Path, rows: &[Row], eps_list: &[f64]) -> DriverResult {
    let mut panels = Vec::new();
    for &eps in eps_list {
        let mut curves = Vec::new();
        for (k, (name, balls)) in [("ball vs model", true), ("model pairs", false)]
            .into_iter()
            .enumerate()
        {
            let mut med = Vec::new();
            let mut p90 = Vec::new();
            for &level in &LEVELS {
                let g: Vec<&Row> = rows
                    .iter()
                    .filter(|r| {
                        r.eps == eps
                            && r.level == level
                            && r.answered()
                            && r.lower > 0.0
                            && (r.class == Class::Ball) == balls
                            && r.class != Class::Convex
                    })
                    .collect();
                if g.is_empty() {
                    continue;
                }
                let depth = median(
                    &g.iter()
                        .map(|r| 0.5 * (r.lower + r.upper))
                        .collect::<Vec<_>>(),
                );
                let w: Vec<f64> = g.iter().map(|r| r.width()).collect();
                med.push((depth, median(&w)));
                p90.push((depth, quantile(&w, 0.9)));
            }
            curves.push(Curve {
                name: format!("{name}: median width"),
                style: 2 * k,
                dashed: false,
                points: med,
            });
            curves.push(Curve {
                name: format!("{name}: 90th percentile"),
                style: 2 * k + 1,
                dashed: true,
                points: p90,
            });
        }
        let depths: Vec<f64> = rows
            .iter()
            .filter(|r| r.eps == eps && r.answered() && r.lower > 0.0)
            .map(|r| 0.5 * (r.lower + r.upper))
            .collect();
        let (lo, hi) = (quantile(&depths, 0.0), quantile(&depths, 1.0));
        let target: Vec<(f64, f64)> = (0..=24)
            .map(|k| {
                let x = lo * (hi / lo).powf(k as f64 / 24.0);
                (x, (4.0 * eps).max(TARGET_REL * x))
            })
            .collect();
        curves.push(Curve {
            name: "target max(2 (eps_a + eps_b), 5 % PD)".into(),
            style: 4,
            dashed: true,
            points: target,
        });
        panels.push(Panel {
            title: format!("eps = {eps:.0e}"),
            curves,
        });
    }
    log_log_panels(
        path,
        "Penetration depth: certified interval width vs depth (paper's models)",
        &panels,
        "depth (interval midpoint)",
        "upper - lower",
        (520, 440),
    )?;
    Ok(())
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let out = args.out.dir;
    let poses = args
        .poses
        .unwrap_or(args.paper.pick(DEFAULT_POSES, PAPER_POSES));
    let coal_poses = args
        .coal_poses
        .unwrap_or(args.paper.pick(DEFAULT_COAL_POSES, PAPER_COAL_POSES));
    let eps_list = args
        .eps
        .or(args.paper.pick(&DEFAULT_EPS[..], &PAPER_EPS[..]));
    let seed = args.seed.or(SEED);
    let started = std::time::Instant::now();
    let mut rows = model_cases(&eps_list, poses, seed)?;
    let mut coal_version = String::from("missing");
    if coal_poses > 0 {
        match CoalPeer::start() {
            Ok(mut coal) => {
                coal_version = coal.version.clone();
                rows.extend(coal_cases(&mut coal, &eps_list, coal_poses, seed)?);
            }
            Err(e) => eprintln!("penetration: coal skipped: {e}"),
        }
    }
    let prov = experiments::provenance::Provenance::collect(
        "penetration (certified penetration depth: width, time, coal EPA)",
        &[
            ("poses", poses.to_string()),
            ("coal_poses", coal_poses.to_string()),
            ("eps", format!("{eps_list:?}")),
            ("levels", format!("{LEVELS:?}")),
            ("seed", seed.to_string()),
            ("coal", coal_version.clone()),
            ("timing", "thread CPU time, one query at a time".into()),
        ],
    );
    std::fs::write(out.join("penetration.csv"), csv(&rows, prov.csv_preamble()))?;

    let mut md = String::from(
        "# Penetration depth: certified interval width, time, coal's EPA\n\n\
         `experiments/src/bin/penetration.rs`. Width target (ball and shallow): `upper - lower \
         <= max(2 (eps_a + eps_b), 5 % PD)`, PD replaced by its certified lower bound. Times: \
         thread CPU, `signed_distance` vs `distance` at the same pose, pair and eps.\n\n\
         | class | eps | cases | overlapping | width target met | median width / eps | p90 width / eps | median width / lower | median signed us | median distance us | median ratio | p90 ratio |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for class in [Class::Ball, Class::Shallow, Class::Deep, Class::Convex] {
        for &eps in &eps_list {
            let g: Vec<&Row> = rows
                .iter()
                .filter(|r| r.class == class && r.eps == eps)
                .collect();
            if !g.is_empty() {
                md += &summary_line(class, eps, &g);
            }
        }
    }
    let ratios = |convex: bool| -> Vec<f64> {
        rows.iter()
            .filter(|r| r.answered() && (r.class == Class::Convex) == convex)
            .map(|r| r.signed_us / r.distance_us)
            .collect()
    };
    let targeted: Vec<&Row> = rows
        .iter()
        .filter(|r| r.class.targeted() && r.answered())
        .collect();
    let met = targeted.iter().filter(|r| r.met()).count();
    let _ = write!(
        md,
        "\nMedian time ratio (target <= 10): {:.2} over the paper's models (ball, shallow and \
         deep together), {:.2} over the convex pairs (whose distance query certifies the overlap \
         in closed form or by the convex path, in a few microseconds). Ball and shallow: width \
         target met on {met} of {} ({:.1} %).\n\n",
        median(&ratios(false)),
        median(&ratios(true)),
        targeted.len(),
        100.0 * met as f64 / targeted.len().max(1) as f64
    );
    md += &misses(&rows);
    md += &coal_table(&rows, &coal_version);
    md += &prov.markdown_footer();
    std::fs::write(out.join("penetration.md"), &md)?;
    draw(&out.join("penetration.svg"), &rows, &eps_list)?;
    print!("{md}");
    eprintln!(
        "penetration: {} cases in {:.1} s; wrote {}/penetration.{{csv,md,svg}}",
        rows.len(),
        started.elapsed().as_secs_f64(),
        out.display()
    );
    let empty = rows
        .iter()
        .filter(|r| r.answered() && (r.lower > r.upper || r.upper.is_nan()))
        .count();
    let coal_out = rows.iter().filter(|r| r.coal_violates()).count();
    if empty + coal_out > 0 {
        return Err(CheckFailed(format!(
            "{empty} empty intervals, {coal_out} coal depths outside the interval that the \
             oracle does not explain (see penetration.md)"
        ))
        .into());
    }
    Ok(())
}
