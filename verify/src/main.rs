//! `verify`: cross-checks of revdist against independent references.

mod cli;

use clap::Parser;

fn main() {
    cli::Cli::parse().command.run();
}
