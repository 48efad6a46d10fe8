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

mod figures;
mod levels;
mod measure;
mod method;
mod report;
mod row;
mod summary;

use crate::args::{accuracy, model_pairs, positive_count, ModelPair};
use crate::cli::{given_or, Common};
use crate::driver::{self, DriverResult};
use crate::poses::{CLOSE_GAPS, CLOSE_SEED};
use crate::provenance::Provenance;
use crate::shapes::profile;
use clap::Parser;
use figures::figures;
use measure::run_pair;
use report::{cost_table, markdown};
use row::{cross_checks, RawRow, Row};
use std::fmt::Write as _;
use std::time::Instant;

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

/// What accuracy costs: on the same seeded poses near contact, per model pair, query time,
/// build time and memory against the certified error bound, for revdist at eps 1e-2 .. 1e-8
/// (default tolerance, tolerance 0, and refined) and for FCL 0.7 OBBRSS and RSS on certified
/// meshes at eps 1e-2 .. 1e-6 (up to a cap on the predicted triangle count); every revdist
/// answer is cross-checked against every FCL answer of the same pose. Writes pareto.csv,
/// pareto.md and pareto_{time,build,memory}.svg (200 poses per pair; 1,000 with --paper).
#[derive(Parser)]
pub struct Args {
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
    shard: crate::shard::Flags,
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

/// The driver's body: measures every pair (or this shard's pairs, or merges shards' rows),
/// writes the outputs and fails on any cross-check violation.
pub fn run(cli: Args) -> DriverResult {
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
