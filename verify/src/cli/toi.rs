//! `verify toi`: its flags and run ([`verify::toi`]).

use super::parse_shard;
use clap::Args;

#[derive(Args)]
pub struct ToiArgs {
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
}

impl ToiArgs {
    pub fn run(self) {
        let Self {
            count,
            seed,
            eps,
            threads,
            shard,
        } = self;
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
}
