//! A seeded tail benchmark: queries tried as a new user would try them, each timed alone, to
//! see how far the slow tail of revdist's query times reaches; the study is
//! [`experiments::tails`].
//!
//! Usage: `tails [--poses N] [--eps E,...] [--seed S] [--out DIR]`.

fn main() {
    experiments::driver::run(experiments::tails::run)
}
