//! The paper's Tables 1 and 2 and Figure 9 (section 5) against FCL, in one run:
//!
//! * **Table 1, data size**: bytes of revdist's query tree (the flat arrays a query touches)
//!   and of its biarc tree, against FCL 0.7 `BVHModel<OBBRSS>` and `BVHModel<RSS>` on a
//!   certified mesh of the same eps (two-sided Hausdorff error <= eps, `revdist::tessellate`,
//!   the layout with the fewest triangles), counting FCL's node, triangle, vertex and index
//!   arrays ([`verify::baselines::fcl::FclMesh::bytes`]).
//! * **Table 2, node counts**: biarc-tree nodes (and leaves, depth, spirals) against FCL's
//!   BV count and the mesh's triangle count.
//! * **Figure 9, construction time**: revdist's tree build (biarc tree + query tree, the
//!   median of [`BUILD_REPEATS`] builds) against FCL's (certified tessellation + BVH build),
//!   per model and for the deformable model M_t averaged over its frames.
//!
//! Both model families are reported: the paper's five models as exact lines and arcs, and
//! their freeform cubic B-spline variants (`NAME_ff`) when the build has them.
//!
//! Usage: `bvh_tables [--out DIR] [--morph-frames N] [--paper]`. Writes `bvh_tables.csv`,
//! `bvh_tables.md` and `build_time.svg` (default `figures`).

use experiments::baseline_mesh::Layout;
use experiments::plot::{colour, grouped_bars_coloured, shades, BarSeries};
use experiments::progress;
use experiments::provenance::Provenance;
use experiments::shapes::{query_tree_bytes, PAPER_EPS, PAPER_MODELS};
use experiments::stats::{human_bytes, mean, median};
use revdist::biarc::BiarcTree;
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;

/// revdist tree builds per model and eps; the median is reported (builds take 20-400 us, so
/// one build is at the mercy of the scheduler).
const BUILD_REPEATS: usize = 7;
/// M_t frames for revdist's mean build time (default run); FCL uses [`FCL_MORPH_FRAMES`].
const DEFAULT_MORPH_FRAMES: usize = 50;
/// M_t frames for FCL's mean build time: a certified mesh and two BVHs per frame take up to
/// seconds at eps 1e-5, so fewer frames, spread over the whole cycle.
const FCL_MORPH_FRAMES: usize = 5;
/// Frames with `--paper` (the paper averages over its whole animation).
const PAPER_MORPH_FRAMES: usize = 500;
const PAPER_FCL_MORPH_FRAMES: usize = 50;
/// Suffix of the freeform variants' names.
const FREEFORM_SUFFIX: &str = "_ff";

struct Args {
    out: PathBuf,
    morph_frames: usize,
    fcl_morph_frames: usize,
}

fn parse_args() -> Result<Args, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut a = Args {
        out: PathBuf::from("figures"),
        morph_frames: DEFAULT_MORPH_FRAMES,
        fcl_morph_frames: FCL_MORPH_FRAMES,
    };
    let mut i = 0;
    while i < args.len() {
        let value = || {
            args.get(i + 1)
                .cloned()
                .ok_or_else(|| format!("{} needs a value", args[i]))
        };
        match args[i].as_str() {
            "--out" => a.out = PathBuf::from(value()?),
            "--morph-frames" => {
                let v = value()?;
                a.morph_frames = match v.parse::<usize>() {
                    Ok(n) if n > 0 => n,
                    _ => {
                        return Err(format!(
                            "--morph-frames needs a positive integer, got '{v}'"
                        ))
                    }
                };
                a.fcl_morph_frames = a.fcl_morph_frames.min(a.morph_frames);
            }
            "--paper" => {
                a.morph_frames = PAPER_MORPH_FRAMES;
                a.fcl_morph_frames = PAPER_FCL_MORPH_FRAMES;
                i += 1;
                continue;
            }
            "-h" | "--help" => {
                println!("usage: bvh_tables [--out DIR] [--morph-frames N] [--paper]");
                std::process::exit(0);
            }
            o => return Err(format!("unknown argument '{o}' (try --help)")),
        }
        i += 2;
    }
    Ok(a)
}

