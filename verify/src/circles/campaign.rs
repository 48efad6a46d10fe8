//! `verify circles`: the catalogue and `count` random and scaled cases, tallied.

use super::cases::{catalogue_cases, random_case, scaled_case};
use super::check::run_case;
use super::summary::Summary;
use revdist::rng::SplitMix64;

/// Runs `count` random + scaled cases and the full catalogue (with `motions` rigid motions
/// per perturbed entry).
pub fn run(count: usize, seed: u64, motions: usize) -> Summary {
    let mut rng = SplitMix64(seed);
    let mut s = Summary::default();
    let trace = std::env::var_os("VERIFY_TRACE").is_some();
    for case in catalogue_cases(&mut rng, motions) {
        if trace {
            eprintln!("{}", case.label);
        }
        let o = run_case(&case);
        s.record(&case, &o);
    }
    for i in 0..count {
        let case = if i % 2 == 0 {
            random_case(&mut rng)
        } else {
            scaled_case(&mut rng)
        };
        let o = run_case(&case);
        s.record(&case, &o);
    }
    s
}
