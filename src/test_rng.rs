//! Seeded random numbers for the crate's tests, one module for every test in `src/`.
//!
//! Tests that draw random configurations depend on the exact sequence they draw (a different
//! sequence tests different configurations), so this module keeps each generator the tests
//! were written with, under one name per algorithm:
//! * [`Lcg`], Knuth's MMIX linear congruential generator (the top 53 bits of the state),
//!   used by the query's tests;
//! * [`SplitMix64`], the crate's shared generator ([`crate::rng`]), used by the circle tests
//!   and the one to use for new tests; the rejection-sampled unit vector and rigid motion
//!   the tests draw with it are defined here;
//! * [`XorShift64`] (Marsaglia 2003, shifts 13/7/17), used by the radial-field test.

use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use std::f64::consts::TAU;

/// Knuth's MMIX LCG; `f` is uniform in [0, 1).
pub(crate) struct Lcg(pub(crate) u64);

impl Lcg {
    /// The next number, uniform in [0, 1).
    pub(crate) fn f(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// The shared generator ([`crate::rng`]), under the name the tests import it by.
pub(crate) use crate::rng::SplitMix64;

/// The tests' own geometric draws, in the way their seeds were written with.
impl SplitMix64 {
    /// A random unit vector (rejection sampling in the unit ball's shell above 0.1).
    pub(crate) fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
                self.range(-1.0, 1.0),
            );
            let n = v.norm();
            if n > 0.1 && n <= 1.0 {
                return v / n;
            }
        }
    }

    /// A random rigid motion: a rotation about a random axis and a shift of length below
    /// `shift`.
    pub(crate) fn motion(&mut self, shift: f64) -> Isometry3<f64> {
        let axis = nalgebra::Unit::new_normalize(self.unit());
        let rot = UnitQuaternion::from_axis_angle(&axis, self.range(0.0, TAU));
        let t = self.unit() * self.range(0.0, shift);
        Isometry3::from_parts(Translation3::from(t), rot)
    }
}

/// Marsaglia's xorshift64 (shifts 13, 7, 17); `signed` is uniform in [-1, 1).
pub(crate) struct XorShift64(pub(crate) u64);

impl XorShift64 {
    /// The next number, uniform in [-1, 1).
    pub(crate) fn signed(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    }
}
