//! A certified lower bound of the penetration depth by covering a ball of B's translations
//! (module doc of [`mod@crate::query::penetration`]).
//!
//! **Statement.** `PD(A, B) >= L` when every translation `t` with `|t| < L` leaves A and
//! `B + t` overlapping. A point `x` whose certified signed margins against A and `B + t0`
//! sum to `sigma > 0` ([`Probe::certified_bound`]) certifies every `t` with
//! `|t - t0| < sigma`: B's true signed margin at `x` is 1-Lipschitz in B's translation, so
//! the true sum stays positive there, and a positive sum means overlapping interiors (the
//! signed-margin bound, read at the pose `B + t`). The ball `|t| < L` is certified once such
//! balls cover it. The deepest point's certificate is the ball about `t0 = 0`; where several
//! contact regions each block some of the ways out (a bump pressed into a groove, touching
//! both walls), the depth exceeds any one point's sum and only several balls reach it.
//!
//! **Covering.** The translations from the known lower bound `r0` to the goal are split into
//! cells: a direction patch of one face of a cube (a square of the face's gnomonic
//! coordinates) times a radial interval `[r0, r1]`. Every translation `r d` of a cell lies
//! within `r1 chord + (r1 - r0) / 2` of the cell's centre translation `r_m d_c`, `chord` the
//! largest distance from `d_c` to a corner's direction: the patch is a convex spherical
//! quadrilateral well inside a hemisphere, so it lies in the (convex) cap about `d_c` that
//! holds its corners. A cell is certified by an ascent of the certified sum at its centre
//! translation; it is split (radially in two, or its patch in four, whichever halves the
//! larger part of its reach) when not, and abandoned below the resolution, which caps `L` at
//! its inner radius. Cells are taken by increasing inner radius, so a cap drops every cell
//! beyond it. Only the final evaluation of each ascent enters the certificate, with the
//! query's rounding slack at the moved pose and the rounding of the cell's own geometry
//! added.

use super::deepest::{Allowance, Pair, Probe};
use crate::bvh::QueryTree;
use crate::num::SmallestFirst;
use crate::query::front::distance::query_slack;
use nalgebra::{Isometry3, Point3, Translation3, Vector3};
use std::collections::BinaryHeap;
use std::time::Instant;

/// Most cells one covering may certify or split; past it the covering is capped at the inner
/// radius of the next cell (a weaker bound, still certified).
pub const MAX_CELLS: usize = 1500;

/// Relative allowance for the rounding of a cell's directions, centre and reach (a few ulps
/// of the translations' coordinates, far below the resolutions asked).
const CELL_ROUNDING_REL: f64 = 1e-12;

/// Share of a cell's reach to which its ascent resolves the sum (the sum must exceed the
/// reach; resolving it much finer than that share spends probes on nothing).
const CELL_STEP_SHARE: f64 = 0.1;

/// A cell of the translation ball: a patch `[u0, u1] x [v0, v1]` of cube face `face` times
/// the radial interval `[r0, r1]`, with the point that certified its parent best.
#[derive(Debug, Clone, Copy)]
struct Cell {
    face: usize,
    u0: f64,
    u1: f64,
    v0: f64,
    v1: f64,
    r0: f64,
    r1: f64,
    /// The parent's best point and the translation it was found at.
    hint: Option<(Point3<f64>, Vector3<f64>)>,
}

/// Unit direction of the gnomonic coordinates `(u, v)` on cube face `face` (axis
/// `face / 2`, sign `+` for even faces).
fn direction(face: usize, u: f64, v: f64) -> Vector3<f64> {
    let axis = face / 2;
    let sign = if face.is_multiple_of(2) { 1.0 } else { -1.0 };
    let mut d = Vector3::zeros();
    d[axis] = sign;
    d[(axis + 1) % 3] = u;
    d[(axis + 2) % 3] = v;
    d.normalize()
}

impl Cell {
    fn centre_direction(&self) -> Vector3<f64> {
        direction(
            self.face,
            0.5 * (self.u0 + self.u1),
            0.5 * (self.v0 + self.v1),
        )
    }

