//! Unit tests of the rational unit vectors and of the sample check.

use super::circle::rational_unit;
use super::{Key, Level, Sample};
use revdist::rng::SplitMix64;
use rug::Rational;

#[test]
fn rational_units_are_unit() {
    let mut rng = SplitMix64(3);
    for _ in 0..20 {
        let u = rational_unit(&mut rng);
        let n: Rational = u.iter().map(|c| Rational::from(c * c)).sum();
        assert_eq!(n, 1);
    }
}

#[test]
fn a_wrong_answer_fails_the_check() {
    let s = Sample {
        key: Key {
            level: Level::Solid,
            family: "touching",
            delta: Some(3),
        },
        variant: "sphere-sphere",
        seed: 0,
        exact: 1e-3,
        value: 1e-3 + 3e-5,
        abs_err: 3e-5,
        rel_err: 1e-5,
        bound: 2e-5,
        lower: 9e-4,
        upper: 1.1e-3,
        certified: true,
        seconds: 0.0,
        reproducer: None,
    };
    assert!(!s.ok());
    assert!(Sample {
        abs_err: 1e-6,
        ..s.clone()
    }
    .ok());
    assert!(!Sample {
        abs_err: 1e-6,
        certified: false,
        ..s
    }
    .ok());
}
