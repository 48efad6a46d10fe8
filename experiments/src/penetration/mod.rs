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
//! independent of `revdist::query`: below the interval, by the oracle's certified point bound
//! (`c_A(x) + c_B(x) <= PD`, signed clearances, `verify::penetration::oracle::common_point_bound`); above it, by
//! the oracle's verdict that B moved by `upper` along revdist's direction is apart. A depth the
//! oracle shows to be wrong is coal's error (counted, with its size); any other depth outside
//! the interval is a violation (exit status 1).
//!

mod cases;
mod figure;
mod report;
mod row;

use crate::cli::{Eps, Out, Paper, Seed};
use crate::driver::{CheckFailed, DriverResult};
use crate::peers::coal::CoalPeer;
use crate::stats::median;
use cases::{coal_cases, model_cases};
use clap::Parser;
use figure::draw;
use report::{coal_table, csv, misses, summary_line};
use row::{Class, Row};
use std::fmt::Write as _;

/// Relative pushes `p / size` of the default run and of `--paper`.
const LEVELS: [f64; 6] = [1e-4, 1e-3, 1e-2, 3e-2, 0.1, 0.3];
const DEFAULT_POSES: usize = 2;
const PAPER_POSES: usize = 20;
const DEFAULT_COAL_POSES: usize = 6;
const PAPER_COAL_POSES: usize = 100;
const DEFAULT_EPS: [f64; 2] = [1e-3, 1e-4];
/// `--paper`: the paper's three eps (`experiments::shapes::PAPER_EPS`).
const PAPER_EPS: [f64; 3] = crate::shapes::PAPER_EPS;
const SEED: u64 = 40;
/// Share of the size up to which a contact is shallow (the 1 %).
const SHALLOW: f64 = 0.01;
/// The target's share of the depth.
const TARGET_REL: f64 = 0.05;
/// coal's `EPA_DEFAULT_TOLERANCE` (coal/narrowphase/narrowphase_defaults.h).
const COAL_EPA_TOLERANCE: f64 = 1e-6;

#[derive(Parser, Debug)]
#[command(about = "Penetration depth: interval width vs depth and eps, time, coal's EPA")]
pub struct Args {
    /// Poses per pair, eps and depth level [default: 2; --paper: 20, and eps 1e-5 too]
    #[arg(long, value_name = "N", value_parser = crate::args::positive_count)]
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

/// The driver's body: the model and coal cases, `penetration.csv`, `.md` (also to stdout)
/// and `.svg`, and failure on any unexplained coal depth.
pub fn run(args: Args) -> DriverResult {
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
    let prov = crate::provenance::Provenance::collect(
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
         `experiments/src/penetration/`. Width target (ball and shallow): `upper - lower \
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
