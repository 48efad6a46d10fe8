//! What accuracy costs: query time, build time and memory against the
//! accuracy achieved, for revdist and FCL 0.7, on the same seeded poses near contact in one run.
//!
//! * revdist at eps 1e-2 .. 1e-8 with its default tolerance (the query stops once the
//!   certified interval is at most eps_a + eps_b wide), with tolerance 0 (as narrow as the
//!   trees allow), and refined (witnesses polished on the exact surfaces, which lowers the
//!   upper bound) at a few eps. Its accuracy is the certified interval width `upper - lower`
//!   of each answer: the worst (max) and the median over the poses.
//! * FCL `BVHModel<OBBRSS>` and `<RSS>` on certified meshes (`revdist::tessellate`, two-sided
//!   Hausdorff bound h <= eps) at eps 1e-2 .. 1e-6, stopping before a level whose predicted
//!   triangle count (the last level's times eps_prev / eps: a mesh of error eps needs
//!   ~eps^-1 triangles) exceeds a cap. Its accuracy is h_a + h_b: the width of the interval
//!   `d ± (h_a + h_b)` that holds the true distance. Both layouts of `fcl_bench` (balanced,
//!   and capped meridian edges where the cap applies) are timed and the faster one is kept per
//!   row, as there.
//! * Build time: revdist's trees (median of a few builds) against tessellation + BVH build;
//!   memory: revdist's query-tree arrays against FCL's (`FclMesh::bytes`); one structure when
//!   A = B.
//! * Every revdist answer is cross-checked against every FCL answer of the same pose
//!   (`verify::crosscheck::criterion`): the intervals must meet. Violations are counted per
//!   row; any violation makes the run exit with status 1 after writing the outputs.
//!
//! Queries are timed one at a time on one thread; per pose all methods run back to back in an
//! order that rotates from pose to pose (drift and cache warm-up spread evenly).
//!
//! Usage: `pareto [--poses N] [--pairs a-b,...] [--paper] [--out DIR] [--eps E,...]
//! [--refine-eps E,...] [--fcl-eps E,...] [--max-triangles N]`. Writes `DIR/pareto.csv`,
//! `DIR/pareto.md` and `DIR/pareto_{time,build,memory}.svg` (default `figures`). Defaults:
//! 200 poses per pair (`--paper`: 1000), pairs pawn-cup, table-lightmill, torus-torus, a cap of
//! 2M predicted triangles (the coarsest FCL level is always built). About a minute on 2 cores.

use clap::Parser;
use experiments::args::{accuracy, model_pairs, positive_count, ModelPair};
use experiments::baseline_mesh::{agrees_with_fcl, Layout, LAYOUT_NAMES};
use experiments::cli::{given_or, Common};
use experiments::driver::{self, DriverResult};
use experiments::plot::{log_log_panels, Curve, Panel};
use experiments::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use experiments::progress::bar;
use experiments::provenance::Provenance;
use experiments::shapes::{diagonal, profile, query_tree_bytes};
use experiments::shard::{Cells, Field, Record, Scalar};
use experiments::stats::{human_bytes, log_log_slope, median, quantile, us};
use experiments::table::Table;
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::{distance, Distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::FclMesh;

/// Representative pairs: two paper pairs (one where revdist is slower than FCL at coarse eps,
/// one where the two are close) and the torus pair of `fcl_bench`.
const DEFAULT_PAIRS: &str = "pawn-cup,table-lightmill,torus-torus";
/// revdist's eps (default tolerance and tolerance 0).
const REV_EPS: [f64; 7] = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8];
/// eps of the refined mode.
const REFINE_EPS: [f64; 3] = [1e-2, 1e-4, 1e-6];
/// FCL's mesh eps (finer levels are skipped when they would exceed the triangle cap).
const FCL_EPS: [f64; 5] = [1e-2, 1e-3, 1e-4, 1e-5, 1e-6];
/// Largest predicted triangle count (distinct meshes of a pair, one layout) FCL is run at.
const MAX_TRIANGLES: usize = 2_000_000;
/// Poses per pair by default and with `--paper`.
const DEFAULT_POSES: usize = 200;
const PAPER_POSES: usize = 1000;
/// revdist tree builds per level (the median is reported: one build takes ~0.01-1 ms).
const BUILD_REPEATS: usize = 5;

/// A curve of the figures: one accuracy mode of one method.
#[derive(Clone, Copy, PartialEq, Eq, Debug)]
enum Method {
    Rev,
    RevTol0,
    RevRefined,
    FclObbrss,
    FclRss,
}

const METHODS: [Method; 5] = [
    Method::Rev,
    Method::RevTol0,
    Method::RevRefined,
    Method::FclObbrss,
    Method::FclRss,
];

