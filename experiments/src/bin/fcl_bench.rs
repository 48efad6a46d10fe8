//! revdist against FCL 0.7 at equal accuracy (issues 11 and 12): in one run and on the same
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
//!   against the meshes' bounds h_a + h_b, and the speed ratio FCL / revdist;
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
//! revdist and FCL OBBRSS (each layout) also run *blocked*: each alone over all poses in a
//! row, the usual benchmark loop over one pair (its code and, for revdist's small trees, its
//! data stay cached from pose to pose).
//!
//! Usage: `fcl_bench [--poses N] [--poses-1e-5 N] [--eps E]... [--pairs a-b,...] [--full]
//! [--out DIR]`. Writes `DIR/fcl_bench.csv` and `DIR/fcl_bench.md` (default `figures`).

use experiments::args as cli;
use experiments::baseline_mesh::{agrees_with_fcl, Layout};
use experiments::poses::{close_poses, pair_seed, CLOSE_GAPS, CLOSE_SEED};
use experiments::shapes::query_tree_bytes;
use experiments::stats::{human_bytes, median, quantile, time_each, us};
use nalgebra::Isometry3;
use revdist::biarc::BiarcTree;
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::{Duration, Instant};

/// The issue-11 table.
const DEFAULT_PAIRS: &str = "torus-torus,pawn-pawn,pawn-cup,cup-bottle,table-lightmill";
/// Accuracies of the comparison.
const DEFAULT_EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];
/// Poses per pair at eps 1e-3 and 1e-4 (default run).
const DEFAULT_POSES: usize = 200;
/// Poses per pair at eps 1e-5 and below (default run): the same first poses, fewer of them,
/// since FCL's queries are slowest there.
const DEFAULT_POSES_FINE: usize = 100;
/// Poses per pair with `--full`.
const FULL_POSES: usize = 1000;
/// Gap range of the poses (log-uniform), as in issue 11.
const GAPS: (f64, f64) = CLOSE_GAPS;
/// Capped layout: longest meridian edge as a fraction of the profile's bounding-box diagonal.
const EDGE_CAP_REL: f64 = 1.0 / 64.0;

/// The torus of issue 11: R 1, r 0.25 as one exact circle.
fn profile(name: &str) -> Result<Profile, Box<dyn std::error::Error>> {
    if name == "torus" {
        use revdist::models::primitives::{arc, deg};
        return Ok(Profile::new(
            "torus",
            vec![arc([1.0, 0.0], 0.25, deg(-90.0), deg(270.0))?],
        )?);
    }
    Ok(revdist::models::model(name)?)
}

fn diagonal(p: &Profile) -> f64 {
    let b = p.bounding_box();
    (b.max.x - b.min.x).hypot(b.max.y - b.min.y)
}

struct Args {
    poses: usize,
    poses_fine: usize,
    eps: Vec<f64>,
    pairs: Vec<(String, String)>,
    out: PathBuf,
}

fn parse_args() -> Result<Args, String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let mut a = Args {
        poses: DEFAULT_POSES,
        poses_fine: DEFAULT_POSES_FINE,
        eps: vec![],
        pairs: vec![],
        out: PathBuf::from("figures"),
    };
    let mut pairs = DEFAULT_PAIRS.to_string();
    let mut i = 0;
    let value = |i: usize| cli::value(&args, i);
    while i < args.len() {
        let flag = args[i].as_str();
        match flag {
            "--full" => {
                a.poses = FULL_POSES;
                a.poses_fine = FULL_POSES;
                i += 1;
                continue;
            }
            "--poses" => a.poses = cli::count(&value(i)?, flag)?,
            "--poses-1e-5" => a.poses_fine = cli::count(&value(i)?, flag)?,
            "--eps" => a.eps.extend(cli::eps_list(&value(i)?, flag)?),
            "--pairs" => pairs = value(i)?,
            "--out" => a.out = PathBuf::from(value(i)?),
            "-h" | "--help" => {
                println!("usage: fcl_bench [--poses N] [--poses-1e-5 N] [--eps E]... [--pairs a-b,...] [--full] [--out DIR]");
                std::process::exit(0);
            }
            o => return Err(format!("unknown argument '{o}' (try --help)")),
        }
        i += 2;
    }
    if a.eps.is_empty() {
        a.eps = DEFAULT_EPS.to_vec();
    }
    a.pairs = cli::pairs(&pairs, "--pairs")?;
    Ok(a)
}