/// One row: a model (or M_t's mean) at one eps.
#[derive(Default, Clone)]
struct Row {
    family: &'static str,
    model: String,
    eps: f64,
    spirals: f64,
    nodes: f64,
    leaves: f64,
    depth: f64,
    biarc_bytes: f64,
    query_bytes: f64,
    rev_build_us: f64,
    triangles: f64,
    obbrss_bvs: f64,
    rss_bvs: f64,
    obbrss_bytes: f64,
    rss_bytes: f64,
    mesh_ms: f64,
    obbrss_build_ms: f64,
    rss_build_ms: f64,
    /// Certified Hausdorff bound of the mesh FCL used.
    mesh_bound: f64,
}

/// revdist's side of a row: tree statistics and the median build time.
fn revdist_side(
    row: &mut Row,
    p: &Arc<Profile>,
    eps: f64,
) -> Result<(), Box<dyn std::error::Error>> {
    let mut times = Vec::with_capacity(BUILD_REPEATS);
    let mut solid = None;
    for _ in 0..BUILD_REPEATS {
        let t = Instant::now();
        let s = Solid::from_profile(Arc::clone(p), eps)?;
        times.push(t.elapsed().as_secs_f64() * 1e6);
        solid = Some(s);
    }
    let solid = solid.expect("BUILD_REPEATS > 0");
    let s = BiarcTree::build(p, eps)?.stats();
    row.spirals = s.spirals as f64;
    row.nodes = s.nodes as f64;
    row.leaves = s.leaves as f64;
    row.depth = s.depth as f64;
    row.biarc_bytes = s.bytes as f64;
    row.query_bytes = query_tree_bytes(&solid.tree) as f64;
    row.rev_build_us = median(&times);
    Ok(())
}

/// FCL's side: the layout with the fewest triangles (the smallest memory; the capped layout
/// only ever adds triangles), its BV counts, bytes and build times.
fn fcl_side(row: &mut Row, p: &Profile, eps: f64) -> Result<(), Box<dyn std::error::Error>> {
    let l = Layout::build(p, eps, None)?;
    row.triangles = l.triangles() as f64;
    row.obbrss_bvs = l.obbrss.num_bvs() as f64;
    row.rss_bvs = l.rss.num_bvs() as f64;
    row.obbrss_bytes = l.obbrss.bytes() as f64;
    row.rss_bytes = l.rss.bytes() as f64;
    row.mesh_ms = l.mesh_time.as_secs_f64() * 1e3;
    row.obbrss_build_ms = l.obbrss.build_time().as_secs_f64() * 1e3;
    row.rss_build_ms = l.rss.build_time().as_secs_f64() * 1e3;
    row.mesh_bound = l.cm.bound;
    Ok(())
}

/// Field-wise mean of rows (for M_t over its frames).
fn mean_row(rows: &[Row], fcl_rows: &[Row]) -> Row {
    let m = |f: fn(&Row) -> f64, rs: &[Row]| mean(&rs.iter().map(f).collect::<Vec<_>>());
    Row {
        family: "deforming",
        model: "M_t (mean)".into(),
        eps: rows[0].eps,
        spirals: m(|r| r.spirals, rows),
        nodes: m(|r| r.nodes, rows),
        leaves: m(|r| r.leaves, rows),
        depth: m(|r| r.depth, rows),
        biarc_bytes: m(|r| r.biarc_bytes, rows),
        query_bytes: m(|r| r.query_bytes, rows),
        rev_build_us: m(|r| r.rev_build_us, rows),
        triangles: m(|r| r.triangles, fcl_rows),
        obbrss_bvs: m(|r| r.obbrss_bvs, fcl_rows),
        rss_bvs: m(|r| r.rss_bvs, fcl_rows),
        obbrss_bytes: m(|r| r.obbrss_bytes, fcl_rows),
        rss_bytes: m(|r| r.rss_bytes, fcl_rows),
        mesh_ms: m(|r| r.mesh_ms, fcl_rows),
        obbrss_build_ms: m(|r| r.obbrss_build_ms, fcl_rows),
        rss_build_ms: m(|r| r.rss_build_ms, fcl_rows),
        mesh_bound: fcl_rows.iter().map(|r| r.mesh_bound).fold(0.0, f64::max),
    }
}

