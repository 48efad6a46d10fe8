//! The paper's Figure 12 (section 5): all 15 pairs of the five static models in continuous
//! motion, the average query time of revdist against FCL 0.7 at eps 1e-3, 1e-4 and 1e-5, as
//! grouped bars with the speed-up.
//!
//! **Motion.** Per pair, a seeded [`SmoothMotion`]: B's rotation and its approach direction
//! about A move smoothly through random keyframes while the target gap follows a
//! log-sinusoid in [`GAPS`] (often close, never touching); each frame slides B along the
//! direction to its gap with trees at placement accuracy. All poses are placed before any
//! timing, and the same poses serve every method and eps.
//!
//! **Methods.** revdist at its default tolerance (interval width <= eps_a + eps_b), warm
//! started from the previous frame's best leaf pair (`distance_cached`, the intended use in
//! motion); FCL `BVHModel<OBBRSS>` on certified meshes of the same eps in two layouts
//! (balanced vertices, and meridian edges capped), keeping the faster layout per row as
//! `fcl_bench` does. Queries are timed one at a time on one thread, methods interleaved
//! per frame in a rotating order. Every revdist answer is cross-checked against FCL's
//! (`verify::crosscheck::criterion`); violations are reported and fail the run.
//!
//! Usage: `motion [--frames N] [--frames-1e-5 N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--out DIR]`. Writes `motion.csv`, `motion.md` and `motion_eps{E}.svg` (default `figures`).

use experiments::args;
use experiments::baseline_mesh::{
    agrees_with_fcl, certified_mesh, obbrss_of, EDGE_CAP_REL, LAYOUT_NAMES,
};
use experiments::plot::{colour, grouped_bars_coloured, BarSeries};
use experiments::poses::{pair_seed, SmoothMotion};
use experiments::progress;
use experiments::provenance::Provenance;
use experiments::shapes::{diagonal, paper_pairs, PAPER_EPS};
use experiments::stats::{mean, median, time_each, us};
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::{distance_cached, QueryCache, QueryOptions};
use revdist::solid::Solid;
use revdist::tessellate::CertifiedMesh;
use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::PathBuf;
use std::sync::Arc;
use std::time::Instant;
use verify::baselines::fcl::FclMesh;

/// Frames per pair at eps >= 5e-5 (default run).
const DEFAULT_FRAMES: usize = 200;
/// Frames per pair at eps < 5e-5 (default run; the same motion, its first frames).
const DEFAULT_FRAMES_FINE: usize = 100;
/// Frames with `--paper` (the paper's 50,000).
const PAPER_FRAMES: usize = 50_000;
/// Gap range of the motion (model units; the models are 1-3 units tall).
const GAPS: (f64, f64) = (1e-3, 3e-1);
/// Keyframes of the rotation and direction per 1,000 frames (at least 4).
const KEYS_PER_1000_FRAMES: usize = 8;
/// Gap oscillations per 1,000 frames.
const GAP_PERIODS_PER_1000_FRAMES: f64 = 5.0;
/// Seed of the motions (xor a hash of the pair name).
const SEED: u64 = 0xf16_0012;

struct Args {
    frames: usize,
    frames_fine: usize,
    eps: Vec<f64>,
    pairs: Vec<(String, String)>,
    out: PathBuf,
}

fn parse_args() -> Result<Args, String> {
    let argv: Vec<String> = std::env::args().skip(1).collect();
    let mut a = Args {
        frames: DEFAULT_FRAMES,
        frames_fine: DEFAULT_FRAMES_FINE,
        eps: PAPER_EPS.to_vec(),
        pairs: paper_pairs()
            .into_iter()
            .map(|(x, y)| (x.to_string(), y.to_string()))
            .collect(),
        out: PathBuf::from("figures"),
    };
    let mut i = 0;
    while i < argv.len() {
        match argv[i].as_str() {
            "--frames" => a.frames = args::count(&args::value(&argv, i)?, "--frames")?,
            "--frames-1e-5" => {
                a.frames_fine = args::count(&args::value(&argv, i)?, "--frames-1e-5")?
            }
            "--eps" => a.eps = args::eps_list(&args::value(&argv, i)?, "--eps")?,
            "--pairs" => a.pairs = args::pairs(&args::value(&argv, i)?, "--pairs")?,
            "--out" => a.out = PathBuf::from(args::value(&argv, i)?),
            "--paper" => {
                a.frames = PAPER_FRAMES;
                a.frames_fine = PAPER_FRAMES;
                i += 1;
                continue;
            }
            "-h" | "--help" => {
                println!(
                    "usage: motion [--frames N] [--frames-1e-5 N] [--eps E,...] [--pairs a-b,...] [--paper] [--out DIR]"
                );
                std::process::exit(0);
            }
            o => return Err(format!("unknown argument '{o}' (try --help)")),
        }
        i += 2;
    }
    a.frames_fine = a.frames_fine.min(a.frames);
    Ok(a)
}

