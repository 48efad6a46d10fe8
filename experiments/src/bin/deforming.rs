//! The paper's Figure 8 (section 5): each static model against the deforming model M_t, the
//! average time per frame with the deforming solid's structure rebuilt every frame, revdist
//! against FCL 0.7, at eps 1e-3, 1e-4 and 1e-5.
//!
//! **Frames.** M_t runs through `frames` frames t_k = k / frames of its cycle (pawn -> cup ->
//! bottle -> table -> lightmill -> pawn). Static model X sits at the identity; M_t is placed
//! along a fixed random direction with a fixed random rotation (seeded per X), slid so the
//! gap follows a smooth schedule g_k between [`GAPS`] (log-sinusoidal, two periods per
//! cycle): close but separated. Placement uses trees at [`PLACEMENT_EPS`] and is done before
//! any timing.
//!
//! **What a frame costs.** revdist: build M_t's tree at eps (`Solid::from_profile`) plus the
//! distance query (warm-started from the previous frame, the intended use in motion). FCL:
//! certified tessellation of M_t at eps (two-sided Hausdorff error <= eps), `BVHModel<OBBRSS>`
//! build from scratch (the shim has no refit; a refit would need a mesh with the same
//! connectivity, which a certified tessellation of a changing profile does not keep), plus
//! the distance query. One rebuild per frame serves all five static models, but each pair's
//! per-frame time counts it in full, as a scene with one pair would. Every revdist answer is
//! cross-checked against FCL's (`verify::crosscheck::criterion`).
//!
//! Usage: `deforming [--frames N] [--frames-1e-5 N] [--eps E,...] [--paper] [--seed S]
//! [--out DIR]`.
//! Writes `deforming.csv`, `deforming.md` and `deforming.svg` (default `figures`).

use clap::Parser;
use experiments::baseline_mesh::{agrees_with_fcl, certified_mesh, obbrss_of, Layout};
use experiments::cli::{count_at, Eps, Frames, Out, Paper, Seed};
use experiments::driver::{self, DriverResult};
use experiments::plot::{colour, grouped_bars_coloured, shades, BarSeries};
use experiments::poses::{log_uniform, slide_to_gap, PLACEMENT_EPS};
use experiments::progress;
use experiments::provenance::Provenance;
use experiments::shapes::{centre, diagonal, PAPER_EPS, PAPER_MODELS};
use experiments::stats::{mean, us};
use experiments::table::Table;
use experiments::{Draw, SplitMix};
use nalgebra::{Isometry3, UnitQuaternion, Vector3};
use revdist::profile::Profile;
use revdist::query::{distance_cached, QueryCache, QueryOptions};
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;

/// Frames per eps >= 5e-5 (default run).
const DEFAULT_FRAMES: usize = 40;
/// Frames at eps < 5e-5 (default run): FCL's rebuild of M_t takes about a second there.
const DEFAULT_FRAMES_FINE: usize = 6;
/// Frames with `--paper` (all eps).
const PAPER_FRAMES: usize = 200;
/// Range of the gap schedule.
const GAPS: (f64, f64) = (2e-3, 1e-1);
/// Default seed of the directions and rotations.
const SEED: u64 = 0x0f16_0008;

/// Each static model against the deforming model M_t (the paper's Figure 8): the mean time
/// per frame with M_t's structure rebuilt every frame, revdist (tree build + warm-started
/// certified query) against FCL 0.7 (certified tessellation + OBBRSS build + query), as M_t
/// runs through its cycle at a smoothly varying gap; every revdist answer is cross-checked
/// against FCL's. Writes deforming.csv, .md and .svg (40 frames per eps, 6 below 5e-5; 200
/// with --paper).
#[derive(Parser)]
struct Args {
    #[command(flatten)]
    out: Out,
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    frames: Frames,
    #[command(flatten)]
    paper: Paper,
    #[command(flatten)]
    seed: Seed,
    #[command(flatten)]
    shard: experiments::shard::Flags,
}