/// The models of both families that this build provides.
fn model_list() -> Vec<(&'static str, String)> {
    let mut v: Vec<(&'static str, String)> = PAPER_MODELS
        .iter()
        .map(|m| ("exact", m.to_string()))
        .collect();
    for m in PAPER_MODELS {
        let name = format!("{m}{FREEFORM_SUFFIX}");
        if revdist::models::model(&name).is_ok() {
            v.push(("freeform", name));
        }
    }
    v
}

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    let started = Instant::now();
    let models = model_list();
    let prov = Provenance::collect(
        "bvh_tables (paper Tables 1-2, Figure 9)",
        &[
            ("eps", format!("{PAPER_EPS:?}")),
            (
                "models",
                models
                    .iter()
                    .map(|m| m.1.as_str())
                    .collect::<Vec<_>>()
                    .join(" "),
            ),
            ("build_repeats", BUILD_REPEATS.to_string()),
            ("morph_frames_revdist", args.morph_frames.to_string()),
            ("morph_frames_fcl", args.fcl_morph_frames.to_string()),
            (
                "fcl_mesh",
                "certified tessellation, balanced vertices, no edge cap".into(),
            ),
        ],
    );
    let steps =
        (PAPER_EPS.len() * (models.len() + args.morph_frames + args.fcl_morph_frames)) as u64;
    let bar = progress::bar(steps, "bvh_tables");
    let mut rows = Vec::new();
    for &eps in &PAPER_EPS {
        for (family, name) in &models {
            let p = Arc::new(revdist::models::model(name)?);
            let mut row = Row {
                family,
                model: name.clone(),
                eps,
                ..Row::default()
            };
            revdist_side(&mut row, &p, eps)?;
            fcl_side(&mut row, &p, eps)?;
            rows.push(row);
            bar.inc(1);
        }
        // M_t: revdist over `morph_frames` frames, FCL over a spread subset.
        let mut rev = Vec::new();
        let mut fcl = Vec::new();
        for k in 0..args.morph_frames {
            let t = k as f64 / args.morph_frames as f64;
            let p = Arc::new(revdist::models::morph(t)?);
            let mut row = Row::default();
            revdist_side(&mut row, &p, eps)?;
            rev.push(row);
            bar.inc(1);
        }
        for k in 0..args.fcl_morph_frames {
            let t = k as f64 / args.fcl_morph_frames as f64;
            let p = revdist::models::morph(t)?;
            let mut row = Row::default();
            fcl_side(&mut row, &p, eps)?;
            fcl.push(row);
            bar.inc(1);
        }
        let mut m = mean_row(&rev, &fcl);
        m.eps = eps;
        rows.push(m);
    }
    bar.finish_and_clear();
    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("bvh_tables.csv"), csv(&rows, &prov))?;
    let md = markdown(&rows, &prov, started.elapsed().as_secs_f64());
    std::fs::write(args.out.join("bvh_tables.md"), &md)?;
    draw_build_times(&args.out.join("build_time.svg"), &rows)?;
    print!("{md}");
    Ok(())
}

fn csv(rows: &[Row], prov: &Provenance) -> String {
    let mut s = prov.csv_preamble();
    s.push_str("family,model,eps,spirals,biarc_nodes,biarc_leaves,depth,biarc_tree_bytes,query_tree_bytes,revdist_build_us,triangles,obbrss_bvs,rss_bvs,obbrss_bytes,rss_bytes,mesh_ms,obbrss_build_ms,rss_build_ms,mesh_hausdorff_bound\n");
    for r in rows {
        let _ = writeln!(
            s,
            "{},{},{:e},{:.1},{:.1},{:.1},{:.1},{:.0},{:.0},{:.2},{:.0},{:.0},{:.0},{:.0},{:.0},{:.3},{:.3},{:.3},{:.4e}",
            r.family,
            r.model,
            r.eps,
            r.spirals,
            r.nodes,
            r.leaves,
            r.depth,
            r.biarc_bytes,
            r.query_bytes,
            r.rev_build_us,
            r.triangles,
            r.obbrss_bvs,
            r.rss_bvs,
            r.obbrss_bytes,
            r.rss_bytes,
            r.mesh_ms,
            r.obbrss_build_ms,
            r.rss_build_ms,
            r.mesh_bound
        );
    }
    s
}

