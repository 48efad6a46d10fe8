//! `verify penetration`: its flags and run ([`verify::penetration`]).

use super::require_positive_eps;
use clap::Args;

#[derive(Args)]
pub struct PenetrationArgs {
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
    /// Run only these case indices (comma separated, seeded as in the full campaign),
    /// instead of `0..count`.
    #[arg(long, value_delimiter = ',')]
    cases: Vec<usize>,
    #[arg(long, default_value = "target/verify-penetration")]
    out: std::path::PathBuf,
}

impl PenetrationArgs {
    pub fn run(self) {
        let Self {
            count,
            seed,
            eps,
            threads,
            oracle_every,
            cases,
            out,
        } = self;
        require_positive_eps(&eps);
        let opts = verify::penetration::Options {
            count,
            seed,
            eps,
            threads,
            out,
            oracle_every,
            cases,
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
}
