//! revdist beside its peers in one run (`docs/verification.md`, "Peers"): FCL 0.7 (`BVHModel<OBBRSS>` and `<RSS>`),
//! coal 3 (`BVHModel<OBBRSS>` and its exact primitives with GJK, in a process of its own:
//! `experiments::peers::coal`) and parry3d 0.31 (`TriMesh` and its exact primitives:
//! `experiments::peers::parry`).
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
//! widened by coal's GJK error bound ([`COAL_GJK_TOLERANCE`]); parry3d's exact primitives, which
//! state no tolerance, are reported with their largest excess ([`PARRY_GROSS_EXCESS`] fails).
//! A violation fails the run (exit status 1, after writing the outputs).
//!
//! Without coal (scripts/deps.sh installs it) coal's columns say so and the rest runs.
//!
//! Usage: `peers [--poses N] [--parry-poses N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--seed S] [--out DIR]`. Writes `DIR/peers.csv`, `DIR/peers_convex.csv`, `DIR/peers.md` and
//! `DIR/peers.svg` (default `figures`).

use clap::Parser;
use experiments::args::{model_pairs, positive_count};
use experiments::baseline_mesh::{agrees_with_fcl, certified_mesh};
use experiments::cli::Common;
use experiments::driver::{self, check_violations, DriverResult};
use experiments::peers::coal::CoalPeer;
use experiments::peers::convex::{primitive, CONVEX_MODELS};
use experiments::peers::parry::{self, ParryShape};
use experiments::plot::{grouped_bars, BarSeries};
use experiments::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use experiments::shapes::{diagonal, profile, query_tree_bytes, timed_pair};
use experiments::shard::{Field, Scalar};
use experiments::stats::{human_bytes, median, time_each, us};
use experiments::table::Table;
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::{distance, Distance, QueryOptions};
use revdist::solid::Solid;
use std::collections::hash_map::{Entry, HashMap};
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::{Bv, FclMesh};
use verify::baselines::TriMesh;

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
struct Args {
    #[command(flatten)]
    common: Common,
    /// parry3d's poses per mesh row, the first of the row's [default: 8; --paper: all]
    #[arg(long = "parry-poses", value_name = "N", value_parser = positive_count)]
    parry_poses: Option<usize>,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// A pair's profiles and its poses.
type PlacedPair = (Arc<Profile>, Arc<Profile>, Vec<Isometry3<f64>>);

/// One method's numbers in a row: median query time, build time, memory.
#[derive(Clone, Copy, Default)]
struct Timed {
    us: f64,
    build_ms: f64,
    bytes: usize,
}

/// One row of the mesh table.
struct Row {
    pair: String,
    eps: f64,
    poses: usize,
    parry_poses: usize,
    tris: usize,
    h_sum: f64,
    rev: Timed,
    fcl_obbrss: Timed,
    fcl_rss: Timed,
    /// coal `BVHModel<OBBRSS>`, or why it did not run.
    coal: Result<Timed, String>,
    parry: Timed,
    /// Hook for OpenCASCADE's median time per query on the true surfaces (the peers-occt work,
    /// `verify/src/baselines/occt*`): `None` until it is wired in; counted among the peers of
    /// [`Row::fastest`] when present.
    occt_us: Option<f64>,
    max_width: f64,
    violations: usize,
}

/// A [`Timed`] in a raw row: `us/build_ms/bytes`.
impl Field for Timed {
    fn text(&self) -> String {
        format!(
            "{}/{}/{}",
            self.us.text(),
            self.build_ms.text(),
            self.bytes.text()
        )
    }
    fn parse(cell: &str) -> Result<Self, String> {
        let parts: Vec<&str> = cell.split('/').collect();
        match parts[..] {
            [us, build_ms, bytes] => Ok(Timed {
                us: Field::parse(us)?,
                build_ms: Field::parse(build_ms)?,
                bytes: Field::parse(bytes)?,
            }),
            _ => Err(format!("'{cell}' is not us/build_ms/bytes")),
        }
    }
}
impl Scalar for Timed {}

experiments::shard_record!(Row {
    pair,
    eps,
    poses,
    parry_poses,
    tris,
    h_sum,
    rev,
    fcl_obbrss,
    fcl_rss,
    coal,
    parry,
    occt_us,
    max_width,
    violations,
});

impl Row {
    /// The peers' median times by name (those that ran).
    fn peers(&self) -> Vec<(&'static str, f64)> {
        let mut v = vec![
            ("FCL OBBRSS", self.fcl_obbrss.us),
            ("FCL RSS", self.fcl_rss.us),
            ("parry3d", self.parry.us),
        ];
        if let Ok(c) = &self.coal {
            v.push(("coal OBBRSS", c.us));
        }
        if let Some(t) = self.occt_us {
            v.push(("OCCT", t));
        }
        v
    }
    /// The fastest peer of the row and its median.
    fn fastest(&self) -> (&'static str, f64) {
        self.peers()
            .into_iter()
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .expect("FCL always runs")
    }
    /// Fastest peer's median over revdist's (> 1: revdist is faster).
    fn ratio(&self) -> f64 {
        self.fastest().1 / self.rev.us
    }
}

/// One row of the convex table.
struct ConvexRow {
    pair: String,
    poses: usize,
    rev_us: f64,
    /// revdist with `QueryOptions { convex_path: true, .. }` (off by default today; the convex
    /// work makes it the default).
    rev_convex_us: Option<f64>,
    coal: Result<f64, String>,
    parry_us: f64,
    /// parry3d's largest distance outside revdist's certified interval.
    parry_excess: f64,
    max_width: f64,
    violations: usize,
}

experiments::shard_record!(ConvexRow {
    pair,
    poses,
    rev_us,
    rev_convex_us,
    coal,
    parry_us,
    parry_excess,
    max_width,
    violations,
});

impl ConvexRow {
    fn fastest(&self) -> (&'static str, f64) {
        match &self.coal {
            Ok(c) if *c < self.parry_us => ("coal GJK", *c),
            _ => ("parry3d", self.parry_us),
        }
    }
}

type Res<T> = Result<T, Box<dyn std::error::Error>>;

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
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
        ("pairs", experiments::args::pair_list(&pairs)),
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
    let prov = experiments::provenance::Provenance::collect(
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

/// One row of the mesh table.
fn mesh_row(
    pair: &str,
    (pa, pb): (&Arc<Profile>, &Arc<Profile>),
    eps: f64,
    poses: &[Isometry3<f64>],
    (parry_poses, parry_budget): (usize, Option<f64>),
    coal: &mut Result<CoalPeer, String>,
) -> Res<Row> {
    let same = pa.name() == pb.name();
    let size = diagonal(pa) + diagonal(pb);
    // revdist.
    let (sa, sb, rev_build_ms) = timed_pair(pa, pb, eps)?;
    let rev_bytes = query_tree_bytes(&sa.tree) + if same { 0 } else { query_tree_bytes(&sb.tree) };
    // The certified meshes every mesh peer gets (balanced layout).
    let (ma, ta) = certified_mesh(pa, eps, None)?;
    let (mb, tb) = if same {
        (ma.clone(), ta)
    } else {
        certified_mesh(pb, eps, None)?
    };
    let mesh_ms = (ta + if same { std::time::Duration::ZERO } else { tb }).as_secs_f64() * 1e3;
    let h_sum = ma.bound + mb.bound;
    let tris = ma.mesh.triangle_count() + mb.mesh.triangle_count();
    let opts = QueryOptions::default();
    let answers: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &opts))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |b| {
        std::hint::black_box(distance(&sa, &b, &opts));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev = Timed {
        us: median(&times),
        build_ms: rev_build_ms,
        bytes: rev_bytes,
    };
    let max_width = answers
        .iter()
        .map(|d| d.upper - d.lower)
        .fold(0.0, f64::max);
    let mut violations = 0;
    let mut check = |name: &str, i: usize, d: f64| {
        if !agrees(&answers[i], d, h_sum, &poses[i], size) {
            violations += 1;
            eprintln!(
                "VIOLATION {pair} eps {eps:e} pose {i}: {name} {d:e} outside revdist [{:e}, \
                 {:e}] widened by h_a + h_b = {h_sum:e}",
                answers[i].lower, answers[i].upper
            );
        }
    };
    // FCL, both BVs (mesh time counted in each build).
    let id = Isometry3::identity();
    let mut fcl = Vec::new();
    for bv in [Bv::Obbrss, Bv::Rss] {
        let fa = FclMesh::new(
            &TriMesh::from_points(&ma.mesh.vertices, &ma.mesh.triangles),
            bv,
        )?;
        let fb = if same {
            None
        } else {
            Some(FclMesh::new(
                &TriMesh::from_points(&mb.mesh.vertices, &mb.mesh.triangles),
                bv,
            )?)
        };
        let fbr = fb.as_ref().unwrap_or(&fa);
        for (i, p) in poses.iter().enumerate() {
            check(
                if bv == Bv::Obbrss {
                    "FCL OBBRSS"
                } else {
                    "FCL RSS"
                },
                i,
                fa.distance(fbr, &id, p)?.distance,
            );
        }
        let times = time_each(poses, |p| {
            std::hint::black_box(fa.distance(fbr, &id, p)?);
            Ok::<(), Box<dyn std::error::Error>>(())
        })?;
        let build = fa.build_time()
            + fb.as_ref()
                .map_or(std::time::Duration::ZERO, |f| f.build_time());
        fcl.push(Timed {
            us: median(&times),
            build_ms: mesh_ms + build.as_secs_f64() * 1e3,
            bytes: fa.bytes() + fb.as_ref().map_or(0, |f| f.bytes()),
        });
    }
    // coal, in its own process.
    let coal_timed = match coal {
        Ok(peer) => {
            let ba = peer.mesh("A", &ma)?;
            let bb = if same {
                Default::default()
            } else {
                peer.mesh("B", &mb)?
            };
            let answers_c = peer.query("A", if same { "A" } else { "B" }, poses)?;
            for (i, a) in answers_c.iter().enumerate() {
                check("coal OBBRSS", i, a.distance);
            }
            let times: Vec<f64> = answers_c.iter().map(|a| a.us).collect();
            Ok(Timed {
                us: median(&times),
                build_ms: mesh_ms + ba.build_ms + bb.build_ms,
                bytes: ba.bytes + bb.bytes,
            })
        }
        Err(e) => Err(e.clone()),
    };
    // parry3d, on the first poses only.
    let qa = ParryShape::mesh(&ma)?;
    let qb = if same {
        None
    } else {
        Some(ParryShape::mesh(&mb)?)
    };
    let qbr = qb.as_ref().unwrap_or(&qa);
    let parry_pose: Vec<_> = poses[..parry_poses.min(poses.len())]
        .iter()
        .map(parry::pose)
        .collect();
    let mut parry_d = Vec::with_capacity(parry_pose.len());
    let mut times = Vec::with_capacity(parry_pose.len());
    for p in &parry_pose {
        let t = Instant::now();
        parry_d.push(qa.distance(qbr, p)?);
        times.push(us(t.elapsed()));
        if parry_budget.is_some_and(|b| times.iter().sum::<f64>() > b * 1e6) {
            break;
        }
    }
    let pp = &poses[..times.len()];
    for (i, d) in parry_d.iter().enumerate() {
        check("parry3d", i, *d);
    }
    let parry_t = Timed {
        us: median(&times),
        build_ms: mesh_ms
            + (qa.build + qb.as_ref().map_or(std::time::Duration::ZERO, |q| q.build)).as_secs_f64()
                * 1e3,
        bytes: qa.bytes + qb.as_ref().map_or(0, |q| q.bytes),
    };
    Ok(Row {
        pair: pair.to_owned(),
        eps,
        poses: poses.len(),
        parry_poses: pp.len(),
        tris,
        h_sum,
        rev,
        fcl_obbrss: fcl[0],
        fcl_rss: fcl[1],
        coal: coal_timed,
        parry: parry_t,
        occt_us: None,
        max_width,
        violations,
    })
}

/// One row of the convex table: models `a` and `b` as revdist solids and as exact primitives.
fn convex_row(
    a: &str,
    b: &str,
    n: usize,
    seed: u64,
    coal: &mut Result<CoalPeer, String>,
) -> Res<ConvexRow> {
    let pair = format!("{a}-{b}");
    let (pa, pb) = (Arc::new(profile(a)?), Arc::new(profile(b)?));
    let poses = close_poses(&pa, &pb, n, CLOSE_GAPS, pair_seed(seed, &pair), || {})?;
    let size = diagonal(&pa) + diagonal(&pb);
    let sa = Solid::from_profile(Arc::clone(&pa), CONVEX_EPS)?;
    let sb = Solid::from_profile(Arc::clone(&pb), CONVEX_EPS)?;
    let opts = QueryOptions::default();
    let answers: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &opts))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |s| {
        std::hint::black_box(distance(&sa, &s, &opts));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev_us = median(&times);
    // revdist's convex path (GJK on the biarc solids, off by default): its own intervals,
    // cross-checked against coal like the default's.
    let fast = QueryOptions {
        convex_path: true,
        ..QueryOptions::default()
    };
    let answers_fast: Vec<Distance> = poses
        .iter()
        .map(|p| distance(&sa, &sb.with_pose(*p), &fast))
        .collect();
    let times = time_each(poses.iter().map(|p| sb.with_pose(*p)), |s| {
        std::hint::black_box(distance(&sa, &s, &fast));
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let rev_convex_us = Some(median(&times));
    let max_width = answers
        .iter()
        .chain(&answers_fast)
        .map(|d| d.upper - d.lower)
        .fold(0.0, f64::max);
    let (ka, kb) = (
        primitive(a).ok_or_else(|| format!("no primitive for {a}"))?,
        primitive(b).ok_or_else(|| format!("no primitive for {b}"))?,
    );
    let mut violations = 0;
    let coal_us = match coal {
        Ok(peer) => {
            peer.primitive("PA", &ka)?;
            peer.primitive("PB", &kb)?;
            let ans = peer.query("PA", "PB", &poses)?;
            for (i, x) in ans.iter().enumerate() {
                let slack = COAL_GJK_TOLERANCE
                    * (1.0 + x.distance.abs() + ka.swept_radius() + kb.swept_radius());
                for (opts, ans) in [("default", &answers[i]), ("convex path", &answers_fast[i])] {
                    if !agrees(ans, x.distance, slack, &poses[i], size) {
                        violations += 1;
                        eprintln!(
                            "VIOLATION {pair} pose {i}: coal GJK {:e} outside revdist ({opts}) \
                             [{:e}, {:e}] widened by coal's GJK error bound {slack:e}",
                            x.distance, ans.lower, ans.upper
                        );
                    }
                }
            }
            Ok(median(&ans.iter().map(|x| x.us).collect::<Vec<_>>()))
        }
        Err(e) => Err(e.clone()),
    };
    let (qa, qb) = (ParryShape::primitive(&ka), ParryShape::primitive(&kb));
    let pp: Vec<_> = poses.iter().map(parry::pose).collect();
    let mut ds = Vec::with_capacity(pp.len());
    let times = time_each(&pp, |p| {
        ds.push(qa.distance(&qb, p)?);
        Ok::<(), Box<dyn std::error::Error>>(())
    })?;
    let parry_excess = ds
        .iter()
        .zip(&answers)
        .map(|(d, a)| (a.lower - d).max(d - a.upper).max(0.0))
        .fold(0.0, f64::max);
    if parry_excess > PARRY_GROSS_EXCESS {
        violations += 1;
        eprintln!("VIOLATION {pair}: parry3d off revdist's interval by {parry_excess:e}");
    }
    Ok(ConvexRow {
        pair,
        poses: poses.len(),
        rev_us,
        rev_convex_us,
        coal: coal_us,
        parry_us: median(&times),
        parry_excess,
        max_width,
        violations,
    })
}

fn opt_us(v: Option<f64>) -> String {
    v.map_or_else(String::new, |t| format!("{t:.2}"))
}

/// The columns of `peers.csv` (coal's are empty when it did not run; `coal_status` says why).
fn mesh_csv() -> Table<'static, Row> {
    let f2 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.2}", f(r));
    let f3 = |f: fn(&Row) -> f64| move |r: &Row| format!("{:.3}", f(r));
    let n = |f: fn(&Row) -> usize| move |r: &Row| f(r).to_string();
    let coal = |f: fn(&Timed) -> String| move |r: &Row| r.coal.as_ref().map_or(String::new(), f);
    Table::new()
        .csv("pair", |r: &Row| r.pair.clone())
        .csv("eps", |r| format!("{:e}", r.eps))
        .csv("poses", n(|r| r.poses))
        .csv("parry_poses", n(|r| r.parry_poses))
        .csv("triangles", n(|r| r.tris))
        .csv("h_sum", |r| format!("{:.4e}", r.h_sum))
        .csv("rev_median_us", f2(|r| r.rev.us))
        .csv("fcl_obbrss_median_us", f2(|r| r.fcl_obbrss.us))
        .csv("fcl_rss_median_us", f2(|r| r.fcl_rss.us))
        .csv("coal_obbrss_median_us", coal(|t| format!("{:.2}", t.us)))
        .csv("parry_median_us", f2(|r| r.parry.us))
        .csv("occt_median_us", |r| opt_us(r.occt_us))
        .csv("fastest_peer", |r| r.fastest().0.into())
        .csv("ratio_fastest_peer_over_rev", f3(Row::ratio))
        .csv("rev_build_ms", f3(|r| r.rev.build_ms))
        .csv("fcl_obbrss_build_ms", f3(|r| r.fcl_obbrss.build_ms))
        .csv("fcl_rss_build_ms", f3(|r| r.fcl_rss.build_ms))
        .csv(
            "coal_obbrss_build_ms",
            coal(|t| format!("{:.3}", t.build_ms)),
        )
        .csv("parry_build_ms", f3(|r| r.parry.build_ms))
        .csv("rev_bytes", n(|r| r.rev.bytes))
        .csv("fcl_obbrss_bytes", n(|r| r.fcl_obbrss.bytes))
        .csv("fcl_rss_bytes", n(|r| r.fcl_rss.bytes))
        .csv("coal_obbrss_bytes", coal(|t| t.bytes.to_string()))
        .csv("parry_bytes", n(|r| r.parry.bytes))
        .csv("rev_max_width", |r| format!("{:.4e}", r.max_width))
        .csv("violations", n(|r| r.violations))
        .csv("coal_status", |r| match &r.coal {
            Ok(_) => "ran".into(),
            Err(e) => e.replace(',', ";"),
        })
}

