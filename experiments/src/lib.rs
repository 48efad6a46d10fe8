//! Shared pieces of the research drivers (the binaries under `src/bin/`), and the bodies of
//! the larger drivers (`fcl_bench`, `pareto`, `peers`, `penetration`, `stability`, `tails`):
//! a module folder each, whose binary is a thin `main`.

pub mod args;
pub mod baseline_mesh;
pub mod cli;
pub mod driver;
pub mod fcl_bench;
pub mod pareto;
pub mod peers;
pub mod penetration;
pub mod plot;
pub mod poses;
pub mod progress;
pub mod rng;
/// Provenance lines of every CSV (lives in `verify`, which writes reports too).
pub use verify::provenance;
pub mod shapes;
/// `--shard I/N` and `--merge DIR...` of the long drivers (lives in `verify`, whose
/// `crosscheck` has them too).
pub use verify::shard;
pub use verify::shard_record;
pub mod stability;
pub mod stats;
pub mod table;
pub mod tails;

pub use rng::{Draw, SplitMix};
