//! Numerical stability near degenerate configurations: the error of
//! revdist's answers against exact references as a configuration is moved a distance
//! `delta = 10^-k` (k = 16..1) away from a degenerate one, and at the degenerate
//! configuration itself (`delta = 0`).
//!
//! # Circle level
//!
//! Each family takes entries of the degenerate catalogue of `verify circles`
//! ([`verify::circles::catalogue`], A the unit circle): coaxial (and concentric coplanar),
//! meridian, centre on the other's axis (D1, D1b, D6 and the larger circle's centre on the
//! smaller one's axis), Villarceau, and the two pinned pairs with exactly 8 binormals. A
//! perturbation of size `delta` moves B's centre by `delta` along a random direction, tilts
//! B's plane by an angle of about `delta` about a random axis and changes B's radius by
//! `+-delta`, all in exact rationals (directions are rational points of the unit sphere, the
//! tilt a rational quaternion); the pair is then moved by a random rational rigid motion
//! (translation up to 10 per coordinate). The double-precision solver
//! ([`mod@revdist::circle::min_distance`]) sees the rounded data; the reference is the exact
//! minimum distance of the rational data from the degree-8 polynomial in exact rationals
//! (Sturm isolation, MPFR refinement to ~1e-70: [`verify::circles::run_case`]), or the
//! catalogue's analytic value for the continua at `delta = 0`.
//!
//! The error is relative to the size of the data the solver sees,
//! `size = max(ra, rb, |C_b - C_a|) + |t|` (`t` the rigid motion's translation): rounding the
//! inputs alone moves the answer by a few `2^-53 size` (the distance is 1-Lipschitz in the
//! centres and `r`-Lipschitz in the normals). [`CIRCLE_REL_BOUND`] (`64 * 2^-53`) is the
//! bound checked; the solver's documented guarantee is looser, `1e-12 size`
//! ([`revdist::circle::TIE_REL_TOL`]: below it ties and continua are not resolved).
//!
//! # Solid level
//!
//! Certified queries ([`fn@revdist::query::distance`], default tolerance `eps_a + eps_b`) on
//! pairs whose distance has a closed form, derived beside each constructor in
//! `solid_case`; the closed form is evaluated in 256-bit MPFR from the exact values of the
//! `f64` data (rug), so the cancellation in e.g. `|c_b - c_a| - 1.5` at a gap of 1e-16 costs
//! nothing. The families: coaxial stacks (gap `delta` along a common axis), touching pairs
//! moved `delta` apart along a random direction, nested pairs whose inner surface is `delta`
//! inside the outer one (distance 0: solids, not surfaces), and pairs tangent along a whole
//! circle lifted `delta` apart. The relative pose `P` is built in `f64`; both solids are then
//! moved by a random rigid motion `M` (A at `M`, B at `M P`), so the query also sees the
//! rounding of `M^-1 (M P)`. The reference is the exact distance for `P`. Each answer must
//! satisfy `lower <= exact <= upper` (compared exactly) and `|value - exact| <= eps_a +
//! eps_b`.

mod circle;
mod exact;
mod jobs;
mod raw;
mod sample;
mod solid;
mod solid_case;
mod solids;
mod summary;
#[cfg(test)]
mod tests;

pub use circle::circle_sample;
pub use jobs::{
    circle_jobs, circle_samples, circle_samples_where, solid_jobs, solid_samples,
    solid_samples_where,
};
pub use sample::Sample;
pub use solid::solid_sample;
pub use solids::Shapes;
pub use summary::{summarise, Row};

use revdist::rng::SplitMix64;

/// Error type of this module.
pub type Error = Box<dyn std::error::Error + Send + Sync>;

/// Perturbation exponents: `delta = 10^-k` for k in 1..=16.
pub const DELTA_EXPONENTS: std::ops::RangeInclusive<i32> = 1..=16;

