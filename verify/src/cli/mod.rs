//! The `verify` command line: its subcommands, each with its flags and run in a module of
//! its own, and the argument parsers they share.

mod bounds;
mod circles;
mod crosscheck;
mod oracle;
mod penetration;
mod queries;
mod toi;

use clap::{Parser, Subcommand};

#[derive(Parser)]
#[command(name = "verify", about = "Independent checks of revdist")]
pub struct Cli {
    #[command(subcommand)]
    pub command: Command,
}

#[derive(Subcommand)]
pub enum Command {
    /// Circle/circle minimum distance and binormal counts against exact arithmetic.
    Circles(circles::CirclesArgs),
    /// Search random rational pairs for exactly 8 binormals (exact Sturm count) and print
    /// them as pinned test vectors.
    Eight(circles::EightArgs),
    /// Certified distance queries against the independent oracle: built-in
    /// models, M_t frames and random freeform profiles under far, separated, near-touching,
    /// touching, overlapping, nested and coincident poses.
    Queries(queries::QueriesArgs),
    /// Certified penetration depth and signed distance against independent references on
    /// the exact profiles: exact depths of balls, the oracle's separating translations and
    /// common points (verify/src/penetration/mod.rs). Exit status 1 on any violation.
    Penetration(penetration::PenetrationArgs),
    /// Adds up the shards of one `verify queries` campaign (their --out directories, each
    /// with a summary.json); exit status 1 when any case failed.
    MergeQueries(queries::MergeQueriesArgs),
    /// revdist against FCL meshes (certified tessellations) on the paper models and M_t
    /// frames, and against CGAL / libccd on convex pairs; writes crosscheck.md, .csv and
    /// failures.jsonl (verify/src/crosscheck/mod.rs states the agreement criterion).
    Crosscheck(crosscheck::CrosscheckArgs),
    /// The lower-bound chain link by link: every node, piece, stage-1, subdivision, kernel
    /// and leaf-stage lower bound, the closed forms and the convex path on whole primitives,
    /// and the time of impact's motion, against MPFR on adversarial configurations
    /// (docs/verification.md); exit status 1 on any violation.
    Bounds(bounds::BoundsArgs),
    /// Certified time of impact (`revdist toi`) against the oracle sampled densely along
    /// random motions (head-on, grazing, rotating, never touching, both moving) over the
    /// built-in models and M_t frames; exit status 1 when any motion fails.
    Toi(toi::ToiArgs),
    /// One query checked against the oracle: solids as profile files or by any shape name
    /// the campaigns print (built-in models, morph@T, straight-span, prim-..., frozen-...,
    /// rand-s<SEED>-<K>), B placed by --pose-b as in `revdist distance`.
    Oracle(oracle::OracleArgs),
}

impl Command {
    /// Runs the subcommand; exits the process with its status when that is not 0.
    pub fn run(self) {
        match self {
            Command::Circles(args) => args.run(),
            Command::Eight(args) => args.run(),
            Command::Queries(args) => args.run(),
            Command::Penetration(args) => args.run(),
            Command::MergeQueries(args) => args.run(),
            Command::Crosscheck(args) => args.run(),
            Command::Bounds(args) => args.run(),
            Command::Toi(args) => args.run(),
            Command::Oracle(args) => args.run(),
        }
    }
}

/// Exits with status 2 unless `eps` is a non-empty list of positive numbers (`--eps` of
/// `verify queries` and `verify penetration`).
fn require_positive_eps(eps: &[f64]) {
    if eps.is_empty() || eps.iter().any(|e| !(e.is_finite() && *e > 0.0)) {
        eprintln!("error: --eps needs positive numbers, got {eps:?}");
        std::process::exit(2);
    }
}

/// `I/N` with `I < N`, for `--shard` ([`verify::shard::Shard`]).
fn parse_shard(text: &str) -> Result<(usize, usize), String> {
    let s: verify::shard::Shard = text.parse()?;
    Ok((s.index, s.count))
}
