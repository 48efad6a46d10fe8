//! The biarc tree of a profile (Son et al. 2020, section 4.1, Algorithm 1): an AABB hierarchy
//! over the profile's spirals, and under each spiral a binary tree of biarcs split at the mid
//! parameter until the bilens bound is at most `eps`.
//!
//! Storage is flat: every node is a `Copy` struct in one `Vec`, children are `u32` indices
//! (the two children of a node are adjacent), and [`BiarcTree::rebuild`] refills the same
//! vectors, so rebuilding a deforming profile allocates nothing once capacities have grown.
//!
//! **Three kinds of spiral** ([`SpiralBound`]). A spiral's nodes are biarcs with the bilens bound
//! when the piece is a short spiral. Where rounding cannot establish that:
//! - a span whose curvature-derivative test (or rho', z') was rounding noise, an exact circle
//!   written as a rational span or a near-circle whose curvature may be non-monotone at that
//!   level, keeps biarcs but bounds each arc by its certified distance from its curve part
//!   ([`super::arc_deviation`]), which needs no spiral property (every rational arc of the
//!   built-in models; the bounds match the bilens ones there to rounding);
//! - a span straight only to working precision (its curvature below the split's noise test, so
//!   an inflection may hide in it), and any spiral on which the biarc build fails (no
//!   minor-arc biarc, a zero tangent, a joint that is not G1: near-stationary points,
//!   micro-spirals between two rounded roots, fins that rounding bends), uses chords (two
//!   collinear segments) bounded by the piece's control polygon, which converges
//!   quadratically instead of cubically. The built-in exact models have none; the freeform
//!   ones and M_t frames a few straight spans, which are single chords either way.
//!
//! **What a node guarantees** (all in the (rho, z) half-plane, all two-sided where stated):
//! - [`BiarcNode::eps`]: the two-sided Hausdorff distance between the node's curve piece and its
//!   biarc is at most `eps` (bilens bound, [`super::bound`], the arc deviation bound, or the
//!   control-polygon bound of a chord node), and so is the distance to the biarc with its
//!   near-straight arcs replaced by chords (their sagitta is added;
//!   [`super::arc::FLAT_RADIUS_REL`]).
//! - [`BiarcNode::bounding_disk`]: the curve piece lies inside the disk.
//! - [`BiarcNode::chord`] with [`BiarcNode::chord_distance`]: every point of the curve piece is
//!   within `chord_distance` of the chord segment (the paper's "line segment that best
//!   approximates the biarc", revolved into a truncated cone).
//! - [`SpiralInfo::aabb`] and [`UpperNode::aabb`]: boxes containing the curve.

use nalgebra::Point2;

use super::arc::Arc;
use super::disk::Disk;
use super::fit::CurveSample;
use super::span::{SpanCurve, MAX_SPAN_DEGREE};
use super::BiarcError;
use crate::nurbs::Aabb2;
use crate::profile::Profile;

mod node_geometry;
mod piece_curve;
mod spirals;

use node_geometry::{arc_aabb, chord_arcs, make_node, placeholder, segment_distance};
use piece_curve::SpanRecord;

/// G1 defect (radians) allowed at the joints of [`SpiralBound::ArcDeviation`] spirals. Their
/// curvature may vary non-monotonically at the spiral split's noise level (relative 1e-10),
/// so the J-circle need not cross the curve and the joint is G1 only to the piece's departure
/// from a spiral: 1.7e-11 rad measured on a quarter circle whose middle control point moved
/// by 1e-11. The bound does not depend on it; a larger defect means the piece is no
/// near-circle and the spiral falls back to the control polygon.
pub const ARC_DEVIATION_G1_TOL: f64 = 1e-9;

/// Index of a node in [`BiarcTree::nodes`] or [`BiarcTree::upper_nodes`].
pub type NodeId = u32;

/// Sentinel for "no children".
const NO_CHILD: u32 = u32::MAX;

/// Depth cap of a spiral's biarc tree. Each level shrinks the bound ~8x, so 60 levels would take
/// any bound far below rounding; reaching it means `eps` is unreachable in floating point.
pub const MAX_DEPTH: u32 = 60;

/// Smallest accepted `eps`, relative to the profile size (bounding-box diagonal): below it the
/// floating-point slack of the bounds (~1e-14 of the coordinates) would dominate.
pub use crate::limits::{MAX_EPS_REL, MIN_EPS_REL};

