//! The campaign: the pool, the fixed cases first, then `count` drawn cases over worker
//! threads sharing one tree per (shape, eps). Panics inside queries are caught and reported
//! with their location; a panic while placing a pose (an oracle bug) is a warning.

use super::cases::{make_case, Case, PoseKind};
use super::checked_query::run_case;
use super::panics::{panic_message, record_panic_location};
use super::pool::{build_pool, ShapeSet};
use super::regressions::regression_cases;
use super::report::Summary;
use super::tree_cache::TreeCache;
use std::path::PathBuf;
use std::sync::{Arc, Mutex};
use std::time::Instant;

/// Default tree eps values drawn from.
pub const DEFAULT_EPS: [f64; 4] = [1e-3, 1e-4, 1e-5, 1e-6];

/// Campaign settings.
#[derive(Debug, Clone)]
pub struct CampaignOptions {
    /// Random cases (the fixed regression cases come on top).
    pub count: usize,
    pub seed: u64,
    /// Tree eps values to draw from.
    pub eps: Vec<f64>,
    /// Where reproducers go.
    pub out: PathBuf,
    /// Worker threads (0: all cores).
    pub threads: usize,
    /// Random profiles in the pool (0: from the count).
    pub random_profiles: usize,
    /// Include the fixed regression cases.
    pub regressions: bool,
    /// Failures printed in full.
    pub print_failures: usize,
    /// Draw every solid from the balls, capsules and solid tori (`PRIMITIVE_PREFIX` shapes,
    /// `ring`, `sphere`, `capsule`), whose queries take the closed form of
    /// `revdist::query::closed_form` (a capsule against a solid torus the traversal).
    pub primitives: bool,
    /// Draw every solid from the shapes revdist certifies convex (the GJK path); ignored
    /// with `primitives`.
    pub convex: bool,
    /// Run only the cases of one shard: `(i, n)` keeps the cases whose index is `i` modulo
    /// `n` (the fixed cases first, then the drawn ones, as numbered without sharding), so
    /// that `n` runs with the same seed and count cover the campaign exactly once.
    pub shard: Option<(usize, usize)>,
}

impl CampaignOptions {
    /// The shapes the drawn cases come from.
    pub fn shape_set(&self) -> ShapeSet {
        match (self.primitives, self.convex) {
            (true, _) => ShapeSet::Primitives,
            (false, true) => ShapeSet::Convex,
            _ => ShapeSet::All,
        }
    }
}

impl Default for CampaignOptions {
    fn default() -> Self {
        CampaignOptions {
            count: 1000,
            seed: 1,
            eps: DEFAULT_EPS.to_vec(),
            out: PathBuf::from("target/verify-queries"),
            threads: 0,
            random_profiles: 0,
            regressions: true,
            shard: None,
            print_failures: 25,
            primitives: false,
            convex: false,
        }
    }
}

/// Runs the campaign. Panics inside queries are caught and reported as failures (the panic
/// hook is replaced by a silent one that records the location while the campaign runs).
pub fn run(opts: &CampaignOptions) -> Summary {
    let previous = std::panic::take_hook();
    std::panic::set_hook(Box::new(record_panic_location));
    let s = run_inner(opts);
    std::panic::set_hook(previous);
    s
}

fn run_inner(opts: &CampaignOptions) -> Summary {
    let start = Instant::now();
    let n_random = if opts.random_profiles > 0 {
        opts.random_profiles
    } else {
        (opts.count / 8).clamp(10, 200)
    };
    let shapes = Arc::new(build_pool(opts.seed, n_random));
    let mut ids: Vec<Option<Case>> = Vec::new();
    if opts.regressions {
        ids.extend(regression_cases(&shapes).into_iter().map(Some));
    }
    let n_fixed = ids.len();
    ids.extend((0..opts.count).map(|_| None));
    let threads = if opts.threads > 0 {
        opts.threads
    } else {
        std::thread::available_parallelism().map_or(2, |n| n.get())
    };
    let mine: Vec<usize> = match opts.shard {
        Some((i, n)) => (0..ids.len()).filter(|k| k % n == i).collect(),
        None => (0..ids.len()).collect(),
    };
    let trees = TreeCache::default();
    let next = std::sync::atomic::AtomicUsize::new(0);
    let results = Mutex::new(Vec::with_capacity(ids.len()));
    std::thread::scope(|scope| {
        for _ in 0..threads {
            scope.spawn(|| loop {
                let j = next.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                let Some(&i) = mine.get(j) else {
                    break;
                };
                let t0 = Instant::now();
                let case = match &ids[i] {
                    Some(c) => c.clone(),
                    None => {
                        let made = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
                            make_case(i - n_fixed, opts.seed, &shapes, &opts.eps, opts.shape_set())
                        }));
                        match made {
                            Ok(c) => c,
                            Err(e) => {
                                // An oracle bug, not a query failure: report and go on.
                                eprintln!(
                                    "warning: placing case {} panicked: {}",
                                    i - n_fixed,
                                    panic_message(e.as_ref())
                                );
                                continue;
                            }
                        }
                    }
                };
                let place_time = t0.elapsed();
                let mut r = run_case(case, &shapes, &trees);
                r.place_time = place_time;
                results.lock().expect("not poisoned").push(r);
            });
        }
    });
    let mut results = results.into_inner().expect("not poisoned");
    results.sort_by_key(|r| (r.case.kind != PoseKind::Regression, r.case.id));
    Summary {
        results,
        shapes,
        wall: start.elapsed(),
        out: opts.out.clone(),
    }
}
