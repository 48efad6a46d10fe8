//! revdist against FCL 0.7 at equal accuracy (`docs/protocols.md`): in one run and on the same
//! seeded poses near contact (gaps log-uniform in [1e-3, 1e-1]), per model pair and eps,
//!
//! * the median and p90 query time of revdist at its default tolerance (`Tolerance::Trees`:
//!   interval width <= eps_a + eps_b, the error a distance between meshes of Hausdorff error
//!   eps has; balls and solid tori in closed form) and at tolerance 0 with the traversal
//!   only (run until nothing narrows, no closed form);
//! * the median query time of FCL `BVHModel<OBBRSS>` and `BVHModel<RSS>` on certified meshes
//!   (`revdist::tessellate`, two-sided Hausdorff bound <= eps) in two layouts, Balanced
//!   vertices with and without a cap on the meridian edge length (sliver fans on flat disks
//!   are slow for FCL; the cap helps there and costs triangles elsewhere), keeping the faster
//!   layout per row to be fair to FCL;
//! * build time (revdist tree vs tessellation + BVH), memory (revdist query tree vs FCL's
//!   node, triangle and vertex arrays), triangle counts, revdist's widest certified interval
//!   against the meshes' bounds h_a + h_b, and the speed ratio of the faster FCL BV
//!   (OBBRSS or RSS, each in its faster layout; RSS is often 10-20% faster) over revdist,
//!   with a column naming that BV;
//! * a cross-check of every timed answer: revdist's interval must meet FCL's `d ± (h_a +
//!   h_b)` (`verify::crosscheck::criterion`); the count of violations is reported.
//!
//! Queries are timed one at a time on one thread; for each pose all methods run back to back
//! in an order that rotates from pose to pose, so drift and cache warm-up spread evenly. Each
//! method's query is timed twice on its pose, back to back: the first time comes after the
//! other methods' queries, so its data and code have left the caches (FCL's meshes take
//! megabytes; the cross-check's reference answers are computed in a pass of their own, so
//! that no untimed query warms a timed one): the *cold* time, the
//! headline, as when an application alternates between many pairs. The second time is the
//! *warm* time of the same query with its trees and code cached. After the interleaved pass,
//! revdist, FCL OBBRSS (each layout) and FCL RSS (its faster cold layout) also run
//! *blocked*: each alone over all poses in a
//! row, the usual benchmark loop over one pair (its code and, for revdist's small trees, its
//! data stay cached from pose to pose).
//!
//! Default pairs: the exact models (torus-torus, pawn-pawn, pawn-cup, cup-bottle,
//! table-lightmill) at eps 1e-3, 1e-4, 1e-5, and the freeform family
//! (pawn_ff-pawn_ff, pawn_ff-cup_ff, cup_ff-bottle_ff, table_ff-lightmill_ff) and M_t frames
//! (morph@0.3-pawn, morph@0.7-cup). To keep the default run (and the main job's step) near
//! 1.5x the exact pairs' time, the added pairs run at half the poses and at eps 1e-3 and 1e-4
//! only (their eps-1e-5 meshes take seconds per pair to build), unless `--paper` or `--eps`
//! is given. `--pairs` runs the pairs given, all alike.

mod csv;
mod measure;
mod report;
mod row;

use crate::args::{model_pairs, positive_count, ModelPair};
use crate::baseline_mesh::LAYOUT_NAMES;
use crate::cli::{count_at, Common};
use crate::driver::DriverResult;
use crate::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use crate::shapes::{profile, PAPER_EPS};
use clap::Parser;
use csv::csv_table;
use measure::bench_row;
use nalgebra::Isometry3;
use report::markdown;
use revdist::profile::Profile;
use row::{Row, BV_NAMES};
use std::collections::HashMap;
use std::sync::Arc;
use std::time::Instant;

