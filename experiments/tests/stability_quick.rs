//! A slice of the stability study (`experiments::stability`): every family,
//! delta = 0 and six sizes 1e-16..1e-1, checked against the same bounds as the full run.
//!
//! * Circle level (4 seeds per family and delta): `|d - d_exact| <= 64 u size` (u = 2^-53): the rounding of the inputs
//!   and of the solver's own frame change and evaluation, with a margin of 4 (derivation at
//!   `CIRCLE_REL_BOUND`).
//! * Solid level: `lower <= d_exact <= upper` (compared exactly in MPFR) and
//!   `|value - d_exact| <= eps_a + eps_b`, the certified query's contract.
//!
//! The closed forms themselves are checked against their construction: every family except
//! the nested one places the solids `delta` apart, so the exact distance must be `delta` up
//! to the rounding of the `f64` construction; nested solids have distance 0.
//!
//! Run: `cargo test --release -p experiments --test stability_quick`.

use experiments::stability::{
    circle_samples, delta_value, solid_sample, Config, Sample, Shapes, CIRCLE_FAMILIES,
    CIRCLE_REL_BOUND, SOLID_FAMILIES, UNIT_ROUNDOFF,
};
use rayon::prelude::*;

/// delta = 0 and six sizes over the whole range.
const DELTAS: [Option<i32>; 7] = [None, Some(16), Some(10), Some(7), Some(4), Some(2), Some(1)];

/// Tree accuracy of the solid cases (the full run's default).
const EPS: f64 = 1e-5;

/// Rounding of the f64 constructions of the solid cases (positions of size <= 3 built from
/// a few operations): the exact gap may differ from delta by this much.
const CONSTRUCTION_SLACK: f64 = 64.0 * UNIT_ROUNDOFF * 3.0;

fn failures(samples: &[Sample]) -> String {
    samples
        .iter()
        .filter(|s| !s.ok())
        .map(|s| s.describe())
        .collect::<Vec<_>>()
        .join("\n")
}

#[test]
fn circle_errors_stay_at_rounding_level() {
    assert_eq!(CIRCLE_REL_BOUND, 64.0 * UNIT_ROUNDOFF);
    let cfg = Config {
        seeds: 4,
        deltas: DELTAS.to_vec(),
        eps: EPS,
    };
    let samples = circle_samples(&cfg, None).expect("circle cases run");
    assert_eq!(samples.len(), CIRCLE_FAMILIES.len() * DELTAS.len() * 4);
    let bad = failures(&samples);
    assert!(bad.is_empty(), "circle cases above 64 u size:\n{bad}");
    // Every catalogue label of every family was exercised.
    for (_, labels) in CIRCLE_FAMILIES {
        for l in labels {
            assert!(samples.iter().any(|s| s.variant == *l), "{l} not run");
        }
    }
}

#[test]
fn solid_answers_are_certified_and_within_eps() {
    // Every variant of every family once at every delta (the variant index as the seed).
    let shapes = Shapes::new(EPS).expect("shapes build");
    let jobs: Vec<(usize, Option<i32>, usize)> = SOLID_FAMILIES
        .iter()
        .enumerate()
        .flat_map(|(fi, (_, variants))| {
            DELTAS
                .iter()
                .flat_map(move |&d| (0..variants.len()).map(move |vi| (fi, d, vi)))
        })
        .collect();
    let samples: Vec<Sample> = jobs
        .par_iter()
        .map(|&(fi, d, vi)| solid_sample(&shapes, fi, d, vi).expect("solid case runs"))
        .collect();
    let bad = failures(&samples);
    assert!(bad.is_empty(), "solid cases failing:\n{bad}");
    for (_, variants) in SOLID_FAMILIES {
        for v in variants {
            let n = samples.iter().filter(|s| s.variant == *v).count();
            assert_eq!(n, DELTAS.len(), "{v}");
        }
    }
    for s in &samples {
        assert_eq!(s.bound, 2.0 * EPS, "{}", s.describe());
        let expected = if s.key.family == "nested" {
            0.0
        } else {
            delta_value(s.key.delta)
        };
        // Tilted stacks have the gap d cos(d) = d - d^3 / 2 + ...
        assert!(
            (s.exact - expected).abs() <= CONSTRUCTION_SLACK + expected.powi(3),
            "reference is not the constructed gap: {}",
            s.describe()
        );
        if s.key.family == "nested" {
            assert_eq!(
                s.value,
                0.0,
                "nested solids have distance 0: {}",
                s.describe()
            );
        }
    }
}