/// FCL's structures of one shape at one eps: both layouts' certified meshes and OBBRSS.
struct FclShape {
    layouts: Vec<(CertifiedMesh, FclMesh)>,
}

impl FclShape {
    fn build(p: &Profile, eps: f64) -> Result<FclShape, Box<dyn std::error::Error>> {
        let mut layouts = Vec::new();
        for cap in [None, Some(EDGE_CAP_REL * diagonal(p))] {
            // The capped layout needs a cap above 2 eps (the tessellator's requirement).
            let cap = cap.filter(|&c| c > 2.0 * eps);
            let (cm, _) = certified_mesh(p, eps, cap)?;
            let bvh = obbrss_of(&cm)?;
            layouts.push((cm, bvh));
        }
        Ok(FclShape { layouts })
    }
}

/// One pair at one eps.
struct Row {
    pair: String,
    eps: f64,
    frames: usize,
    rev_us: Vec<f64>,
    /// Per layout: query times.
    fcl_us: Vec<Vec<f64>>,
    /// Blocked: revdist alone over the whole motion (warm starts), then FCL OBBRSS in the
    /// faster layout alone: mean query times.
    rev_blocked_mean: f64,
    fcl_blocked_mean: f64,
    best: usize,
    triangles: Vec<usize>,
    node_pairs: f64,
    exact_leaves: f64,
    /// Smallest distance revdist returned over the motion (-1 if it reported an overlap).
    min_gap: f64,
    violations: usize,
}

impl Row {
    fn fcl_mean(&self) -> f64 {
        mean(&self.fcl_us[self.best])
    }
    fn ratio(&self) -> f64 {
        self.fcl_mean() / mean(&self.rev_us)
    }
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
    let frames_at = |eps: f64| {
        if eps < 5e-5 {
            args.frames_fine
        } else {
            args.frames
        }
    };
    let keys = (KEYS_PER_1000_FRAMES * args.frames / 1000).max(4);
    let periods = (GAP_PERIODS_PER_1000_FRAMES * args.frames as f64 / 1000.0).max(1.0);
    let prov = Provenance::collect(
        "motion (paper Figure 12: 15 pairs in continuous motion)",
        &[
            ("frames", args.frames.to_string()),
            ("frames_eps_below_5e-5", args.frames_fine.to_string()),
            ("eps", format!("{:?}", args.eps)),
            ("gaps", format!("{GAPS:?}")),
            ("keyframes", keys.to_string()),
            ("gap_periods", format!("{periods}")),
            (
                "revdist",
                "default tolerance, warm start (distance_cached)".into(),
            ),
            (
                "fcl",
                "OBBRSS on certified meshes, faster of two layouts".into(),
            ),
            ("seed", format!("{SEED:#x}")),
        ],
    );
    let mut profiles: HashMap<String, Arc<Profile>> = HashMap::new();
    for (a, b) in &args.pairs {
        for n in [a, b] {
            if !profiles.contains_key(n) {
                profiles.insert(n.clone(), Arc::new(experiments::shapes::profile(n)?));
            }
        }
    }

    // 1. Motions, placed before any timing.
    let bar = progress::bar((args.pairs.len() * args.frames) as u64, "motion: place");
    let mut motions: Vec<Vec<Isometry3<f64>>> = Vec::new();
    for (a, b) in &args.pairs {
        let name = format!("{a}-{b}");
        let m = SmoothMotion::new(pair_seed(SEED, &name), keys, GAPS, periods);
        motions.push(m.poses(&profiles[a], &profiles[b], args.frames, || bar.inc(1))?);
    }
    bar.finish_and_clear();

