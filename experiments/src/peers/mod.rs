//! revdist beside its peers in one run, the `peers` driver (`docs/verification.md`, "Peers"):
//! FCL 0.7 (`BVHModel<OBBRSS>` and `<RSS>`, `crate::baseline_mesh`), coal 3 (`BVHModel<OBBRSS>`
//! and its exact primitives with GJK, in a process of its own: [`coal`]) and parry3d 0.31
//! (`TriMesh` and its exact primitives: [`parry`]); [`convex`] gives the convex solids of
//! revolution as the exact primitives both know.
//!
//! * Mesh table: per model pair and eps, on the same seeded poses near contact as `fcl_bench`
//!   (gaps log-uniform in [1e-3, 1e-1]), revdist at its default tolerance (interval width <=
//!   eps_a + eps_b) against each peer on the same certified mesh (`revdist::tessellate`, balanced
//!   layout, two-sided Hausdorff bound <= eps; `fcl_bench` also times FCL on a capped layout and
//!   in cold and warm modes): median query time, build time, memory, and the ratio of the
//!   fastest peer of the row over revdist. parry3d's TriMesh-TriMesh distance is one-sided
//!   (best-first over mesh 1's BVH against mesh 2's whole AABB, then one BVH query into mesh 2
//!   per leaf triangle) and slow on big meshes, so it runs on the first `--parry-poses` poses
//!   of each row only (the table says how many).
//! * Convex table: the convex solids of revolution (sphere, capsule, cylinder, cone; every
//!   unordered pair) with revdist's default options and its convex path (`QueryOptions {
//!   convex_path: true, .. }`) beside coal's and parry3d's exact primitives (GJK), on the
//!   same poses.
//!
//! All methods run *blocked* (each alone over the poses of a row, the usual benchmark loop),
//! one query at a time on one thread; coal times each query inside its own process. Every
//! answer is cross-checked against revdist's certified interval: a mesh distance must lie in
//! it widened by the meshes' Hausdorff bounds h_a + h_b, coal's exact primitives within it
//! widened by coal's GJK error bound (`COAL_GJK_TOLERANCE`); parry3d's exact primitives, which
//! state no tolerance, are reported with their largest excess (`PARRY_GROSS_EXCESS` fails).
//! A violation fails the run (exit status 1, after writing the outputs).
//!
//! Without coal (scripts/deps.sh installs it) coal's columns say so and the rest runs.

pub mod coal;
pub mod convex;
mod convex_row;
mod figure;
mod mesh_row;
pub mod parry;
mod report;
mod rows;

use crate::args::{model_pairs, positive_count};
use crate::baseline_mesh::agrees_with_fcl;
use crate::cli::Common;
use crate::driver::{check_violations, DriverResult};
use crate::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use crate::shapes::profile;
use clap::Parser;
use coal::CoalPeer;
use convex::CONVEX_MODELS;
use convex_row::convex_row;
use figure::figure;
use mesh_row::mesh_row;
use nalgebra::Isometry3;
use report::{convex_csv, markdown, mesh_csv};
use revdist::profile::Profile;
use revdist::query::Distance;
use rows::Row;
use std::collections::hash_map::{Entry, HashMap};
use std::sync::Arc;
use std::time::Instant;

/// The mesh pairs: `fcl_bench`'s default list (the exact models, the freeform family, M_t
/// frames).
const DEFAULT_PAIRS: &str = "torus-torus,pawn-pawn,pawn-cup,cup-bottle,table-lightmill,\
                             pawn_ff-pawn_ff,pawn_ff-cup_ff,cup_ff-bottle_ff,\
                             table_ff-lightmill_ff,morph@0.3-pawn,morph@0.7-cup";
