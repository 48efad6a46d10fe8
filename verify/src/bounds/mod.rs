//! `verify bounds`: the lower-bound chain of the distance query audited link by link against
//! MPFR (`docs/verification.md`, "The lower-bound chain, link by link").
//!
//! **Why the test can fail.** For any two surface points `p`, `q` the true distance is at
//! most `|p - q|`, so a lower bound `l` is wrong as soon as `l > |p - q| + allowance` for
//! one realised pair, whatever the true minimum is. The search ([`nearest`]) finds
//! near-minimising pairs in f64 (grid, pattern search, alternating projections, seeded with
//! the constructed contact and the exact kernel's witnesses); their distances are then
//! evaluated in MPFR at 256 bits from the exact f64 parameters ([`exact`]) and rounded up.
//! The allowance is the bound's own declared slack and nothing more: 0 for the bounds that
//! subtract [`revdist::tolerances::BOUND_SLACK`] themselves (every bound of
//! `query::bound`, stage 1, subdivision), the query's slack
//! ([`revdist::query::query_slack`]) for the values the traversal widens by it (the exact
//! kernel and the leaf stages). How close the realised pairs come to the minimum (the test's
//! power) is reported against the exact kernel.

pub mod chain;
pub mod checks;
pub mod exact;
pub mod motion;
pub mod nearest;
pub mod pieces;
pub mod report;
pub mod solids;

use pieces::FAMILIES;
use report::{Power, Report, Tally};
use revdist::rng::SplitMix64;

/// The links of the lower-bound chain checked here.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bound {
    /// `sphere_bound`: bounding spheres of two pieces' disks.
    Sphere,
    /// `torus_bound`: solid tori of two pieces' disks.
    Torus,
    /// `shell_bound`: spherical shells of arcs centred near the axis.
    Shell,
    /// `slab_bound`: height slabs.
    Slab,
    /// `hull_bound` and `hull_bound_until`: convex hulls of chords minus sagittas.
    Hull,
    /// `node_pair_bound` with `BoundKind::Sphere`.
    NodeSphere,
    /// `node_pair_bound` with `BoundKind::Torus` (spheres, node hulls, solid tori).
    NodeTorus,
    /// Stage 1: `patch_lower`.
    PatchLower,
    /// `patch_lower_bound`: the subdivision bound.
    Subdivision,
    /// `sector_lower_bound`: the subdivision into sectors.
    Sectors,
    /// `patch_distance` when not sampled: the exact kernel.
    Kernel,
    /// `LeafPair::bounds`, `tightened_lower`, `exact` lower fields.
    LeafStages,
    /// The closed forms of balls and solid tori (whole solids, [`solids`]).
    ClosedForm,
    /// The convex path's certified interval (whole convex solids, [`solids`]).
    Convex,
    /// The time of impact's motion: its rounding and its speed bound ([`motion`]).
    MotionRounding,
    MotionSpeed,
}

pub const BOUNDS: [Bound; 16] = [
    Bound::Sphere,
    Bound::Torus,
    Bound::Shell,
    Bound::Slab,
    Bound::Hull,
    Bound::NodeSphere,
    Bound::NodeTorus,
    Bound::PatchLower,
    Bound::Subdivision,
    Bound::Sectors,
    Bound::Kernel,
    Bound::LeafStages,
    Bound::ClosedForm,
    Bound::Convex,
    Bound::MotionRounding,
    Bound::MotionSpeed,
];

impl Bound {
    pub fn name(self) -> &'static str {
        match self {
            Bound::Sphere => "sphere",
            Bound::Torus => "torus",
            Bound::Shell => "shell",
            Bound::Slab => "slab",
            Bound::Hull => "hull",
            Bound::NodeSphere => "node-sphere",
            Bound::NodeTorus => "node-torus",
            Bound::PatchLower => "patch-lower",
            Bound::Subdivision => "subdivision",
            Bound::Sectors => "sectors",
            Bound::Kernel => "kernel",
            Bound::LeafStages => "leaf-stages",
            Bound::ClosedForm => "closed-form",
            Bound::Convex => "convex",
            Bound::MotionRounding => "motion-rounding",
            Bound::MotionSpeed => "motion-speed",
        }
    }

    /// Whether the bound is checked on whole solids or motions ([`solids`], [`motion`])
    /// rather than piece chains.
    pub fn whole_solids(self) -> bool {
        matches!(
            self,
            Bound::ClosedForm | Bound::Convex | Bound::MotionRounding | Bound::MotionSpeed
        )
    }

    pub fn from_name(s: &str) -> Option<Bound> {
        BOUNDS.iter().copied().find(|b| b.name() == s)
    }
}

/// Mixed into the seed for the whole-solid configurations' random stream.
const SOLIDS_STREAM: u64 = 0x0050_11d5;

/// A campaign's options.
#[derive(Debug, Clone)]
pub struct Options {
    /// Configurations (each one checks every selected bound).
    pub count: usize,
    pub seed: u64,
    /// Only these bounds (all when empty).
    pub bounds: Vec<Bound>,
    /// Worker threads.
    pub threads: usize,
}

/// Runs the campaign: configuration `k` is drawn from `SplitMix64(seed).fork(k)`, its
/// family in turn from [`FAMILIES`].
pub fn run(opts: &Options) -> Report {
    let start = std::time::Instant::now();
    let selected: Vec<Bound> = if opts.bounds.is_empty() {
        BOUNDS.to_vec()
    } else {
        opts.bounds.clone()
    };
    let threads = opts.threads.max(1);
    let pieces_wanted = selected.iter().any(|b| !b.whole_solids());
    let results: Vec<(Vec<(Bound, Tally)>, Power)> = std::thread::scope(|s| {
        let handles: Vec<_> = (0..threads)
            .map(|w| {
                let selected = selected.clone();
                s.spawn(move || {
                    let mut tallies: Vec<(Bound, Tally)> =
                        selected.iter().map(|b| (*b, Tally::default())).collect();
                    let mut power = Power::default();
                    let root = SplitMix64(opts.seed);
                    let solids_root = SplitMix64(opts.seed ^ SOLIDS_STREAM);
                    for k in (w..opts.count).step_by(threads) {
                        if pieces_wanted {
                            let mut rng = root.fork(k as u64);
                            let family = FAMILIES[k % FAMILIES.len()];
                            let cfg = pieces::draw(&mut rng, family);
                            let mut sink = checks::Sink {
                                tallies: &mut tallies,
                                power: &mut power,
                            };
                            checks::check(&cfg, &mut rng, &mut sink);
                        }
                        // The whole-solid links draw from their own stream, so that the
                        // piece configurations stay the same whichever bounds are asked.
                        for (b, t) in tallies.iter_mut() {
                            let mut rng = solids_root.fork(k as u64);
                            match b {
                                Bound::MotionRounding => motion::check(true, &mut rng, t),
                                Bound::MotionSpeed => motion::check(false, &mut rng, t),
                                _ => solids::check(*b, &mut rng, t),
                            }
                        }
                    }
                    (tallies, power)
                })
            })
            .collect();
        handles
            .into_iter()
            .map(|h| h.join().expect("worker"))
            .collect()
    });
    let mut report = Report {
        seed: opts.seed,
        tallies: selected.iter().map(|b| (*b, Tally::default())).collect(),
        ..Report::default()
    };
    for (tallies, power) in results {
        for ((_, t), (_, o)) in report.tallies.iter_mut().zip(&tallies) {
            t.merge(o);
        }
        report.power.merge(&power);
    }
    report.seconds = start.elapsed().as_secs_f64();
    report
}
