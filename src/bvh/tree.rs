//! The query's view of a solid's bounding-volume hierarchy (paper section 4.1): a binary
//! tree whose leaves are biarcs (one or two profile pieces) with their approximation bound
//! `eps`, and whose every node stores a disk of the (rho, z) half-plane that contains both
//! the original curve piece under it and its approximation. Revolved, the disk is a solid
//! torus containing the corresponding part of the solid's boundary (see [`crate::query::bound::node_pair`]).

use super::convex::ConvexHullData;
use super::deep_interior::DeepCache;
use super::hull::{HullRef, NodeHull, UpperHull};
use super::offset_solid::{detect, OffsetSolid};
use super::patch::{Patch, ProfileArc};
use crate::biarc::Disk;
use crate::biarc::{Arc as BiarcArc, BiarcTree};
use crate::num::cross2;
use crate::profile::ProfileKind;
use nalgebra::{Point2, Vector2};

/// Marker for "no child".
pub const NO_CHILD: u32 = u32::MAX;

/// One leaf: a biarc (or a single piece) with its bound.
#[derive(Debug, Clone, PartialEq)]
pub struct Leaf {
    /// The pieces of the approximation, in profile order.
    pub pieces: Vec<ProfileArc>,
    /// Two-sided Hausdorff bound between the original curve piece and `pieces`.
    pub eps: f64,
    /// Disk containing the original curve piece and `pieces`.
    pub bound: Disk,
}

impl Leaf {
    /// Leaf from approximation pieces and their bound: the disk around the pieces, grown
    /// by `eps` so that it also contains the original curve (Hausdorff distance <= eps).
    pub fn new(pieces: Vec<ProfileArc>, eps: f64) -> Leaf {
        let mut disk = pieces[0].bounding_disk();
        for p in &pieces[1..] {
            disk = disk.union(&p.bounding_disk());
        }
        Leaf {
            pieces,
            eps,
            bound: disk.inflated(eps),
        }
    }
}

/// A node of the query tree.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Node {
    pub bound: Disk,
    /// Largest leaf eps below the node.
    pub eps: f64,
    pub children: [u32; 2],
    /// For leaves: range of patches in [`QueryTree::patches`].
    pub patch_start: u32,
    pub patch_end: u32,
}

impl Node {
    pub fn is_leaf(&self) -> bool {
        self.children[0] == NO_CHILD
    }
}

/// Flat binary tree over a profile's leaves.
#[derive(Debug, Clone, PartialEq)]
pub struct QueryTree {
    pub nodes: Vec<Node>,
    pub patches: Vec<Patch>,
    pub root: u32,
    /// Profile pieces in order (for point-in-profile tests). A caller that changes it must
    /// call [`QueryTree::index_chain`], which derives [`QueryTree::node_ends`] and the
    /// orientation from it.
    pub chain: Vec<ProfileArc>,
    pub kind: ProfileKind,
    /// Largest leaf eps.
    pub eps: f64,
    /// The bound the tree was asked for (a biarc tree's build eps; [`QueryTree::eps`] for
    /// trees built from leaves). `eps <= target_eps`. The default query tolerance
    /// ([`crate::query::Tolerance::Trees`]) is the sum of both trees' `target_eps`.
    pub target_eps: f64,
    /// First and last chain point under each node (`None` for nodes without pieces), when
    /// the leaves' pieces are consecutive runs of [`QueryTree::chain`] in order and join up
    /// (checked by [`QueryTree::index_chain`]); empty otherwise. Point-in-solid tests use it
    /// to skip whole subtrees ([`super::containment`]).
    pub node_ends: Vec<Option<[Point2<f64>; 2]>>,
    /// The solid is a ball or a solid torus (the chain is one circle): queries between two
    /// such solids take the closed form of [`crate::query::closed_form`] instead of a traversal.
    pub offset: Option<OffsetSolid>,
    /// The solid is certified convex (set by [`crate::solid::Solid::from_profile`], which
    /// has the exact profile): queries between two such solids take the convex fast path
    /// ([`crate::query::convex`]).
    pub convex: Option<ConvexHullData>,
    /// Per node below the upper level, a hull of parallels that contains its original curve
    /// piece's surface up to its `grow` (the node's own biarc chords, grown by their
    /// sagittas and the biarc's bound; paper 4.1's fat biarcs), for the node-pair hull bound
    /// ([`crate::bvh::hull::ParallelHull::bound`]). `None` for nodes with an arc above a half
    /// turn; empty for trees built from leaves; the upper level has [`Self::upper_hulls`].
    pub hulls: Vec<Option<NodeHull>>,
    /// Per node of the upper level over the spirals (index `node - upper_start`), the hull
    /// of the spirals' node hulls below it ([`UpperHull`], [`super::hull::ParallelHull::union_of`]) when
    /// every spiral root has one and their union's convex hull has at most
    /// [`super::hull::UPPER_POINTS`] vertices.
    pub upper_hulls: Vec<Option<UpperHull>>,
    /// Nodes from this index on form the upper level over the spirals of a biarc tree
    /// (disks around several spirals, no biarc and no hull; [`QueryTree::from_biarc_tree`]);
    /// `u32::MAX` for trees built from leaves.
    upper_start: u32,
    /// [`QueryTree::orientation`] of the chain, computed at construction (interpenetration
    /// checks ask for it in every query that reaches an exact solve; a pass over the chain
    /// with nine sine/cosine pairs per piece was 1.5% of the query time at eps 1e-4).
    chain_orientation: f64,
    /// [`QueryTree::deep_interior`], computed on first use.
    deep: DeepCache,
}

