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
//!
//! Usage: `fcl_bench [--poses N] [--poses-1e-5 N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--seed S] [--out DIR]` (`--full` is an alias of `--paper`). Writes `DIR/fcl_bench.csv` and `DIR/fcl_bench.md` (default `figures`).

use clap::Parser;
use experiments::args::{model_pairs, positive_count, ModelPair};
use experiments::baseline_mesh::{agrees_with_fcl, Layout};
use experiments::cli::{count_at, Common};
use experiments::driver::{self, DriverResult};
use experiments::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use experiments::shapes::{diagonal, profile, query_tree_bytes, timed_pair, PAPER_EPS};
use experiments::stats::{human_bytes, median, quantile, time_each, us};
use experiments::table::Table;
use nalgebra::Isometry3;
use revdist::biarc::BiarcTree;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions, Tolerance};
use std::collections::HashMap;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::{Duration, Instant};

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
struct Args {
    #[command(flatten)]
    common: Common,
    /// Poses per pair at eps < 5e-5, the first of the same sequence [default: 100; --paper: 1000]
    #[arg(long = "poses-1e-5", value_name = "N", value_parser = positive_count)]
    poses_fine: Option<usize>,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// A pair's profiles and its poses (placed once, for the largest pose count of its eps).
type PlacedPair = (Arc<Profile>, Arc<Profile>, Vec<Isometry3<f64>>);

/// One row of the table: one work unit (pair, eps) of `--shard`.
#[derive(Default)]
struct Row {
    pair: String,
    eps: f64,
    poses: usize,
    rev_trees: (f64, f64),
    rev_exact: (f64, f64),
    /// Per layout: (OBBRSS median, RSS median).
    fcl: Vec<(f64, f64)>,
    /// Warm medians (the query repeated at once on the same pose): revdist at the default
    /// tolerance, and FCL OBBRSS and RSS per layout.
    rev_trees_warm: f64,
    fcl_obbrss_warm: Vec<f64>,
    fcl_rss_warm: Vec<f64>,
    /// Blocked medians (each method alone over all poses in a row): revdist, FCL OBBRSS per
    /// layout, and FCL RSS in its faster cold layout (`best_rss`).
    rev_trees_blocked: f64,
    fcl_obbrss_blocked: Vec<f64>,
    fcl_rss_blocked: f64,
    best_obbrss: usize,
    best_rss: usize,
    tris: Vec<usize>,
    h_sum: Vec<f64>,
    rev_build_ms: f64,
    mesh_ms: Vec<f64>,
    obbrss_build_ms: Vec<f64>,
    rss_build_ms: Vec<f64>,
    rev_bytes: usize,
    rev_tree_bytes: usize,
    obbrss_bytes: Vec<usize>,
    rss_bytes: Vec<usize>,
    max_width: f64,
    violations: usize,
}

experiments::shard_record!(Row {
    pair,
    eps,
    poses,
    rev_trees,
    rev_exact,
    fcl,
    rev_trees_warm,
    fcl_obbrss_warm,
    fcl_rss_warm,
    rev_trees_blocked,
    fcl_obbrss_blocked,
    fcl_rss_blocked,
    best_obbrss,
    best_rss,
    tris,
    h_sum,
    rev_build_ms,
    mesh_ms,
    obbrss_build_ms,
    rss_build_ms,
    rev_bytes,
    rev_tree_bytes,
    obbrss_bytes,
    rss_bytes,
    max_width,
    violations,
});

const LAYOUT_NAMES: [&str; 2] = ["balanced", "capped"];

/// FCL's two bounding-volume types, as the tables name them.
const BV_NAMES: [&str; 2] = ["OBBRSS", "RSS"];

/// The faster of FCL's two BVs given their times `(OBBRSS, RSS)`: its index in [`BV_NAMES`]
/// and its time (OBBRSS on a tie).
fn faster_bv((obbrss, rss): (f64, f64)) -> (usize, f64) {
    if rss < obbrss {
        (1, rss)
    } else {
        (0, obbrss)
    }
}

impl Row {
    /// FCL OBBRSS's and RSS's cold medians in their faster layouts.
    fn best_obbrss_us(&self) -> f64 {
        self.fcl[self.best_obbrss].0
    }
    fn best_rss_us(&self) -> f64 {
        self.fcl[self.best_rss].1
    }
    /// The faster FCL BV cold (each BV in its faster layout): index in [`BV_NAMES`], median.
    fn faster(&self) -> (usize, f64) {
        faster_bv((self.best_obbrss_us(), self.best_rss_us()))
    }
    /// The layout of the faster FCL BV cold.
    fn faster_layout(&self) -> usize {
        [self.best_obbrss, self.best_rss][self.faster().0]
    }
    /// The faster FCL BV warm and blocked (each BV in its faster cold layout).
    fn faster_warm(&self) -> (usize, f64) {
        faster_bv((
            self.fcl_obbrss_warm[self.best_obbrss],
            self.fcl_rss_warm[self.best_rss],
        ))
    }
    fn faster_blocked(&self) -> (usize, f64) {
        faster_bv((
            self.fcl_obbrss_blocked[self.best_obbrss],
            self.fcl_rss_blocked,
        ))
    }
    /// The faster FCL BV over revdist (default tolerance), cold, warm and blocked.
    fn ratio(&self) -> f64 {
        self.faster().1 / self.rev_trees.0
    }
    fn warm_ratio(&self) -> f64 {
        self.faster_warm().1 / self.rev_trees_warm
    }
    fn blocked_ratio(&self) -> f64 {
        self.faster_blocked().1 / self.rev_trees_blocked
    }
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
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
    let prov = experiments::provenance::Provenance::collect(
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

fn bench_row(
    pair: &str,
    (pa, pb): (&Arc<Profile>, &Arc<Profile>),
    eps: f64,
    poses: &[Isometry3<f64>],
) -> Result<Row, Box<dyn std::error::Error>> {
    let same = Arc::ptr_eq(pa, pb) || pa.name() == pb.name();
    // Configuration size for the cross-check's rounding slack.
    let size = diagonal(pa) + diagonal(pb);
    // revdist: tree build (biarc tree + query tree), timed per distinct shape.
    let (sa, sb, rev_build_ms) = timed_pair(pa, pb, eps)?;
    let tree_bytes = |p: &Profile| -> Result<usize, Box<dyn std::error::Error>> {
        Ok(BiarcTree::build(p, eps)?.stats().bytes)
    };
    let rev_tree_bytes = tree_bytes(pa)? + if same { 0 } else { tree_bytes(pb)? };
    let rev_bytes = query_tree_bytes(&sa.tree) + if same { 0 } else { query_tree_bytes(&sb.tree) };

    // FCL: both layouts of both shapes.
    let mut layouts = Vec::new();
    for cap_rel in [None, Some(EDGE_CAP_REL)] {
        let la = Layout::build(pa, eps, cap_rel.map(|c| c * diagonal(pa)))?;
        let lb = if same {
            None
        } else {
            Some(Layout::build(pb, eps, cap_rel.map(|c| c * diagonal(pb)))?)
        };
        layouts.push((la, lb));
    }
    let mut row = Row {
        pair: pair.to_owned(),
        eps,
        poses: poses.len(),
        rev_build_ms,
        rev_bytes,
        rev_tree_bytes,
        ..Row::default()
    };
    for (la, lb) in &layouts {
        let lb = lb.as_ref().unwrap_or(la);
        let sum = |f: &dyn Fn(&Layout) -> f64| f(la) + if same { 0.0 } else { f(lb) };
        row.tris
            .push(la.cm.mesh.triangle_count() + lb.cm.mesh.triangle_count());
        row.h_sum.push(la.cm.bound + lb.cm.bound);
        row.mesh_ms.push(sum(&|l| l.mesh_time.as_secs_f64() * 1e3));
        row.obbrss_build_ms
            .push(sum(&|l| l.obbrss.build_time().as_secs_f64() * 1e3));
        row.rss_build_ms
            .push(sum(&|l| l.rss.build_time().as_secs_f64() * 1e3));
        row.obbrss_bytes
            .push(sum(&|l| l.obbrss.bytes() as f64) as usize);
        row.rss_bytes.push(sum(&|l| l.rss.bytes() as f64) as usize);
    }

    // Timing: every method once per pose, in a rotating order.
    let trees = QueryOptions::default();
    // Tolerance 0 and no closed form: the traversal itself, also for the torus pair (whose
    // default query is the closed form of `revdist::query::offset`).
    let exact = QueryOptions {
        tolerance: Tolerance::Absolute(0.0),
        closed_form: false,
        ..QueryOptions::default()
    };
    let n_methods = 2 + 2 * layouts.len();
    let id = Isometry3::identity();
    // The cross-check's reference answers first, in a pass of their own: an untimed FCL
    // query between the timed ones would warm the caches for the FCL method after it.
    let reference: Vec<f64> = {
        let (la, lb) = &layouts[0];
        let lb = lb.as_ref().unwrap_or(la);
        poses
            .iter()
            .map(|pose| {
                la.obbrss
                    .distance(&lb.obbrss, &id, pose)
                    .map(|f| f.distance)
            })
            .collect::<Result<_, _>>()?
    };
    let mut times = vec![Vec::with_capacity(poses.len()); n_methods];
    // Every method is repeated at once (warm), also those whose warm time is not reported,
    // so that each cold query follows the same kind of work whatever method came before.
    let mut warm_times = vec![Vec::with_capacity(poses.len()); n_methods];
    for (i, pose) in poses.iter().enumerate() {
        let b = sb.with_pose(*pose);
        for k in 0..n_methods {
            let m = (k + i) % n_methods;
            match m {
                0 | 1 => {
                    let opts = if m == 0 { &trees } else { &exact };
                    let t = Instant::now();
                    let d = distance(&sa, &b, opts);
                    times[m].push(us(t.elapsed()));
                    let t = Instant::now();
                    std::hint::black_box(distance(&sa, &b, opts));
                    warm_times[m].push(us(t.elapsed()));
                    if m == 0 {
                        row.max_width = row.max_width.max(d.upper - d.lower);
                    }
                    // Cross-check against the balanced OBBRSS answer (the reference pass).
                    if !agrees_with_fcl(&d, reference[i], row.h_sum[0], pose, size) {
                        row.violations += 1;
                    }
                }
                _ => {
                    let l = (m - 2) / 2;
                    let (la, lb) = &layouts[l];
                    let lb = lb.as_ref().unwrap_or(la);
                    let (ma, mb) = if (m - 2) % 2 == 0 {
                        (&la.obbrss, &lb.obbrss)
                    } else {
                        (&la.rss, &lb.rss)
                    };
                    let t = Instant::now();
                    let f = ma.distance(mb, &id, pose)?;
                    times[m].push(us(t.elapsed()));
                    std::hint::black_box(f);
                    let t = Instant::now();
                    std::hint::black_box(ma.distance(mb, &id, pose)?);
                    warm_times[m].push(us(t.elapsed()));
                }
            }
        }
    }
    row.rev_trees = (median(&times[0]), quantile(&times[0], 0.9));
    row.rev_exact = (median(&times[1]), quantile(&times[1], 0.9));
    for l in 0..layouts.len() {
        row.fcl
            .push((median(&times[2 + 2 * l]), median(&times[3 + 2 * l])));
        row.fcl_obbrss_warm.push(median(&warm_times[2 + 2 * l]));
        row.fcl_rss_warm.push(median(&warm_times[3 + 2 * l]));
    }
    row.rev_trees_warm = median(&warm_times[0]);
    let best = |f: &dyn Fn(&(f64, f64)) -> f64| {
        (0..row.fcl.len())
            .min_by(|&x, &y| f(&row.fcl[x]).total_cmp(&f(&row.fcl[y])))
            .expect("a layout")
    };
    row.best_obbrss = best(&|x| x.0);
    row.best_rss = best(&|x| x.1);
    // Blocked: each method alone over all poses (answers were cross-checked above).
    let blocked = time_each(poses.iter().map(|pose| sb.with_pose(*pose)), |b| {
        std::hint::black_box(distance(&sa, &b, &trees));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    row.rev_trees_blocked = median(&blocked);
    for (la, lb) in &layouts {
        let lb = lb.as_ref().unwrap_or(la);
        let blocked = time_each(poses, |pose| {
            std::hint::black_box(la.obbrss.distance(&lb.obbrss, &id, pose)?);
            Ok::<(), Box<dyn std::error::Error>>(())
        })?;
        row.fcl_obbrss_blocked.push(median(&blocked));
    }
    // FCL RSS blocked in its faster cold layout only (the blocked ratio takes the faster BV).
    let (la, lb) = &layouts[row.best_rss];
    let lb = lb.as_ref().unwrap_or(la);
    let blocked = time_each(poses, |pose| {
        std::hint::black_box(la.rss.distance(&lb.rss, &id, pose)?);
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    row.fcl_rss_blocked = median(&blocked);
    Ok(row)
}

/// The columns of `fcl_bench.csv` (index 0 of a per-layout field: balanced, 1: capped).
fn csv_table() -> Table<'static, Row> {
    let fixed = |digits: usize, f: fn(&Row) -> f64| move |r: &Row| format!("{:.*}", digits, f(r));
    let sci4 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.4e}", f(r));
    let count = |f: fn(&Row) -> usize| move |r: &Row| f(r).to_string();
    Table::new()
        .csv("pair", |r: &Row| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .csv("poses", count(|r| r.poses))
        .csv("rev_trees_median_us", fixed(2, |r| r.rev_trees.0))
        .csv("rev_trees_p90_us", fixed(2, |r| r.rev_trees.1))
        .csv("rev_tol0_median_us", fixed(2, |r| r.rev_exact.0))
        .csv("rev_tol0_p90_us", fixed(2, |r| r.rev_exact.1))
        .csv("fcl_obbrss_balanced_us", fixed(2, |r| r.fcl[0].0))
        .csv("fcl_rss_balanced_us", fixed(2, |r| r.fcl[0].1))
        .csv("fcl_obbrss_capped_us", fixed(2, |r| r.fcl[1].0))
        .csv("fcl_rss_capped_us", fixed(2, |r| r.fcl[1].1))
        .csv("best_obbrss_layout", |r| LAYOUT_NAMES[r.best_obbrss].into())
        .csv("best_rss_layout", |r| LAYOUT_NAMES[r.best_rss].into())
        // The headline: the faster FCL BV (cold, each BV in its faster layout) over revdist.
        .csv("faster_fcl_bv", |r| BV_NAMES[r.faster().0].into())
        .csv("faster_fcl_bv_layout", |r| {
            LAYOUT_NAMES[r.faster_layout()].into()
        })
        .csv("faster_fcl_bv_us", fixed(2, |r| r.faster().1))
        .csv("ratio_vs_faster_fcl_bv", fixed(3, Row::ratio))
        .csv(
            "ratio_vs_faster_fcl_bv_tol0",
            fixed(3, |r| r.faster().1 / r.rev_exact.0),
        )
        .csv(
            "ratio_obbrss_over_rev",
            fixed(3, |r| r.best_obbrss_us() / r.rev_trees.0),
        )
        .csv(
            "ratio_rss_over_rev",
            fixed(3, |r| r.best_rss_us() / r.rev_trees.0),
        )
        .csv("tris_balanced", count(|r| r.tris[0]))
        .csv("tris_capped", count(|r| r.tris[1]))
        .csv("h_sum_balanced", sci4(|r| r.h_sum[0]))
        .csv("h_sum_capped", sci4(|r| r.h_sum[1]))
        .csv("rev_max_width", sci4(|r| r.max_width))
        .csv("rev_build_ms", fixed(3, |r| r.rev_build_ms))
        .csv("mesh_ms_balanced", fixed(3, |r| r.mesh_ms[0]))
        .csv(
            "obbrss_build_ms_balanced",
            fixed(3, |r| r.obbrss_build_ms[0]),
        )
        .csv("rss_build_ms_balanced", fixed(3, |r| r.rss_build_ms[0]))
        .csv("mesh_ms_capped", fixed(3, |r| r.mesh_ms[1]))
        .csv("obbrss_build_ms_capped", fixed(3, |r| r.obbrss_build_ms[1]))
        .csv("rss_build_ms_capped", fixed(3, |r| r.rss_build_ms[1]))
        .csv("rev_query_tree_bytes", count(|r| r.rev_bytes))
        .csv("rev_biarc_tree_bytes", count(|r| r.rev_tree_bytes))
        .csv("obbrss_bytes_balanced", count(|r| r.obbrss_bytes[0]))
        .csv("rss_bytes_balanced", count(|r| r.rss_bytes[0]))
        .csv("obbrss_bytes_capped", count(|r| r.obbrss_bytes[1]))
        .csv("rss_bytes_capped", count(|r| r.rss_bytes[1]))
        .csv("violations", count(|r| r.violations))
        // Warm and blocked columns come last (readers find columns by their header).
        .csv("rev_trees_warm_median_us", fixed(2, |r| r.rev_trees_warm))
        .csv(
            "fcl_obbrss_balanced_warm_us",
            fixed(2, |r| r.fcl_obbrss_warm[0]),
        )
        .csv(
            "fcl_obbrss_capped_warm_us",
            fixed(2, |r| r.fcl_obbrss_warm[1]),
        )
        .csv("fcl_rss_balanced_warm_us", fixed(2, |r| r.fcl_rss_warm[0]))
        .csv("fcl_rss_capped_warm_us", fixed(2, |r| r.fcl_rss_warm[1]))
        .csv("faster_fcl_bv_warm", |r| BV_NAMES[r.faster_warm().0].into())
        .csv("ratio_vs_faster_fcl_bv_warm", fixed(3, Row::warm_ratio))
        .csv(
            "rev_trees_blocked_median_us",
            fixed(2, |r| r.rev_trees_blocked),
        )
        .csv(
            "fcl_obbrss_balanced_blocked_us",
            fixed(2, |r| r.fcl_obbrss_blocked[0]),
        )
        .csv(
            "fcl_obbrss_capped_blocked_us",
            fixed(2, |r| r.fcl_obbrss_blocked[1]),
        )
        .csv(
            "fcl_rss_best_layout_blocked_us",
            fixed(2, |r| r.fcl_rss_blocked),
        )
        .csv("faster_fcl_bv_blocked", |r| {
            BV_NAMES[r.faster_blocked().0].into()
        })
        .csv(
            "ratio_vs_faster_fcl_bv_blocked",
            fixed(3, Row::blocked_ratio),
        )
}

/// The `pair` and `eps` columns that open every Markdown table.
fn pair_and_eps() -> Table<'static, Row> {
    Table::new()
        .markdown("pair", |r: &Row| r.pair.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
}

/// The main Markdown table: cold medians, the faster layout per FCL column.
fn cold_table() -> Table<'static, Row> {
    pair_and_eps()
        .markdown("poses", |r| r.poses.to_string())
        .right()
        .markdown("triangles A+B", |r| r.tris[r.best_obbrss].to_string())
        .right()
        .markdown("revdist median / p90 us", |r| {
            format!("{:.1} / {:.1}", r.rev_trees.0, r.rev_trees.1)
        })
        .right()
        .markdown("revdist tol 0, traversal, median us", |r| {
            format!("{:.1}", r.rev_exact.0)
        })
        .right()
        .markdown("FCL OBBRSS median us", |r| {
            format!(
                "{:.1} ({})",
                r.best_obbrss_us(),
                LAYOUT_NAMES[r.best_obbrss]
            )
        })
        .right()
        .markdown("FCL RSS median us", |r| {
            format!("{:.1} ({})", r.best_rss_us(), LAYOUT_NAMES[r.best_rss])
        })
        .right()
        .markdown("faster FCL BV", |r| BV_NAMES[r.faster().0].into())
        .markdown("ratio vs faster FCL BV", |r| format!("{:.2}", r.ratio()))
        .right()
        .markdown("build revdist / mesh+OBBRSS ms", |r| {
            let o = r.best_obbrss;
            let fcl = r.mesh_ms[o] + r.obbrss_build_ms[o];
            format!("{:.2} / {fcl:.1}", r.rev_build_ms)
        })
        .right()
        .markdown("memory revdist / OBBRSS / RSS", |r| {
            let rev = human_bytes(r.rev_bytes as f64);
            let obbrss = human_bytes(r.obbrss_bytes[r.best_obbrss] as f64);
            format!(
                "{rev} / {obbrss} / {}",
                human_bytes(r.rss_bytes[r.best_rss] as f64)
            )
        })
        .right()
        .markdown("max width / h_a+h_b", |r| {
            format!("{:.2e} / {:.2e}", r.max_width, r.h_sum[r.best_obbrss])
        })
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

/// Blocked and warm medians, FCL's faster BV in each mode (each BV in its faster cold layout).
fn blocked_warm_table() -> Table<'static, Row> {
    let us = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.1}", f(r));
    let ratio = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.2}", f(r));
    let fcl = |f: fn(&Row) -> (usize, f64)| {
        move |r: &Row| {
            let (bv, t) = f(r);
            format!("{t:.1} ({})", BV_NAMES[bv])
        }
    };
    pair_and_eps()
        .markdown("revdist blocked", us(|r| r.rev_trees_blocked))
        .right()
        .markdown("FCL blocked (faster BV)", fcl(Row::faster_blocked))
        .right()
        .markdown("ratio blocked vs faster FCL BV", ratio(Row::blocked_ratio))
        .right()
        .markdown("revdist warm", us(|r| r.rev_trees_warm))
        .right()
        .markdown("FCL warm (faster BV)", fcl(Row::faster_warm))
        .right()
        .markdown("ratio warm vs faster FCL BV", ratio(Row::warm_ratio))
        .right()
        .markdown(
            "cold / blocked revdist",
            ratio(|r| r.rev_trees.0 / r.rev_trees_blocked),
        )
        .right()
        .markdown(
            "cold / blocked FCL",
            ratio(|r| r.faster().1 / r.faster_blocked().1),
        )
        .right()
}

/// FCL's medians in every layout.
fn layouts_table() -> Table<'static, Row> {
    let layout = |l: usize| move |r: &Row| format!("{:.1} / {:.1}", r.fcl[l].0, r.fcl[l].1);
    pair_and_eps()
        .markdown("balanced OBBRSS / RSS", layout(0))
        .right()
        .markdown("tris", |r| r.tris[0].to_string())
        .right()
        .markdown("capped OBBRSS / RSS", layout(1))
        .right()
        .markdown("tris", |r| r.tris[1].to_string())
        .right()
}

fn machine() -> String {
    let cpu = std::fs::read_to_string("/proc/cpuinfo")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("model name"))
                .and_then(|l| l.split_once(':'))
                .map(|(_, v)| v.trim().to_owned())
        })
        .unwrap_or_else(|| "unknown CPU".into());
    let cores = std::thread::available_parallelism().map_or(0, |n| n.get());
    format!("{cpu}, {cores} cores")
}

