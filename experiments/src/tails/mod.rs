//! A seeded tail benchmark: queries tried as a new user would try them,
//! each timed alone, to see how far the slow tail of revdist's query times reaches.
//!
//! **Queries.** `--poses N` (default 2,000) seeded queries over the 16 built-in models
//! ([`revdist::models::model_names`], exact and freeform `*_ff`, and the frame
//! `MORPH_FRAME` of the deformable model M_t), each with
//!
//! * eps drawn from {1e-4, 1e-5, 1e-6, 1e-7} (`--eps` replaces the set);
//! * tolerance 0 on a tenth of the queries (drawn), the default tolerance
//!   (`upper - lower <= eps_a + eps_b`) otherwise;
//! * a configuration: nine in ten are *random*: two random models, B with a random rotation
//!   slid along a random direction towards A until the solids' distance is the gap, drawn
//!   log-uniform in [1e-7, 1]; every tenth query (indices 9, 19, ...) is degenerate, the
//!   kinds in turn:
//!   - `coaxial`: B on A's axis, same axis direction, lowered along z onto A until the gap
//!     (log-uniform in [1e-7, 1]);
//!   - `flipped`: the same with B upside down;
//!   - `identical`: A and a copy of A, translated by an offset log-uniform in [1e-9, 1e-2]
//!     along a random direction and turned about the axis (they overlap; `gap` holds the
//!     offset);
//!   - `cup_rest`: a solid lowered along the axis of `cup` or `cup_ff`, upright or upside down,
//!     until it rests within the gap (log-uniform in [1e-7, 1e-2]) on the rim, the walls or the
//!     floor, depending on its width (a sphere on the rim, a bottle neck first into the cup);
//!   - `nested`: a smaller solid inside a larger one, same axis (the pairs of built-in models
//!     that nest, found at start-up), moved along the axis until the gap between their
//!     surfaces is the drawn gap (log-uniform in [1e-7, half the centred clearance]); solid
//!     distance 0.
//!
//! Gaps are placed by bisection on the distance between the boundary surfaces with trees of
//! eps `PLACE_EPS` and a width of 1% of the gap, accepted within 5%; so `gap` is the
//! distance of the exact solids to a few percent. Placement runs on all cores, before any
//! timing; trees are built once per (model, eps), also before any timing.
//!
//! **Timing.** One thread, one query at a time in the seeded order (models and eps change
//! from query to query), each query run once and timed: the *cold* time, the first and only
//! run of that query, as a user's single query runs (no untimed warm-up run of the same
//! query; its trees were built earlier and other queries ran in between, so they come from
//! memory rather than the caches; the process and its code are warm). The query is
//! `revdist::query::try_distance`, which the `revdist distance` command runs, on the pose as
//! that command parses it from the reproducer line.
//!
//! **Outputs** (`--out`, default `figures`): `tails.csv`, one row per query with a reproducer
//! command line `revdist distance A B --eps E [--tolerance 0] --json --pose-b '{...}'`, and
//! `tails.md`: median, p90, p99, p99.9, max and p99/median overall, per family (exact models,
//! freeform, M_t, degenerate), per kind, per eps and per tolerance, the targets
//! (p99 <= 10x the median, max <= 20 ms), and the ten slowest queries with their reproducers.

mod nesting;
mod place;
mod query;
mod report;
mod slide;
#[cfg(test)]
mod tests;
mod timing;

use crate::cli::{Eps, Out, Poses, Seed};
use crate::driver::DriverResult;
use crate::provenance::Provenance;
use crate::shapes::profile;
use crate::SplitMix;
use clap::Parser;
use nesting::nesting_pairs;
use place::Ctx;
use query::{Kind, Placed, Spec, DEGENERATE_KINDS};
use rayon::prelude::*;
use report::{csv_table, markdown};
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;
use timing::{build_trees, time_queries};

/// Queries in a default run.
const DEFAULT_QUERIES: usize = 2000;
/// The eps a query draws from.
const DEFAULT_EPS: [f64; 4] = [1e-4, 1e-5, 1e-6, 1e-7];
/// Default seed.
const SEED: u64 = 0x27_7a11;
/// The M_t frame among the models.
const MORPH_FRAME: &str = "morph@0.3";
/// Gap range of the random and stacked configurations (log-uniform).
const GAPS: (f64, f64) = (1e-7, 1.0);
/// Gap range of a solid resting in the cup.
const CUP_GAPS: (f64, f64) = (1e-7, 1e-2);
/// Offsets of the identical solids.
const OFFSETS: (f64, f64) = (1e-9, 1e-2);
/// Eps of the trees that place the gaps: the narrowest leaf interval `4 PLACE_EPS` is 4% of
/// the smallest gap (and a query's interval is usually narrower: leaves are more accurate
/// than their bound). Not 1e-10: `table_ff`'s tree takes 1.2 million leaves and 7 s there.
const PLACE_EPS: f64 = 1e-9;
/// Width of a placement query, relative to the gap; a placement is accepted within
/// `ACCEPT_REL` of the gap.
const PLACE_WIDTH_REL: f64 = 0.01;
const ACCEPT_REL: f64 = 0.05;
/// Points scanned along a slide before the bisection, and bisection steps.
const SCAN_STEPS: usize = 24;
const BISECTION_STEPS: usize = 80;
/// Eps of the trees that screen the model pairs for nesting.
const NEST_SCREEN_EPS: f64 = 1e-3;
/// Draws per query before giving up.
const MAX_DRAWS: usize = 200;
/// One query in this many is degenerate, one in this many runs at tolerance 0.
const DEGENERATE_EVERY: usize = 10;
const TOL0_EVERY: f64 = 10.0;
/// Cups for `cup_rest`, and the solids that rest in them.
const CUPS: [&str; 2] = ["cup", "cup_ff"];
const CUP_GUESTS: [&str; 10] = [
    "sphere",
    "pawn",
    "pawn_ff",
    "bottle",
    "bottle_ff",
    "lightmill",
    "lightmill_ff",
    "capsule",
    "cone",
    MORPH_FRAME,
];
/// The targets.
const TARGET_P99_OVER_MEDIAN: f64 = 10.0;
const TARGET_MAX_US: f64 = 20_000.0;

