//! Time of impact: revdist's certified search (`revdist::toi`) against FCL 0.7's continuous
//! collision (`fcl::continuousCollide` on two `fcl::InterpMotion`s with the frame origin as
//! reference point: the same motion as revdist's; the shim builds them because FCL 0.7's
//! `Transform3` overload leaves the reference point uninitialised) on certified
//! meshes of the same solids (`revdist::tessellate`, two-sided Hausdorff bound <= eps,
//! FCL `BVHModel<OBBRSS>`), in one run, over the 15 pairs of the paper's five models and
//! three eps.
//!
//! Motions (seeded, the same for both libraries): B starts outside A's bounding ball and
//! heads through A's centre turning by up to 1 rad (head-on); B turns in place by 1-2.5 rad
//! about its own origin near A (rotating); B passes by A at a random offset (passing, may
//! miss). Each library answers the same question: the first time the solids (meshes) touch.
//!
//! Judged against revdist's certified answers (never against each other's timings):
//! revdist with `D = 0` gives `[t_lower, t_upper]` (apart before, overlapping at `t_upper`);
//! a second search with `D = h_a + h_b` (the meshes' bounds) gives the time `t_mesh` before
//! which even the meshes must be apart (a mesh point is within `h` of the surface). FCL
//!
//! * *misses* a contact when revdist certifies one (`D = 0`) and FCL reports none;
//! * reports an *impossible* contact when its time of contact is before `t_mesh` (or it
//!   reports one where revdist certifies the solids stay more than `h_a + h_b` apart);
//! * otherwise agrees; the table gives the median `|toc_FCL - t_upper|`.
//!
//! Times are the searching thread's CPU time (`CLOCK_THREAD_CPUTIME_ID`; the CSV has the
//! wall-clock time too), median over the pair's motions: on a machine shared with other jobs
//! the wall clock measured the load (8x the CPU time in the run of the README). FCL
//! runs conservative advancement and its naive solver (`CCDC_NAIVE`: discrete checks at 100
//! evenly spaced times), both with FCL's default `toc_err = 1e-4`; revdist runs with its
//! default time tolerance 1e-6 and the trees' default query tolerance.
//!
//! The summary per eps gives revdist's median, p90, p99 and largest time, FCL conservative
//! advancement's median and misses, and the contact intervals' width in units of
//! `2 eps / closing speed` (the closing speed measured by two queries at tolerance `eps / 10`
//! shortly before `t_lower`, outside the timed search).
//!
//! Usage: `toi_bench [--motions N] [--eps E,...] [--seed S] [--out DIR] [--revdist-only]`.
//! Writes `DIR/toi_bench.csv`, `DIR/toi_bench.md` and `DIR/toi_bench.svg`; with
//! `--revdist-only` FCL (and the meshes) are skipped and only the summary is written.

use clap::Parser;
use experiments::baseline_mesh::obbrss_of;
use experiments::cli::{Eps, Out, Seed};
use experiments::driver::{self, DriverResult};
use experiments::plot::{grouped_bars, BarSeries};
use experiments::shapes::{centre, paper_pairs, profile};
use experiments::stats::{median, quantile};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::query::{try_distance, QueryOptions, Tolerance};
use revdist::solid::Solid;
use revdist::tessellate::CertifiedMesh;
use revdist::toi::{time_of_impact, Motion, ToiOptions, ToiOutcome};
use std::fmt::Write as _;
use std::sync::Arc;
use std::time::Instant;
use verify::timing::thread_cpu_us;

/// Runs `f`, returning its result, wall time and thread CPU time (microseconds).
fn timed<T>(f: impl FnOnce() -> T) -> (T, f64, f64) {
    let (w, c) = (Instant::now(), thread_cpu_us());
    let r = f();
    (r, w.elapsed().as_secs_f64() * 1e6, thread_cpu_us() - c)
}
use verify::baselines::fcl::{CcdSolver, FclMesh};

/// Default eps: the paper's 1e-3 and 1e-4, and 1e-2 (its 1e-5 meshes take seconds to build
/// per model and FCL's advancement re-transforms every vertex at every step).
const DEFAULT_EPS: [f64; 3] = [1e-2, 1e-3, 1e-4];
const DEFAULT_MOTIONS: usize = 3;
const SEED: u64 = 32;
/// FCL's default `toc_err` (`ContinuousCollisionRequest`).
const FCL_TOC_ERR: f64 = 1e-4;
/// Samples of FCL's naive solver.
const FCL_NAIVE_SAMPLES: u64 = 100;

