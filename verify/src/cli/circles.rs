//! `verify circles` and `verify eight`: their flags and runs ([`verify::circles`]).

use clap::Args;

#[derive(Args)]
pub struct CirclesArgs {
    /// Number of random and scaled pairs (the catalogue is always included).
    #[arg(long, default_value_t = 100_000)]
    count: usize,
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Random rigid motions per perturbed catalogue entry.
    #[arg(long, default_value_t = 20)]
    motions: usize,
}

impl CirclesArgs {
    pub fn run(self) {
        let s = verify::circles::run(self.count, self.seed, self.motions);
        println!("{s}");
        if s.total().1 > 0 {
            std::process::exit(1);
        }
    }
}

#[derive(Args)]
pub struct EightArgs {
    #[arg(long, default_value_t = 2000)]
    count: usize,
    #[arg(long, default_value_t = 1)]
    seed: u64,
    /// Smallest separation of the 8 roots theta (radians) for a case to be printed.
    #[arg(long, default_value_t = 0.05)]
    min_gap: f64,
}

impl EightArgs {
    pub fn run(self) {
        verify::circles::print_eight(self.count, self.seed, self.min_gap)
    }
}