fn markdown(rows: &[Row], prov: &Provenance, secs: f64) -> String {
    let mut s = String::new();
    let _ = writeln!(
        s,
        "# BVH data size, node counts and construction time (paper Tables 1-2, Figure 9)\n\n\
         revdist's trees against FCL 0.7 on certified meshes of the same eps (two-sided Hausdorff \
         error <= eps, the layout with the fewest triangles). `_ff` are the freeform cubic \
         B-spline variants of the paper's models; M_t is the mean over its frames. Generated by \
         `experiments/src/bin/bvh_tables.rs` in {secs:.0} s.\n"
    );
    let _ = writeln!(s, "## Table 1: data size\n");
    let _ = writeln!(
        s,
        "| model | eps | revdist query tree | revdist biarc tree | FCL OBBRSS | FCL RSS | OBBRSS / revdist |\n| --- | --- | --- | --- | --- | --- | --- |"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {} | {} | {} | {} | {:.0}x |",
            r.model,
            r.eps,
            human_bytes(r.query_bytes),
            human_bytes(r.biarc_bytes),
            human_bytes(r.obbrss_bytes),
            human_bytes(r.rss_bytes),
            r.obbrss_bytes / r.query_bytes
        );
    }
    let _ = writeln!(s, "\n## Table 2: node counts\n");
    let _ = writeln!(
        s,
        "| model | eps | spirals | biarc nodes | leaves | depth | triangles | FCL OBBRSS BVs | FCL RSS BVs |\n| --- | --- | --- | --- | --- | --- | --- | --- | --- |"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} |",
            r.model,
            r.eps,
            r.spirals,
            r.nodes,
            r.leaves,
            r.depth,
            r.triangles,
            r.obbrss_bvs,
            r.rss_bvs
        );
    }
    let _ = writeln!(s, "\n## Figure 9: construction time\n");
    let _ = writeln!(
        s,
        "revdist: biarc tree + query tree (median of {BUILD_REPEATS} builds). FCL: certified \
         tessellation + BVH build (one build).\n\n\
         | model | eps | revdist (us) | tessellation (ms) | FCL OBBRSS build (ms) | FCL RSS build (ms) | (tessellation + OBBRSS) / revdist |\n| --- | --- | --- | --- | --- | --- | --- |"
    );
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {:.1} | {:.1} | {:.1} | {:.1} | {:.0}x |",
            r.model,
            r.eps,
            r.rev_build_us,
            r.mesh_ms,
            r.obbrss_build_ms,
            r.rss_build_ms,
            (r.mesh_ms + r.obbrss_build_ms) * 1e3 / r.rev_build_us
        );
    }
    s.push_str(&prov.markdown_footer());
    s
}

/// Figure 9: build time per model, revdist vs FCL (tessellation + OBBRSS), one bar per eps.
fn draw_build_times(
    path: &std::path::Path,
    rows: &[Row],
) -> Result<(), Box<dyn std::error::Error>> {
    let mut categories: Vec<String> = Vec::new();
    for r in rows {
        if !categories.contains(&r.model) {
            categories.push(r.model.clone());
        }
    }
    let value = |model: &str, eps: f64, f: &dyn Fn(&Row) -> f64| {
        rows.iter()
            .find(|r| r.model == model && r.eps == eps)
            .map(f)
            .unwrap_or(f64::NAN)
    };
    let mut series = Vec::new();
    for &eps in &PAPER_EPS {
        series.push(BarSeries {
            name: format!("revdist {eps:.0e}"),
            values: categories
                .iter()
                .map(|m| value(m, eps, &|r| r.rev_build_us * 1e-3))
                .collect(),
        });
    }
    for &eps in &PAPER_EPS {
        series.push(BarSeries {
            name: format!("FCL {eps:.0e}"),
            values: categories
                .iter()
                .map(|m| value(m, eps, &|r| r.mesh_ms + r.obbrss_build_ms))
                .collect(),
        });
    }
    let labels: Vec<String> = categories
        .iter()
        .map(|c| c.replace(" (mean)", ""))
        .collect();
    let mut colours = shades(colour(0), PAPER_EPS.len());
    colours.extend(shades(colour(1), PAPER_EPS.len()));
    grouped_bars_coloured(
        path,
        "BVH construction time: revdist tree vs FCL (certified mesh + OBBRSS)",
        &labels,
        &series,
        &colours,
        "build time (ms)",
        true,
        None,
        (1200, 520),
    )
}