#[derive(Parser, Debug)]
#[command(about = "Time of impact: revdist vs FCL 0.7 continuous collision")]
struct Args {
    /// Motions per pair and eps
    #[arg(long, default_value_t = DEFAULT_MOTIONS)]
    motions: usize,
    #[command(flatten)]
    eps: Eps,
    #[command(flatten)]
    seed: Seed,
    #[command(flatten)]
    out: Out,
    /// Skip FCL and the meshes (revdist's searches and the summary only)
    #[arg(long)]
    revdist_only: bool,
}

struct Rng(u64);
impl Rng {
    fn unit(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.unit()
    }
    fn dir(&mut self) -> Vector3<f64> {
        let z = self.range(-1.0, 1.0);
        let phi = self.range(0.0, std::f64::consts::TAU);
        let r = (1.0 - z * z).sqrt();
        Vector3::new(r * phi.cos(), r * phi.sin(), z)
    }
}

/// The motions of one pair: start and end poses of B (A stays at the identity).
fn motions(
    n: usize,
    (za, ra): (f64, f64),
    (zb, rb): (f64, f64),
    rng: &mut Rng,
) -> Vec<[Isometry3<f64>; 2]> {
    let ca = Point3::new(0.0, 0.0, za);
    let cb = Vector3::new(0.0, 0.0, zb);
    let place = |r: UnitQuaternion<f64>, c: Point3<f64>| {
        Isometry3::from_parts(Translation3::from(c.coords - r * cb), r)
    };
    (0..n)
        .map(|k| {
            let u = rng.dir();
            let r0 = UnitQuaternion::from_scaled_axis(rng.dir() * rng.range(0.0, 3.0));
            match k % 3 {
                0 => {
                    let r1 = UnitQuaternion::from_scaled_axis(rng.dir() * rng.range(0.0, 1.0)) * r0;
                    [
                        place(r0, ca + u * (ra + rb) * 1.1),
                        place(r1, ca - u * 0.2 * (ra + rb)),
                    ]
                }
                1 => {
                    let p0 = place(r0, ca + u * (ra + rb) * rng.range(0.4, 0.8));
                    let r1 = UnitQuaternion::from_scaled_axis(rng.dir() * rng.range(1.0, 2.5)) * r0;
                    [p0, Isometry3::from_parts(p0.translation, r1)]
                }
                _ => {
                    let w = u.cross(&rng.dir()).normalize();
                    let off = w * (ra + rb) * rng.range(0.2, 0.7);
                    let len = (ra + rb) * 1.2;
                    [place(r0, ca + off + u * len), place(r0, ca + off - u * len)]
                }
            }
        })
        .collect()
}

/// One motion's answers.
struct Run {
    /// Thread CPU time and wall time of revdist's search.
    revdist_us: f64,
    revdist_wall_us: f64,
    queries: usize,
    certificates: usize,
    /// `(t_upper - t_lower) * closing speed / (2 eps)` for a contact (NaN otherwise).
    width_ratio: f64,
    outcome: ToiOutcome,
    t_lower: f64,
    t_upper: Option<f64>,
    t_mesh: f64,
    /// Per FCL solver: (CPU us, collide, toc, supported, wall us).
    fcl: [(f64, bool, f64, bool, f64); 2],
}

struct Row {
    pair: String,
    eps: f64,
    triangles: usize,
    runs: Vec<Run>,
}

impl Row {
    fn median_us(&self, f: impl Fn(&Run) -> f64) -> f64 {
        median(&self.runs.iter().map(f).collect::<Vec<_>>())
    }
    /// (misses, impossible contacts, unsupported, median |toc - t_upper| over agreeing contacts)
    fn judge(&self, k: usize) -> (usize, usize, usize, f64) {
        let (mut miss, mut bad, mut unsup, mut diffs) = (0, 0, 0, Vec::new());
        for r in &self.runs {
            let (_, collide, toc, ok, _) = r.fcl[k];
            if !ok {
                unsup += 1;
                continue;
            }
            if r.outcome == ToiOutcome::Contact && !collide {
                miss += 1;
            } else if collide && toc < r.t_mesh {
                bad += 1;
            } else if let (true, Some(tu)) = (collide, r.t_upper) {
                diffs.push((toc - tu).abs());
            }
        }
        let d = if diffs.is_empty() {
            f64::NAN
        } else {
            median(&diffs)
        };
        (miss, bad, unsup, d)
    }
}

