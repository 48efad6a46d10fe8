//! `verify queries`: a campaign of certified distance queries checked against the oracle.
//!
//! Cases pair built-in models (the exact ones and the freeform variants `pawn_ff`, ...),
//! frames of the deforming model M_t (every 0.05) and seeded random freeform profiles
//! ([`crate::random_profiles`]) under poses of every kind: far (translation ~1e3 and ~1e6),
//! separated, near-touching (gaps 1e-2..1e-7), touching (gap 0), overlapping, nested (a small
//! solid inside a large one, deep or near the wall), coincident (same solid, same pose), corner
//! contacts (a quarter of the cases, gaps 0, +-1e-13..1e-5 and overlaps), with
//! tree eps in 1e-3..1e-6, some with a tolerance or refined witnesses. Cases that failed
//! before the certificates were made rigorous and the failures found against earlier cores
//! (frozen with their profiles in `verify/regressions/`) come first.
//!
//! * `pool.rs`: the shapes cases draw from;
//! * `pose_spec.rs`: a pose of B as `revdist distance` reads it;
//! * `cases.rs`: what a case is and how one is drawn from the seed;
//! * `placement.rs`: poses that aim at a gap (Newton on the translation, the oracle's quick mode);
//! * `corners.rs`: corner contacts (a corner circle of A against a corner, an axis end or a
//!   smooth point of B);
//! * `frozen.rs`: the fixed cases' list `verify/regressions/campaign-cases.txt` and the random
//!   profiles frozen beside it;
//! * `regressions.rs`: the fixed cases, on the pool's shapes;
//! * `checked_query.rs`: one query, its oracle and its checks (cold and warm-started);
//! * `tree_cache.rs`: the trees, built once per (shape, eps) and shared by the workers;
//! * `panics.rs`: a caught panic's message and location;
//! * `run.rs`: the campaign over worker threads, with panics caught;
//! * `report.rs`: the summary, reproducers and the report text.

mod cases;
mod checked_query;
mod corners;
mod frozen;
pub mod merge;
mod panics;
mod placement;
mod pool;
mod pose_spec;
mod regressions;
mod report;
mod run;
mod tree_cache;

pub use cases::{make_case, Case, PoseKind};
pub use checked_query::{single, CaseResult};
pub use pool::{
    build_pool, pool_shape, pool_shape_names, straight_span_profile, Shape, ShapeSet,
    FROZEN_PREFIX, PRIMITIVE_PREFIX,
};
pub use pose_spec::PoseSpec;
pub use regressions::regression_cases;
pub use report::Summary;
pub use run::{run, CampaignOptions, DEFAULT_EPS};
