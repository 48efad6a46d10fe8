//! `verify`: cross-checks of revdist against independent references.

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "verify", about = "Independent checks of revdist")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Circle/circle minimum distance and binormal counts against exact arithmetic.
    Circles {
        /// Number of random and scaled pairs (the catalogue is always included).
        #[arg(long, default_value_t = 100_000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Random rigid motions per perturbed catalogue entry.
        #[arg(long, default_value_t = 20)]
        motions: usize,
    },
    /// Search random rational pairs for exactly 8 binormals (exact Sturm count) and print
    /// them as pinned test vectors.
    Eight {
        #[arg(long, default_value_t = 2000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Smallest separation of the 8 roots theta (radians) for a case to be printed.
        #[arg(long, default_value_t = 0.05)]
        min_gap: f64,
    },
    /// Certified distance queries against the independent oracle: built-in
    /// models, M_t frames and random freeform profiles under far, separated, near-touching,
    /// touching, overlapping, nested and coincident poses.
    Queries {
        /// Random cases (the fixed regression cases come on top).
        #[arg(long, default_value_t = 1000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Tree eps values to draw from, comma separated.
        #[arg(long, value_delimiter = ',', default_values_t = verify::queries::DEFAULT_EPS.to_vec())]
        eps: Vec<f64>,
        /// Directory for reproducers (random profiles as TOML, failures.jsonl).
        #[arg(long, default_value = "target/verify-queries")]
        out: std::path::PathBuf,
        /// Worker threads (default: all cores).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// Random profiles in the pool (default: count / 8, between 10 and 200).
        #[arg(long, default_value_t = 0)]
        random_profiles: usize,
        /// Failures printed in full.
        #[arg(long, default_value_t = 25)]
        show: usize,
        /// Leave out the fixed regression cases.
        #[arg(long)]
        no_regressions: bool,
        /// Draw every solid from the balls and solid tori (closed-form queries).
        #[arg(long)]
        primitives: bool,
        /// Draw every solid from the shapes certified convex (the GJK path).
        #[arg(long)]
        convex: bool,
        /// Run one shard I/N of the campaign (cases whose index is I modulo N; the same
        /// --seed and --count in every shard); merge the shards' --out directories with
        /// `verify merge-queries`.
        #[arg(long, value_parser = parse_shard, allow_hyphen_values = true)]
        shard: Option<(usize, usize)>,
    },
    /// Certified penetration depth and signed distance against independent references on
    /// the exact profiles: exact depths of balls, the oracle's separating translations and
    /// common points (verify/src/penetration/mod.rs). Exit status 1 on any violation.
    Penetration {
        #[arg(long, default_value_t = 1000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Tree eps values to draw from, comma separated.
        #[arg(long, value_delimiter = ',', default_values_t = vec![1e-3, 1e-4])]
        eps: Vec<f64>,
        /// Worker threads (default: all cores).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// Run the oracle's separation and common-point checks on every N-th case.
        #[arg(long, default_value_t = 1)]
        oracle_every: usize,
        #[arg(long, default_value = "target/verify-penetration")]
        out: std::path::PathBuf,
    },
    /// Adds up the shards of one `verify queries` campaign (their --out directories, each
    /// with a summary.json); exit status 1 when any case failed.
    MergeQueries {
        /// The shards' output directories.
        #[arg(required = true)]
        dirs: Vec<std::path::PathBuf>,
    },
    /// revdist against FCL meshes (certified tessellations) on the paper models and M_t
    /// frames, and against CGAL / libccd on convex pairs; writes crosscheck.md, .csv and
    /// failures.jsonl (verify/src/crosscheck/mod.rs states the agreement criterion).
    Crosscheck {
        /// Poses per mesh pair and eps (1000 gives the committed `figures/crosscheck-1000/`).
        #[arg(long, default_value_t = verify::crosscheck::options::DEFAULT_POSES)]
        poses: usize,
        /// Poses per convex pair and eps (0: no convex checks).
        #[arg(long, default_value_t = verify::crosscheck::options::DEFAULT_CONVEX_POSES)]
        convex_poses: usize,
        /// Eps of trees and meshes (repeat the flag or separate by commas).
        #[arg(long, value_delimiter = ',', default_values_t = verify::crosscheck::options::DEFAULT_EPS.to_vec())]
        eps: Vec<f64>,
        /// Poses per pair of the OpenCASCADE sweep (0: leave it out).
        #[arg(long, default_value_t = verify::crosscheck::options::DEFAULT_OCCT_POSES)]
        occt_poses: usize,
        /// Eps of revdist's trees judged against OCCT.
        #[arg(long, value_delimiter = ',', default_values_t = verify::crosscheck::options::DEFAULT_OCCT_EPS.to_vec())]
        occt_eps: Vec<f64>,
        /// Only the OCCT pairs whose names contain this (e.g. "pawn", "_ff", "morph").
        #[arg(long)]
        occt_only: Option<String>,
        /// Output directory of the report.
        #[arg(long, default_value = "figures/crosscheck")]
        out: std::path::PathBuf,
        /// A small slice (8 poses per mesh pair, 4 per convex pair) for a smoke test.
        #[arg(long)]
        quick: bool,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Worker threads (default: all cores).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// `--shard I/N`: only the jobs (blocks of poses of a pair and eps) numbered I modulo
        /// N, raw rows to OUT/crosscheck.rows.csv; `--merge DIR,...`: the report of the shards.
        #[command(flatten)]
        shard: verify::shard::Flags,
    },
    /// The lower-bound chain link by link: every node, piece, stage-1, subdivision, kernel
    /// and leaf-stage lower bound, the closed forms and the convex path on whole primitives,
    /// and the time of impact's motion, against MPFR on adversarial configurations
    /// (docs/verification.md); exit status 1 on any violation.
    Bounds {
        #[arg(long, default_value_t = 1000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Only this bound (repeat or separate by commas): sphere, torus, shell, slab, hull,
        /// node-sphere, node-torus, patch-lower, subdivision, sectors, kernel, leaf-stages,
        /// closed-form, convex, motion-rounding, motion-speed.
        #[arg(long, value_delimiter = ',')]
        bound: Vec<String>,
        /// Worker threads.
        #[arg(long, default_value_t = 1)]
        threads: usize,
    },
    /// Certified time of impact (`revdist toi`) against the oracle sampled densely along
    /// random motions (head-on, grazing, rotating, never touching, both moving) over the
    /// built-in models and M_t frames; exit status 1 when any motion fails.
    Toi {
        #[arg(long, default_value_t = 2000)]
        count: usize,
        #[arg(long, default_value_t = 1)]
        seed: u64,
        /// Tree eps values to draw from, comma separated.
        #[arg(long, value_delimiter = ',', default_values_t = verify::toi::DEFAULT_EPS.to_vec())]
        eps: Vec<f64>,
        /// Worker threads (default: all cores).
        #[arg(long, default_value_t = 0)]
        threads: usize,
        /// Run one shard I/N (cases whose index is I modulo N).
        #[arg(long, value_parser = parse_shard, allow_hyphen_values = true)]
        shard: Option<(usize, usize)>,
    },
    /// One query checked against the oracle: solids as profile files or by any shape name
    /// the campaigns print (built-in models, morph@T, straight-span, prim-..., frozen-...,
    /// rand-s<SEED>-<K>), B placed by --pose-b as in `revdist distance`.
    Oracle {
        a: String,
        b: String,
        #[arg(long, default_value = "{}")]
        pose_b: String,
        #[arg(long, default_value_t = 1e-4)]
        eps: f64,
        /// Target width of the query's interval (default: the trees' accuracy).
        #[arg(long)]
        tolerance: Option<f64>,
        /// Refine the query's witnesses on the exact surfaces.
        #[arg(long)]
        refine: bool,
    },
}