/// Per static model and eps: sums over frames.
#[derive(Default, Clone)]
struct Row {
    model: String,
    eps: f64,
    frames: usize,
    rev_build_us: Vec<f64>,
    rev_query_us: Vec<f64>,
    fcl_mesh_us: Vec<f64>,
    fcl_bvh_us: Vec<f64>,
    fcl_query_us: Vec<f64>,
    triangles: Vec<f64>,
    gaps: Vec<f64>,
    violations: usize,
}

experiments::shard_record!(Row {
    model,
    eps,
    frames,
    rev_build_us,
    rev_query_us,
    fcl_mesh_us,
    fcl_bvh_us,
    fcl_query_us,
    triangles,
    gaps,
    violations,
});

impl Row {
    fn rev_frame(&self) -> f64 {
        mean(&self.rev_build_us) + mean(&self.rev_query_us)
    }
    fn fcl_frame(&self) -> f64 {
        mean(&self.fcl_mesh_us) + mean(&self.fcl_bvh_us) + mean(&self.fcl_query_us)
    }
    /// FCL's time per frame over revdist's.
    fn ratio(&self) -> f64 {
        self.fcl_frame() / self.rev_frame()
    }
}

/// The smooth gap schedule at frame `k` of `n`: log-sinusoidal between [`GAPS`].
fn gap_at(k: usize, n: usize) -> f64 {
    let s = 0.5 + 0.5 * (4.0 * std::f64::consts::PI * k as f64 / n as f64).cos();
    (GAPS.0.ln() + (GAPS.1.ln() - GAPS.0.ln()) * s).exp()
}

fn main() {
    driver::run(run)
}