/// Spirals of consecutive spans merge only when their tangents at the knot agree to this
/// angle (radians): C1 / G1 knots of B-splines agree to rounding (~1e-16), creases by far more.
pub const MERGE_TANGENT_TOL: f64 = 1e-10;

/// Relative size below which a derivative or curvature difference counts as zero in the merge
/// test (values at the knot computed from two spans differ by rounding, ~1e-15 relative).
pub const MERGE_ZERO_REL: f64 = 1e-12;

/// Errors building a biarc tree.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TreeError {
    /// `eps` is not a positive finite number.
    #[error("eps must be positive and finite, got {0}")]
    InvalidEps(f64),
    /// `eps` is below what floating point can certify for this profile.
    #[error(
        "eps = {eps:e} is below {min:e} (1e-12 of the profile size), which rounding cannot certify"
    )]
    EpsTooSmall {
        /// Requested bound.
        eps: f64,
        /// Smallest accepted bound for this profile.
        min: f64,
    },
    /// `eps` is so coarse that the approximation would no longer resemble the profile.
    #[error(
        "eps = {eps:e} is above {max:e} ({MAX_EPS_REL} of the profile size): too coarse to resemble the solid"
    )]
    EpsTooLarge {
        /// Requested bound.
        eps: f64,
        /// Largest accepted bound for this profile.
        max: f64,
    },
    /// A span of a piece has a degree above [`MAX_SPAN_DEGREE`].
    #[error("piece {piece} has degree {degree}, above the supported {max}")]
    DegreeTooHigh {
        /// Piece index.
        piece: usize,
        /// Its degree.
        degree: usize,
        /// The supported maximum.
        max: usize,
    },
    /// Fitting a biarc failed on a spiral of a piece.
    #[error("piece {piece}: {source}")]
    Fit {
        /// Piece index.
        piece: usize,
        /// The fitting error.
        source: BiarcError,
    },
    /// Subdivision reached [`MAX_DEPTH`] without meeting `eps`.
    #[error("piece {piece}: bound {reached:e} still above eps after {MAX_DEPTH} subdivisions")]
    BoundNotReached {
        /// Piece index.
        piece: usize,
        /// The bound of the deepest node.
        reached: f64,
    },
}

/// One node of a spiral's biarc tree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BiarcNode {
    arcs: [Arc; 2],
    eps: f64,
    disk: Disk,
    chord_distance: f64,
    t0: f64,
    t1: f64,
    spiral: u32,
    first_child: u32,
    depth: u32,
}

impl BiarcNode {
    /// The biarc: `arcs()[0].start` is the curve point at `param_range().0`, `arcs()[1].end`
    /// the one at `param_range().1`; the arcs meet G1 at the joint (a curve point).
    pub fn arcs(&self) -> &[Arc; 2] {
        &self.arcs
    }
    /// The biarc as the query revolves it: arcs of radius above `flat_radius` (the tree's
    /// [`BiarcTree::flat_radius`]) replaced by their chords.
    pub fn revolved_arcs(&self, flat_radius: f64) -> [Arc; 2] {
        self.arcs.map(|a| a.flattened(flat_radius))
    }

    /// Guaranteed two-sided Hausdorff bound between the node's curve piece and its biarc, with
    /// arcs of radius above [`BiarcTree::flat_radius`] replaced by their chords.
    pub fn eps(&self) -> f64 {
        self.eps
    }

    /// A disk that contains the node's curve piece (and its biarc).
    pub fn bounding_disk(&self) -> Disk {
        self.disk
    }
    /// The chord segment (start and end point of the piece).
    pub fn chord(&self) -> (Point2<f64>, Point2<f64>) {
        (self.arcs[0].start, self.arcs[1].end)
    }
    /// Every point of the curve piece (and of the biarc) is within this distance of
    /// [`BiarcNode::chord`].
    pub fn chord_distance(&self) -> f64 {
        self.chord_distance
    }
    /// Parameter interval of the piece in its profile piece's (NURBS) parameter.
    pub fn param_range(&self) -> (f64, f64) {
        (self.t0, self.t1)
    }
    /// Index of the spiral ([`BiarcTree::spirals`]) this node belongs to.
    pub fn spiral(&self) -> usize {
        self.spiral as usize
    }
    /// Depth below the spiral's root (root = 0).
    pub fn depth(&self) -> u32 {
        self.depth
    }
    /// True for a leaf (its bound is <= the tree's eps).
    pub fn is_leaf(&self) -> bool {
        self.first_child == NO_CHILD
    }
    /// The two children (first half, second half of the parameter range), or `None` for a leaf.
    pub fn children(&self) -> Option<[NodeId; 2]> {
        (!self.is_leaf()).then(|| [self.first_child, self.first_child + 1])
    }
}