fn main() {
    let cli = Cli::parse();
    match cli.command {
        Command::Circles {
            count,
            seed,
            motions,
        } => {
            let s = verify::circles::run(count, seed, motions);
            println!("{s}");
            if s.total().1 > 0 {
                std::process::exit(1);
            }
        }
        Command::Eight {
            count,
            seed,
            min_gap,
        } => verify::circles::print_eight(count, seed, min_gap),
        Command::Queries {
            count,
            seed,
            eps,
            out,
            threads,
            random_profiles,
            show,
            no_regressions,
            primitives,
            convex,
            shard,
        } => {
            if eps.is_empty() || eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
                eprintln!("error: --eps needs positive numbers, got {eps:?}");
                std::process::exit(2);
            }
            let opts = verify::queries::CampaignOptions {
                count,
                seed,
                eps,
                out,
                threads,
                random_profiles,
                regressions: !no_regressions,
                print_failures: show,
                primitives,
                convex,
                shard,
            };
            let s = verify::queries::run(&opts);
            if let Err(e) = s
                .write_reproducers()
                .and_then(|()| s.write_summary(seed, count, shard))
            {
                eprintln!("error: writing reproducers to {}: {e}", opts.out.display());
            }
            print!("{}", s.report(show));
            if s.violation_count() > 0 {
                std::process::exit(1);
            }
        }
        Command::Bounds {
            count,
            seed,
            bound,
            threads,
        } => {
            let mut bounds = Vec::new();
            for name in &bound {
                match verify::bounds::Bound::from_name(name) {
                    Some(b) => bounds.push(b),
                    None => {
                        eprintln!("unknown bound {name:?}");
                        std::process::exit(2);
                    }
                }
            }
            let r = verify::bounds::run(&verify::bounds::Options {
                count,
                seed,
                bounds,
                threads,
            });
            println!("{r}");
            if r.violations() > 0 {
                std::process::exit(1);
            }
        }
        Command::Toi {
            count,
            seed,
            eps,
            threads,
            shard,
        } => {
            let opts = verify::toi::Options {
                count,
                seed,
                eps,
                shard,
                threads,
            };
            match verify::toi::run(&opts) {
                Ok(r) => {
                    print!("{}", r.summary());
                    std::process::exit(i32::from(!r.failures.is_empty()));
                }
                Err(e) => {
                    eprintln!("error: {e}");
                    std::process::exit(2);
                }
            }
        }
        Command::Penetration {
            count,
            seed,
            eps,
            threads,
            oracle_every,
            out,
        } => {
            if eps.is_empty() || eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
                eprintln!("error: --eps needs positive numbers, got {eps:?}");
                std::process::exit(2);
            }
            let opts = verify::penetration::Options {
                count,
                seed,
                eps,
                threads,
                out,
                oracle_every,
            };
            match verify::penetration::run(&opts) {
                Ok(s) if s.violations == 0 => {}
                Ok(_) => std::process::exit(1),
                Err(e) => {
                    eprintln!("error: {e}");
                    std::process::exit(2);
                }
            }
        }
        Command::MergeQueries { dirs } => match verify::queries::merge::merge(&dirs) {
            Ok((report, failed)) => {
                print!("{report}");
                if failed {
                    std::process::exit(1);
                }
            }
            Err(e) => {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        },
        Command::Crosscheck {
            poses,
            convex_poses,
            eps,
            occt_poses,
            occt_eps,
            occt_only,
            out,
            quick,
            seed,
            threads,
            shard,
        } => std::process::exit(crosscheck_command(
            (poses, convex_poses, occt_poses),
            eps,
            OcctSweep {
                eps: occt_eps,
                only: occt_only,
            },
            (&out, &shard),
            quick,
            seed,
            threads,
        )),
        Command::Oracle {
            a,
            b,
            pose_b,
            eps,
            tolerance,
            refine,
        } => {
            if let Err(e) = oracle_command(&a, &b, &pose_b, eps, tolerance, refine) {
                eprintln!("error: {e}");
                std::process::exit(2);
            }
        }
    }
}