impl QueryTree {
    /// The cache that [`QueryTree::deep_interior`] (computed in [`super::inscribed`]) fills.
    pub(super) fn deep_cache(&self) -> &DeepCache {
        &self.deep
    }

    /// Balanced tree over consecutive leaves (profile order).
    ///
    /// # Panics
    /// Never: an empty leaf list gives an empty tree whose root is [`NO_CHILD`].
    pub fn from_leaves(leaves: Vec<Leaf>, kind: ProfileKind) -> QueryTree {
        let mut t = QueryTree {
            nodes: Vec::with_capacity(2 * leaves.len()),
            patches: Vec::new(),
            root: NO_CHILD,
            chain: leaves
                .iter()
                .flat_map(|l| l.pieces.iter().copied())
                .collect(),
            kind,
            eps: leaves.iter().map(|l| l.eps).fold(0.0, f64::max),
            target_eps: 0.0,
            node_ends: Vec::new(),
            offset: None,
            convex: None,
            hulls: Vec::new(),
            upper_hulls: Vec::new(),
            upper_start: u32::MAX,
            chain_orientation: 1.0,
            deep: DeepCache::default(),
        };
        t.target_eps = t.eps;
        if !leaves.is_empty() {
            t.root = t.build(&leaves);
        }
        t.index_chain();
        t.offset = detect(&t.chain, t.kind, t.eps);
        t
    }

    fn build(&mut self, leaves: &[Leaf]) -> u32 {
        if leaves.len() == 1 {
            let l = &leaves[0];
            let start = self.patches.len() as u32;
            self.patches.extend(l.pieces.iter().map(|p| Patch::new(*p)));
            let snap = l.pieces.iter().map(Patch::snap_error).fold(0.0, f64::max);
            self.nodes.push(Node {
                bound: l.bound.inflated(snap),
                eps: l.eps + snap,
                children: [NO_CHILD, NO_CHILD],
                patch_start: start,
                patch_end: self.patches.len() as u32,
            });
            return self.nodes.len() as u32 - 1;
        }
        let mid = leaves.len() / 2;
        let a = self.build(&leaves[..mid]);
        let b = self.build(&leaves[mid..]);
        self.push_parent(a, b)
    }

    /// Appends an inner node over `a` and `b` whose disk is the union of theirs.
    fn push_parent(&mut self, a: u32, b: u32) -> u32 {
        let (na, nb) = (self.nodes[a as usize], self.nodes[b as usize]);
        self.nodes.push(Node {
            bound: na.bound.union(&nb.bound),
            eps: na.eps.max(nb.eps),
            children: [a, b],
            patch_start: 0,
            patch_end: 0,
        });
        self.nodes.len() as u32 - 1
    }

