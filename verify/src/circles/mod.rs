//! `verify circles`: the double-precision circle solver (`revdist::circle`) against the exact
//! reference ([`crate::exact_circle`]) on random, scaled, near-touching and catalogued
//! (perturbed, rigidly moved) circle pairs with rational data.

mod campaign;
mod cases;
mod catalogue;
mod check;
mod eight;
mod rcircle;
mod summary;
#[cfg(test)]
mod tests;

pub use campaign::run;
pub use cases::{catalogue_cases, random_case, random_motion, scaled_case, Case};
pub use catalogue::{catalogue, CatalogueEntry};
pub use check::{run_case, Outcome};
pub use eight::print_eight;
pub use rcircle::RCircle;
pub use summary::Summary;

/// Pass threshold: |d_float - d_exact| <= REL_TOL * scale, scale = max(ra, rb, |Cb - Ca|)
/// (the accuracy the solver promises; `docs/verification.md`, section 3).
pub const REL_TOL: f64 = 1e-12;

/// Binormal counts are compared only when the circles are at least this far apart
/// (relative to the scale): at an intersection the binormal direction is undefined.
const COUNT_MIN_GAP: f64 = 1e-6;

/// Count mismatches are triaged by the smallest separation of the exact roots theta: below
/// this (radians) two roots are not resolvable in double precision. Near a double root
/// P ~ a (theta - theta0)^2 - a delta^2 / 4 for roots delta apart, and P carries absolute
/// noise nu ~ 64 eps (poly8::COEFF_NOISE_FACTOR) of its terms (~1e-14 at unit scale), so the
/// pair is visible only if a delta^2 / 4 > nu, i.e. delta > 2 sqrt(nu / a) ~ 2e-7 for a ~ 1;
/// moreover the solver sees the f64 rounding of the moved rational data (relative
/// perturbation ~1e-15), which alone moves a near-double root pair by ~sqrt(1e-15) ~ 3e-8
/// and can create or destroy the pair. 1e-6 covers both with a factor 5 margin for
/// curvature a < 1.
pub const CLUSTER_GAP: f64 = 1e-6;