/// `(t_upper - t_lower) * c / (2 eps)` with `c` the closing speed just before `t_lower`:
/// the drop of the distance (queries at tolerance `eps / 10`) over a time `dt` in which it
/// changes by about `10 eps` at the speed bound.
fn width_ratio(
    sa: &Solid,
    sb: &Solid,
    mb: &Motion,
    r: &revdist::toi::TimeOfImpact,
    eps: f64,
) -> f64 {
    let Some(tu) = r.t_upper else {
        return f64::NAN;
    };
    let opts = QueryOptions {
        tolerance: Tolerance::Absolute(eps / 10.0),
        ..QueryOptions::default()
    };
    let value = |t: f64| {
        try_distance(sa, &sb.with_pose(mb.pose_at(t)), &opts).map_or(f64::NAN, |d| d.value)
    };
    let dt = (10.0 * eps / r.speed_bound).min(r.t_lower);
    if dt <= 0.0 {
        return f64::NAN;
    }
    let closing = (value(r.t_lower - dt) - value(r.t_lower)) / dt;
    (tu - r.t_lower) * closing.max(0.0) / (2.0 * eps)
}

fn measure(
    na: &str,
    nb: &str,
    eps: f64,
    n: usize,
    seed: u64,
    revdist_only: bool,
) -> Result<Row, Box<dyn std::error::Error>> {
    let (pa, pb) = (profile(na)?, profile(nb)?);
    let (ca, cb) = (centre(&pa), centre(&pb));
    if revdist_only {
        return measure_revdist(na, nb, pa, pb, eps, n, seed);
    }
    let mesh = |p: &revdist::profile::Profile| -> Result<(CertifiedMesh, FclMesh), Box<dyn std::error::Error>> {
        let (cm, _) = experiments::baseline_mesh::certified_mesh(p, eps, None)?;
        let m = obbrss_of(&cm)?;
        Ok((cm, m))
    };
    let (cma, fa) = mesh(&pa)?;
    let (cmb, fb) = mesh(&pb)?;
    let sa = Solid::from_profile(Arc::new(pa), eps)?;
    let sb = Solid::from_profile(Arc::new(pb), eps)?;
    let mut rng = Rng(seed ^ (na.len() as u64 * 131 + nb.len() as u64 * 7919) ^ eps.to_bits());
    let fixed = Motion::fixed(Isometry3::identity())?;
    let id = Isometry3::identity();
    let mut runs = Vec::new();
    for [b0, b1] in motions(n, ca, cb, &mut rng) {
        let mb = Motion::new(b0, b1)?;
        let (r, revdist_wall_us, revdist_us) =
            timed(|| time_of_impact(&sa, &fixed, &sb, &mb, &ToiOptions::default()));
        let r = r?;
        let mesh_opts = ToiOptions {
            contact_distance: cma.bound + cmb.bound,
            ..ToiOptions::default()
        };
        let rm = time_of_impact(&sa, &fixed, &sb, &mb, &mesh_opts)?;
        let mut fcl = [(0.0, false, 0.0, false, 0.0); 2];
        for (k, solver) in [CcdSolver::ConservativeAdvancement, CcdSolver::Naive]
            .into_iter()
            .enumerate()
        {
            let (out, wall, cpu) = timed(|| {
                fa.continuous_collide(
                    &fb,
                    [&id, &id],
                    [&b0, &b1],
                    solver,
                    FCL_NAIVE_SAMPLES,
                    FCL_TOC_ERR,
                )
            });
            let out = out?;
            fcl[k] = (cpu, out.collide, out.time_of_contact, out.supported, wall);
        }
        runs.push(Run {
            revdist_us,
            revdist_wall_us,
            queries: r.queries,
            certificates: r.certificates,
            width_ratio: width_ratio(&sa, &sb, &mb, &r, eps),
            outcome: r.outcome,
            t_lower: r.t_lower,
            t_upper: r.t_upper,
            t_mesh: if rm.outcome == ToiOutcome::Apart {
                f64::INFINITY
            } else {
                rm.t_lower
            },
            fcl,
        });
    }
    Ok(Row {
        pair: format!("{na}-{nb}"),
        eps,
        triangles: cma.mesh.triangles.len() + cmb.mesh.triangles.len(),
        runs,
    })
}