fn run(args: Args) -> DriverResult {
    let eps_list = args.eps.or(&PAPER_EPS);
    let frames = args.frames.or(args.paper.pick(
        (DEFAULT_FRAMES, DEFAULT_FRAMES_FINE),
        (PAPER_FRAMES, PAPER_FRAMES),
    ));
    let seed = args.seed.or(SEED);
    let started = Instant::now();
    let settings = vec![
        ("frames", frames.0.to_string()),
        ("frames_eps_below_5e-5", frames.1.to_string()),
        ("eps", format!("{eps_list:?}")),
        (
            "gaps",
            format!("{GAPS:?} log-sinusoidal, two periods per cycle"),
        ),
        (
            "revdist",
            "default tolerance, warm start from the previous frame".into(),
        ),
        (
            "fcl",
            "certified tessellation (balanced) + OBBRSS build from scratch per frame".into(),
        ),
        ("seed", format!("{seed:#x}")),
    ];
    let prov = Provenance::collect(
        "deforming (paper Figure 8: static models vs M_t, rebuild included)",
        &settings
            .iter()
            .cloned()
            .chain(args.shard.provenance())
            .collect::<Vec<_>>(),
    );
    // The work units: one per eps (the frames of an eps share M_t's rebuild and the warm
    // starts); this run's.
    let mine: Vec<usize> = args.shard.units(eps_list.len());
    let statics: Vec<Arc<Profile>> = PAPER_MODELS
        .iter()
        .map(|m| revdist::models::model(m).map(Arc::new))
        .collect::<Result<_, _>>()?;
    let frames_at = |eps: f64| count_at(eps, frames);

    // Placement, before any timing: per static model a direction and rotation, per frame a pose.
    let max_frames = mine
        .iter()
        .map(|&e| frames_at(eps_list[e]))
        .max()
        .unwrap_or(0);
    let total: usize = mine.iter().map(|&e| frames_at(eps_list[e])).sum();
    let bar = progress::bar(
        (PAPER_MODELS.len() * max_frames + total) as u64,
        "deforming",
    );
    // Per static model: its placement tree, a fixed approach direction and rotation, and a
    // fixed factor in [0.95, 1.05) on the gap schedule, so the five models' gaps differ.
    let fixed: Vec<(Solid, Vector3<f64>, UnitQuaternion<f64>, f64)> = statics
        .iter()
        .enumerate()
        .map(|(m, x)| {
            let mut rng = SplitMix(seed ^ (m as u64 * 0x9e37));
            let (dir, rot) = (rng.unit_vector(), rng.rotation());
            let factor = 1.0 + 0.1 * (log_uniform(&mut rng, 1.0, 2.0) - 1.5);
            Ok((
                Solid::from_profile(Arc::clone(x), PLACEMENT_EPS)?,
                dir,
                rot,
                factor,
            ))
        })
        .collect::<Result<_, Box<dyn std::error::Error>>>()?;
    // Per unit of this run: [model][frame].
    let mut placement: Vec<Vec<Vec<Isometry3<f64>>>> = Vec::new();
    let mut gaps: Vec<Vec<Vec<f64>>> = Vec::new();
    for &e in &mine {
        let n = frames_at(eps_list[e]);
        let mut per_model = vec![Vec::with_capacity(n); statics.len()];
        let mut per_gap = vec![Vec::with_capacity(n); statics.len()];
        for k in 0..n {
            let frame = Arc::new(revdist::models::morph(k as f64 / n as f64)?);
            let fine_b = Solid::from_profile(Arc::clone(&frame), PLACEMENT_EPS)?;
            for (m, x) in statics.iter().enumerate() {
                let (fine_x, dir, rot, factor) = &fixed[m];
                let ((zx, rx), (zb, rb)) = (centre(x), centre(&frame));
                let g = gap_at(k, n) * factor;
                let pose = slide_to_gap(fine_x, &fine_b, (zx, zb), rx + rb, dir, rot, g)
                    .ok_or_else(|| {
                        format!(
                            "could not place M_t frame {k} at gap {g:.1e} from {}",
                            PAPER_MODELS[m]
                        )
                    })?;
                per_model[m].push(pose);
                per_gap[m].push(g);
            }
        }
        placement.push(per_model);
        gaps.push(per_gap);
    }

    let mut rows = Vec::new();
    for (ei, &unit) in mine.iter().enumerate() {
        let eps = eps_list[unit];
        let n = frames_at(eps);
        // Static structures (not timed: they are built once per run).
        let static_solids: Vec<Solid> = statics
            .iter()
            .map(|p| Solid::from_profile(Arc::clone(p), eps))
            .collect::<Result<_, _>>()?;
        let static_meshes: Vec<Layout> = statics
            .iter()
            .map(|p| Layout::build(p, eps, None))
            .collect::<Result<_, _>>()?;
        let mut eps_rows: Vec<Row> = PAPER_MODELS
            .iter()
            .map(|m| Row {
                model: m.to_string(),
                eps,
                frames: n,
                ..Row::default()
            })
            .collect();
        let mut caches: Vec<QueryCache> =
            (0..statics.len()).map(|_| QueryCache::default()).collect();
        let opts = QueryOptions::default();
        for k in 0..n {
            let frame = Arc::new(revdist::models::morph(k as f64 / n as f64)?);
            // revdist: rebuild M_t's tree.
            let t = Instant::now();
            let solid = Solid::from_profile(Arc::clone(&frame), eps)?;
            let rev_build = us(t.elapsed());
            // FCL: certified mesh and OBBRSS from scratch.
            let (cm, mesh_time) = certified_mesh(&frame, eps, None)?;
            let mesh_us = us(mesh_time);
            let fcl = obbrss_of(&cm)?;
            let bvh_us = us(fcl.build_time());
            let size_b = diagonal(&frame);
            for (m, row) in eps_rows.iter_mut().enumerate() {
                let pose = placement[ei][m][k];
                let posed = solid.with_pose(pose);
                let t = Instant::now();
                let d = distance_cached(&static_solids[m], &posed, &opts, &mut caches[m]);
                let q_us = us(t.elapsed());
                let t = Instant::now();
                let f = static_meshes[m]
                    .obbrss
                    .distance(&fcl, &Isometry3::identity(), &pose)?;
                let f_us = us(t.elapsed());
                let h = static_meshes[m].cm.bound + cm.bound;
                if !agrees_with_fcl(&d, f.distance, h, &pose, diagonal(&statics[m]) + size_b) {
                    row.violations += 1;
                    eprintln!(
                        "violation: {} vs morph@{} eps {eps:e}: revdist [{}, {}], FCL {} +- {h}",
                        PAPER_MODELS[m],
                        k as f64 / n as f64,
                        d.lower,
                        d.upper,
                        f.distance
                    );
                }
                row.rev_build_us.push(rev_build);
                row.rev_query_us.push(q_us);
                row.fcl_mesh_us.push(mesh_us);
                row.fcl_bvh_us.push(bvh_us);
                row.fcl_query_us.push(f_us);
                row.triangles.push(cm.mesh.triangles.len() as f64);
                row.gaps.push(gaps[ei][m][k]);
            }
            bar.inc(1);
        }
        rows.extend(eps_rows.into_iter().map(|r| (unit, r)));
    }
    bar.finish_and_clear();
    let Some(rows) = args.shard.finish(
        (&args.out.dir, "deforming"),
        &settings,
        eps_list.len(),
        rows,
    )?
    else {
        return Ok(()); // a shard: its raw rows are written
    };
    let out = &args.out.dir;
    let csv = prov.csv_preamble() + &frame_table().csv_text(&rows);
    std::fs::write(out.join("deforming.csv"), csv)?;
    let md = markdown(&rows, &prov, started.elapsed().as_secs_f64());
    std::fs::write(out.join("deforming.md"), &md)?;
    draw(&out.join("deforming.svg"), &rows, &eps_list)?;
    print!("{md}");
    let violations = rows.iter().map(|r| r.violations).sum();
    driver::check_violations(violations, "(see above)")
}