/// The eps of a default run (1e-5 meshes take seconds per pair to build and parry3d's
/// queries on them take seconds; `--eps` or `--paper` adds it).
const DEFAULT_EPS: [f64; 2] = [1e-3, 1e-4];
/// The eps of a `--paper` run.
const PAPER_EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];
/// Poses per mesh row and per convex pair (default run; `--paper`: [`PAPER_POSES`]).
const DEFAULT_POSES: usize = 40;
const PAPER_POSES: usize = 1000;
/// parry3d's poses per mesh row (the first of the row's poses): its one-sided TriMesh
/// traversal takes 6 ms at 2k triangles and 340 ms at 33k (shared/notes/peers.md), so this
/// cap keeps the main job's step near a minute. `--parry-poses` changes it.
const DEFAULT_PARRY_POSES: usize = 8;
/// parry3d's time budget per mesh row in a default run, seconds: it stops after the pose
/// that exceeds it (at least one pose; at 110k triangles one query takes seconds). Chosen so
/// that parry3d's share of the main job's step stays under a minute over 22 rows.
const PARRY_ROW_BUDGET_S: f64 = 2.0;
/// Poses per convex pair of a default run.
const CONVEX_POSES: usize = 100;
/// revdist's eps for the convex solids (lines and circular arcs are exact biarcs, so the
/// trees stay small; the interval is then as narrow as the peers' GJK tolerance).
const CONVEX_EPS: f64 = 1e-6;
/// coal's GJK tolerance `tol` (`GJK_DEFAULT_TOLERANCE` = 1e-6,
/// coal/narrowphase/narrowphase_defaults.h; the program reports it and the run checks it).
/// coal's default convergence test stops when `||x^k|| - ||x*|| <= tol + tol ||x^k||` (GJK
/// of coal 3, `checkConvergence`, criterion Default), `||x^k||` being the distance between the
/// primitives' cores (spheres and capsules are swept), so an exact-primitive answer may exceed
/// the true distance by `tol (1 + d + swept radii)`: the widening of revdist's interval in
/// the cross-check of coal's exact primitives.
const COAL_GJK_TOLERANCE: f64 = 1e-6;
/// parry3d states no distance tolerance for its exact primitives. Its answers are reported
/// with their largest excess over revdist's certified interval; an excess above this (1e-4,
/// a hundred times coal's stated GJK error at unit scale) would mean a wrong placement or
/// shape rather than GJK convergence, and fails the run.
const PARRY_GROSS_EXCESS: f64 = 1e-4;

/// revdist beside FCL, coal and parry3d in one run: mesh table per pair and eps, and the
/// convex solids against the peers' exact primitives. Writes peers.csv, peers_convex.csv,
/// peers.md and peers.svg.
#[derive(Parser)]
pub struct Args {
    #[command(flatten)]
    common: Common,
    /// parry3d's poses per mesh row, the first of the row's [default: 8; --paper: all]
    #[arg(long = "parry-poses", value_name = "N", value_parser = positive_count)]
    parry_poses: Option<usize>,
    #[command(flatten)]
    shard: crate::shard::Flags,
}

/// A pair's profiles and its poses.
type PlacedPair = (Arc<Profile>, Arc<Profile>, Vec<Isometry3<f64>>);

