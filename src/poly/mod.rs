//! Polynomial utilities: Bernstein (Bezier) form on [0, 1] and a real-root finder that keeps
//! even-multiplicity roots (used by the circle/circle binormal polynomial, paper Appendix A,
//! and by profile segmentation).
//!
//! The root finder follows the spirit of Machchhar & Elber 2016 ("Revisiting the problem of
//! zeros of univariate scalar Beziers"): Bernstein sign-variation (Descartes) tests prune and
//! isolate, a safeguarded Newton iteration converges on isolated roots. Roots of even
//! multiplicity produce no sign change, so they are found as sign changes of the derivative
//! where the polynomial itself vanishes to within its rounding-noise bound.

pub mod bernstein;
pub mod fixed;
pub mod minimize;
pub mod solve;

pub use bernstein::{odd_roots, roots, solve, Bernstein, RootSet};
pub use fixed::FixedVec;

#[cfg(test)]
mod tests;