    /// The query view of a biarc tree: its spiral subtrees copied node by node (their disks
    /// contain both the curve piece and the biarc), under a balanced upper level over the
    /// spirals in profile order whose disks are unions of the children's disks.
    pub fn from_biarc_tree(bt: &BiarcTree, kind: ProfileKind) -> QueryTree {
        let mut t = QueryTree {
            nodes: Vec::with_capacity(bt.nodes().len() + bt.spirals().len()),
            patches: Vec::new(),
            root: NO_CHILD,
            chain: bt
                .leaves()
                .flat_map(|l| {
                    l.arcs()
                        .iter()
                        .filter(|a| a.length > 0.0)
                        .map(|a| piece_of_arc(a, bt.flat_radius()))
                })
                .collect(),
            kind,
            eps: 0.0,
            target_eps: 0.0,
            node_ends: Vec::new(),
            offset: None,
            convex: None,
            hulls: Vec::new(),
            upper_hulls: Vec::new(),
            upper_start: u32::MAX,
            chain_orientation: 1.0,
            deep: DeepCache::default(),
        };
        let roots: Vec<u32> = bt
            .spirals()
            .iter()
            .map(|s| t.copy_subtree(bt, s.root))
            .collect();
        t.eps = t
            .nodes
            .iter()
            .filter(|n| n.is_leaf())
            .map(|n| n.eps)
            .fold(0.0, f64::max);
        t.target_eps = t.eps.max(bt.eps());
        t.upper_start = t.nodes.len() as u32;
        if !roots.is_empty() {
            t.root = t.build_upper(&roots);
        }
        // The upper nodes over the spirals have no biarc: their hulls are unions, kept apart
        // (`hulls` covers the spirals' nodes only).
        t.hulls.truncate(t.upper_start as usize);
        for id in t.upper_start as usize..t.nodes.len() {
            let [c0, c1] = t.nodes[id].children;
            let hull = match (t.hull_ref(c0), t.hull_ref(c1)) {
                (Some(a), Some(b)) => a.union(&b),
                _ => None,
            };
            t.upper_hulls.push(hull);
        }
        t.index_chain();
        t.offset = detect(&t.chain, t.kind, t.eps);
        t
    }

    /// Fills [`QueryTree::node_ends`], or leaves it empty when the leaves' patches are not
    /// the chain's pieces in order, joined within `1e-9` of the coordinates.
    /// Also computes the chain's orientation ([`QueryTree::orientation`]).
    pub fn index_chain(&mut self) {
        self.chain_orientation = orientation_of(&self.chain);
        self.node_ends.clear();
        if self.chain.len() != self.patches.len() || self.root == NO_CHILD {
            return;
        }
        let mut ends = vec![None; self.nodes.len()];
        if self.ends_of(self.root, &mut ends) {
            self.node_ends = ends;
        }
    }

    /// Post-order fill of `ends` under `id`; `false` when two consecutive runs do not join.
    fn ends_of(&self, id: u32, ends: &mut [Option<[Point2<f64>; 2]>]) -> bool {
        let n = self.nodes[id as usize];
        if n.is_leaf() {
            let (s, e) = (n.patch_start as usize, n.patch_end as usize);
            ends[id as usize] = (s < e).then(|| [self.chain[s].start(), self.chain[e - 1].end()]);
            return true;
        }
        let [c0, c1] = n.children;
        if !self.ends_of(c0, ends) || !self.ends_of(c1, ends) {
            return false;
        }
        ends[id as usize] = match (ends[c0 as usize], ends[c1 as usize]) {
            (Some([a, j0]), Some([j1, b])) => {
                let tol = 1e-9 * (1.0 + j0.coords.norm());
                if (j0 - j1).norm() > tol {
                    return false;
                }
                Some([a, b])
            }
            (x, None) => x,
            (None, y) => y,
        };
        true
    }

    fn copy_subtree(&mut self, bt: &BiarcTree, id: u32) -> u32 {
        let n = bt.node(id);
        let bound = n.bounding_disk();
        let mut node = Node {
            bound,
            eps: n.eps(),
            children: [NO_CHILD, NO_CHILD],
            patch_start: 0,
            patch_end: 0,
        };
        let hull = node_hull(n.arcs(), n.eps(), bt.flat_radius());
        if let Some([c0, c1]) = n.children() {
            let a = self.copy_subtree(bt, c0);
            let b = self.copy_subtree(bt, c1);
            node.children = [a, b];
        } else {
            node.patch_start = self.patches.len() as u32;
            for a in n.arcs().iter().filter(|a| a.length > 0.0) {
                let piece = piece_of_arc(a, bt.flat_radius());
                node.eps += Patch::snap_error(&piece) + piece.representation_error();
                self.patches.push(Patch::new(piece));
            }
            node.patch_end = self.patches.len() as u32;
        }
        // Children were copied first, so `hulls` is aligned with `nodes` here.
        self.nodes.push(node);
        self.hulls.push(hull);
        self.nodes.len() as u32 - 1
    }

