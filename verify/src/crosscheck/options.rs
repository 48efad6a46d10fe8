//! What a cross-check run covers: poses, eps, seed, threads and the shape pairs.

use super::shapes::{CONVEX_MODELS, MORPH_FRAMES, PAPER_MODELS};

/// Default poses per mesh pair and eps (about 4 minutes on 2 cores with the default eps).
pub const DEFAULT_POSES: usize = 100;
/// Default poses per convex pair and eps (CGAL's exact hull distance dominates).
pub const DEFAULT_CONVEX_POSES: usize = 20;
/// Default eps values (two decades, as in the committed reports).
pub const DEFAULT_EPS: [f64; 2] = [1e-3, 1e-4];
/// Default poses per pair of the OCCT sweep (`docs/verification.md`: at least 200 per pair). 45 pairs x 200
/// poses at 5-20 ms per OCCT query: about 1.5 minutes on 2 cores.
pub const DEFAULT_OCCT_POSES: usize = 200;
/// Eps of revdist's trees in the OCCT sweep: the default of the mesh check, and 1e-7, where
/// revdist's interval (2e-7 wide) is as sharp as OCCT's tolerance and 1e-6 gaps are resolved.
pub const DEFAULT_OCCT_EPS: [f64; 2] = [1e-4, 1e-7];
/// What to run.
#[derive(Debug, Clone)]
pub struct Options {
    /// Poses per mesh pair and eps.
    pub poses: usize,
    /// Poses per convex pair and eps (0 leaves the convex checks out).
    pub convex_poses: usize,
    pub eps: Vec<f64>,
    pub seed: u64,
    /// Worker threads (0: all cores).
    pub threads: usize,
    /// Mesh pairs (default: [`default_pairs`]).
    pub pairs: Vec<(String, String)>,
    /// Convex pairs (default: [`convex_pairs`]).
    pub convex_pairs: Vec<(String, String)>,
    /// Poses per pair of the OCCT sweep (0 leaves it out; one OCCT query per pose).
    pub occt_poses: usize,
    /// Eps of revdist's trees judged against each OCCT answer.
    pub occt_eps: Vec<f64>,
    /// Pairs of the OCCT sweep (default: [`super::occt_pairs::occt_pairs`]).
    pub occt_pairs: Vec<(String, String)>,
    /// Run only this shard's jobs ([`super::runner::run_units`] numbers them).
    pub shard: Option<crate::shard::Shard>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            poses: DEFAULT_POSES,
            convex_poses: DEFAULT_CONVEX_POSES,
            eps: DEFAULT_EPS.to_vec(),
            seed: 1,
            threads: 0,
            pairs: default_pairs(),
            convex_pairs: convex_pairs(),
            occt_poses: DEFAULT_OCCT_POSES,
            occt_eps: DEFAULT_OCCT_EPS.to_vec(),
            occt_pairs: super::occt_pairs::occt_pairs(),
            shard: None,
        }
    }
}

/// The 15 pairs (i <= j) of the paper models, then each M_t frame against each model.
pub fn default_pairs() -> Vec<(String, String)> {
    let mut v = Vec::new();
    for (i, a) in PAPER_MODELS.iter().enumerate() {
        for b in &PAPER_MODELS[i..] {
            v.push((a.to_string(), b.to_string()));
        }
    }
    for m in MORPH_FRAMES {
        for b in PAPER_MODELS {
            v.push((m.to_string(), b.to_string()));
        }
    }
    v
}

/// The 10 pairs (i <= j) of the convex models.
pub fn convex_pairs() -> Vec<(String, String)> {
    let mut v = Vec::new();
    for (i, a) in CONVEX_MODELS.iter().enumerate() {
        for b in &CONVEX_MODELS[i..] {
            v.push((a.to_string(), b.to_string()));
        }
    }
    v
}