/// The pairs of the speed table: two solid tori (closed form) and four pairs of the paper's
/// exact models.
const DEFAULT_PAIRS: &str = "torus-torus,pawn-pawn,pawn-cup,cup-bottle,table-lightmill";
/// Added to the default list: the freeform family (NURBS profiles, `*_ff`) and
/// frames of the deformable model M_t (`morph@T`). Without `--paper` these run at
/// [`ADDED_EPS`] only (unless `--eps` is given) and at 1/[`ADDED_POSES_DIVISOR`] of the poses,
/// so that the default run (and the main job's step) takes about 1.5x the exact pairs' time:
/// their meshes at eps 1e-5 take seconds per pair to tessellate and build.
const ADDED_PAIRS: &str = "pawn_ff-pawn_ff,pawn_ff-cup_ff,cup_ff-bottle_ff,\
                           table_ff-lightmill_ff,morph@0.3-pawn,morph@0.7-cup";
/// The eps of the added pairs in a default run (`--eps` or `--paper`: the full list).
const ADDED_EPS: [f64; 2] = [1e-3, 1e-4];
/// The added pairs run this fraction of the poses (rounded up) in a default run.
const ADDED_POSES_DIVISOR: usize = 2;
/// Poses per pair at eps 1e-3 and 1e-4 (default run).
const DEFAULT_POSES: usize = 200;
/// Poses per pair at eps 1e-5 and below (default run): the same first poses, fewer of them,
/// since FCL's queries are slowest there.
const DEFAULT_POSES_FINE: usize = 100;
/// Poses per pair with `--paper` (alias `--full`).
const FULL_POSES: usize = 1000;
/// Gap range of the poses (log-uniform), shared with `query_cost` and `pareto`.
const GAPS: (f64, f64) = CLOSE_GAPS;
/// Capped layout: longest meridian edge as a fraction of the profile's bounding-box diagonal.
const EDGE_CAP_REL: f64 = 1.0 / 64.0;

/// revdist against FCL 0.7 at equal accuracy: per model pair and eps, on the same seeded
/// poses near contact, the median query time of revdist (default tolerance, and tolerance 0
/// with the traversal only) and of FCL OBBRSS and RSS on certified meshes in two layouts
/// (cold, warm and blocked), with build times, memory, triangle counts, the widest certified
/// interval, the speed ratios (vs the faster FCL BV) and a cross-check of every answer.
/// Writes fcl_bench.csv and .md (200 poses per pair, 100 below eps 5e-5; 1,000 with --paper,
/// alias --full; the default freeform and M_t pairs: half the poses, eps 1e-3 and 1e-4).
#[derive(Parser)]
#[command(mut_arg("paper", |a| a.visible_alias("full")))]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// Poses per pair at eps < 5e-5, the first of the same sequence [default: 100; --paper: 1000]
    #[arg(long = "poses-1e-5", value_name = "N", value_parser = positive_count)]
    poses_fine: Option<usize>,
    #[command(flatten)]
    shard: crate::shard::Flags,
}

/// A pair's profiles and its poses (placed once, for the largest pose count of its eps).
type PlacedPair = (Arc<Profile>, Arc<Profile>, Vec<Isometry3<f64>>);