fn convex_csv() -> Table<'static, ConvexRow> {
    Table::new()
        .csv("pair", |r: &ConvexRow| r.pair.clone())
        .csv("poses", |r| r.poses.to_string())
        .csv("rev_median_us", |r| format!("{:.3}", r.rev_us))
        .csv("rev_convex_path_median_us", |r| opt_us(r.rev_convex_us))
        .csv("coal_gjk_median_us", |r| {
            r.coal.as_ref().map_or(String::new(), |t| format!("{t:.3}"))
        })
        .csv("parry_median_us", |r| format!("{:.3}", r.parry_us))
        .csv("fastest_peer", |r| r.fastest().0.into())
        .csv("ratio_fastest_peer_over_rev", |r| {
            format!("{:.3}", r.fastest().1 / r.rev_us)
        })
        .csv("ratio_fastest_peer_over_rev_convex_path", |r| {
            r.rev_convex_us
                .map_or_else(String::new, |c| format!("{:.3}", r.fastest().1 / c))
        })
        .csv("parry_max_excess", |r| format!("{:.3e}", r.parry_excess))
        .csv("rev_max_width", |r| format!("{:.4e}", r.max_width))
        .csv("violations", |r| r.violations.to_string())
}

fn mesh_md(coal_note: &str) -> Table<'static, Row> {
    let note = coal_note.to_owned();
    let time_build_mem = |t: &Timed| {
        format!(
            "{:.1} / {:.1} / {}",
            t.us,
            t.build_ms,
            human_bytes(t.bytes as f64)
        )
    };
    Table::new()
        .markdown("pair", |r: &Row| r.pair.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
        .markdown("poses (parry3d)", |r| {
            format!("{} ({})", r.poses, r.parry_poses)
        })
        .right()
        .markdown("triangles A+B", |r| r.tris.to_string())
        .right()
        .markdown("revdist", move |r| time_build_mem(&r.rev))
        .right()
        .markdown("FCL OBBRSS", move |r| time_build_mem(&r.fcl_obbrss))
        .right()
        .markdown("FCL RSS", move |r| time_build_mem(&r.fcl_rss))
        .right()
        .markdown("coal OBBRSS", move |r| {
            r.coal
                .as_ref()
                .map_or_else(|_| note.clone(), time_build_mem)
        })
        .right()
        .markdown("parry3d (one-sided)", move |r| time_build_mem(&r.parry))
        .right()
        .markdown("OCCT", |r| {
            r.occt_us.map_or_else(|| "-".into(), |t| format!("{t:.0}"))
        })
        .right()
        .markdown("fastest peer", |r| r.fastest().0.into())
        .markdown("ratio", |r| format!("{:.2}", r.ratio()))
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

fn convex_md(coal_note: &str) -> Table<'static, ConvexRow> {
    let note = coal_note.to_owned();
    Table::new()
        .markdown("pair", |r: &ConvexRow| r.pair.clone())
        .markdown("poses", |r| r.poses.to_string())
        .right()
        .markdown("revdist default", |r| format!("{:.2}", r.rev_us))
        .right()
        .markdown("revdist convex path", |r| {
            r.rev_convex_us
                .map_or_else(|| "-".into(), |t| format!("{t:.2}"))
        })
        .right()
        .markdown("coal GJK", move |r| {
            r.coal
                .as_ref()
                .map_or_else(|_| note.clone(), |t| format!("{t:.2}"))
        })
        .right()
        .markdown("parry3d", |r| format!("{:.2}", r.parry_us))
        .right()
        .markdown("fastest peer", |r| r.fastest().0.into())
        .markdown("ratio default / convex path", |r| {
            let f = r.fastest().1;
            match r.rev_convex_us {
                Some(c) => format!("{:.2} / {:.2}", f / r.rev_us, f / c),
                None => format!("{:.2} / -", f / r.rev_us),
            }
        })
        .right()
        .markdown("parry3d max excess", |r| format!("{:.1e}", r.parry_excess))
        .right()
        .markdown("revdist max width", |r| format!("{:.1e}", r.max_width))
        .right()
        .markdown("violations", |r| r.violations.to_string())
        .right()
}

