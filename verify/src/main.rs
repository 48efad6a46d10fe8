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
    }
}
