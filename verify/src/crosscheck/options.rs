//! What a cross-check run covers: poses, eps, seed, threads and the shape pairs.

use super::shapes::{CONVEX_MODELS, MORPH_FRAMES, PAPER_MODELS};

/// Default poses per mesh pair and eps (about 4 minutes on 2 cores with the default eps).
pub const DEFAULT_POSES: usize = 100;
/// Default poses per convex pair and eps (CGAL's exact hull distance dominates).
pub const DEFAULT_CONVEX_POSES: usize = 20;
/// Default eps values (two decades, as in the committed reports).
pub const DEFAULT_EPS: [f64; 2] = [1e-3, 1e-4];
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