/// The driver's body: times every (pair, eps) row (or this shard's rows, or merges shards'
/// rows) and writes `fcl_bench.csv` and `fcl_bench.md` (the Markdown also to stdout).
pub fn run(args: Args) -> DriverResult {
    let c = &args.common;
    let poses = (
        c.poses.or(c.paper.pick(DEFAULT_POSES, FULL_POSES)),
        args.poses_fine
            .unwrap_or(c.paper.pick(DEFAULT_POSES_FINE, FULL_POSES)),
    );
    let eps_list = c.eps.or(&PAPER_EPS);
    // (pair, its eps, its pose counts): the given pairs all alike; the default list's added
    // pairs (freeform, M_t) lighter unless --paper (see ADDED_PAIRS).
    let mut plan: Vec<(ModelPair, Vec<f64>, (usize, usize))> = Vec::new();
    if c.pairs.list.is_empty() {
        let light = !c.paper.on;
        let added_eps = if light && c.eps.list.is_empty() {
            ADDED_EPS.to_vec()
        } else {
            eps_list.clone()
        };
        let added_poses = if light {
            (
                poses.0.div_ceil(ADDED_POSES_DIVISOR),
                poses.1.div_ceil(ADDED_POSES_DIVISOR),
            )
        } else {
            poses
        };
        for p in model_pairs(DEFAULT_PAIRS) {
            plan.push((p, eps_list.clone(), poses));
        }
        for p in model_pairs(ADDED_PAIRS) {
            plan.push((p, added_eps.clone(), added_poses));
        }
    } else {
        for p in &c.pairs.list {
            plan.push((p.clone(), eps_list.clone(), poses));
        }
    }
    let seed = c.seed.or(CLOSE_SEED);
    let started = Instant::now();
    let settings = vec![
        ("poses", poses.0.to_string()),
        ("poses_eps_below_5e-5", poses.1.to_string()),
        ("eps", format!("{eps_list:?}")),
        (
            "pairs",
            plan.iter()
                .map(|((a, b), e, (n, n_fine))| format!("{a}-{b} (eps {e:?}, poses {n}/{n_fine})"))
                .collect::<Vec<_>>()
                .join(" "),
        ),
        ("seed", format!("{seed:#x}")),
    ];
    // The work units, in the order of the table: (index into the plan, eps).
    let units: Vec<(usize, f64)> = plan
        .iter()
        .enumerate()
        .flat_map(|(k, (_, pair_eps, _))| pair_eps.iter().map(move |&e| (k, e)))
        .collect();
    // Per pair: its profiles and poses, placed once (fine trees) and reused at every eps.
    let mut placed: HashMap<usize, PlacedPair> = HashMap::new();
    let rows = args.shard.run(
        (&c.out.dir, "fcl_bench"),
        &settings,
        units.len(),
        |u| -> Result<Row, Box<dyn std::error::Error>> {
            let (k, eps) = units[u];
            let ((na, nb), pair_eps, pair_poses) = &plan[k];
            let pair = format!("{na}-{nb}");
            if let std::collections::hash_map::Entry::Vacant(slot) = placed.entry(k) {
                let (pa, pb) = (Arc::new(profile(na)?), Arc::new(profile(nb)?));
                let n_max = pair_eps
                    .iter()
                    .map(|&e| count_at(e, *pair_poses))
                    .max()
                    .unwrap_or(0);
                let p = close_poses(&pa, &pb, n_max, GAPS, pair_seed(seed, &pair), || {})?;
                slot.insert((pa, pb, p));
            }
            let (pa, pb, p) = &placed[&k];
            let n = count_at(eps, *pair_poses);
            let r = bench_row(&pair, (pa, pb), eps, &p[..n])?;
            eprintln!(
                "{pair} eps {eps:.0e}: revdist {:.1} us, FCL {} {:.1} us ({}), ratio {:.2} [{:.0} s]",
                r.rev_trees.0,
                BV_NAMES[r.faster().0],
                r.faster().1,
                LAYOUT_NAMES[r.faster_layout()],
                r.ratio(),
                started.elapsed().as_secs_f64()
            );
            Ok(r)
        },
    )?;
    let Some(rows) = rows else {
        return Ok(()); // a shard: its raw rows are written
    };
    let prov = crate::provenance::Provenance::collect(
        "fcl_bench (revdist vs FCL at equal accuracy)",
        &settings
            .iter()
            .cloned()
            .chain(args.shard.provenance())
            .collect::<Vec<_>>(),
    );
    let out = &c.out.dir;
    let csv = prov.csv_preamble() + &csv_table().csv_text(&rows);
    std::fs::write(out.join("fcl_bench.csv"), csv)?;
    let md = markdown(&rows, poses, started.elapsed());
    let md = md + &prov.markdown_footer();
    std::fs::write(out.join("fcl_bench.md"), &md)?;
    print!("{md}");
    Ok(())
}