/// One spiral: a maximal piece of the profile that is monotone in rho and z, of one convexity
/// and curvature-monotone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SpiralInfo {
    /// Index of the profile piece.
    pub piece: usize,
    /// Parameter interval in the piece.
    pub param_range: (f64, f64),
    /// Root of the spiral's biarc tree in [`BiarcTree::nodes`].
    pub root: NodeId,
    /// Axis-aligned box containing the spiral's curve.
    pub aabb: Aabb2,
    /// First and last span (inclusive) of the spiral in the tree's span table.
    spans: (u32, u32),
    /// How the spiral's node bounds are certified.
    bound: SpiralBound,
}

/// How the node bounds of a spiral are certified, ordered from the bound that needs the most
/// of the piece to the one that needs the least (a spiral merged from two takes the larger).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum SpiralBound {
    /// Biarcs with the bilens bound (section 4.1): the piece is a short spiral.
    Bilens,
    /// Biarcs bounded by each arc's certified distance from its curve part, with no spiral
    /// property ([`super::arc_deviation`]: the circle's implicit equation on the Bernstein
    /// form): for pieces whose curvature-derivative (or rho', z') test was rounding noise, such
    /// as exact circles written as rational spans and near-circles, where the curvature may be
    /// non-monotone at the noise level and the bilens bound is not certain; and for spirals
    /// merged across a knot, whose monotonicity there rests on curvatures compared within a
    /// tolerance.
    ArcDeviation,
    /// Chords with the control-polygon bound: for pieces whose spiral property rounding cannot
    /// establish (a span straight only to working precision, a piece on which no biarc fits:
    /// near-stationary points, micro-spirals between two rounded roots). Each curve piece lies
    /// in the convex hull of its Bezier control points, so their largest distance to the
    /// chord bounds the two-sided Hausdorff distance (see the module doc).
    ControlPolygon,
}

impl SpiralInfo {
    /// How the spiral's node bounds are certified.
    pub fn bound(&self) -> SpiralBound {
        self.bound
    }
}

/// A node of the upper AABB hierarchy over spirals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UpperNode {
    /// Box containing every spiral below.
    pub aabb: Aabb2,
    /// Children in [`BiarcTree::upper_nodes`], or `None` when the node holds one spiral.
    pub children: Option<[NodeId; 2]>,
    /// The spiral of a leaf ([`BiarcTree::spirals`]).
    pub spiral: Option<usize>,
}

/// Node counts, depth and memory of a tree.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct TreeStats {
    /// Number of spirals.
    pub spirals: usize,
    /// Biarc-tree nodes (all spirals).
    pub nodes: usize,
    /// Biarc-tree leaves.
    pub leaves: usize,
    /// Upper-level AABB nodes.
    pub upper_nodes: usize,
    /// Largest biarc depth below a spiral root, plus the upper-level depth.
    pub depth: usize,
    /// Bytes of the flat arrays a query touches (nodes, spirals, upper level).
    pub bytes: usize,
}

#[derive(Debug, Clone, Copy)]
struct Job {
    node: u32,
    a: CurveSample,
    b: CurveSample,
    depth: u32,
}

/// The biarc tree of a profile (see the module doc).
#[derive(Debug, Clone, Default)]
pub struct BiarcTree {
    eps: f64,
    /// Radius above which an arc is revolved as its chord ([`crate::biarc::arc::FLAT_RADIUS_REL`]
    /// times the profile size).
    flat_radius: f64,
    /// The profile's largest coordinate magnitude or bounding-box diagonal, whichever is
    /// larger: the scale of its coordinates' rounding.
    coordinate_scale: f64,
    nodes: Vec<BiarcNode>,
    spirals: Vec<SpiralInfo>,
    upper: Vec<UpperNode>,
    spans: Vec<SpanRecord>,
    coeffs: Vec<[f64; 3]>,
    stack: Vec<Job>,
    max_depth: u32,
    /// Join consecutive spirals that one biarc fits within `eps` ([`BiarcTree::build_merged`]).
    merge_spirals: bool,
}