/// revdist's searches alone (`--revdist-only`).
fn measure_revdist(
    na: &str,
    nb: &str,
    pa: revdist::profile::Profile,
    pb: revdist::profile::Profile,
    eps: f64,
    n: usize,
    seed: u64,
) -> Result<Row, Box<dyn std::error::Error>> {
    let (ca, cb) = (centre(&pa), centre(&pb));
    let sa = Solid::from_profile(Arc::new(pa), eps)?;
    let sb = Solid::from_profile(Arc::new(pb), eps)?;
    let mut rng = Rng(seed ^ (na.len() as u64 * 131 + nb.len() as u64 * 7919) ^ eps.to_bits());
    let fixed = Motion::fixed(Isometry3::identity())?;
    let mut runs = Vec::new();
    for [b0, b1] in motions(n, ca, cb, &mut rng) {
        let mb = Motion::new(b0, b1)?;
        let (r, revdist_wall_us, revdist_us) =
            timed(|| time_of_impact(&sa, &fixed, &sb, &mb, &ToiOptions::default()));
        let r = r?;
        let wr = width_ratio(&sa, &sb, &mb, &r, eps);
        if std::env::var("TOI_DEBUG").is_ok() {
            eprintln!(
                "DBG {na}-{nb} {eps} {revdist_us:.0} q {} s {} c {} {:?} [{}, {:?}] w {wr:.2} L {}",
                r.queries, r.steps, r.certificates, r.outcome, r.t_lower, r.t_upper, r.speed_bound
            );
        }
        runs.push(Run {
            revdist_us,
            revdist_wall_us,
            queries: r.queries,
            certificates: r.certificates,
            width_ratio: wr,
            outcome: r.outcome,
            t_lower: r.t_lower,
            t_upper: r.t_upper,
            t_mesh: f64::NAN,
            fcl: [(f64::NAN, false, f64::NAN, false, f64::NAN); 2],
        });
    }
    Ok(Row {
        pair: format!("{na}-{nb}"),
        eps,
        triangles: 0,
        runs,
    })
}

/// The summary per eps (see the module doc).
fn summary(rows: &[Row], eps_list: &[f64], with_fcl: bool) -> Result<String, std::fmt::Error> {
    let mut md = String::from("| eps | searches | contacts | revdist median ms | p90 | p99 | max | queries (median) | certificates (median) | width / (2 eps / closing), median | max |");
    if with_fcl {
        md += " FCL CA median ms | FCL CA misses | FCL CA / revdist (medians) |";
    }
    md += "\n|---|---|---|---|---|---|---|---|---|---|---|";
    if with_fcl {
        md += "---|---|---|";
    }
    md += "\n";
    for &eps in eps_list {
        let runs: Vec<&Run> = rows
            .iter()
            .filter(|r| r.eps == eps)
            .flat_map(|r| &r.runs)
            .collect();
        let col = |f: &dyn Fn(&Run) -> f64| runs.iter().map(|r| f(r)).collect::<Vec<f64>>();
        let ms = col(&|r| r.revdist_us / 1e3);
        let widths: Vec<f64> = col(&|r| r.width_ratio)
            .into_iter()
            .filter(|w| w.is_finite())
            .collect();
        let contacts = runs
            .iter()
            .filter(|r| r.outcome == ToiOutcome::Contact)
            .count();
        write!(
            md,
            "| {eps:.0e} | {} | {contacts} | {:.3} | {:.3} | {:.3} | {:.3} | {:.0} | {:.0} | {:.2} | {:.2} |",
            runs.len(),
            median(&ms),
            quantile(&ms, 0.9),
            quantile(&ms, 0.99),
            quantile(&ms, 1.0),
            median(&col(&|r| r.queries as f64)),
            median(&col(&|r| r.certificates as f64)),
            median(&widths),
            quantile(&widths, 1.0),
        )?;
        if with_fcl {
            let fcl = median(&col(&|r| r.fcl[0].0 / 1e3));
            let misses = runs
                .iter()
                .filter(|r| r.fcl[0].3 && r.outcome == ToiOutcome::Contact && !r.fcl[0].1)
                .count();
            write!(md, " {fcl:.2} | {misses} | {:.1} |", fcl / median(&ms))?;
        }
        md += "\n";
    }
    Ok(md)
}

