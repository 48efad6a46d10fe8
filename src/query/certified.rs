//! The one certified answer every path of the query returns: the closed form
//! ([`crate::query::closed_form`]), the convex path ([`crate::query::convex`]) and the search
//! with the front door's solid verdict ([`crate::query::search`]), and the counters of the
//! work it took.
//!
//! **The promise.** `lower <= d(A, B) <= upper` for the true solids, `value` in between;
//! `overlap = true` (then `value = lower = upper = 0`) only with a point certified inside
//! both, which is then both witnesses.

use nalgebra::{Isometry3, Point3};

/// A certified distance between two solids with its witnesses. A path answers in A's
/// frame; the query's entry points return it in the world frame (A's frame when A sits at
/// the identity, as in the CLI), under the name [`crate::query::Distance`].
#[derive(Debug, Clone, PartialEq)]
pub struct Certified {
    /// Best estimate, inside `[lower, upper]`.
    pub value: f64,
    /// Certified lower bound of the distance between the solids.
    pub lower: f64,
    /// Certified upper bound.
    pub upper: f64,
    /// Witness point on A (approximating surface, or exact surface after refinement).
    pub point_a: Point3<f64>,
    /// Witness point on B.
    pub point_b: Point3<f64>,
    /// The solids certainly overlap or nest (then `value = lower = upper = 0`).
    pub overlap: bool,
    pub stats: TraversalStats,
}

impl Certified {
    /// Certified overlap: `x` lies inside both true solids.
    pub fn overlap_at(x: Point3<f64>, stats: TraversalStats) -> Certified {
        Certified {
            value: 0.0,
            lower: 0.0,
            upper: 0.0,
            point_a: x,
            point_b: x,
            overlap: true,
            stats,
        }
    }

    /// The same answer with its witnesses mapped by `pose` (A's pose: from A's frame to the
    /// world).
    pub fn placed(self, pose: &Isometry3<f64>) -> Certified {
        Certified {
            point_a: pose * self.point_a,
            point_b: pose * self.point_b,
            ..self
        }
    }
}

/// Counters of one query: the search's work, or which fast path answered it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Serialize)]
pub struct TraversalStats {
    /// Node pairs popped from the queue.
    pub node_pairs: usize,
    /// Leaf pairs settled or bounded by stage-1 bounds alone ([`crate::query::search::leaf`]).
    pub leaf_bounds: usize,
    /// Leaf pairs whose stage-1 bound was sharpened by sub-piece bounds before any exact
    /// solve ([`crate::query::search::leaf::LeafPair::tightened_lower`]).
    pub leaf_tightened: usize,
    /// Leaf pairs that went to the exact stage (some of their patch pairs solved exactly).
    pub leaf_tests: usize,
    /// Patch pairs given cheap bounds (one circle/circle minimum each).
    pub patch_bounds: usize,
    /// Patch pairs solved exactly (up to 4 per leaf pair for biarcs).
    pub patch_tests: usize,
    /// Wall time in stage-1 leaf bounds, nanoseconds (the cost model's time split).
    pub leaf_bounds_ns: u64,
    /// Wall time in exact leaf solves (stage 2), nanoseconds.
    pub leaf_tests_ns: u64,
    /// Node-pair bounds computed.
    pub bound_tests: usize,
    /// Largest queue length.
    pub max_queue: usize,
    /// Queries answered by the closed form for balls and solid tori ([`crate::query::closed_form`]),
    /// or certified overlapping by the solids' inscribed balls and solid tori
    /// ([`crate::bvh::inscribed`]), without a traversal.
    pub closed_forms: usize,
    /// Queries answered by the convex fast path ([`crate::query::convex`]), without a
    /// traversal.
    pub convex_paths: usize,
    /// Patch pairs whose kernel needed a sampled scan, bounded below by subdivision
    /// ([`crate::query::search::leaf::subdivision`]).
    pub subdivided_pairs: usize,
    /// The budget stopped the traversal before the tolerance was reached.
    pub budget_exhausted: bool,
}

impl TraversalStats {
    /// Adds another traversal's counters (a query that traversed twice reports both).
    pub fn add(&mut self, o: &TraversalStats) {
        self.node_pairs += o.node_pairs;
        self.leaf_bounds += o.leaf_bounds;
        self.leaf_tightened += o.leaf_tightened;
        self.leaf_tests += o.leaf_tests;
        self.patch_bounds += o.patch_bounds;
        self.patch_tests += o.patch_tests;
        self.leaf_bounds_ns += o.leaf_bounds_ns;
        self.leaf_tests_ns += o.leaf_tests_ns;
        self.bound_tests += o.bound_tests;
        self.max_queue = self.max_queue.max(o.max_queue);
        self.closed_forms += o.closed_forms;
        self.convex_paths += o.convex_paths;
        self.subdivided_pairs += o.subdivided_pairs;
        self.budget_exhausted |= o.budget_exhausted;
    }
}