    /// The centre translation and the distance within which every translation of the cell
    /// lies of it (module doc).
    fn centre_and_reach(&self) -> (Vector3<f64>, f64) {
        let dc = self.centre_direction();
        let chord = [
            (self.u0, self.v0),
            (self.u0, self.v1),
            (self.u1, self.v0),
            (self.u1, self.v1),
        ]
        .iter()
        .map(|&(u, v)| (direction(self.face, u, v) - dc).norm())
        .fold(0.0, f64::max);
        let reach = self.r1 * chord + 0.5 * (self.r1 - self.r0);
        (dc * (0.5 * (self.r0 + self.r1)), reach)
    }

    /// Halves the larger part of the reach: the radial interval in two, or the patch in
    /// four.
    fn split(&self, hint: Option<(Point3<f64>, Vector3<f64>)>) -> Vec<Cell> {
        let (_, reach) = self.centre_and_reach();
        let radial = 0.5 * (self.r1 - self.r0);
        let base = Cell { hint, ..*self };
        if radial >= reach - radial {
            let r = 0.5 * (self.r0 + self.r1);
            vec![Cell { r1: r, ..base }, Cell { r0: r, ..base }]
        } else {
            let (u, v) = (0.5 * (self.u0 + self.u1), 0.5 * (self.v0 + self.v1));
            vec![
                Cell {
                    u1: u,
                    v1: v,
                    ..base
                },
                Cell {
                    u0: u,
                    v1: v,
                    ..base
                },
                Cell {
                    u1: u,
                    v0: v,
                    ..base
                },
                Cell {
                    u0: u,
                    v0: v,
                    ..base
                },
            ]
        }
    }
}

/// Heap entry: cells by increasing inner radius, and among equal inner radii (the first
/// shell's cells all start at the known bound) the smallest first, so that refinement dives
/// into one direction and an uncovered cell caps the bound early.
fn by_inner(cell: Cell) -> SmallestFirst<Cell> {
    SmallestFirst {
        key: cell.r0,
        tie: cell.centre_and_reach().1,
        item: cell,
    }
}

/// What one covering found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Covered {
    /// Certified: `PD >= lower` (module doc); at least the `from` it was given.
    pub lower: f64,
    /// Cells certified or split.
    pub cells: usize,
    /// Points classified against both solids.
    pub probes: usize,
    /// The centre translation of the cell that capped `lower` below the goal (A's frame,
    /// as B's translations): too small to split, a translation at which no point's margins
    /// could be certified to hold B in, so where a shorter way out may lie; or, when the
    /// cells or the time ran out, the first cell not yet examined.
    pub capped_at: Option<Vector3<f64>>,
    /// The deadline passed before the goal was reached.
    pub timed_out: bool,
}

/// The covering's inputs besides the trees and B's pose in A's frame.
#[derive(Debug, Clone, Copy)]
pub struct CoverSpec<'s> {
    /// A certified lower bound already known: the ball `|t| < from` needs no cells.
    pub from: f64,
    /// The radius to certify: the covering stops there.
    pub goal: f64,
    /// Cells whose reach is at most this are not split: one of them left uncovered caps the
    /// bound at its inner radius.
    pub resolution: f64,
    /// Points (A's frame, at B's given pose) inside the overlap regions: each cell's ascent
    /// starts from them, moved by half the cell's translation, when its parent's point does
    /// not certify it.
    pub anchors: &'s [Point3<f64>],
    /// Step below which an ascent stops (the cell's share of its reach when larger).
    pub step_tol: f64,
    pub deadline: Option<Instant>,
}