/// What the rows and the figure return.
type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// The driver's body: the mesh and convex tables (or this shard's rows of them, or the merge
/// of shards' rows), their outputs, and failure on any cross-check violation.
pub fn run(args: Args) -> DriverResult {
    let c = &args.common;
    let poses = c.poses.or(c.paper.pick(DEFAULT_POSES, PAPER_POSES));
    let parry_poses = args
        .parry_poses
        .unwrap_or(c.paper.pick(DEFAULT_PARRY_POSES, PAPER_POSES))
        .min(poses);
    // No time budget for parry3d at paper scale or when its pose count is given.
    let parry_budget = (!c.paper.on && args.parry_poses.is_none()).then_some(PARRY_ROW_BUDGET_S);
    let eps_list = c.eps.or(c.paper.pick(&DEFAULT_EPS[..], &PAPER_EPS[..]));
    let pairs = c.pairs.or(&model_pairs(DEFAULT_PAIRS));
    let seed = c.seed.or(CLOSE_SEED);
    let started = Instant::now();
    let mut coal = CoalPeer::start().map_err(|e| e.to_string());
    if let Ok(peer) = &coal {
        if peer.gjk_tolerance != COAL_GJK_TOLERANCE {
            return Err(format!(
                "coal reports GJK tolerance {:e}, the cross-check assumes {COAL_GJK_TOLERANCE:e}",
                peer.gjk_tolerance
            )
            .into());
        }
    }
    let coal_version = match &coal {
        Ok(p) => p.version.clone(),
        Err(e) => e.clone(),
    };
    if let Err(e) = &coal {
        eprintln!("peers: {e}");
    }
    let convex_poses = c.poses.or(c.paper.pick(CONVEX_POSES, PAPER_POSES));
    let settings = vec![
        ("poses", poses.to_string()),
        ("parry_poses", parry_poses.to_string()),
        (
            "parry_row_budget_s",
            parry_budget.map_or("none".into(), |b| b.to_string()),
        ),
        ("convex_poses", convex_poses.to_string()),
        ("eps", format!("{eps_list:?}")),
        ("convex_eps", format!("{CONVEX_EPS:e}")),
        ("pairs", crate::args::pair_list(&pairs)),
        ("coal", coal_version.clone()),
        ("parry3d", "parry3d-f64 0.31".into()),
        ("seed", format!("{seed:#x}")),
    ];
    // The work units of `--shard`: the mesh table's rows (pair x eps, a pair's poses placed
    // once per shard and reused at every eps), and the convex table's rows, split alike.
    let units: Vec<(usize, f64)> = (0..pairs.len())
        .flat_map(|p| eps_list.iter().map(move |&e| (p, e)))
        .collect();
    let mut placed: HashMap<usize, PlacedPair> = HashMap::new();
    let rows = args.shard.run(
        (&c.out.dir, "peers"),
        &settings,
        units.len(),
        |u| -> Res<Row> {
            let (k, eps) = units[u];
            let (na, nb) = &pairs[k];
            let pair = format!("{na}-{nb}");
            if let Entry::Vacant(slot) = placed.entry(k) {
                let (pa, pb) = (Arc::new(profile(na)?), Arc::new(profile(nb)?));
                let p = close_poses(&pa, &pb, poses, CLOSE_GAPS, pair_seed(seed, &pair), || {})?;
                slot.insert((pa, pb, p));
            }
            let (pa, pb, p) = &placed[&k];
            let row = mesh_row(
                &pair,
                (pa, pb),
                eps,
                p,
                (parry_poses, parry_budget),
                &mut coal,
            )?;
            let (name, t) = row.fastest();
            eprintln!(
                "{pair} eps {eps:.0e}: revdist {:.1} us, fastest peer {name} {t:.1} us, ratio \
                 {:.2} [{:.0} s]",
                row.rev.us,
                row.ratio(),
                started.elapsed().as_secs_f64()
            );
            Ok(row)
        },
    )?;
    let convex_pairs: Vec<(&str, &str)> = CONVEX_MODELS
        .iter()
        .enumerate()
        .flat_map(|(i, a)| CONVEX_MODELS[i..].iter().map(move |b| (*a, *b)))
        .collect();
    let convex = args.shard.run(
        (&c.out.dir, "peers_convex"),
        &settings,
        convex_pairs.len(),
        |u| {
            let (a, b) = convex_pairs[u];
            convex_row(a, b, convex_poses, seed, &mut coal)
        },
    )?;
    let (Some(rows), Some(convex)) = (rows, convex) else {
        return Ok(()); // a shard: its raw rows are written
    };
    let prov = crate::provenance::Provenance::collect(
        "peers (revdist vs FCL, coal, parry3d in one run)",
        &settings
            .iter()
            .cloned()
            .chain(args.shard.provenance())
            .collect::<Vec<_>>(),
    );
    let out = &c.out.dir;
    std::fs::write(
        out.join("peers.csv"),
        prov.csv_preamble() + &mesh_csv().csv_text(&rows),
    )?;
    std::fs::write(
        out.join("peers_convex.csv"),
        prov.csv_preamble() + &convex_csv().csv_text(&convex),
    )?;
    let md = markdown(&rows, &convex, (parry_poses, parry_budget), &coal_version)
        + &prov.markdown_footer();
    std::fs::write(out.join("peers.md"), &md)?;
    figure(&out.join("peers.svg"), &rows)?;
    print!("{md}");
    let violations: usize = rows.iter().map(|r| r.violations).sum::<usize>()
        + convex.iter().map(|r| r.violations).sum::<usize>();
    check_violations(
        violations,
        "(a peer's distance outside revdist's widened interval; see peers.md)",
    )
}

/// A peer's distance against revdist's certified interval widened by `slack` (mesh bounds or
/// GJK tolerance) and the rounding slack of the configuration.
fn agrees(d: &Distance, peer: f64, slack: f64, pose: &Isometry3<f64>, size: f64) -> bool {
    agrees_with_fcl(d, peer, slack, pose, size)
}