/// A seeded tail benchmark: 2,000 queries (--poses) over the 16 built-in models (exact,
/// freeform, an M_t frame), gaps log-uniform in [1e-7, 1], eps drawn from 1e-4..1e-7,
/// tolerance 0 on a tenth, a tenth degenerate (coaxial and flipped stacks, identical solids,
/// solids resting in the cup, nesting); each query timed alone and cold on one thread.
/// Writes tails.csv (one row per query, with a reproducer command line) and tails.md
/// (median, p90, p99, p99.9, max per family, kind and eps; the ten slowest).
#[derive(Parser)]
pub struct Args {
    #[command(flatten)]
    out: Out,
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    poses: Poses,
    #[command(flatten)]
    seed: Seed,
}

/// The models: the built-ins and one M_t frame.
fn model_list() -> Vec<String> {
    let mut v: Vec<String> = revdist::models::model_names()
        .iter()
        .map(|s| s.to_string())
        .collect();
    v.push(MORPH_FRAME.into());
    v
}

/// The driver's body: places the seeded queries, times each once, and writes `tails.csv` and
/// `tails.md` (the Markdown also to stdout).
pub fn run(args: Args) -> DriverResult {
    let started = Instant::now();
    let n = args.poses.or(DEFAULT_QUERIES);
    let eps_set = args.eps.or(&DEFAULT_EPS);
    let seed = args.seed.or(SEED);
    let models = model_list();
    let mut profiles: HashMap<String, Arc<Profile>> = HashMap::new();
    for m in &models {
        profiles.insert(m.clone(), Arc::new(profile(m)?));
    }
    // Placement trees (all cores).
    let fine: HashMap<String, Solid> = models
        .par_iter()
        .map(|m| {
            Ok((
                m.clone(),
                Solid::from_profile(Arc::clone(&profiles[m]), PLACE_EPS)?,
            ))
        })
        .collect::<Result<_, revdist::biarc::TreeError>>()?;
    let nests = nesting_pairs(&models, &profiles, &fine);
    eprintln!(
        "tails: {} models, {} nesting pairs [{:.1} s]",
        models.len(),
        nests.len(),
        started.elapsed().as_secs_f64()
    );

    // The queries' draws, in order, then their placement (all cores, each from its own seed).
    let mut rng = SplitMix(seed);
    let specs: Vec<Spec> = (0..n)
        .map(|index| {
            let kind = if index % DEGENERATE_EVERY == DEGENERATE_EVERY - 1 {
                DEGENERATE_KINDS[(index / DEGENERATE_EVERY) % DEGENERATE_KINDS.len()]
            } else {
                Kind::Random
            };
            let eps =
                eps_set[((rng.next_f64() * eps_set.len() as f64) as usize).min(eps_set.len() - 1)];
            let tol0 = rng.next_f64() * TOL0_EVERY < 1.0;
            let seed = (rng.next_f64() * (1u64 << 53) as f64) as u64;
            Spec {
                index,
                kind,
                eps,
                tol0,
                seed,
            }
        })
        .collect();
    let ctx = Ctx {
        models: &models,
        profiles: &profiles,
        fine: &fine,
        nests: &nests,
    };
    let placed: Vec<Placed> = specs
        .into_par_iter()
        .map(|s| ctx.place(s))
        .collect::<Result<_, String>>()?;
    eprintln!(
        "tails: {n} queries placed [{:.1} s]",
        started.elapsed().as_secs_f64()
    );

    // Trees once per (model, eps), outside the timing.
    let trees = build_trees(&placed, &profiles)?;
    eprintln!(
        "tails: {} trees built [{:.1} s]",
        trees.len(),
        started.elapsed().as_secs_f64()
    );

    // Timing: one thread, one query at a time, each run once.
    let rows = time_queries(placed, &trees)?;
    let secs = started.elapsed().as_secs_f64();
    eprintln!("tails: {n} queries timed [{secs:.1} s]");

    let prov = Provenance::collect(
        "tails (seeded tail benchmark)",
        &[
            ("queries", n.to_string()),
            ("eps", format!("{eps_set:?}")),
            ("seed", format!("{seed:#x}")),
            ("models", models.join(" ")),
            ("gaps", format!("{GAPS:?}")),
            (
                "timing",
                "one thread, each query run once (cold: no warm-up run)".into(),
            ),
        ],
    );
    let out = &args.out.dir;
    std::fs::write(
        out.join("tails.csv"),
        prov.csv_preamble() + &csv_table().csv_text(&rows),
    )?;
    let md = markdown(&rows, &nests, secs) + &prov.markdown_footer();
    std::fs::write(out.join("tails.md"), &md)?;
    print!("{md}");
    Ok(())
}
