//! revdist beside its peers in one run (`docs/verification.md`, "Peers"): FCL 0.7, coal 3 and
//! parry3d 0.31 on the same certified meshes and exact primitives; the study is
//! [`experiments::peers`].
//!
//! Usage: `peers [--poses N] [--parry-poses N] [--eps E,...] [--pairs a-b,...] [--paper]
//! [--seed S] [--out DIR]`. Writes `DIR/peers.csv`, `DIR/peers_convex.csv`, `DIR/peers.md` and
//! `DIR/peers.svg` (default `figures`).

fn main() {
    experiments::driver::run(experiments::peers::run)
}
