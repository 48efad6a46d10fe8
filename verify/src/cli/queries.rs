//! `verify queries` and `verify merge-queries`: their flags and runs ([`verify::queries`]).

use super::{parse_shard, require_positive_eps};
use clap::Args;

#[derive(Args)]
pub struct QueriesArgs {
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
    /// Draw every solid from the balls, capsules and solid tori (closed-form queries).
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
}

impl QueriesArgs {
    pub fn run(self) {
        let Self {
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
        } = self;
        require_positive_eps(&eps);
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
}

#[derive(Args)]
pub struct MergeQueriesArgs {
    /// The shards' output directories.
    #[arg(required = true)]
    dirs: Vec<std::path::PathBuf>,
}

impl MergeQueriesArgs {
    pub fn run(self) {
        match verify::queries::merge::merge(&self.dirs) {
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
        }
    }
}