impl BiarcTree {
    /// Builds the tree of `profile` with leaf bound `eps`.
    pub fn build(profile: &Profile, eps: f64) -> Result<BiarcTree, TreeError> {
        let mut tree = BiarcTree::default();
        tree.rebuild(profile, eps)?;
        Ok(tree)
    }

    /// [`BiarcTree::build`], then consecutive spirals of a piece that one biarc fits within
    /// `eps` under the arc deviation bound (no spiral property needed) become one spiral
    /// whose tree is a single leaf. The query's trees are built this way
    /// ([`crate::solid::Solid::from_profile`]); the paper's tables and the certified meshes
    /// keep one tree per spiral.
    pub fn build_merged(profile: &Profile, eps: f64) -> Result<BiarcTree, TreeError> {
        let mut tree = BiarcTree {
            merge_spirals: true,
            ..BiarcTree::default()
        };
        tree.rebuild(profile, eps)?;
        Ok(tree)
    }

    /// Checks that `eps` is a bound a tree of `profile` can be built for: positive, finite,
    /// and between [`MIN_EPS_REL`] and [`MAX_EPS_REL`] of the profile size.
    pub fn check_eps(profile: &Profile, eps: f64) -> Result<(), TreeError> {
        if !(eps > 0.0 && eps.is_finite()) {
            return Err(TreeError::InvalidEps(eps));
        }
        let size = profile.bounding_box().diagonal();
        if eps < MIN_EPS_REL * size {
            return Err(TreeError::EpsTooSmall {
                eps,
                min: MIN_EPS_REL * size,
            });
        }
        if eps > MAX_EPS_REL * size {
            return Err(TreeError::EpsTooLarge {
                eps,
                max: MAX_EPS_REL * size,
            });
        }
        Ok(())
    }

    /// The smallest bound a tree of `profile` accepts ([`MIN_EPS_REL`] of its size).
    pub fn min_eps(profile: &Profile) -> f64 {
        MIN_EPS_REL * profile.bounding_box().diagonal()
    }

    /// Rebuilds in place for a new (e.g. deformed) profile, reusing all allocations.
    pub fn rebuild(&mut self, profile: &Profile, eps: f64) -> Result<(), TreeError> {
        BiarcTree::check_eps(profile, eps)?;
        let bbox = profile.bounding_box();
        let size = bbox.diagonal();
        self.eps = eps;
        self.coordinate_scale = size.max(bbox.min.coords.amax()).max(bbox.max.coords.amax());
        self.flat_radius = crate::biarc::arc::FLAT_RADIUS_REL * size;
        self.nodes.clear();
        self.spirals.clear();
        self.upper.clear();
        self.spans.clear();
        self.coeffs.clear();
        self.max_depth = 0;
        self.load_spans(profile)?;
        self.segment();
        if self.merge_spirals {
            self.merge_spirals();
        }
        for s in 0..self.spirals.len() {
            self.build_spiral(s)?;
        }
        self.build_upper();
        Ok(())
    }

    fn load_spans(&mut self, profile: &Profile) -> Result<(), TreeError> {
        for (piece, curve) in profile.pieces().iter().enumerate() {
            if curve.degree() > MAX_SPAN_DEGREE {
                return Err(TreeError::DegreeTooHigh {
                    piece,
                    degree: curve.degree(),
                    max: MAX_SPAN_DEGREE,
                });
            }
            for span in curve.bezier_spans() {
                let offset = self.coeffs.len() as u32;
                self.coeffs.extend_from_slice(&span.homogeneous);
                self.spans.push(SpanRecord {
                    piece: piece as u32,
                    t0: span.t0,
                    t1: span.t1,
                    offset,
                    len: span.homogeneous.len() as u32,
                });
            }
        }
        Ok(())
    }