fn run(args: Args) -> DriverResult {
    let eps_list = args.eps.or(&DEFAULT_EPS);
    let seed = args.seed.or(SEED);
    let pairs = paper_pairs();
    let mut rows = Vec::new();
    for &eps in &eps_list {
        for (na, nb) in &pairs {
            rows.push(measure(na, nb, eps, args.motions, seed, args.revdist_only)?);
        }
    }
    let sum = summary(&rows, &eps_list, !args.revdist_only)?;
    if args.revdist_only {
        print!("{sum}");
        return Ok(());
    }
    let mut csv = String::from("pair,eps,motion,triangles,revdist_cpu_us,revdist_wall_us,queries,certificates,width_ratio,outcome,t_lower,t_upper,t_mesh,fcl_ca_cpu_us,fcl_ca_collide,fcl_ca_toc,fcl_ca_supported,fcl_ca_wall_us,fcl_naive_cpu_us,fcl_naive_collide,fcl_naive_toc,fcl_naive_supported,fcl_naive_wall_us\n");
    for row in &rows {
        for (i, r) in row.runs.iter().enumerate() {
            let f = |k: usize| {
                let (us, c, t, s, w) = row.runs[i].fcl[k];
                format!("{us:.1},{c},{t},{s},{w:.1}")
            };
            writeln!(
                csv,
                "{},{},{i},{},{:.1},{:.1},{},{},{:.3},{},{},{},{},{},{}",
                row.pair,
                row.eps,
                row.triangles,
                r.revdist_us,
                r.revdist_wall_us,
                r.queries,
                r.certificates,
                r.width_ratio,
                r.outcome.name(),
                r.t_lower,
                r.t_upper.map_or(String::new(), |t| t.to_string()),
                r.t_mesh,
                f(0),
                f(1)
            )?;
        }
    }
    let mut md = String::from("| pair | eps | triangles | revdist ms (CPU) | queries | contacts | FCL CA ms (CPU) | CA misses | CA impossible | CA median abs(toc - t_upper) | FCL naive ms (CPU) | naive misses | naive impossible |\n|---|---|---|---|---|---|---|---|---|---|---|---|---|\n");
    let (mut tot_miss, mut tot_bad, mut tot) = ([0; 2], [0; 2], 0);
    for row in &rows {
        let (m0, b0, u0, d0) = row.judge(0);
        let (m1, b1, _, _) = row.judge(1);
        tot_miss[0] += m0;
        tot_miss[1] += m1;
        tot_bad[0] += b0;
        tot_bad[1] += b1;
        tot += row.runs.len();
        let contacts = row
            .runs
            .iter()
            .filter(|r| r.outcome == ToiOutcome::Contact)
            .count();
        writeln!(
            md,
            "| {} | {:.0e} | {} | {:.2} | {:.0} | {}/{} | {:.2} | {} | {}{} | {:.1e} | {:.2} | {} | {} |",
            row.pair,
            row.eps,
            row.triangles,
            row.median_us(|r| r.revdist_us) / 1e3,
            row.median_us(|r| r.queries as f64),
            contacts,
            row.runs.len(),
            row.median_us(|r| r.fcl[0].0) / 1e3,
            m0,
            b0,
            if u0 > 0 { format!(" ({u0} unsupported)") } else { String::new() },
            d0,
            row.median_us(|r| r.fcl[1].0) / 1e3,
            m1,
            b1
        )?;
    }
    writeln!(
        md,
        "\nOver {tot} motions: FCL conservative advancement missed {} certified contacts and reported {} impossible ones; the naive solver missed {} and reported {} impossible ones. Times: median thread CPU time per search.",
        tot_miss[0], tot_bad[0], tot_miss[1], tot_bad[1]
    )?;
    writeln!(md, "\n## Per eps\n\n{sum}")?;
    let dir = &args.out.dir;
    std::fs::write(dir.join("toi_bench.csv"), csv)?;
    std::fs::write(dir.join("toi_bench.md"), &md)?;
    print!("{md}");
    // Figure: median time per search, one group per pair, revdist and FCL CA per eps.
    let cats: Vec<String> = pairs.iter().map(|(a, b)| format!("{a}-{b}")).collect();
    let mut series = Vec::new();
    for (name, k) in [("revdist", None), ("FCL CA", Some(0))] {
        for &eps in &eps_list {
            let values = cats
                .iter()
                .map(|c| {
                    rows.iter()
                        .find(|r| &r.pair == c && r.eps == eps)
                        .map_or(f64::NAN, |r| {
                            r.median_us(|x| k.map_or(x.revdist_us, |k| x.fcl[k].0)) / 1e3
                        })
                })
                .collect();
            series.push(BarSeries {
                name: format!("{name} {eps:.0e}"),
                values,
            });
        }
    }
    grouped_bars(
        &dir.join("toi_bench.svg"),
        "Time of impact per search: revdist (certified) vs FCL 0.7 conservative advancement",
        &cats,
        &series,
        "ms CPU per search (median)",
        true,
        None,
        (1400, 520),
    )?;
    Ok(())
}

fn main() {
    driver::run(run)
}