    fn build_upper(&mut self, roots: &[u32]) -> u32 {
        if roots.len() == 1 {
            return roots[0];
        }
        let mid = roots.len() / 2;
        let a = self.build_upper(&roots[..mid]);
        let b = self.build_upper(&roots[mid..]);
        self.push_parent(a, b)
    }

    /// Exact tree (eps = 0) of given profile pieces, each split into leaves of sweep at most
    /// `max_sweep` (arcs) or length at most `max_len` (segments). Used for analytic solids
    /// (spheres, tori, cylinders) whose profiles are exactly arcs and segments.
    pub fn from_exact_pieces(
        pieces: &[ProfileArc],
        kind: ProfileKind,
        max_sweep: f64,
        max_len: f64,
    ) -> QueryTree {
        let mut leaves = Vec::new();
        for p in pieces {
            let n = match *p {
                ProfileArc::Arc { sweep, .. } => (sweep.abs() / max_sweep).ceil().max(1.0),
                ProfileArc::Segment { start, end } => {
                    ((end - start).norm() / max_len).ceil().max(1.0)
                }
            } as usize;
            for i in 0..n {
                let (s0, s1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                let sub = p.sub_piece(s0, s1);
                leaves.push(Leaf::new(vec![sub], 0.0));
            }
        }
        QueryTree::from_leaves(leaves, kind)
    }

    /// The hull of node `n`: its fat biarc's, or for a node over several spirals the union
    /// of theirs; `None` without one.
    pub fn hull_ref(&self, n: u32) -> Option<HullRef<'_>> {
        if self.over_spirals(n) {
            self.upper_hulls
                .get((n - self.upper_start) as usize)
                .and_then(Option::as_ref)
                .map(HullRef::Upper)
        } else {
            self.hulls
                .get(n as usize)
                .and_then(Option::as_ref)
                .map(HullRef::Node)
        }
    }

    /// The two children of inner node `n`, the one whose disk centre is nearer to the
    /// meridian point `m` first (ties: the first child): a descent that prunes by a best
    /// distance so far visits the likelier side first.
    pub fn children_nearer_first(&self, n: u32, m: Point2<f64>) -> [u32; 2] {
        let [c0, c1] = self.nodes[n as usize].children;
        // Squared distances: the same order without the square roots.
        let dist2 = |k: u32| (m - self.nodes[k as usize].bound.center).norm_squared();
        if dist2(c0) <= dist2(c1) {
            [c0, c1]
        } else {
            [c1, c0]
        }
    }

    /// Whether node `n` is in the upper level over a biarc tree's spirals: its disk is around
    /// several spirals, and it has no biarc and no hull.
    pub fn over_spirals(&self, n: u32) -> bool {
        n >= self.upper_start
    }

    /// Profile orientation: +1 when the region is to the left of the chain (counter-
    /// clockwise loop, closed by the axis for open profiles), -1 otherwise.
    pub fn orientation(&self) -> f64 {
        self.chain_orientation
    }

    /// Outward unit normal of the profile piece `piece` at its planar point `m`.
    pub fn outward_normal(
        &self,
        piece: &ProfileArc,
        m: Point2<f64>,
        orientation: f64,
    ) -> Vector2<f64> {
        // Tangent at the closest parameter; the region lies to the left when orientation>0.
        let t = match *piece {
            ProfileArc::Arc { center, sweep, .. } => {
                let d = (m - center).normalize();
                sweep.signum() * Vector2::new(-d.y, d.x)
            }
            ProfileArc::Segment { start, end } => (end - start).normalize(),
        };
        orientation * Vector2::new(t.y, -t.x)
    }
}

/// The hull of a biarc-tree node's curve piece: its biarc as the query revolves it
/// ([`piece_of_arc`]), which is within `eps` of the piece, and the pieces' representation
/// error.
fn node_hull(arcs: &[BiarcArc; 2], eps: f64, flat_radius: f64) -> Option<NodeHull> {
    let mut pieces = [ProfileArc::Segment {
        start: Point2::origin(),
        end: Point2::origin(),
    }; 2];
    let mut n = 0;
    let mut repr: f64 = 0.0;
    for a in arcs.iter().filter(|a| a.length > 0.0) {
        pieces[n] = piece_of_arc(a, flat_radius);
        repr = repr.max(pieces[n].representation_error());
        n += 1;
    }
    NodeHull::of_pieces(&pieces[..n], eps + repr)
}