/// Poses per mesh pair, per convex pair and per OCCT pair of `verify crosscheck --quick`.
const QUICK_POSES: (usize, usize, usize) = (8, 4, 4);

/// The OCCT sweep's eps and pair filter.
struct OcctSweep {
    eps: Vec<f64>,
    only: Option<String>,
}

/// Runs the cross-check and writes its report; the exit code (0 clean, 1 failures, 2 error).
fn crosscheck_command(
    (poses, convex_poses, occt_poses): (usize, usize, usize),
    eps: Vec<f64>,
    occt: OcctSweep,
    (out, shard): (&std::path::Path, &verify::shard::Flags),
    quick: bool,
    seed: u64,
    threads: usize,
) -> i32 {
    if eps.is_empty() || eps.iter().any(|e| !(e.is_finite() && *e > 0.0 && *e < 1.0)) {
        eprintln!("error: --eps needs numbers in (0, 1), got {eps:?}");
        return 2;
    }
    if occt.eps.is_empty()
        || occt
            .eps
            .iter()
            .any(|e| !(e.is_finite() && *e > 0.0 && *e < 1.0))
    {
        eprintln!(
            "error: --occt-eps needs numbers in (0, 1), got {:?}",
            occt.eps
        );
        return 2;
    }
    let (poses, convex_poses, occt_poses) = if quick {
        QUICK_POSES
    } else {
        (poses, convex_poses, occt_poses)
    };
    if poses == 0 && convex_poses == 0 && occt_poses == 0 {
        eprintln!("error: --poses, --convex-poses and --occt-poses are all 0: nothing to check");
        return 2;
    }
    let mut occt_pairs = verify::crosscheck::occt_pairs::occt_pairs();
    if let Some(only) = &occt.only {
        occt_pairs.retain(|(a, b)| a.contains(only.as_str()) || b.contains(only.as_str()));
        if occt_pairs.is_empty() {
            eprintln!("error: --occt-only '{only}' matches no OCCT pair");
            return 2;
        }
    }
    let opts = verify::crosscheck::Options {
        poses,
        convex_poses,
        occt_poses,
        occt_eps: occt.eps,
        occt_pairs,
        eps,
        seed,
        threads,
        shard: shard.shard,
        ..Default::default()
    };
    let report = match sharded_crosscheck(&opts, out, shard) {
        Ok(Some(r)) => r,
        Ok(None) => return 0, // a shard: its raw rows are written, the merge reports
        Err(e) => {
            eprintln!("error: {e}");
            return 2;
        }
    };
    print!("{}", report.summary());
    if let Err(e) = report.write(out) {
        eprintln!("error: writing the report to {}: {e}", out.display());
        return 2;
    }
    println!("report written to {}", out.display());
    i32::from(report.failures() > 0)
}

