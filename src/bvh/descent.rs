//! One depth-first descent of a query tree's disks for every planar search of its chain
//! (as parry's tree visitors): the visitor decides at each node whether to open it, what to
//! do with a leaf's pieces and which child to open first. Point classification
//! ([`super::containment`]) and the nearest point of the chain ([`nearest_chain_point`],
//! for the convex path's witnesses and ball path) are its two visitors.

use super::patch::Patch;
use super::QueryTree;
use crate::nearest::NearestPoint;
use nalgebra::Point2;
use std::ops::Range;

/// What a visitor does with a node it is shown.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Visit {
    /// Go no further into this node's subtree (pruned, or accounted for as a whole).
    Skip,
    /// Open the node: its pieces when it is a leaf, else its children.
    Open,
}

/// A planar search over a tree's nodes (disks of the (rho, z) half-plane).
pub trait DiskVisitor {
    /// Decides at node `id`, before anything under it is seen.
    fn visit_node(&mut self, tree: &QueryTree, id: u32) -> Visit;
    /// The pieces of a leaf that was opened, as indices into the tree's patches (and into its
    /// chain when the tree indexes one, [`QueryTree::index_chain`]).
    fn visit_leaf(&mut self, tree: &QueryTree, pieces: Range<usize>);
    /// The order in which to open the two children of node `id`.
    fn order(&self, tree: &QueryTree, id: u32) -> [u32; 2];
}

/// Runs `visitor` over `tree` from its root, depth first; nothing for an empty tree.
pub fn descend<V: DiskVisitor>(tree: &QueryTree, visitor: &mut V) {
    if !tree.nodes.is_empty() {
        walk(tree, tree.root, visitor);
    }
}

fn walk<V: DiskVisitor>(tree: &QueryTree, id: u32, visitor: &mut V) {
    if visitor.visit_node(tree, id) == Visit::Skip {
        return;
    }
    let n = &tree.nodes[id as usize];
    if n.is_leaf() {
        visitor.visit_leaf(tree, n.patch_start as usize..n.patch_end as usize);
        return;
    }
    let [first, second] = visitor.order(tree, id);
    walk(tree, first, visitor);
    walk(tree, second, visitor);
}

impl NearestPoint for Patch {
    fn nearest(&self, m: Point2<f64>) -> (f64, Point2<f64>) {
        self.arc.nearest(m)
    }
}

/// The nearest point to `m` of a chain whose pieces are `pieces` (one per patch of the tree,
/// in its order), and the best distance so far.
struct NearestVisitor<'a, P> {
    pieces: &'a [P],
    m: Point2<f64>,
    best: Option<(f64, Point2<f64>)>,
}

impl<P: NearestPoint> DiskVisitor for NearestVisitor<'_, P> {
    fn visit_node(&mut self, tree: &QueryTree, id: u32) -> Visit {
        let bound = &tree.nodes[id as usize].bound;
        if let Some((d, _)) = self.best {
            // `|m - c| - r > d`, compared squared (both sides non-negative): no square root.
            let reach = d + bound.radius;
            if (self.m - bound.center).norm_squared() > reach * reach {
                return Visit::Skip;
            }
        }
        Visit::Open
    }

    fn visit_leaf(&mut self, _tree: &QueryTree, pieces: Range<usize>) {
        for piece in &self.pieces[pieces] {
            let (d, p) = piece.nearest(self.m);
            if self.best.is_none_or(|(b, _)| d < b) {
                self.best = Some((d, p));
            }
        }
    }

    /// Nearer child first.
    fn order(&self, tree: &QueryTree, id: u32) -> [u32; 2] {
        tree.children_nearer_first(id, self.m)
    }
}

/// The point of the tree's chain nearest to the meridian point `m` and its distance: a
/// descent of the tree's disks (each holds its pieces), nearer child first, pruned by the
/// best distance so far. `pieces` are the tree's pieces in any form (one per patch, in
/// order: the patches themselves, or the convex path's [`super::convex::MeridianPiece`]s).
/// `None` for an empty tree.
pub fn nearest_chain_point<P: NearestPoint>(
    tree: &QueryTree,
    pieces: &[P],
    m: Point2<f64>,
) -> Option<(f64, Point2<f64>)> {
    let mut visitor = NearestVisitor {
        pieces,
        m,
        best: None,
    };
    descend(tree, &mut visitor);
    visitor.best
}