/// One row of the table.
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
    /// tolerance, and FCL OBBRSS per layout.
    rev_trees_warm: f64,
    fcl_obbrss_warm: Vec<f64>,
    /// Blocked medians (each method alone over all poses in a row).
    rev_trees_blocked: f64,
    fcl_obbrss_blocked: Vec<f64>,
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

const LAYOUT_NAMES: [&str; 2] = ["balanced", "capped"];

fn main() {
    if let Err(e) = run() {
        eprintln!("error: {e}");
        std::process::exit(2);
    }
}

fn run() -> Result<(), Box<dyn std::error::Error>> {
    let args = parse_args()?;
    let started = Instant::now();
    let mut rows = Vec::new();
    for (na, nb) in &args.pairs {
        let (pa, pb) = (Arc::new(profile(na)?), Arc::new(profile(nb)?));
        // Poses placed once per pair (fine trees), reused at every eps.
        let n_max = args.poses.max(args.poses_fine);
        let pair = format!("{na}-{nb}");
        let poses = close_poses(&pa, &pb, n_max, GAPS, pair_seed(CLOSE_SEED, &pair), || {})?;
        for &eps in &args.eps {
            let n = if eps < 5e-5 {
                args.poses_fine
            } else {
                args.poses
            };
            rows.push(bench_row(&pair, (&pa, &pb), eps, &poses[..n])?);
            let r = rows.last().expect("row");
            eprintln!(
                "{pair} eps {eps:.0e}: revdist {:.1} us, FCL OBBRSS {:.1} us ({}), ratio {:.2} [{:.0} s]",
                r.rev_trees.0,
                r.fcl[r.best_obbrss].0,
                LAYOUT_NAMES[r.best_obbrss],
                r.fcl[r.best_obbrss].0 / r.rev_trees.0,
                started.elapsed().as_secs_f64()
            );
        }
    }
    std::fs::create_dir_all(&args.out)?;
    let prov = experiments::provenance::Provenance::collect(
        "fcl_bench (revdist vs FCL at equal accuracy)",
        &[
            ("poses", args.poses.to_string()),
            ("poses_eps_below_5e-5", args.poses_fine.to_string()),
            ("eps", format!("{:?}", args.eps)),
            (
                "pairs",
                args.pairs
                    .iter()
                    .map(|(a, b)| format!("{a}-{b}"))
                    .collect::<Vec<_>>()
                    .join(" "),
            ),
        ],
    );
    std::fs::write(
        args.out.join("fcl_bench.csv"),
        prov.csv_preamble() + &csv(&rows),
    )?;
    let md = markdown(&rows, &args, started.elapsed());
    let md = md + &prov.markdown_footer();
    std::fs::write(args.out.join("fcl_bench.md"), &md)?;
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
    let t = Instant::now();
    let sa = Solid::from_profile(Arc::clone(pa), eps)?;
    let sb = if same {
        sa.clone()
    } else {
        Solid::from_profile(Arc::clone(pb), eps)?
    };
    let rev_build_ms = t.elapsed().as_secs_f64() * 1e3;
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
    }
    row.rev_trees_warm = median(&warm_times[0]);
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
    let best = |f: &dyn Fn(&(f64, f64)) -> f64| {
        (0..row.fcl.len())
            .min_by(|&x, &y| f(&row.fcl[x]).total_cmp(&f(&row.fcl[y])))
            .expect("a layout")
    };
    row.best_obbrss = best(&|x| x.0);
    row.best_rss = best(&|x| x.1);
    Ok(row)
}

