//! Penetration depth (`revdist::query::penetration`, docs/architecture.md "Signed distance
//! and penetration depth"): the certified interval's width, time and coal 3's EPA depths; the
//! study is [`experiments::penetration`].
//!
//! Usage: `penetration [--poses N] [--coal-poses N] [--eps E,...] [--seed S] [--paper]
//! [--out DIR]`; writes `DIR/penetration.csv`, `.md` and `.svg`.

fn main() {
    experiments::driver::run(experiments::penetration::run)
}
