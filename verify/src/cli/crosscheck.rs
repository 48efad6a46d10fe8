//! `verify crosscheck`: its flags, the checks of their values, and the run, whole or in
//! shards ([`verify::crosscheck`]).

use clap::Args;

#[derive(Args)]
pub struct CrosscheckArgs {
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
}

impl CrosscheckArgs {
    pub fn run(self) {
        let Self {
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
        } = self;
        std::process::exit(crosscheck_command(
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
        ))
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