fn csv(rows: &[Row]) -> String {
    let mut s = String::from(
        "pair,eps,poses,rev_trees_median_us,rev_trees_p90_us,rev_tol0_median_us,rev_tol0_p90_us,\
         fcl_obbrss_balanced_us,fcl_rss_balanced_us,fcl_obbrss_capped_us,fcl_rss_capped_us,\
         best_obbrss_layout,best_rss_layout,ratio_obbrss_over_rev,ratio_rss_over_rev,ratio_obbrss_over_rev_tol0,\
         tris_balanced,tris_capped,h_sum_balanced,h_sum_capped,rev_max_width,\
         rev_build_ms,mesh_ms_balanced,obbrss_build_ms_balanced,rss_build_ms_balanced,mesh_ms_capped,obbrss_build_ms_capped,rss_build_ms_capped,\
         rev_query_tree_bytes,rev_biarc_tree_bytes,obbrss_bytes_balanced,rss_bytes_balanced,obbrss_bytes_capped,rss_bytes_capped,violations,\
         rev_trees_warm_median_us,fcl_obbrss_balanced_warm_us,fcl_obbrss_capped_warm_us,ratio_obbrss_over_rev_warm,\
         rev_trees_blocked_median_us,fcl_obbrss_balanced_blocked_us,fcl_obbrss_capped_blocked_us,ratio_obbrss_over_rev_blocked\n",
    );
    for r in rows {
        let (bo, br) = (r.fcl[r.best_obbrss].0, r.fcl[r.best_rss].1);
        let _ = writeln!(
            s,
            "{},{:e},{},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{:.2},{},{},{:.3},{:.3},{:.3},{},{},{:.4e},{:.4e},{:.4e},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{:.3},{},{},{},{},{},{},{}",
            r.pair,
            r.eps,
            r.poses,
            r.rev_trees.0,
            r.rev_trees.1,
            r.rev_exact.0,
            r.rev_exact.1,
            r.fcl[0].0,
            r.fcl[0].1,
            r.fcl[1].0,
            r.fcl[1].1,
            LAYOUT_NAMES[r.best_obbrss],
            LAYOUT_NAMES[r.best_rss],
            bo / r.rev_trees.0,
            br / r.rev_trees.0,
            bo / r.rev_exact.0,
            r.tris[0],
            r.tris[1],
            r.h_sum[0],
            r.h_sum[1],
            r.max_width,
            r.rev_build_ms,
            r.mesh_ms[0],
            r.obbrss_build_ms[0],
            r.rss_build_ms[0],
            r.mesh_ms[1],
            r.obbrss_build_ms[1],
            r.rss_build_ms[1],
            r.rev_bytes,
            r.rev_tree_bytes,
            r.obbrss_bytes[0],
            r.rss_bytes[0],
            r.obbrss_bytes[1],
            r.rss_bytes[1],
            r.violations
        );
        // Warm columns (appended so that existing readers keep their column indices).
        s.pop();
        let _ = writeln!(
            s,
            ",{:.2},{:.2},{:.2},{:.3},{:.2},{:.2},{:.2},{:.3}",
            r.rev_trees_warm,
            r.fcl_obbrss_warm[0],
            r.fcl_obbrss_warm[1],
            r.fcl_obbrss_warm[r.best_obbrss] / r.rev_trees_warm,
            r.rev_trees_blocked,
            r.fcl_obbrss_blocked[0],
            r.fcl_obbrss_blocked[1],
            r.fcl_obbrss_blocked[r.best_obbrss] / r.rev_trees_blocked
        );
    }
    s
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

fn markdown(rows: &[Row], args: &Args, wall: Duration) -> String {
    let mut s = String::from("# revdist vs FCL 0.7 at equal accuracy\n\n");
    let _ = writeln!(
        s,
        "Machine: {}. Commit: {}. Poses per pair: {} (eps >= 5e-5), {} (eps < 5e-5; the first \
         poses of the same sequence), gaps log-uniform in [{:e}, {:e}], seeded; wall time {:.0} s.\n",
        machine(),
        git_commit(),
        args.poses,
        args.poses_fine,
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
         profile diagonal). Ratio = FCL OBBRSS median / revdist median (default tolerance). \
         Memory: revdist query-tree arrays vs FCL's node, triangle and vertex arrays (both \
         shapes; one when A = B). Build: revdist trees vs tessellation + OBBRSS build (layout \
         of the OBBRSS column). Violations: cases where revdist's interval misses FCL's \
         `d ± (h_a + h_b)`. All times are *cold*: each query runs after the other methods' \
         queries (FCL's meshes take megabytes), so its trees and code come from memory. The \
         second table runs each method *blocked* (alone over all poses in a row, the usual \
         benchmark loop) and *warm* (each query repeated at once on the same pose).\n\n",
    );
    s.push_str("| pair | eps | triangles A+B | revdist median / p90 us | revdist tol 0, traversal, median us | FCL OBBRSS median us | FCL RSS median us | ratio OBBRSS / revdist | build revdist / mesh+OBBRSS ms | memory revdist / OBBRSS / RSS | max width / h_a+h_b | violations |\n");
    s.push_str(
        "| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n",
    );
    for r in rows {
        let (o, rs) = (r.best_obbrss, r.best_rss);
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {} | {:.1} / {:.1} | {:.1} | {:.1} ({}) | {:.1} ({}) | {:.2} | {:.2} / {:.1} | {} / {} / {} | {:.2e} / {:.2e} | {} |",
            r.pair,
            r.eps,
            r.tris[o],
            r.rev_trees.0,
            r.rev_trees.1,
            r.rev_exact.0,
            r.fcl[o].0,
            LAYOUT_NAMES[o],
            r.fcl[rs].1,
            LAYOUT_NAMES[rs],
            r.fcl[o].0 / r.rev_trees.0,
            r.rev_build_ms,
            r.mesh_ms[o] + r.obbrss_build_ms[o],
            human_bytes(r.rev_bytes as f64),
            human_bytes(r.obbrss_bytes[o] as f64),
            human_bytes(r.rss_bytes[rs] as f64),
            r.max_width,
            r.h_sum[o],
            r.violations
        );
    }
    s.push_str("\nBlocked (each method alone over all poses in a row) and warm (each query repeated at once on the same pose); FCL OBBRSS in the layout of the first table; medians, us:\n\n| pair | eps | revdist blocked | FCL blocked | ratio blocked | revdist warm | FCL warm | ratio warm | cold / blocked revdist | cold / blocked FCL |\n| --- | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for r in rows {
        let o = r.best_obbrss;
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {:.1} | {:.1} | {:.2} | {:.1} | {:.1} | {:.2} | {:.2} | {:.2} |",
            r.pair,
            r.eps,
            r.rev_trees_blocked,
            r.fcl_obbrss_blocked[o],
            r.fcl_obbrss_blocked[o] / r.rev_trees_blocked,
            r.rev_trees_warm,
            r.fcl_obbrss_warm[o],
            r.fcl_obbrss_warm[o] / r.rev_trees_warm,
            r.rev_trees.0 / r.rev_trees_blocked,
            r.fcl[o].0 / r.fcl_obbrss_blocked[o]
        );
    }
    s.push_str("\nAll layouts (FCL medians, us; triangles):\n\n| pair | eps | balanced OBBRSS / RSS | tris | capped OBBRSS / RSS | tris |\n| --- | --- | ---: | ---: | ---: | ---: |\n");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {:.1} / {:.1} | {} | {:.1} / {:.1} | {} |",
            r.pair, r.eps, r.fcl[0].0, r.fcl[0].1, r.tris[0], r.fcl[1].0, r.fcl[1].1, r.tris[1]
        );
    }
    s
}
