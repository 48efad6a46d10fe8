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

use clap::Parser;
use experiments::args::positive_count;
use experiments::baseline_mesh::Layout;
use experiments::cli::{Out, Paper};
use experiments::driver::{self, DriverResult};
use experiments::plot::{colour, grouped_bars_coloured, shades, BarSeries};
use experiments::progress;
use experiments::provenance::Provenance;
use experiments::shapes::{query_tree_bytes, PAPER_EPS, PAPER_MODELS};
use experiments::stats::{human_bytes, mean, median};
use experiments::table::Table;
use revdist::biarc::BiarcTree;
use revdist::profile::Profile;
use revdist::solid::Solid;
use std::fmt::Write as _;
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

/// BVH data size, node counts and construction time (the paper's Tables 1-2 and Figure 9):
/// revdist's query tree and biarc tree against FCL 0.7's OBBRSS and RSS hierarchies on
/// certified meshes of the same eps (1e-3, 1e-4, 1e-5), for the paper's five models, their
/// freeform variants and the deforming model M_t averaged over its frames. Writes
/// bvh_tables.csv, bvh_tables.md and build_time.svg.
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    /// M_t frames for revdist's mean build time [default: 50; --paper: 500]
    #[arg(long, value_name = "N", value_parser = positive_count)]
    morph_frames: Option<usize>,
    #[command(flatten)]
    paper: Paper,
}

impl Args {
    /// M_t frames of revdist's and of FCL's mean build time (FCL's never more than revdist's).
    fn morph_frames(&self) -> (usize, usize) {
        let paper = &self.paper;
        let revdist = self
            .morph_frames
            .unwrap_or(paper.pick(DEFAULT_MORPH_FRAMES, PAPER_MORPH_FRAMES));
        let fcl = paper.pick(FCL_MORPH_FRAMES, PAPER_FCL_MORPH_FRAMES);
        (revdist, fcl.min(revdist))
    }
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
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let (morph_frames, fcl_morph_frames) = args.morph_frames();
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
            ("morph_frames_revdist", morph_frames.to_string()),
            ("morph_frames_fcl", fcl_morph_frames.to_string()),
            (
                "fcl_mesh",
                "certified tessellation, balanced vertices, no edge cap".into(),
            ),
        ],
    );
    let steps = (PAPER_EPS.len() * (models.len() + morph_frames + fcl_morph_frames)) as u64;
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
        for k in 0..morph_frames {
            let t = k as f64 / morph_frames as f64;
            let p = Arc::new(revdist::models::morph(t)?);
            let mut row = Row::default();
            revdist_side(&mut row, &p, eps)?;
            rev.push(row);
            bar.inc(1);
        }
        for k in 0..fcl_morph_frames {
            let t = k as f64 / fcl_morph_frames as f64;
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
    let out = &args.out.dir;
    let csv = prov.csv_preamble() + &node_count_table().csv_text(&rows);
    std::fs::write(out.join("bvh_tables.csv"), csv)?;
    let md = markdown(&rows, &prov, started.elapsed().as_secs_f64());
    std::fs::write(out.join("bvh_tables.md"), &md)?;
    draw_build_times(&out.join("build_time.svg"), &rows)?;
    print!("{md}");
    Ok(())
}

/// The `model` and `eps` columns that open every Markdown table.
fn model_and_eps(table: Table<'static, Row>) -> Table<'static, Row> {
    table
        .markdown("model", |r| r.model.clone())
        .markdown("eps", |r| format!("{:.0e}", r.eps))
}

/// The columns of `bvh_tables.csv`, and of Table 2 (node counts) in the Markdown.
fn node_count_table() -> Table<'static, Row> {
    let fixed = |digits: usize, f: fn(&Row) -> f64| move |r: &Row| format!("{:.*}", digits, f(r));
    Table::new()
        .csv("family", |r: &Row| r.family.to_owned())
        .csv("model", |r| r.model.clone())
        .with_markdown_header("model")
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("spirals", fixed(1, |r| r.spirals))
        .with_markdown("spirals", fixed(0, |r| r.spirals))
        .csv("biarc_nodes", fixed(1, |r| r.nodes))
        .with_markdown("biarc nodes", fixed(0, |r| r.nodes))
        .csv("biarc_leaves", fixed(1, |r| r.leaves))
        .with_markdown("leaves", fixed(0, |r| r.leaves))
        .csv("depth", fixed(1, |r| r.depth))
        .with_markdown("depth", fixed(0, |r| r.depth))
        .csv("biarc_tree_bytes", fixed(0, |r| r.biarc_bytes))
        .csv("query_tree_bytes", fixed(0, |r| r.query_bytes))
        .csv("revdist_build_us", fixed(2, |r| r.rev_build_us))
        .csv("triangles", fixed(0, |r| r.triangles))
        .with_markdown_header("triangles")
        .csv("obbrss_bvs", fixed(0, |r| r.obbrss_bvs))
        .with_markdown_header("FCL OBBRSS BVs")
        .csv("rss_bvs", fixed(0, |r| r.rss_bvs))
        .with_markdown_header("FCL RSS BVs")
        .csv("obbrss_bytes", fixed(0, |r| r.obbrss_bytes))
        .csv("rss_bytes", fixed(0, |r| r.rss_bytes))
        .csv("mesh_ms", fixed(3, |r| r.mesh_ms))
        .csv("obbrss_build_ms", fixed(3, |r| r.obbrss_build_ms))
        .csv("rss_build_ms", fixed(3, |r| r.rss_build_ms))
        .csv("mesh_hausdorff_bound", |r| format!("{:.4e}", r.mesh_bound))
}

/// Table 1 (data size) of the Markdown.
fn data_size_table() -> Table<'static, Row> {
    model_and_eps(Table::new())
        .markdown("revdist query tree", |r| human_bytes(r.query_bytes))
        .markdown("revdist biarc tree", |r| human_bytes(r.biarc_bytes))
        .markdown("FCL OBBRSS", |r| human_bytes(r.obbrss_bytes))
        .markdown("FCL RSS", |r| human_bytes(r.rss_bytes))
        .markdown("OBBRSS / revdist", |r| {
            format!("{:.0}x", r.obbrss_bytes / r.query_bytes)
        })
}

/// Figure 9 (construction time) of the Markdown.
fn build_time_table() -> Table<'static, Row> {
    model_and_eps(Table::new())
        .markdown("revdist (us)", |r| format!("{:.1}", r.rev_build_us))
        .markdown("tessellation (ms)", |r| format!("{:.1}", r.mesh_ms))
        .markdown("FCL OBBRSS build (ms)", |r| {
            format!("{:.1}", r.obbrss_build_ms)
        })
        .markdown("FCL RSS build (ms)", |r| format!("{:.1}", r.rss_build_ms))
        .markdown("(tessellation + OBBRSS) / revdist", |r| {
            format!(
                "{:.0}x",
                (r.mesh_ms + r.obbrss_build_ms) * 1e3 / r.rev_build_us
            )
        })
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
    s.push_str(&data_size_table().markdown_text(rows));
    let _ = writeln!(s, "\n## Table 2: node counts\n");
    s.push_str(&node_count_table().markdown_text(rows));
    let _ = writeln!(s, "\n## Figure 9: construction time\n");
    let _ = writeln!(
        s,
        "revdist: biarc tree + query tree (median of {BUILD_REPEATS} builds). FCL: certified \
         tessellation + BVH build (one build).\n"
    );
    s.push_str(&build_time_table().markdown_text(rows));
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
