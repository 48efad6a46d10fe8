//! How hard the oracle works: grid size, cell budget, seeds and the goal of its branch and
//! bound (module documentation of [`super`]).

/// How hard the oracle works.
#[derive(Debug, Clone, Copy)]
pub struct OracleOptions {
    /// Cell evaluations per direction in the branch and bound (after the initial grid).
    pub max_cells: usize,
    /// Stop splitting when `upper - lower <= tau_rel * scale` (scale: the larger profile).
    pub tau_rel: f64,
    /// Initial cell size relative to the source profile's size.
    pub initial_rel: f64,
    /// Local minimisations from the initial grid per direction.
    pub seeds: usize,
    /// Further local minimisations allowed during the branch and bound per direction.
    pub max_refinements: usize,
    /// Run the branch and bound at all (the quick mode only wants the upper estimate).
    pub bound: bool,
    /// The level the lower estimate must reach for its user (a campaign's check b needs it
    /// only up to the query's upper bound plus the slack): the branch and bound stops once
    /// every cell's bound reaches it, or once the realised upper estimate is at or below it
    /// (then no lower estimate can exceed it). Infinite: run to `upper - tau`.
    ///
    /// Without the branch and bound (quick mode) the goal is the level the realised upper
    /// estimate is compared with (a time-of-impact check asks whether some pair is closer
    /// than it, or the solids overlap): when the grid's cells, split best-first up to the
    /// grid's own size, prove the surfaces farther apart than `max(goal, 0)`, no local
    /// minimisation can realise a pair below the goal and the boundaries do not meet, so
    /// the minimisations are skipped; the grids' inside census (which sees nesting) stands.
    pub goal: f64,
}

impl OracleOptions {
    /// Thorough: tight lower estimate (used for the checks).
    pub fn full() -> Self {
        OracleOptions {
            max_cells: 30_000,
            tau_rel: 1e-4,
            initial_rel: 1.0 / 24.0,
            seeds: 6,
            max_refinements: 24,
            bound: true,
            goal: f64::INFINITY,
        }
    }

    /// Cheap: coarse grid and local minimisation only (used to place poses).
    pub fn quick() -> Self {
        OracleOptions {
            max_cells: 0,
            tau_rel: 1e-2,
            initial_rel: 1.0 / 12.0,
            seeds: 4,
            max_refinements: 0,
            bound: false,
            goal: f64::INFINITY,
        }
    }
}