/// The columns of `deforming.csv` and of the table in `deforming.md`.
fn frame_table() -> Table<'static, Row> {
    let us = |digits: usize, f: fn(&Row) -> f64| move |r: &Row| format!("{:.*}", digits, f(r));
    Table::new()
        .csv("static_model", |r: &Row| r.model.clone())
        .with_markdown_header("static model")
        .csv("eps", |r| format!("{:e}", r.eps))
        .with_markdown("eps", |r| format!("{:.0e}", r.eps))
        .csv("frames", |r| r.frames.to_string())
        .with_markdown_header("frames")
        .right()
        .csv("revdist_rebuild_us", us(2, |r| mean(&r.rev_build_us)))
        .csv("revdist_query_us", us(2, |r| mean(&r.rev_query_us)))
        .csv("revdist_frame_us", us(2, Row::rev_frame))
        .markdown("revdist rebuild + query (us)", |r| {
            let (build, query) = (mean(&r.rev_build_us), mean(&r.rev_query_us));
            format!("{build:.0} + {query:.0} = {:.0}", r.rev_frame())
        })
        .right()
        .csv("fcl_tessellate_us", us(1, |r| mean(&r.fcl_mesh_us)))
        .csv("fcl_obbrss_build_us", us(1, |r| mean(&r.fcl_bvh_us)))
        .csv("fcl_query_us", us(2, |r| mean(&r.fcl_query_us)))
        .csv("fcl_frame_us", us(1, Row::fcl_frame))
        .markdown("FCL tessellate + OBBRSS + query (us)", |r| {
            let (mesh, bvh) = (mean(&r.fcl_mesh_us), mean(&r.fcl_bvh_us));
            let query = mean(&r.fcl_query_us);
            format!("{mesh:.0} + {bvh:.0} + {query:.0} = {:.0}", r.fcl_frame())
        })
        .right()
        .csv("ratio_fcl_over_revdist", |r| format!("{:.2}", r.ratio()))
        .with_markdown("FCL / revdist", |r| format!("{:.0}x", r.ratio()))
        .right()
        .csv("mt_triangles_mean", |r| {
            format!("{:.0}", mean(&r.triangles))
        })
        .with_markdown_header("M_t triangles")
        .right()
        .csv("gap_mean", |r| format!("{:.3e}", mean(&r.gaps)))
        .csv("violations", |r| r.violations.to_string())
        .with_markdown_header("violations")
        .right()
}

