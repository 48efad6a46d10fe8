//! Exact reference for circle/circle binormals and minimum distance.
//!
//! Circle A is the canonical circle (centre 0, normal +z, radius `ra`); circle B has a
//! rational centre, a rational rotation (from an integer quaternion, so its axes are exact
//! rationals) and a rational radius. The half-angle binormal polynomial
//! `P(u) = |q|^2 (C . w')^2 - ra^2 (q . w'_xy)^2` (u = tan(theta/2), the same formulation as
//! `revdist::circle::poly8`, but over all of R in exact rationals) is built with `rug`;
//! a Sturm sequence counts its distinct real roots (theta = pi is the root at infinity,
//! detected by a vanishing leading coefficient); the roots of its square-free part are
//! isolated with Sturm counts and refined in MPFR, and the minimum distance is the least
//! point-to-circle distance over them, accurate far beyond 1e-30.

mod analyse;
mod pair;
mod poly;
mod roots;
mod rotation;
mod sturm;

pub use analyse::ExactResult;
pub use poly::RPoly;
pub use rotation::{rotation_from_quaternion, rotation_from_rational_quaternion};
pub use sturm::{count_real_roots, sturm};

use rug::Rational;

/// MPFR working precision (bits) for root refinement and distances: 1e-30 needs ~100 bits;
/// 256 leave ample room for cancellation in the distance formula.
pub const PREC: u32 = 256;

/// Rational 3-vector.
pub type RVec = [Rational; 3];

/// A circle pair with exact data, A canonical.
#[derive(Debug, Clone)]
pub struct ExactPair {
    pub ra: Rational,
    pub c: RVec,
    pub u: RVec,
    pub v: RVec,
    pub rb: Rational,
}
