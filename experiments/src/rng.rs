//! The drivers' random draws: the shared seeded generator (`revdist::rng::SplitMix64`,
//! under the name `SplitMix` the drivers use) and the two geometric draws the drivers'
//! seeds were written with, which no other user of the generator shares.

use nalgebra::{UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;

/// The shared generator, under the drivers' name for it.
pub use revdist::rng::SplitMix64 as SplitMix;

/// Below this norm a candidate of [`Draw::unit_vector`] is drawn again (its direction would
/// come from a point too close to the centre for a well-rounded normalisation).
const MIN_NORM: f64 = 1e-3;

/// The drivers' unit vector and rotation (methods, so that `rng.unit_vector()` reads as
/// before; import the trait with the generator).
pub trait Draw {
    /// A unit vector uniform on the sphere: a point uniform in the unit ball by rejection
    /// from the cube [-1, 1)^3, normalised.
    fn unit_vector(&mut self) -> Vector3<f64>;
    /// A rotation about a direction from [`Draw::unit_vector`] by an angle uniform in
    /// [-pi, pi).
    fn rotation(&mut self) -> UnitQuaternion<f64>;
}

impl Draw for SplitMix64 {
    fn unit_vector(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                2.0 * self.next_f64() - 1.0,
                2.0 * self.next_f64() - 1.0,
                2.0 * self.next_f64() - 1.0,
            );
            let n = v.norm();
            if n > MIN_NORM && n <= 1.0 {
                return v / n;
            }
        }
    }

    fn rotation(&mut self) -> UnitQuaternion<f64> {
        let axis = nalgebra::Unit::new_normalize(self.unit_vector());
        UnitQuaternion::from_axis_angle(&axis, std::f64::consts::PI * (2.0 * self.next_f64() - 1.0))
    }
}