    // 2. Per eps: structures once per shape, then every pair's motion, methods interleaved.
    let mut rows = Vec::new();
    for &eps in &args.eps {
        let n = frames_at(eps);
        let bar = progress::bar(profiles.len() as u64, &format!("meshes {eps:.0e}"));
        let mut solids: HashMap<String, Solid> = HashMap::new();
        let mut fcl: HashMap<String, FclShape> = HashMap::new();
        for (name, p) in &profiles {
            solids.insert(name.clone(), Solid::from_profile(Arc::clone(p), eps)?);
            fcl.insert(name.clone(), FclShape::build(p, eps)?);
            bar.inc(1);
        }
        bar.finish_and_clear();
        let bar = progress::bar((args.pairs.len() * n) as u64, &format!("motion {eps:.0e}"));
        for ((a, b), poses) in args.pairs.iter().zip(&motions) {
            let (sa, sb) = (&solids[a], &solids[b]);
            let (fa, fb) = (&fcl[a], &fcl[b]);
            let size = diagonal(&profiles[a]) + diagonal(&profiles[b]);
            let opts = QueryOptions::default();
            let mut cache = QueryCache::default();
            let layouts = fa.layouts.len().min(fb.layouts.len());
            let mut row = Row {
                pair: format!("{a}-{b}"),
                eps,
                frames: n,
                rev_us: Vec::with_capacity(n),
                fcl_us: vec![Vec::with_capacity(n); layouts],
                rev_blocked_mean: 0.0,
                fcl_blocked_mean: 0.0,
                best: 0,
                triangles: (0..layouts)
                    .map(|l| {
                        fa.layouts[l].0.mesh.triangles.len() + fb.layouts[l].0.mesh.triangles.len()
                    })
                    .collect(),
                node_pairs: 0.0,
                exact_leaves: 0.0,
                min_gap: f64::INFINITY,
                violations: 0,
            };
            for (k, pose) in poses[..n].iter().enumerate() {
                let posed = sb.with_pose(*pose);
                let methods = 1 + layouts;
                // Answers of this frame: revdist's, and FCL's on the balanced layout (the
                // timed call's result is reused for the cross-check).
                let (mut rev, mut fcl_balanced) = (None, None);
                for j in 0..methods {
                    let m = (j + k) % methods;
                    if m == 0 {
                        let t = Instant::now();
                        let d = distance_cached(sa, &posed, &opts, &mut cache);
                        row.rev_us.push(us(t.elapsed()));
                        rev = Some(d);
                    } else {
                        let l = m - 1;
                        let t = Instant::now();
                        let f = fa.layouts[l].1.distance(
                            &fb.layouts[l].1,
                            &Isometry3::identity(),
                            pose,
                        )?;
                        row.fcl_us[l].push(us(t.elapsed()));
                        if l == 0 {
                            fcl_balanced = Some(f.distance);
                        }
                    }
                }
                let (d, f) = (
                    rev.expect("revdist ran this frame"),
                    fcl_balanced.expect("FCL ran this frame"),
                );
                row.node_pairs += d.stats.node_pairs as f64;
                row.exact_leaves += d.stats.leaf_tests as f64;
                row.min_gap = row.min_gap.min(if d.overlap { -1.0 } else { d.value });
                let h = fa.layouts[0].0.bound + fb.layouts[0].0.bound;
                if !agrees_with_fcl(&d, f, h, pose, size) {
                    row.violations += 1;
                    eprintln!(
                        "violation: {a}-{b} eps {eps:e} frame {k}: revdist [{}, {}], FCL {f} +- {h}",
                        d.lower, d.upper
                    );
                }
                bar.inc(1);
            }
            row.node_pairs /= n as f64;
            row.exact_leaves /= n as f64;
            row.best = (0..layouts)
                .min_by(|&x, &y| mean(&row.fcl_us[x]).total_cmp(&mean(&row.fcl_us[y])))
                .unwrap_or(0);
            // Blocked: each method alone over the whole motion, as a simulation loop over
            // one pair runs it (answers were cross-checked above).
            let mut cache = QueryCache::default();
            let times = time_each(poses[..n].iter().map(|pose| sb.with_pose(*pose)), |posed| {
                std::hint::black_box(distance_cached(sa, &posed, &opts, &mut cache));
                Ok::<(), Box<dyn std::error::Error>>(())
            })?;
            row.rev_blocked_mean = mean(&times);
            let l = row.best;
            let times = time_each(&poses[..n], |pose| {
                std::hint::black_box(fa.layouts[l].1.distance(
                    &fb.layouts[l].1,
                    &Isometry3::identity(),
                    pose,
                )?);
                Ok::<(), Box<dyn std::error::Error>>(())
            })?;
            row.fcl_blocked_mean = mean(&times);
            rows.push(row);
        }
        bar.finish_and_clear();
        eprintln!(
            "motion eps {eps:.0e}: {} pairs, {n} frames each [{:.0} s]",
            args.pairs.len(),
            started.elapsed().as_secs_f64()
        );
    }