impl Method {
    /// Name in the CSV.
    fn key(self) -> &'static str {
        match self {
            Method::Rev => "revdist",
            Method::RevTol0 => "revdist_tol0",
            Method::RevRefined => "revdist_refined",
            Method::FclObbrss => "fcl_obbrss",
            Method::FclRss => "fcl_rss",
        }
    }

    /// Name in the tables and legends.
    fn label(self) -> &'static str {
        match self {
            Method::Rev => "revdist, default tolerance",
            Method::RevTol0 => "revdist, tolerance 0",
            Method::RevRefined => "revdist, refined",
            Method::FclObbrss => "FCL OBBRSS",
            Method::FclRss => "FCL RSS",
        }
    }

    fn is_fcl(self) -> bool {
        matches!(self, Method::FclObbrss | Method::FclRss)
    }

    fn options(self) -> QueryOptions {
        QueryOptions {
            tolerance: if self == Method::RevTol0 {
                Tolerance::Absolute(0.0)
            } else {
                Tolerance::Trees
            },
            refine: self == Method::RevRefined,
            ..QueryOptions::default()
        }
    }
}

/// What accuracy costs: on the same seeded poses near contact, per model pair, query time,
/// build time and memory against the certified error bound, for revdist at eps 1e-2 .. 1e-8
/// (default tolerance, tolerance 0, and refined) and for FCL 0.7 OBBRSS and RSS on certified
/// meshes at eps 1e-2 .. 1e-6 (up to a cap on the predicted triangle count); every revdist
/// answer is cross-checked against every FCL answer of the same pose. Writes pareto.csv,
/// pareto.md and pareto_{time,build,memory}.svg (200 poses per pair; 1,000 with --paper).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    common: Common,
    /// Accuracies of the refined revdist mode, in (0, 1) [default: 1e-2,1e-4,1e-6]
    #[arg(long, value_name = "E,...", value_delimiter = ',', value_parser = accuracy)]
    refine_eps: Vec<f64>,
    /// FCL's mesh accuracies, in (0, 1) [default: 1e-2,1e-3,1e-4,1e-5,1e-6]
    #[arg(long, value_name = "E,...", value_delimiter = ',', value_parser = accuracy)]
    fcl_eps: Vec<f64>,
    /// Largest predicted triangle count FCL is run at [default: 2000000]
    #[arg(long, value_name = "N", value_parser = positive_count)]
    max_triangles: Option<usize>,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// What a run measures: the arguments with the defaults filled in.
struct Settings {
    poses: usize,
    pairs: Vec<ModelPair>,
    seed: u64,
    rev_eps: Vec<f64>,
    refine_eps: Vec<f64>,
    fcl_eps: Vec<f64>,
    max_triangles: usize,
}

impl Settings {
    fn new(args: &Args) -> Settings {
        let c = &args.common;
        let mut s = Settings {
            poses: c.poses.or(c.paper.pick(DEFAULT_POSES, PAPER_POSES)),
            pairs: c.pairs.or(&model_pairs(DEFAULT_PAIRS)),
            seed: c.seed.or(CLOSE_SEED),
            rev_eps: c.eps.or(&REV_EPS),
            refine_eps: given_or(&args.refine_eps, &REFINE_EPS),
            fcl_eps: given_or(&args.fcl_eps, &FCL_EPS),
            max_triangles: args.max_triangles.unwrap_or(MAX_TRIANGLES),
        };
        for list in [&mut s.rev_eps, &mut s.refine_eps, &mut s.fcl_eps] {
            list.sort_by(|x, y| y.total_cmp(x));
            list.dedup();
        }
        s
    }
}

/// One row of the table: one method at one eps on one pair.
struct Row {
    method: Method,
    pair: String,
    eps: f64,
    poses: usize,
    /// Certified error bound: revdist's interval width (max / median over the poses), FCL's
    /// h_a + h_b (the same for every pose).
    width_max: f64,
    width_median: f64,
    median_us: f64,
    p90_us: f64,
    build_ms: f64,
    bytes: usize,
    /// revdist only: node pairs popped per query (mean).
    node_pairs: Option<f64>,
    /// revdist only: answers whose certified lower bound is 0 (separation not certified).
    zero_lower: Option<usize>,
    /// FCL only: triangles of the distinct meshes, and the layout kept.
    triangles: Option<usize>,
    layout: Option<&'static str>,
    /// Cross-checks of this row's answers and how many failed.
    checks: usize,
    violations: usize,
}

experiments::shard_record!(Row {
    method,
    pair,
    eps,
    poses,
    width_max,
    width_median,
    median_us,
    p90_us,
    build_ms,
    bytes,
    node_pairs,
    zero_lower,
    triangles,
    layout,
    checks,
    violations,
});

/// A raw row of `--shard`: a row of the table, and on its pair's first row the FCL levels the
/// triangle cap left out.
struct RawRow {
    row: Row,
    skipped: Vec<String>,
}

impl Record for RawRow {
    fn columns() -> Vec<&'static str> {
        let mut c = Row::columns();
        c.push("skipped");
        c
    }
    fn cells(&self) -> Vec<String> {
        let mut c = self.row.cells();
        c.push(self.skipped.text());
        c
    }
    fn from_cells(line: &Cells) -> Result<Self, String> {
        Ok(RawRow {
            row: Row::from_cells(line)?,
            skipped: line.get("skipped")?,
        })
    }
}

