//! One row of the table (one (pair, eps) work unit of `--shard`) and the faster FCL BV and
//! speed ratios it derives.

/// One row of the table: one work unit (pair, eps) of `--shard`.
#[derive(Default)]
pub(super) struct Row {
    pub(super) pair: String,
    pub(super) eps: f64,
    pub(super) poses: usize,
    pub(super) rev_trees: (f64, f64),
    pub(super) rev_exact: (f64, f64),
    /// Per layout: (OBBRSS median, RSS median).
    pub(super) fcl: Vec<(f64, f64)>,
    /// Warm medians (the query repeated at once on the same pose): revdist at the default
    /// tolerance, and FCL OBBRSS and RSS per layout.
    pub(super) rev_trees_warm: f64,
    pub(super) fcl_obbrss_warm: Vec<f64>,
    pub(super) fcl_rss_warm: Vec<f64>,
    /// Blocked medians (each method alone over all poses in a row): revdist, FCL OBBRSS per
    /// layout, and FCL RSS in its faster cold layout (`best_rss`).
    pub(super) rev_trees_blocked: f64,
    pub(super) fcl_obbrss_blocked: Vec<f64>,
    pub(super) fcl_rss_blocked: f64,
    pub(super) best_obbrss: usize,
    pub(super) best_rss: usize,
    pub(super) tris: Vec<usize>,
    pub(super) h_sum: Vec<f64>,
    pub(super) rev_build_ms: f64,
    pub(super) mesh_ms: Vec<f64>,
    pub(super) obbrss_build_ms: Vec<f64>,
    pub(super) rss_build_ms: Vec<f64>,
    pub(super) rev_bytes: usize,
    pub(super) rev_tree_bytes: usize,
    pub(super) obbrss_bytes: Vec<usize>,
    pub(super) rss_bytes: Vec<usize>,
    pub(super) max_width: f64,
    pub(super) violations: usize,
}

crate::shard_record!(Row {
    pair,
    eps,
    poses,
    rev_trees,
    rev_exact,
    fcl,
    rev_trees_warm,
    fcl_obbrss_warm,
    fcl_rss_warm,
    rev_trees_blocked,
    fcl_obbrss_blocked,
    fcl_rss_blocked,
    best_obbrss,
    best_rss,
    tris,
    h_sum,
    rev_build_ms,
    mesh_ms,
    obbrss_build_ms,
    rss_build_ms,
    rev_bytes,
    rev_tree_bytes,
    obbrss_bytes,
    rss_bytes,
    max_width,
    violations,
});

/// FCL's two bounding-volume types, as the tables name them.
pub(super) const BV_NAMES: [&str; 2] = ["OBBRSS", "RSS"];

/// The faster of FCL's two BVs given their times `(OBBRSS, RSS)`: its index in [`BV_NAMES`]
/// and its time (OBBRSS on a tie).
fn faster_bv((obbrss, rss): (f64, f64)) -> (usize, f64) {
    if rss < obbrss {
        (1, rss)
    } else {
        (0, obbrss)
    }
}

impl Row {
    /// FCL OBBRSS's and RSS's cold medians in their faster layouts.
    pub(super) fn best_obbrss_us(&self) -> f64 {
        self.fcl[self.best_obbrss].0
    }
    pub(super) fn best_rss_us(&self) -> f64 {
        self.fcl[self.best_rss].1
    }
    /// The faster FCL BV cold (each BV in its faster layout): index in [`BV_NAMES`], median.
    pub(super) fn faster(&self) -> (usize, f64) {
        faster_bv((self.best_obbrss_us(), self.best_rss_us()))
    }
    /// The layout of the faster FCL BV cold.
    pub(super) fn faster_layout(&self) -> usize {
        [self.best_obbrss, self.best_rss][self.faster().0]
    }
    /// The faster FCL BV warm and blocked (each BV in its faster cold layout).
    pub(super) fn faster_warm(&self) -> (usize, f64) {
        faster_bv((
            self.fcl_obbrss_warm[self.best_obbrss],
            self.fcl_rss_warm[self.best_rss],
        ))
    }
    pub(super) fn faster_blocked(&self) -> (usize, f64) {
        faster_bv((
            self.fcl_obbrss_blocked[self.best_obbrss],
            self.fcl_rss_blocked,
        ))
    }
    /// The faster FCL BV over revdist (default tolerance), cold, warm and blocked.
    pub(super) fn ratio(&self) -> f64 {
        self.faster().1 / self.rev_trees.0
    }
    pub(super) fn warm_ratio(&self) -> f64 {
        self.faster_warm().1 / self.rev_trees_warm
    }
    pub(super) fn blocked_ratio(&self) -> f64 {
        self.faster_blocked().1 / self.rev_trees_blocked
    }
}