/// The cross-check's report: of the whole run, of the shards in `shard.merge` (nothing is
/// run), or `None` for a shard, whose records go to `out` as raw rows.
fn sharded_crosscheck(
    opts: &verify::crosscheck::Options,
    out: &std::path::Path,
    shard: &verify::shard::Flags,
) -> Result<Option<verify::crosscheck::Report>, String> {
    let pairs = |v: &[(String, String)]| {
        v.iter()
            .map(|(a, b)| format!("{a}-{b}"))
            .collect::<Vec<_>>()
            .join(",")
    };
    // What every shard must share (the report's provenance, and the pairs).
    let settings = [
        ("poses", opts.poses.to_string()),
        ("convex_poses", opts.convex_poses.to_string()),
        ("occt_poses", opts.occt_poses.to_string()),
        ("occt_eps", format!("{:?}", opts.occt_eps)),
        ("eps", format!("{:?}", opts.eps)),
        ("seed", opts.seed.to_string()),
        ("pairs", pairs(&opts.pairs)),
        ("convex_pairs", pairs(&opts.convex_pairs)),
        ("occt_pairs", pairs(&opts.occt_pairs)),
    ];
    let (records, units, threads, times) = if shard.merge.is_empty() {
        let r = verify::crosscheck::runner::run_units(opts)?;
        (r.records, r.units, r.threads, (r.prepare_time, r.wall))
    } else {
        (Vec::new(), 0, 0, Default::default())
    };
    if shard.is_shard() {
        std::fs::create_dir_all(out)
            .map_err(|e| format!("cannot create {}: {e}", out.display()))?;
    }
    let records = shard.finish((out, "crosscheck"), &settings, units, records)?;
    Ok(records.map(|r| verify::crosscheck::Report::new(r, opts.clone(), threads, times)))
}