/// Certified lower bound of the penetration depth of the solids of `ta` and `tb` (B placed
/// by `pos_ab` in A's frame) by covering the ball of translations `|t| < spec.goal` (module
/// doc), never below `spec.from`.
pub fn translation_cover_lower(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    spec: &CoverSpec,
) -> Covered {
    let mut out = Covered {
        lower: spec.from,
        cells: 0,
        probes: 0,
        capped_at: None,
        timed_out: false,
    };
    let usable = spec.goal > spec.from
        && spec.from >= 0.0
        && spec.resolution > 0.0
        && spec.goal.is_finite()
        && !spec.anchors.is_empty();
    if !usable {
        return out;
    }
    let rounding = CELL_ROUNDING_REL * (1.0 + pos_ab.translation.vector.norm() + spec.goal);
    let mut limit = spec.goal;
    let mut heap = BinaryHeap::new();
    for face in 0..6 {
        for (u0, u1) in [(-1.0, 0.0), (0.0, 1.0)] {
            for (v0, v1) in [(-1.0, 0.0), (0.0, 1.0)] {
                heap.push(by_inner(Cell {
                    face,
                    u0,
                    u1,
                    v0,
                    v1,
                    r0: spec.from,
                    r1: spec.goal,
                    hint: None,
                }));
            }
        }
    }
    while let Some(SmallestFirst { item: mut cell, .. }) = heap.pop() {
        if cell.r0 >= limit {
            break;
        }
        cell.r1 = cell.r1.min(limit);
        let out_of_time = spec.deadline.is_some_and(|d| Instant::now() >= d);
        if out.cells >= MAX_CELLS || out_of_time {
            out.timed_out = out_of_time;
            limit = cell.r0;
            out.capped_at = Some(cell.centre_and_reach().0);
            break;
        }
        out.cells += 1;
        let (t, reach) = cell.centre_and_reach();
        let moved = Isometry3::from_parts(
            Translation3::from(pos_ab.translation.vector + t),
            pos_ab.rotation,
        );
        // The translation as the two floating-point poses realise it.
        let realised = moved.translation.vector - pos_ab.translation.vector;
        let need = reach + (realised - t).norm() + rounding;
        let w = Allowance {
            e_a: ta.eps,
            e_b: tb.eps,
            slack: query_slack(ta, tb, &moved),
        };
        let mut pair = Pair::new(ta, tb, moved);
        let step_tol = spec.step_tol.max(CELL_STEP_SHARE * reach);
        let covers = |p: &Probe| p.bound(&w) > need;
        // The parent's point first, moved by half the change of translation (the lens of a
        // shallow overlap follows B by about half its motion), then the anchors likewise.
        let mut seeds: Vec<Point3<f64>> = Vec::with_capacity(1 + spec.anchors.len());
        if let Some((x, t_parent)) = cell.hint {
            seeds.push(x + 0.5 * (t - t_parent));
        }
        let mut best: Option<Probe> = None;
        let try_seeds = |pair: &mut Pair, seeds: &[Point3<f64>], best: &mut Option<Probe>| {
            if seeds.is_empty() {
                return false;
            }
            let climbed = pair
                .certify_from(seeds, 0.5 * reach, step_tol, &w, need)
                .expect("seeds given");
            if best.is_none_or(|b| climbed.bound(&w) > b.bound(&w)) {
                *best = Some(climbed);
            }
            covers(&climbed)
        };
        let mut certified = try_seeds(&mut pair, &seeds, &mut best);
        // The anchors when the parent's region certifies nothing here (it separated).
        let hint_lost = best.is_none_or(|p| p.certified_bound(&w).is_none());
        if !certified && hint_lost {
            seeds.clear();
            seeds.extend(spec.anchors.iter().map(|x| x + 0.5 * t));
            certified = try_seeds(&mut pair, &seeds, &mut best);
        }
        out.probes += pair.probes;
        if certified {
            continue;
        }
        if reach <= spec.resolution {
            limit = cell.r0;
            out.capped_at = Some(t);
            continue;
        }
        let hint = best
            .filter(|p| p.certified_bound(&w).is_some())
            .map(|p| (p.x, t))
            .or(cell.hint);
        for child in cell.split(hint) {
            heap.push(by_inner(child));
        }
    }
    out.lower = (limit - rounding).max(spec.from);
    out
}
