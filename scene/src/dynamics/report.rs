//! What one step (or a frame's steps) did: query counts, certified minima, scalings and the
//! energy guard.

/// What one step (or a frame's steps) did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct StepReport {
    pub steps: usize,
    /// Queries by kind: static-dynamic, dynamic-dynamic.
    pub queries: [usize; 2],
    /// Static-static queries (never made; counted to prove it).
    pub static_static_queries: usize,
    /// Pairs looked at by the broad phase.
    pub pair_checks: usize,
    /// Second queries at the narrowest width, for pairs near the clearance.
    pub tight_queries: usize,
    /// Pairs within reach by their bounding spheres but skipped thanks to a carried bound.
    pub carried_skips: usize,
    /// Smallest certified lower bound of the step's queries (infinity without queries).
    pub min_lower: f64,
    /// Smallest certified lower bound of a pair not queried (bounding-sphere gap or carried
    /// bound).
    pub min_unqueried: f64,
    /// Bodies whose velocity was scaled by the per-body caps or the pairwise bounds.
    pub scaled: usize,
    /// Bodies stopped because a pair stayed violated (or started inside the clearance).
    pub stopped: usize,
    /// Steps in which the energy guard scaled all velocities.
    pub energy_guard: usize,
    /// Largest energy increase of a step (negative: it decreased).
    pub max_energy_increase: f64,
    /// Queries that reported overlap (must stay 0).
    pub overlaps: usize,
}

impl StepReport {
    /// An empty report (infinite minima, no energy change seen).
    pub fn new() -> StepReport {
        StepReport {
            min_lower: f64::INFINITY,
            min_unqueried: f64::INFINITY,
            max_energy_increase: f64::NEG_INFINITY,
            ..StepReport::default()
        }
    }

    pub(super) fn absorb(&mut self, o: &StepReport) {
        self.steps += o.steps;
        self.queries[0] += o.queries[0];
        self.queries[1] += o.queries[1];
        self.static_static_queries += o.static_static_queries;
        self.pair_checks += o.pair_checks;
        self.tight_queries += o.tight_queries;
        self.carried_skips += o.carried_skips;
        self.min_lower = self.min_lower.min(o.min_lower);
        self.min_unqueried = self.min_unqueried.min(o.min_unqueried);
        self.scaled += o.scaled;
        self.stopped += o.stopped;
        self.energy_guard += o.energy_guard;
        self.max_energy_increase = self.max_energy_increase.max(o.max_energy_increase);
        self.overlaps += o.overlaps;
    }
}