fn markdown(
    rows: &[Row],
    convex: &[ConvexRow],
    (parry_poses, parry_budget): (usize, Option<f64>),
    coal: &str,
) -> String {
    let note = match rows.first().map(|r| &r.coal) {
        Some(Err(e)) => e.clone(),
        _ => "coal missing: run scripts/deps.sh".into(),
    };
    let mut s = String::from("# revdist beside its peers: FCL 0.7, coal 3, parry3d 0.31\n\n");
    s.push_str(&format!(
        "coal: {coal}. Single thread, one query at a time, each method *blocked* (alone over \
         the poses of a row; coal times its queries in its own process). Poses near contact \
         (gaps log-uniform in [{:e}, {:e}], seeded as in fcl_bench). Each cell: median query \
         us / build ms (tessellation included for the mesh peers) / memory (both shapes; one \
         when A = B). Mesh peers get the same certified mesh (balanced layout, two-sided \
         Hausdorff bound <= eps). parry3d's TriMesh-TriMesh distance is one-sided (best-first \
         over mesh 1's BVH against mesh 2's whole AABB, then one BVH query into mesh 2 per \
         leaf triangle) and runs on the first {parry_poses} poses of each row only{}. Ratio = \
         fastest peer's median / revdist's (> 1: revdist faster). OCCT: hook for the \
         OpenCASCADE cross-check's time per query (not measured here). Violations: a peer's \
         distance outside revdist's certified interval widened by h_a + h_b.\n\n",
        CLOSE_GAPS.0,
        CLOSE_GAPS.1,
        parry_budget.map_or(String::new(), |b| format!(
            ", stopping after the pose that exceeds {b} s of its queries (the count in brackets)"
        ))
    ));
    s.push_str(&mesh_md(&note).markdown_text(rows));
    s.push_str(&format!(
        "\nConvex solids of revolution (revdist eps {CONVEX_EPS:e}; peers: exact primitives, \
         GJK), median us per query. Violations: coal's distance outside revdist's interval \
         widened by coal's GJK error bound tol (1 + d + swept radii), tol = \
         {COAL_GJK_TOLERANCE:e} (its default convergence test), or parry3d's off by more than \
         {PARRY_GROSS_EXCESS:e}; parry3d states no tolerance, its largest excess over \
         revdist's interval is listed. revdist convex path: `QueryOptions {{ convex_path: true, \
         .. }}` (GJK on the biarc solids; coal is checked against its intervals too). Ratio: \
         fastest peer's median / revdist's (default / convex path; > 1: revdist faster).\n\n"
    ));
    s.push_str(&convex_md(&note).markdown_text(convex));
    s
}

/// Median query time per row, one bar per method (log scale).
fn figure(path: &std::path::Path, rows: &[Row]) -> Res<()> {
    let categories: Vec<String> = rows
        .iter()
        .map(|r| format!("{} {:.0e}", r.pair, r.eps))
        .collect();
    let series = |name: &str, f: &dyn Fn(&Row) -> f64| BarSeries {
        name: name.into(),
        values: rows.iter().map(f).collect(),
    };
    let s = vec![
        series("revdist", &|r| r.rev.us),
        series("FCL OBBRSS", &|r| r.fcl_obbrss.us),
        series("FCL RSS", &|r| r.fcl_rss.us),
        series("coal OBBRSS", &|r| {
            r.coal.as_ref().map_or(f64::NAN, |t| t.us)
        }),
        series("parry3d (one-sided)", &|r| r.parry.us),
    ];
    let width = (160 + 90 * rows.len()).max(800) as u32;
    grouped_bars(
        path,
        "Median query time near contact, us (blocked)",
        &categories,
        &s,
        "us per query",
        true,
        None,
        (width, 520),
    )?;
    Ok(())
}
