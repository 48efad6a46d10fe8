//! What accuracy costs: query time, build time and memory against the accuracy achieved, for
//! revdist and FCL 0.7 on the same seeded poses near contact in one run; the study is
//! [`experiments::pareto`].
//!
//! Usage: `pareto [--poses N] [--pairs a-b,...] [--paper] [--out DIR] [--eps E,...]
//! [--refine-eps E,...] [--fcl-eps E,...] [--max-triangles N]`. Writes `DIR/pareto.csv`,
//! `DIR/pareto.md` and `DIR/pareto_{time,build,memory}.svg` (default `figures`). Defaults:
//! 200 poses per pair (`--paper`: 1000), pairs pawn-cup, table-lightmill, torus-torus, a cap of
//! 2M predicted triangles (the coarsest FCL level is always built). About a minute on 2 cores.

fn main() {
    experiments::driver::run(experiments::pareto::run)
}