/// A biarc tree arc as a profile piece: its chord when the arc is flat for `flat_radius`
/// (the tree's node bounds already count the sagitta), else the arc in centre form.
pub fn piece_of_arc(a: &BiarcArc, flat_radius: f64) -> ProfileArc {
    let a = a.flattened(flat_radius);
    match (a.center(), a.angle_range()) {
        (Some(center), Some((phi_start, _))) if !a.is_segment() => ProfileArc::Arc {
            center,
            radius: a.radius(),
            phi_start,
            sweep: a.sweep,
        },
        _ => ProfileArc::Segment {
            start: a.start,
            end: a.end,
        },
    }
}

/// The orientation of a chain ([`QueryTree::orientation`]): the sign of its signed area by
/// the shoelace formula on a fine sampling of the chain.
fn orientation_of(chain: &[ProfileArc]) -> f64 {
    let mut area = 0.0;
    let mut prev: Option<Point2<f64>> = None;
    let mut first = None;
    for p in chain {
        for i in 0..=8 {
            let q = p.point_at(i as f64 / 8.0);
            if let Some(pr) = prev {
                area += cross2(pr.coords, q.coords);
            } else {
                first = Some(q);
            }
            prev = Some(q);
        }
    }
    if let (Some(a), Some(b)) = (prev, first) {
        area += cross2(a.coords, b.coords);
    }
    if area >= 0.0 {
        1.0
    } else {
        -1.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::model;
    use crate::solid::Solid;
    use std::sync::Arc;

    /// Planar distance from `x` to the convex hull of the points `(+-rho, z)` (the meridian
    /// section of the hull of parallels), from the support function over 3,600 directions:
    /// at most the true distance, so a value above the allowed growth proves a violation.
    fn hull_distance(x: Point2<f64>, pts: &[Point2<f64>]) -> f64 {
        (0..3600)
            .map(|k| {
                let a = k as f64 * std::f64::consts::TAU / 3600.0;
                let n = Vector2::new(a.cos(), a.sin());
                let h = pts
                    .iter()
                    .flat_map(|p| [Vector2::new(p.x, p.y), Vector2::new(-p.x, p.y)])
                    .map(|p| n.dot(&p))
                    .fold(f64::NEG_INFINITY, f64::max);
                n.dot(&x.coords) - h
            })
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Every node's hull (a fat biarc's, or over several spirals their union's) contains, up
    /// to its growth, the patches of every leaf below it up to that leaf's eps (hence the
    /// original curve, which is within the leaf eps of its patches): dense samples of the
    /// patches on the paper models at two eps.
    #[test]
    fn node_hulls_contain_the_pieces_below() {
        for name in ["pawn", "cup", "bottle", "table", "lightmill"] {
            for eps in [1e-2, 1e-4] {
                let s = Solid::from_profile(Arc::new(model(name).unwrap()), eps).unwrap();
                let t = &s.tree;
                let (mut checked, mut upper) = (0, 0);
                for id in 0..t.nodes.len() {
                    let Some(hull) = t.hull_ref(id as u32) else {
                        continue;
                    };
                    upper += usize::from(t.over_spirals(id as u32));
                    let (pts, grow) = hull.points_and_grow_for_tests();
                    let pts = &pts;
                    let mut stack = vec![id as u32];
                    while let Some(n) = stack.pop() {
                        let node = &t.nodes[n as usize];
                        if !node.is_leaf() {
                            stack.extend(node.children);
                            continue;
                        }
                        for p in &t.patches[node.patch_start as usize..node.patch_end as usize] {
                            for i in 0..=64 {
                                let x = p.arc.point_at(i as f64 / 64.0);
                                let d = hull_distance(x, pts);
                                assert!(
                                    d <= grow + node.eps + 1e-12,
                                    "{name} eps {eps} node {id}: {d} > {grow} + {}",
                                    node.eps
                                );
                            }
                        }
                    }
                    checked += 1;
                }
                assert!(checked >= 3, "{name}: {checked} hulls");
                assert!(upper >= 2, "{name}: {upper} hulls over spirals");
            }
        }
    }
}