    std::fs::create_dir_all(&args.out)?;
    std::fs::write(args.out.join("motion.csv"), csv(&rows, &prov))?;
    let md = markdown(&rows, &prov, started.elapsed().as_secs_f64());
    std::fs::write(args.out.join("motion.md"), &md)?;
    for &eps in &args.eps {
        draw(&args.out, &rows, eps)?;
    }
    print!("{md}");
    let violations: usize = rows.iter().map(|r| r.violations).sum();
    if violations > 0 {
        return Err(format!("{violations} cross-check violations (see above)").into());
    }
    Ok(())
}

fn csv(rows: &[Row], prov: &Provenance) -> String {
    let mut s = prov.csv_preamble();
    s.push_str("pair,eps,frames,revdist_mean_us,revdist_median_us,fcl_obbrss_balanced_mean_us,fcl_obbrss_capped_mean_us,best_layout,fcl_best_mean_us,fcl_best_median_us,ratio_fcl_over_revdist_mean,triangles_best,mean_node_pairs,mean_leaf_tests,min_distance,violations,revdist_blocked_mean_us,fcl_best_blocked_mean_us,ratio_blocked\n");
    for r in rows {
        let lay = |l: usize| {
            r.fcl_us
                .get(l)
                .map(|v| format!("{:.2}", mean(v)))
                .unwrap_or_default()
        };
        let _ = writeln!(
            s,
            "{},{:e},{},{:.2},{:.2},{},{},{},{:.2},{:.2},{:.3},{},{:.1},{:.1},{:.3e},{},{:.2},{:.2},{:.3}",
            r.pair,
            r.eps,
            r.frames,
            mean(&r.rev_us),
            median(&r.rev_us),
            lay(0),
            lay(1),
            LAYOUT_NAMES[r.best],
            r.fcl_mean(),
            median(&r.fcl_us[r.best]),
            r.ratio(),
            r.triangles[r.best],
            r.node_pairs,
            r.exact_leaves,
            r.min_gap,
            r.violations,
            r.rev_blocked_mean,
            r.fcl_blocked_mean,
            r.fcl_blocked_mean / r.rev_blocked_mean
        );
    }
    s
}