impl Field for Method {
    fn text(&self) -> String {
        self.key().to_owned()
    }
    fn parse(cell: &str) -> Result<Self, String> {
        METHODS
            .into_iter()
            .find(|m| m.key() == cell)
            .ok_or_else(|| format!("'{cell}' is not a method"))
    }
}
impl Scalar for Method {}

/// revdist's solids of one pair at one eps.
struct RevLevel {
    eps: f64,
    a: Solid,
    b: Solid,
    build_ms: f64,
    bytes: usize,
}

fn rev_level(
    pa: &Arc<Profile>,
    pb: &Arc<Profile>,
    same: bool,
    eps: f64,
) -> Result<RevLevel, Box<dyn std::error::Error>> {
    let build = || -> Result<(Solid, Solid), Box<dyn std::error::Error>> {
        let a = Solid::from_profile(Arc::clone(pa), eps)?;
        let b = if same {
            a.clone()
        } else {
            Solid::from_profile(Arc::clone(pb), eps)?
        };
        Ok((a, b))
    };
    let mut times = Vec::with_capacity(BUILD_REPEATS);
    let mut solids = None;
    for _ in 0..BUILD_REPEATS {
        let t = Instant::now();
        solids = Some(build()?);
        times.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let (a, b) = solids.expect("BUILD_REPEATS > 0");
    let bytes = query_tree_bytes(&a.tree) + if same { 0 } else { query_tree_bytes(&b.tree) };
    Ok(RevLevel {
        eps,
        a,
        b,
        build_ms: median(&times),
        bytes,
    })
}

/// One mesh layout of a pair: A's meshes and B's (`None` when B is A).
struct LayoutPair {
    name: &'static str,
    a: Layout,
    b: Option<Layout>,
}

/// FCL's meshes of one pair at one eps, in every layout that applies: balanced, and capped
/// when the cap is above the tessellator's minimum for both shapes.
struct FclLevel {
    eps: f64,
    layouts: Vec<LayoutPair>,
}

impl FclLevel {
    fn build(
        pa: &Profile,
        pb: &Profile,
        same: bool,
        eps: f64,
    ) -> Result<FclLevel, Box<dyn std::error::Error>> {
        let mut caps = vec![(LAYOUT_NAMES[0], None, None)];
        if let (Some(ca), Some(cb)) = (Layout::capped_edge(pa, eps), Layout::capped_edge(pb, eps)) {
            caps.push((LAYOUT_NAMES[1], Some(ca), Some(cb)));
        }
        let layouts = caps
            .into_iter()
            .map(|(name, ca, cb)| {
                let a = Layout::build(pa, eps, ca)?;
                let b = if same {
                    None
                } else {
                    Some(Layout::build(pb, eps, cb)?)
                };
                Ok(LayoutPair { name, a, b })
            })
            .collect::<Result<_, Box<dyn std::error::Error>>>()?;
        Ok(FclLevel { eps, layouts })
    }
}

impl LayoutPair {
    fn b(&self) -> &Layout {
        self.b.as_ref().unwrap_or(&self.a)
    }

    /// Sum of `f` over the distinct meshes.
    fn sum(&self, f: impl Fn(&Layout) -> f64) -> f64 {
        f(&self.a) + self.b.as_ref().map_or(0.0, f)
    }

    /// h_a + h_b.
    fn h_sum(&self) -> f64 {
        self.a.cm.bound + self.b().cm.bound
    }

    fn triangles(&self) -> usize {
        self.sum(|x| x.triangles() as f64) as usize
    }
}

/// The hierarchy of `method` (FCL OBBRSS or RSS) in a layout.
fn bvh(l: &Layout, method: Method) -> &FclMesh {
    if method == Method::FclObbrss {
        &l.obbrss
    } else {
        &l.rss
    }
}

/// One timed configuration: a revdist mode at a level, or an FCL hierarchy of a layout.
#[derive(Clone, Copy)]
struct Slot {
    method: Method,
    level: usize,
    layout: usize,
}

/// Per slot: query times, revdist widths, cross-checks and violations.
#[derive(Default, Clone)]
struct Samples {
    times: Vec<f64>,
    widths: Vec<f64>,
    node_pairs: usize,
    zero_lower: usize,
    checks: usize,
    violations: usize,
}

/// What one pair contributes: its rows and the FCL levels skipped by the triangle cap.
struct PairResult {
    rows: Vec<Row>,
    skipped: Vec<String>,
}

fn main() {
    driver::run(run)
}

fn run(cli: Args) -> DriverResult {
    let args = Settings::new(&cli);
    let out = &cli.common.out.dir;
    // Check the model names before any work.
    for (a, b) in &args.pairs {
        profile(a)?;
        profile(b)?;
    }
    let started = Instant::now();
    let load_start = load_average();
    let settings = vec![
        ("pairs", pairs_text(&args.pairs)),
        ("poses_per_pair", args.poses.to_string()),
        (
            "gaps",
            format!("log-uniform [{:e}, {:e}]", CLOSE_GAPS.0, CLOSE_GAPS.1),
        ),
        ("seed", format!("{:#x} xor hash(pair)", args.seed)),
        ("revdist_eps", eps_text(&args.rev_eps)),
        ("refine_eps", eps_text(&args.refine_eps)),
        ("fcl_eps", eps_text(&args.fcl_eps)),
        ("max_triangles", args.max_triangles.to_string()),
        ("revdist_build_repeats", BUILD_REPEATS.to_string()),
    ];
    let prov = Provenance::collect(
        "pareto",
        &settings
            .iter()
            .cloned()
            .chain(cli.shard.provenance())
            .collect::<Vec<_>>(),
    );
    // The work units: one per pair (every revdist answer of a pose is checked against every
    // FCL answer of that pose, so a pair's methods and levels run together).
    let raw = cli.shard.run_many(
        (out, "pareto"),
        &settings,
        args.pairs.len(),
        |u| -> Result<Vec<RawRow>, Box<dyn std::error::Error>> {
            let (na, nb) = &args.pairs[u];
            let r = run_pair(na, nb, &args)?;
            let mut notes = Some(r.skipped);
            Ok(r.rows
                .into_iter()
                .map(|row| RawRow {
                    row,
                    skipped: notes.take().unwrap_or_default(),
                })
                .collect())
        },
    )?;
    let Some(raw) = raw else {
        return Ok(()); // a shard: its raw rows are written
    };
    let skipped: Vec<String> = raw.iter().flat_map(|r| r.skipped.clone()).collect();
    let rows: Vec<Row> = raw.into_iter().map(|r| r.row).collect();
    let wall = started.elapsed().as_secs_f64();
    let load = format!("{load_start} / {}", load_average());
    let mut csv = prov.csv_preamble();
    let _ = writeln!(csv, "# load_average_1min_start_end: {load}");
    csv.push_str(&cost_table().csv_text(&rows));
    std::fs::write(out.join("pareto.csv"), csv)?;
    let md = markdown(&rows, &skipped, &args, &prov, (wall, &load));
    std::fs::write(out.join("pareto.md"), &md)?;
    figures(out, &rows, &args)?;
    let (checks, violations) = cross_checks(&rows);
    eprintln!(
        "wrote pareto.{{csv,md}} and pareto_{{time,build,memory}}.svg to {} ({} rows, {checks} cross-checks, {violations} violations, {wall:.0} s)",
        out.display(),
        rows.len()
    );
    let detail = "(revdist's interval missed FCL's); see pareto.md";
    driver::check_violations(violations, detail)
}

/// The 1-minute load average (other processes competing for the cores make timings noisy).
fn load_average() -> String {
    std::fs::read_to_string("/proc/loadavg")
        .ok()
        .and_then(|s| s.split_whitespace().next().map(str::to_owned))
        .unwrap_or_else(|| "unknown".into())
}

fn eps_text(v: &[f64]) -> String {
    v.iter()
        .map(|e| format!("{e:e}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn pairs_text(v: &[(String, String)]) -> String {
    v.iter()
        .map(|(a, b)| format!("{a}-{b}"))
        .collect::<Vec<_>>()
        .join(",")
}

fn run_pair(na: &str, nb: &str, args: &Settings) -> Result<PairResult, Box<dyn std::error::Error>> {
    let pair_started = Instant::now();
    let pair = format!("{na}-{nb}");
    let (pa, pb) = (Arc::new(profile(na)?), Arc::new(profile(nb)?));
    let same = na == nb;
    let size = diagonal(&pa) + diagonal(&pb);

    let pb_bar = bar(args.poses as u64, &format!("poses {pair}"));
    let poses = close_poses(
        &pa,
        &pb,
        args.poses,
        CLOSE_GAPS,
        pair_seed(args.seed, &pair),
        || pb_bar.inc(1),
    )?;
    pb_bar.finish_and_clear();

    // revdist levels (every eps of either list).
    let mut rev_eps: Vec<f64> = args
        .rev_eps
        .iter()
        .chain(&args.refine_eps)
        .copied()
        .collect();
    rev_eps.sort_by(|x, y| y.total_cmp(x));
    rev_eps.dedup();
    let rev: Vec<RevLevel> = rev_eps
        .iter()
        .map(|&e| rev_level(&pa, &pb, same, e))
        .collect::<Result<_, _>>()?;

    // FCL levels, coarse to fine, until the predicted triangle count exceeds the cap.
    let mut fcl: Vec<FclLevel> = Vec::new();
    let mut skipped = Vec::new();
    let build_bar = bar(args.fcl_eps.len() as u64, &format!("meshes {pair}"));
    for &eps in &args.fcl_eps {
        if let Some(prev) = fcl.last() {
            let tris = prev
                .layouts
                .iter()
                .map(LayoutPair::triangles)
                .max()
                .unwrap_or(0);
            let predicted = tris as f64 * prev.eps / eps;
            if predicted > args.max_triangles as f64 {
                skipped.push(format!(
                    "{pair}: FCL at eps {eps:.0e} and finer not run: predicted {:.1}M triangles \
                     ({tris} at eps {:.0e} times {:.0}) exceed the cap of {:.1}M",
                    predicted / 1e6,
                    prev.eps,
                    prev.eps / eps,
                    args.max_triangles as f64 / 1e6
                ));
                break;
            }
        }
        fcl.push(FclLevel::build(&pa, &pb, same, eps)?);
        build_bar.inc(1);
    }
    build_bar.finish_and_clear();
    for s in &skipped {
        eprintln!("{s}");
    }

    // The timed slots.
    let mut slots = Vec::new();
    for (k, lv) in rev.iter().enumerate() {
        let modes: &[Method] = match (
            args.rev_eps.contains(&lv.eps),
            args.refine_eps.contains(&lv.eps),
        ) {
            (true, true) => &[Method::Rev, Method::RevTol0, Method::RevRefined],
            (true, false) => &[Method::Rev, Method::RevTol0],
            (false, true) => &[Method::RevRefined],
            (false, false) => &[],
        };
        for &method in modes {
            slots.push(Slot {
                method,
                level: k,
                layout: 0,
            });
        }
    }
    for (k, lv) in fcl.iter().enumerate() {
        for layout in 0..lv.layouts.len() {
            for method in [Method::FclObbrss, Method::FclRss] {
                slots.push(Slot {
                    method,
                    level: k,
                    layout,
                });
            }
        }
    }
    let mut samples = vec![Samples::default(); slots.len()];
    let id = Isometry3::identity();
    let time_bar = bar(poses.len() as u64, &format!("timing {pair}"));
    for (i, pose) in poses.iter().enumerate() {
        let posed: Vec<Solid> = rev.iter().map(|lv| lv.b.with_pose(*pose)).collect();
        let mut rev_answers: Vec<(usize, Distance)> = Vec::new();
        let mut fcl_answers: Vec<(usize, f64, f64)> = Vec::new();
        for j in 0..slots.len() {
            let s_idx = (j + i) % slots.len();
            let s = slots[s_idx];
            if s.method.is_fcl() {
                let lp = &fcl[s.level].layouts[s.layout];
                let (ma, mb) = (bvh(&lp.a, s.method), bvh(lp.b(), s.method));
                let t = Instant::now();
                let f = ma.distance(mb, &id, pose)?;
                samples[s_idx].times.push(us(t.elapsed()));
                fcl_answers.push((s_idx, f.distance, lp.h_sum()));
            } else {
                let opts = s.method.options();
                let t = Instant::now();
                let d = distance(&rev[s.level].a, &posed[s.level], &opts);
                samples[s_idx].times.push(us(t.elapsed()));
                samples[s_idx].widths.push(d.upper - d.lower);
                samples[s_idx].node_pairs += d.stats.node_pairs;
                samples[s_idx].zero_lower += usize::from(d.lower <= 0.0);
                rev_answers.push((s_idx, d));
            }
        }
        for (r, d) in &rev_answers {
            for &(f, fd, h) in &fcl_answers {
                let ok = agrees_with_fcl(d, fd, h, pose, size);
                for k in [*r, f] {
                    samples[k].checks += 1;
                    samples[k].violations += usize::from(!ok);
                }
            }
        }
        time_bar.inc(1);
    }
    time_bar.finish_and_clear();

    let mut rows = Vec::new();
    for (s, smp) in slots
        .iter()
        .zip(&samples)
        .filter(|(s, _)| !s.method.is_fcl())
    {
        let lv = &rev[s.level];
        rows.push(Row {
            method: s.method,
            pair: pair.clone(),
            eps: lv.eps,
            poses: smp.times.len(),
            width_max: smp.widths.iter().copied().fold(0.0, f64::max),
            width_median: median(&smp.widths),
            median_us: median(&smp.times),
            p90_us: quantile(&smp.times, 0.9),
            build_ms: lv.build_ms,
            bytes: lv.bytes,
            node_pairs: Some(smp.node_pairs as f64 / smp.times.len().max(1) as f64),
            zero_lower: Some(smp.zero_lower),
            triangles: None,
            layout: None,
            checks: smp.checks,
            violations: smp.violations,
        });
    }
    for (k, lv) in fcl.iter().enumerate() {
        for method in [Method::FclObbrss, Method::FclRss] {
            // The faster layout for this hierarchy.
            let (idx, best) = slots
                .iter()
                .enumerate()
                .filter(|(_, s)| s.method == method && s.level == k)
                .min_by(|x, y| median(&samples[x.0].times).total_cmp(&median(&samples[y.0].times)))
                .expect("a layout per level");
            let lp = &lv.layouts[best.layout];
            let smp = &samples[idx];
            let h = lp.h_sum();
            let build_ms =
                lp.sum(|x| (x.mesh_time + bvh(x, method).build_time()).as_secs_f64() * 1e3);
            let bytes = lp.sum(|x| bvh(x, method).bytes() as f64) as usize;
            rows.push(Row {
                method,
                pair: pair.clone(),
                eps: lv.eps,
                poses: smp.times.len(),
                width_max: h,
                width_median: h,
                median_us: median(&smp.times),
                p90_us: quantile(&smp.times, 0.9),
                build_ms,
                bytes,
                node_pairs: None,
                zero_lower: None,
                triangles: Some(lp.triangles()),
                layout: Some(lp.name),
                checks: smp.checks,
                violations: smp.violations,
            });
        }
    }
    rows.sort_by(|x, y| {
        let m = |r: &Row| METHODS.iter().position(|&m| m == r.method);
        m(x).cmp(&m(y)).then(y.eps.total_cmp(&x.eps))
    });
    if let Some(r) = rows.iter().find(|r| r.method == Method::Rev) {
        eprintln!(
            "{pair}: {} poses, {} revdist and {} FCL configurations [{:.0} s]",
            r.poses,
            slots.iter().filter(|s| !s.method.is_fcl()).count(),
            slots.iter().filter(|s| s.method.is_fcl()).count(),
            pair_started.elapsed().as_secs_f64()
        );
    }
    Ok(PairResult { rows, skipped })
}

/// The columns of `pareto.csv` and of the per-pair tables in `pareto.md`.
fn cost_table() -> Table<'static, Row> {
    let or_dash = |v: Option<String>| v.unwrap_or_else(|| "-".into());
    Table::new()
        .csv("method", |r: &Row| r.method.key().to_owned())
        .with_markdown("method", |r| r.method.label().to_owned())
        .csv("pair", |r| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("poses", |r| r.poses.to_string())
        .csv("width_max", |r| format!("{:.4e}", r.width_max))
        .csv("width_median", |r| format!("{:.4e}", r.width_median))
        .markdown("certified error: max / median", |r| {
            format!("{:.2e} / {:.2e}", r.width_max, r.width_median)
        })
        .right()
        .csv("query_median_us", |r| format!("{:.2}", r.median_us))
        .csv("query_p90_us", |r| format!("{:.2}", r.p90_us))
        .markdown("query median / p90 (us)", |r| {
            format!("{:.1} / {:.1}", r.median_us, r.p90_us)
        })
        .right()
        .markdown("node pairs / query", move |r| {
            or_dash(r.node_pairs.map(|n| format!("{n:.0}")))
        })
        .right()
        .markdown("lower = 0", move |r| {
            or_dash(r.zero_lower.map(|n| n.to_string()))
        })
        .right()
        .csv("build_ms", |r| format!("{:.4}", r.build_ms))
        .with_markdown("build (ms)", |r| format!("{:.3}", r.build_ms))
        .right()
        .csv("bytes", |r| r.bytes.to_string())
        .with_markdown("memory", |r| human_bytes(r.bytes as f64))
        .right()
        .csv("mean_node_pairs", |r| {
            r.node_pairs.map_or(String::new(), |n| format!("{n:.1}"))
        })
        .csv("zero_lower", |r| {
            r.zero_lower.map_or(String::new(), |n| n.to_string())
        })
        .csv("triangles", |r| {
            r.triangles.map_or(String::new(), |t| t.to_string())
        })
        .markdown("triangles (layout)", move |r| {
            or_dash(
                r.triangles
                    .map(|t| format!("{t} ({})", r.layout.unwrap_or(""))),
            )
        })
        .right()
        .csv("layout", |r| r.layout.unwrap_or("").to_owned())
        .csv("checks", |r| r.checks.to_string())
        .csv("violations", |r| r.violations.to_string())
        .markdown("violations / checks", |r| {
            format!("{} / {}", r.violations, r.checks)
        })
        .right()
}

/// The row of `method` on `pair` at `eps`.
fn find<'a>(rows: &'a [Row], method: Method, pair: &str, eps: f64) -> Option<&'a Row> {
    rows.iter()
        .find(|r| r.method == method && r.pair == pair && r.eps == eps)
}

/// `run`: wall time (s) and the load averages at start / end.
fn markdown(
    rows: &[Row],
    skipped: &[String],
    args: &Settings,
    prov: &Provenance,
    (wall, load): (f64, &str),
) -> String {
    let mut s =
        String::from("# What accuracy costs: revdist and FCL on the accuracy/cost plane\n\n");
    let _ = writeln!(
        s,
        "Per model pair, {} seeded poses near contact (gaps log-uniform in [{:e}, {:e}], the \
         poses of `fcl_bench`), the same poses for every method and accuracy, timed one query \
         at a time on one thread with the methods interleaved per pose (wall time {wall:.0} s; \
         1-minute load average at start / end {load} on {} cores: above ~1, other processes \
         shared the cores and absolute times are noisier, ratios less so).\n",
        args.poses,
        CLOSE_GAPS.0,
        CLOSE_GAPS.1,
        prov.get("threads_available").unwrap_or("?")
    );
    s.push_str(
        "**Certified error bound** (x axis of the figures, model length units): for revdist the \
         width `upper - lower` of the certified interval it returns (worst over the poses in the \
         figures; median beside it here); for FCL `h_a + h_b`, the meshes' certified Hausdorff \
         bounds, since the truth lies in `d_FCL ± (h_a + h_b)`. revdist at its default \
         tolerance stops once the width is at most `eps_a + eps_b`; at tolerance 0 it narrows \
         as far as its trees allow; refined polishes the witnesses on the exact surfaces, which \
         lowers the upper bound. FCL runs `BVHModel<OBBRSS>` and `<RSS>` on certified meshes \
         (the faster of two layouts per row). Build: revdist's trees (median of a few builds) \
         against tessellation + BVH build (one build). Memory: revdist's query-tree arrays \
         against FCL's node, triangle and vertex arrays. One structure when A = B. \
         Violations: revdist answers whose interval misses an FCL interval of the same pose \
         (each revdist answer against every FCL answer).\n\n",
    );
    s.push_str(
        "![query time](pareto_time.svg)\n\n![build time](pareto_build.svg)\n\n\
         ![memory](pareto_memory.svg)\n\n\
         Points stacked at the left edge (a few 1e-10) sit at the rounding floor of revdist's \
         bounds: where every leaf pair is resolved exactly (the torus is one exact circle, the \
         table and lightmill are mostly exact lines and arcs), a finer eps buys no more \
         accuracy and only costs time. revdist's three modes share one tree per eps, so in the \
         build and memory figures they differ only in x.\n\n",
    );
    s.push_str("## What the curves show\n\n");
    s.push_str(&summary(rows, args));
    if !skipped.is_empty() {
        s.push_str("\nNot run (triangle count ~ eps^-1):\n\n");
        for k in skipped {
            let _ = writeln!(s, "- {k}");
        }
    }
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let table = cost_table();
    for pair in &pairs {
        let _ = writeln!(s, "\n## {pair}\n");
        s.push_str(&table.markdown_text(rows.iter().filter(|r| &r.pair == pair)));
    }
    s.push_str(&prov.markdown_footer());
    s
}

/// Cross-checks of revdist answers against FCL answers, and how many failed, over all rows.
fn cross_checks(rows: &[Row]) -> (usize, usize) {
    rows.iter()
        .filter(|r| !r.method.is_fcl())
        .fold((0, 0), |(c, v), r| (c + r.checks, v + r.violations))
}

/// Sentences on what the data show, computed from the rows (so they stay true when rerun).
fn summary(rows: &[Row], args: &Settings) -> String {
    let mut s = String::new();
    let (checks, violations) = cross_checks(rows);
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let of = |m: Method, pair: &str| -> Vec<&Row> {
        rows.iter()
            .filter(|r| r.method == m && r.pair == pair)
            .collect()
    };

    // Query time at equal eps: FCL OBBRSS median / revdist median (default tolerance).
    let (mut ahead, mut behind, mut trend) = (Vec::new(), Vec::new(), Vec::new());
    for pair in &pairs {
        let ratios: Vec<(f64, f64)> = of(Method::FclObbrss, pair)
            .iter()
            .filter_map(|f| {
                find(rows, Method::Rev, pair, f.eps).map(|r| (f.eps, f.median_us / r.median_us))
            })
            .collect();
        for &(eps, ratio) in &ratios {
            let txt = format!("{pair} at eps {eps:.0e} ({ratio:.2}x)");
            if ratio < 1.0 {
                behind.push(txt);
            } else {
                ahead.push(txt);
            }
        }
        if let (Some(first), Some(last)) = (ratios.first(), ratios.last()) {
            if ratios.len() > 1 {
                trend.push(format!(
                    "{pair} {:.2}x at {:.0e} to {:.2}x at {:.0e}",
                    first.1, first.0, last.1, last.0
                ));
            }
        }
    }
    let list = |v: &[String]| {
        if v.is_empty() {
            "none".to_string()
        } else {
            v.join(", ")
        }
    };
    let _ = writeln!(
        s,
        "- **Query time at equal eps** (FCL OBBRSS median / revdist median at its default \
         tolerance, the same poses): revdist is faster on {}; **revdist is behind** on {}. \
         From the coarsest to the finest eps FCL ran at, the ratio goes {}: FCL's time grows with \
         its mesh, revdist's slowly with eps.",
        list(&ahead),
        list(&behind),
        list(&trend)
    );

    // Coarse eps: the default tolerance slower than tolerance 0.
    let mut slow = Vec::new();
    for pair in &pairs {
        for r in of(Method::Rev, pair) {
            if let Some(t0) = find(rows, Method::RevTol0, pair, r.eps) {
                if r.median_us > 1.5 * t0.median_us && r.zero_lower.unwrap_or(0) > 0 {
                    slow.push(format!(
                        "{pair} at eps {:.0e}: {:.0} us against {:.0} us, lower bound 0 in {} of \
                         {} answers",
                        r.eps,
                        r.median_us,
                        t0.median_us,
                        r.zero_lower.unwrap_or(0),
                        r.poses
                    ));
                }
            }
        }
    }
    if !slow.is_empty() {
        let _ = writeln!(
            s,
            "- **Coarse trees are slow at the default tolerance**: {}. An interval up to \
             eps_a + eps_b wide reaches 0 for the closest poses, and the query then spends its \
             time on deciding whether the solids overlap (fewer node pairs than at tolerance 0, \
             yet slower); tolerance 0 narrows the interval first and is faster there.",
            slow.join("; ")
        );
    }

    // Structure cost against accuracy: fitted exponents over the three finest eps of each
    // method (where the leaves, not the pieces of the profile, set the size).
    let exponent = |m: Method, pair: &str, y: &dyn Fn(&Row) -> f64| -> String {
        let mut pts: Vec<(f64, f64)> = of(m, pair).iter().map(|r| (r.eps, y(r))).collect();
        pts.sort_by(|a, b| a.0.total_cmp(&b.0));
        pts.truncate(3);
        // An exponent that rounds to 0 is shown as 0.00, not -0.00.
        log_log_slope(&pts).map_or("-".to_string(), |e| {
            format!("{:.2}", if e.abs() < 0.005 { 0.0 } else { -e })
        })
    };
    let fits: Vec<String> = pairs
        .iter()
        .map(|p| {
            let bytes = |r: &Row| r.bytes as f64;
            let build = |r: &Row| r.build_ms;
            format!(
                "{p} {} / {} (memory), {} / {} (build)",
                exponent(Method::FclObbrss, p, &bytes),
                exponent(Method::Rev, p, &bytes),
                exponent(Method::FclObbrss, p, &build),
                exponent(Method::Rev, p, &build)
            )
        })
        .collect();
    let finest = |f: &dyn Fn(&Row) -> bool| {
        rows.iter()
            .filter(|r| f(r))
            .map(|r| r.width_max)
            .fold(f64::MAX, f64::min)
    };
    let _ = writeln!(
        s,
        "- **Structure cost**: memory and build time grow as eps^-k, k fitted over each \
         method's three finest eps (FCL OBBRSS / revdist): {}. A mesh of error eps needs \
         ~eps^-1 triangles, a biarc tree ~eps^-1/3 leaves (cubic convergence), and none more \
         where the profile is exact lines and arcs (the torus is one circle). revdist's \
         certified width reaches {:.1e} (the rounding floor of its bounds), FCL's mesh bound \
         {:.1e}, where the next mesh would exceed the triangle cap.",
        fits.join("; "),
        finest(&|r| !r.method.is_fcl()),
        finest(&|r| r.method.is_fcl()),
    );

    // Refinement: its cost and what it narrows.
    let mut refine = Vec::new();
    for pair in &pairs {
        for r in of(Method::RevRefined, pair) {
            if let Some(d) = find(rows, Method::Rev, pair, r.eps) {
                refine.push(format!(
                    "{pair} at {:.0e}: +{:.0} us, width max {:.1e} to {:.1e}, median {:.1e} to \
                     {:.1e}",
                    r.eps,
                    r.median_us - d.median_us,
                    d.width_max,
                    r.width_max,
                    d.width_median,
                    r.width_median
                ));
            }
        }
    }
    if !refine.is_empty() {
        let _ = writeln!(
            s,
            "- **Refined** answers move the upper bound onto the exact surfaces (the lower bound \
             stays the trees'), against the default tolerance: {}.",
            refine.join("; ")
        );
    }
    let _ = writeln!(
        s,
        "- **Cross-check**: every revdist answer against every FCL answer of its pose: \
         {violations} violations in {checks} checks."
    );
    s
}

fn figures(out: &Path, rows: &[Row], args: &Settings) -> Result<(), Box<dyn std::error::Error>> {
    let pairs: Vec<String> = args.pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let panels = |y: &dyn Fn(&Row) -> f64| -> Vec<Panel> {
        pairs
            .iter()
            .map(|pair| Panel {
                title: pair.clone(),
                curves: METHODS
                    .iter()
                    .enumerate()
                    .map(|(k, &m)| Curve {
                        name: m.label().to_string(),
                        style: k,
                        dashed: m.is_fcl(),
                        points: rows
                            .iter()
                            .filter(|r| r.method == m && &r.pair == pair)
                            .map(|r| (r.width_max, y(r)))
                            .collect(),
                    })
                    .collect(),
            })
            .collect()
    };
    let x_desc = "certified error bound: interval width (model length units)";
    let size = (430, 430);
    log_log_panels(
        &out.join("pareto_time.svg"),
        &format!("What accuracy costs: median query time over {} poses near contact (lower left is better)", args.poses),
        &panels(&|r| r.median_us),
        x_desc,
        "median query time (us)",
        size,
    )?;
    log_log_panels(
        &out.join("pareto_build.svg"),
        "What accuracy costs: build time (revdist trees; FCL tessellation + BVH)",
        &panels(&|r| r.build_ms),
        x_desc,
        "build time (ms)",
        size,
    )?;
    log_log_panels(
        &out.join("pareto_memory.svg"),
        "What accuracy costs: memory (revdist query trees; FCL BVH, triangles, vertices)",
        &panels(&|r| r.bytes as f64),
        x_desc,
        "memory (bytes)",
        size,
    )?;
    Ok(())
}