    fn span_curve(&self, span: usize) -> SpanCurve<'_> {
        let r = &self.spans[span];
        SpanCurve {
            homogeneous: &self.coeffs[r.offset as usize..(r.offset + r.len) as usize],
        }
    }

    /// Upper AABB hierarchy: spirals in profile order, halved recursively (consecutive spirals
    /// are spatial neighbours along the curve).
    fn build_upper(&mut self) {
        if self.spirals.is_empty() {
            return;
        }
        self.upper.push(UpperNode {
            aabb: self.spirals[0].aabb,
            children: None,
            spiral: None,
        });
        let mut work = vec![(0u32, 0usize, self.spirals.len())];
        while let Some((node, lo, hi)) = work.pop() {
            let aabb = self.spirals[lo..hi]
                .iter()
                .map(|s| s.aabb)
                .reduce(Aabb2::union)
                .unwrap_or(self.spirals[lo].aabb);
            let mut n = UpperNode {
                aabb,
                children: None,
                spiral: None,
            };
            if hi - lo == 1 {
                n.spiral = Some(lo);
            } else {
                let first = self.upper.len() as u32;
                let mid = (lo + hi) / 2;
                for _ in 0..2 {
                    self.upper.push(n);
                }
                n.children = Some([first, first + 1]);
                work.push((first, lo, mid));
                work.push((first + 1, mid, hi));
            }
            self.upper[node as usize] = n;
        }
    }

    /// The leaf bound the tree was built with.
    pub fn eps(&self) -> f64 {
        self.eps
    }

    /// Radius above which the query revolves an arc as its chord (counted in node bounds).
    pub fn flat_radius(&self) -> f64 {
        self.flat_radius
    }
    /// All biarc nodes (flat; index with [`NodeId`]).
    pub fn nodes(&self) -> &[BiarcNode] {
        &self.nodes
    }
    /// One biarc node.
    pub fn node(&self, id: NodeId) -> &BiarcNode {
        &self.nodes[id as usize]
    }
    /// The spirals, in profile order.
    pub fn spirals(&self) -> &[SpiralInfo] {
        &self.spirals
    }
    /// Root nodes of the spirals' biarc trees, in profile order.
    pub fn roots(&self) -> impl Iterator<Item = NodeId> + '_ {
        self.spirals.iter().map(|s| s.root)
    }
    /// The upper AABB hierarchy over spirals; its root is index 0 (empty for an empty tree).
    pub fn upper_nodes(&self) -> &[UpperNode] {
        &self.upper
    }
    /// Root of the upper hierarchy, if any.
    pub fn upper_root(&self) -> Option<NodeId> {
        (!self.upper.is_empty()).then_some(0)
    }
    /// The leaves in profile order: a G1 arc spline within `eps` of the profile.
    pub fn leaves(&self) -> impl Iterator<Item = &BiarcNode> + '_ {
        LeafIter {
            tree: self,
            spiral: 0,
            stack: Vec::new(),
        }
    }
    /// Node counts, depth and bytes.
    pub fn stats(&self) -> TreeStats {
        let upper_depth = (self.spirals.len().max(1) as f64).log2().ceil() as usize;
        TreeStats {
            spirals: self.spirals.len(),
            nodes: self.nodes.len(),
            leaves: self.nodes.iter().filter(|n| n.is_leaf()).count(),
            upper_nodes: self.upper.len(),
            depth: self.max_depth as usize + 1 + upper_depth,
            bytes: std::mem::size_of_val(self.nodes.as_slice())
                + std::mem::size_of_val(self.spirals.as_slice())
                + std::mem::size_of_val(self.upper.as_slice()),
        }
    }
}

struct LeafIter<'a> {
    tree: &'a BiarcTree,
    spiral: usize,
    stack: Vec<NodeId>,
}

impl<'a> Iterator for LeafIter<'a> {
    type Item = &'a BiarcNode;
    fn next(&mut self) -> Option<&'a BiarcNode> {
        loop {
            if let Some(id) = self.stack.pop() {
                let n = self.tree.node(id);
                match n.children() {
                    Some([a, b]) => {
                        self.stack.push(b);
                        self.stack.push(a);
                    }
                    None => return Some(n),
                }
            } else if self.spiral < self.tree.spirals.len() {
                self.stack.push(self.tree.spirals[self.spiral].root);
                self.spiral += 1;
            } else {
                return None;
            }
        }
    }
}

#[cfg(test)]
mod tests;