fn git_commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_owned())
        .unwrap_or_else(|| "unknown".into())
}

/// `poses`: per pair at eps >= 5e-5 and below.
fn markdown(rows: &[Row], poses: (usize, usize), wall: Duration) -> String {
    let mut s = String::from("# revdist vs FCL 0.7 at equal accuracy\n\n");
    let _ = writeln!(
        s,
        "Machine: {}. Commit: {}. Poses per pair: {} (eps >= 5e-5), {} (eps < 5e-5; the first \
         poses of the same sequence; the default list's freeform and M_t pairs: half as many, \
         at eps 1e-3 and 1e-4 only, unless --paper; the `poses` column tells), gaps \
         log-uniform in [{:e}, {:e}], seeded; wall time {:.0} s.\n",
        machine(),
        git_commit(),
        poses.0,
        poses.1,
        GAPS.0,
        GAPS.1,
        wall.as_secs_f64()
    );
    s.push_str(
        "Single thread, one query at a time, methods interleaved per pose. revdist: default \
         tolerance (certified interval width <= eps_a + eps_b; balls and solid tori in closed form) \
         and tolerance 0 with the traversal only (no closed form). FCL: \
         `BVHModel<OBBRSS>` / `<RSS>` on certified meshes (two-sided Hausdorff bound <= eps), \
         the faster of two layouts per column (balanced; meridian edges capped at 1/64 of the \
         profile diagonal). Ratio = median of the faster FCL BV (OBBRSS or RSS, each in its \
         faster layout; named in the column before) / revdist median (default tolerance). \
         Memory: revdist query-tree arrays vs FCL's node, triangle and vertex arrays (both \
         shapes; one when A = B). Build: revdist trees vs tessellation + OBBRSS build (layout \
         of the OBBRSS column). Violations: cases where revdist's interval misses FCL's \
         `d ± (h_a + h_b)`. All times are *cold*: each query runs after the other methods' \
         queries (FCL's meshes take megabytes), so its trees and code come from memory. The \
         second table runs each method *blocked* (alone over all poses in a row, the usual \
         benchmark loop) and *warm* (each query repeated at once on the same pose).\n\n",
    );
    s.push_str(&cold_table().markdown_text(rows));
    s.push_str(
        "\nBlocked (each method alone over all poses in a row) and warm (each query repeated at \
         once on the same pose); FCL: the faster BV in that mode, each BV in its layout of the \
         first table; medians, us:\n\n",
    );
    s.push_str(&blocked_warm_table().markdown_text(rows));
    s.push_str("\nAll layouts (FCL medians, us; triangles):\n\n");
    s.push_str(&layouts_table().markdown_text(rows));
    s
}
