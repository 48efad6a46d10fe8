//! revdist against FCL 0.7 at equal accuracy (`docs/protocols.md`), per model pair and eps on
//! the same seeded poses near contact; the study is [`experiments::fcl_bench`].
//!
//! Usage: `fcl_bench [--poses N] [--poses-1e-5 N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--seed S] [--out DIR]` (`--full` is an alias of `--paper`). Writes `DIR/fcl_bench.csv` and `DIR/fcl_bench.md` (default `figures`).

fn main() {
    experiments::driver::run(experiments::fcl_bench::run)
}