fn markdown(rows: &[Row], prov: &Provenance, secs: f64) -> String {
    let mut s = String::from(
        "# The 15 model pairs in continuous motion (paper Figure 12)\n\n\
         Mean query time over a smooth random rigid motion per pair (gap between 1e-3 and 0.3, \
         often close), revdist at its default tolerance with warm starts against FCL \
         `BVHModel<OBBRSS>` on certified meshes of the same eps (the faster of two layouts), \
         one query at a time, methods interleaved per frame (so each query finds the caches \
         holding the other method's data: revdist's trees and code come from memory). Ratio = \
         FCL mean / revdist mean (> 1: revdist faster). Every revdist answer is checked against \
         FCL's. *Blocked*: each method alone over the whole motion, as a simulation loop over \
         one pair runs it.\n\n",
    );
    let eps_list: Vec<f64> = {
        let mut v: Vec<f64> = rows.iter().map(|r| r.eps).collect();
        v.dedup();
        v
    };
    for &e in &eps_list {
        let _ = writeln!(s, "![eps {e:.0e}](motion_eps{e:.0e}.svg)\n");
    }
    s.push_str("| pair | eps | frames | revdist mean / median (us) | FCL OBBRSS mean / median (us) | layout | ratio | blocked revdist / FCL mean (us) | blocked ratio | triangles A+B | node pairs | leaf tests | violations |\n| --- | --- | ---: | ---: | ---: | --- | ---: | ---: | ---: | ---: | ---: | ---: | ---: |\n");
    for r in rows {
        let _ = writeln!(
            s,
            "| {} | {:.0e} | {} | {:.0} / {:.0} | {:.0} / {:.0} | {} | {:.2}x | {:.0} / {:.0} | {:.2}x | {} | {:.0} | {:.1} | {} |",
            r.pair,
            r.eps,
            r.frames,
            mean(&r.rev_us),
            median(&r.rev_us),
            r.fcl_mean(),
            median(&r.fcl_us[r.best]),
            LAYOUT_NAMES[r.best],
            r.ratio(),
            r.rev_blocked_mean,
            r.fcl_blocked_mean,
            r.fcl_blocked_mean / r.rev_blocked_mean,
            r.triangles[r.best],
            r.node_pairs,
            r.exact_leaves,
            r.violations
        );
    }
    s.push('\n');
    for &e in &eps_list {
        let sel: Vec<&Row> = rows.iter().filter(|r| r.eps == e).collect();
        let ratios: Vec<f64> = sel.iter().map(|r| r.ratio()).collect();
        let behind: Vec<&str> = sel
            .iter()
            .filter(|r| r.ratio() < 1.0)
            .map(|r| r.pair.as_str())
            .collect();
        let blocked: Vec<f64> = sel
            .iter()
            .map(|r| r.fcl_blocked_mean / r.rev_blocked_mean)
            .collect();
        let _ = writeln!(
            s,
            "- eps {e:.0e}, blocked: speed-up {:.2}x to {:.2}x (median {:.2}x).",
            blocked.iter().copied().fold(f64::INFINITY, f64::min),
            blocked.iter().copied().fold(0.0, f64::max),
            median(&blocked)
        );
        let _ = writeln!(
            s,
            "- eps {e:.0e}: speed-up {:.2}x to {:.2}x (median {:.2}x); revdist behind on {}.",
            ratios.iter().copied().fold(f64::INFINITY, f64::min),
            ratios.iter().copied().fold(0.0, f64::max),
            median(&ratios),
            if behind.is_empty() {
                "no pair".to_string()
            } else {
                format!(
                    "{} of {} pairs ({})",
                    behind.len(),
                    sel.len(),
                    behind.join(", ")
                )
            }
        );
    }
    let _ = writeln!(
        s,
        "\nGenerated by `experiments/src/bin/motion.rs` in {secs:.0} s."
    );
    s.push_str(&prov.markdown_footer());
    s
}

/// Figure 12 at one eps: one group per pair, revdist and FCL, ratio above each group.
fn draw(out: &std::path::Path, rows: &[Row], eps: f64) -> Result<(), Box<dyn std::error::Error>> {
    let sel: Vec<&Row> = rows.iter().filter(|r| r.eps == eps).collect();
    let cats: Vec<String> = sel.iter().map(|r| r.pair.clone()).collect();
    let series = vec![
        BarSeries {
            name: "revdist".into(),
            values: sel.iter().map(|r| mean(&r.rev_us)).collect(),
        },
        BarSeries {
            name: "FCL OBBRSS".into(),
            values: sel.iter().map(|r| r.fcl_mean()).collect(),
        },
    ];
    let notes: Vec<String> = sel.iter().map(|r| format!("{:.1}x", r.ratio())).collect();
    grouped_bars_coloured(
        &out.join(format!("motion_eps{eps:.0e}.svg")),
        &format!("Pairs in continuous motion, eps {eps:.0e}: mean query time (speed-up above)"),
        &cats,
        &series,
        &[colour(0), colour(1)],
        "mean query time (us)",
        true,
        Some(&notes),
        (1500, 520),
    )
}