/// A shape by any name the campaigns print (see `verify::queries::pool_shape`) or a profile
/// file.
fn load(spec: &str) -> Result<revdist::profile::Profile, String> {
    if let Some(p) = verify::queries::pool_shape(spec) {
        return p.map_err(|e| format!("'{spec}': {e}"));
    }
    let path = std::path::Path::new(spec);
    let looks_like_a_file = path.exists()
        || path.components().count() > 1
        || matches!(
            path.extension().and_then(|e| e.to_str()),
            Some("toml" | "json")
        );
    if looks_like_a_file {
        return revdist::profile_file::load_path(path).map_err(|e| format!("'{spec}': {e}"));
    }
    Err(format!(
        "unknown shape '{spec}': give a profile file (.toml or .json) or a shape name the \
         campaigns print: {}",
        verify::queries::pool_shape_names()
    ))
}

/// Parses `{"translation": [..], "rotation": [w, x, y, z]}` (both optional).
fn parse_pose(s: &str) -> Result<verify::queries::PoseSpec, String> {
    let nums = |key: &str, n: usize| -> Result<Option<Vec<f64>>, String> {
        let Some(i) = s.find(&format!("\"{key}\"")) else {
            return Ok(None);
        };
        let rest = &s[i..];
        let (open, close) = (
            rest.find('[').ok_or("missing '['")?,
            rest.find(']').ok_or("missing ']'")?,
        );
        let v: Vec<f64> = rest[open + 1..close]
            .split(',')
            .map(|x| x.trim().parse::<f64>().map_err(|e| format!("{key}: {e}")))
            .collect::<Result<_, _>>()?;
        if v.len() != n {
            return Err(format!("{key} needs {n} numbers"));
        }
        Ok(Some(v))
    };
    let t = nums("translation", 3)?.unwrap_or(vec![0.0; 3]);
    let r = nums("rotation", 4)?.unwrap_or(vec![1.0, 0.0, 0.0, 0.0]);
    Ok(verify::queries::PoseSpec {
        translation: [t[0], t[1], t[2]],
        rotation: [r[0], r[1], r[2], r[3]],
    })
}

fn oracle_command(
    a: &str,
    b: &str,
    pose: &str,
    eps: f64,
    tolerance: Option<f64>,
    refine: bool,
) -> Result<(), String> {
    let (pa, pb) = (load(a)?, load(b)?);
    let pose = parse_pose(pose)?;
    let (d, o, v, tq, to) = verify::queries::single(&pa, &pb, &pose, eps, tolerance, refine)?;
    println!(
        "query   value {:.12e} interval [{:.12e}, {:.12e}] overlap {} ({:.3} ms)",
        d.value,
        d.lower,
        d.upper,
        d.overlap,
        tq.as_secs_f64() * 1e3
    );
    println!(
        "        point_a {:?} point_b {:?}",
        d.point_a.coords.as_slice(),
        d.point_b.coords.as_slice()
    );
    println!(
        "oracle  surface distance in [{:.12e}, {:.12e}], overlap {} (a in b {}, b in a {}), min signed {:.3e}; {} cells, {} refinements{} ({:.1} ms)",
        o.lower,
        o.upper,
        o.overlap(),
        o.a_in_b,
        o.b_in_a,
        o.min_signed,
        o.cells,
        o.refinements,
        if o.budget_hit { ", budget hit" } else { "" },
        to.as_secs_f64() * 1e3
    );
    println!(
        "        point_a {:?} point_b {:?}",
        o.point_a.coords.as_slice(),
        o.point_b.coords.as_slice()
    );
    if let Some(p) = o.deep_point {
        println!(
            "        deepest boundary sample inside the other solid: {:?} (depth {:.3e})",
            p.coords.as_slice(),
            -o.min_signed
        );
    }
    if v.is_empty() {
        println!("no violations");
    }
    for x in &v {
        println!(
            "VIOLATION {}: {} (excess {:.3e})",
            x.check.name(),
            x.detail,
            x.excess
        );
    }
    Ok(())
}

/// `I/N` with `I < N`, for `--shard` ([`verify::shard::Shard`]).
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let s: verify::shard::Shard = text.parse()?;
    Ok((s.index, s.count))
}