fn markdown(rows: &[Row], prov: &Provenance, secs: f64) -> String {
    let mut s = String::from(
        "# Static models against the deforming M_t (paper Figure 8)\n\n\
         Mean time per frame, the deforming solid's structure rebuilt every frame: revdist = \
         M_t's tree build + certified query (default tolerance, warm start); FCL = certified \
         tessellation of M_t + OBBRSS build + query. M_t moves through its whole cycle while \
         the gap follows a smooth schedule in [2e-3, 1e-1]. Every revdist answer is checked \
         against FCL's (`violations`).\n\n\
         ![Figure 8](deforming.svg)\n\n",
    );
    s.push_str(&frame_table().markdown_text(rows));
    let q_ratio: Vec<String> = rows
        .iter()
        .map(|r| {
            format!(
                "{} {:.0e}: {:.2}x",
                r.model,
                r.eps,
                mean(&r.fcl_query_us) / mean(&r.rev_query_us)
            )
        })
        .collect();
    let _ = writeln!(
        s,
        "\nThe rebuild decides the comparison: FCL's per-frame cost is almost all tessellation \
         and BVH construction. Queries alone (FCL query / revdist query): {}. Generated by \
         `experiments/src/bin/deforming.rs` in {secs:.0} s.",
        q_ratio.join(", ")
    );
    s.push_str(&prov.markdown_footer());
    s
}

/// Grouped bars: one group per static model, revdist and FCL per eps (log time per frame),
/// the speed-up at the finest eps above each group.
fn draw(
    path: &std::path::Path,
    rows: &[Row],
    eps: &[f64],
) -> Result<(), Box<dyn std::error::Error>> {
    let cats: Vec<String> = PAPER_MODELS.iter().map(|m| format!("{m} vs M_t")).collect();
    let get = |m: &str, e: f64, f: &dyn Fn(&Row) -> f64| {
        rows.iter()
            .find(|r| r.model == m && r.eps == e)
            .map(f)
            .unwrap_or(f64::NAN)
    };
    let mut series = Vec::new();
    for &e in eps {
        series.push(BarSeries {
            name: format!("revdist {e:.0e}"),
            values: PAPER_MODELS
                .iter()
                .map(|m| get(m, e, &|r| r.rev_frame() * 1e-3))
                .collect(),
        });
    }
    for &e in eps {
        series.push(BarSeries {
            name: format!("FCL {e:.0e}"),
            values: PAPER_MODELS
                .iter()
                .map(|m| get(m, e, &|r| r.fcl_frame() * 1e-3))
                .collect(),
        });
    }
    let finest = eps.iter().copied().fold(f64::INFINITY, f64::min);
    let notes: Vec<String> = PAPER_MODELS
        .iter()
        .map(|m| format!("{:.0}x at {finest:.0e}", get(m, finest, &Row::ratio)))
        .collect();
    let mut colours = shades(colour(0), eps.len());
    colours.extend(shades(colour(1), eps.len()));
    grouped_bars_coloured(
        path,
        "Static model vs deforming M_t: time per frame, rebuild included",
        &cats,
        &series,
        &colours,
        "mean time per frame (ms)",
        true,
        Some(&notes),
        (1200, 540),
    )
}