/// Unit roundoff of `f64`, `2^-53`.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// Circle-level bound on `|d - d_exact| / size` (see the module documentation for `size`):
/// `64 u`, `u = 2^-53`.
///
/// Why this value: the solver sees the rounded data. Rounding B's centre (coordinates of
/// magnitude <= size) moves it by <= sqrt(3) u size, rounding the axes moves B's points by
/// <= sqrt(6) u rb, and the distance is 1-Lipschitz in the points: ~5 u size. The solver then
/// maps the pair to a local frame (dot products of 3 terms: ~3 u size per coordinate, both
/// circles) and evaluates the distance at its polished roots (~4 u size): about 16 u size in
/// all, times a margin of 4. The solver's own documented guarantee is far looser,
/// [`revdist::circle::TIE_REL_TOL`] (`1e-12`: ties and continua below it are not resolved);
/// at 64 seeds per family and delta the measured worst is below 3 u.
pub const CIRCLE_REL_BOUND: f64 = 64.0 * UNIT_ROUNDOFF;

/// Default tree accuracy of the solid level.
pub const DEFAULT_EPS: f64 = 1e-5;

/// Which level a sample belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Level {
    Circle,
    Solid,
}

impl Level {
    pub fn name(self) -> &'static str {
        match self {
            Level::Circle => "circle",
            Level::Solid => "solid",
        }
    }
}

/// Circle-level families: (family, catalogue labels cycled over the seeds).
pub const CIRCLE_FAMILIES: [(&str, &[&str]); 5] = [
    ("coaxial", &["coaxial", "concentric coplanar"]),
    ("meridian", &["D2 meridian"]),
    (
        "centre on axis",
        &[
            "D1 centre on axis",
            "D1b centre on axis",
            "D6 centre on axis",
            "larger centre on smaller axis",
        ],
    ),
    ("Villarceau", &["D3 Villarceau"]),
    ("8 binormals", &["8 binormals A", "8 binormals B"]),
];

/// Solid-level families: (family, variants cycled over the seeds).
pub const SOLID_FAMILIES: [(&str, &[&str]); 4] = [
    (
        "coaxial stacks",
        &[
            "sphere on cylinder (off axis)",
            "cylinder on cylinder (tilted)",
            "cylinder on cone apex (tilted)",
            "ring on ring",
        ],
    ),
    (
        "touching",
        &["sphere-sphere", "sphere-torus", "cylinders side by side"],
    ),
    (
        "nested",
        &["ball in sphere", "ball in cylinder", "cone in cylinder"],
    ),
    (
        "tangent along a circle",
        &[
            "sphere in torus hole (off axis)",
            "ring around cone",
            "ring around ring",
        ],
    ),
];

/// What a run covers.
#[derive(Debug, Clone)]
pub struct Config {
    /// Seeds (random perturbation directions and rigid motions) per family and delta.
    pub seeds: usize,
    /// `Some(k)`: `delta = 10^-k`; `None`: the degenerate configuration itself.
    pub deltas: Vec<Option<i32>>,
    /// Tree accuracy of the solid level.
    pub eps: f64,
}

impl Config {
    /// Every delta in [`DELTA_EXPONENTS`] plus `delta = 0`.
    pub fn full(seeds: usize, eps: f64) -> Config {
        let mut deltas = vec![None];
        deltas.extend(DELTA_EXPONENTS.rev().map(Some));
        Config { seeds, deltas, eps }
    }
}

/// `delta` as a number (0 for the degenerate configuration).
pub fn delta_value(d: Option<i32>) -> f64 {
    d.map_or(0.0, |k| 10f64.powi(-k))
}

/// What a sample is grouped by: level, family and perturbation (`None`: delta = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    pub level: Level,
    pub family: &'static str,
    pub delta: Option<i32>,
}

/// A seed for case (family, variant, delta, seed), independent of the run's order.
fn case_seed(level: Level, family: usize, delta: Option<i32>, seed: usize) -> u64 {
    let mut g = SplitMix64(
        0x0057_ab1e
            ^ ((level as u64) << 56)
            ^ ((family as u64) << 48)
            ^ ((delta.map_or(0, |k| k as u64 + 1)) << 40)
            ^ seed as u64,
    );
    g.next_f64().to_bits()
}
