//! A certified lower bound of a ball's translational depth in a solid of revolution, by
//! covering a disk of the solid's meridian plane (module doc of
//! [`mod@crate::query::penetration`]).
//!
//! **Statement.** Let the open ball `U(c, r)` lie inside the true solid B, and let A be a
//! solid of revolution. Translating B by `t` leaves A and `B + t` overlapping whenever
//! `d(c + t, A) < r`: the ball `U(c + t, r)` then holds a point of A, and A, a solid, has
//! interior points there too. So `PD(A, B) >= L` as soon as every point within `L` of `c`
//! lies closer than `r` to A. A's distance is the planar distance of the meridian point
//! `(hypot(x, y), z)` to the profile region, and a point within `L` of `c` has its meridian
//! point within `L` of `c`'s (`| |q_xy| - |c_xy| | <= |q_xy - c_xy|`), so it is enough that
//! the half-disk `D(m_c, L)`, `rho >= 0`, of the meridian plane lies in the region where the
//! profile region is nearer than `r`.
//!
//! **Certificate.** The approximating chain's classification and margin `m` at a meridian
//! point `q` bound the true distance ([`crate::bvh::containment`]): 0 when `q` is inside by
//! more than the tree's bound `e`, at most `m + e` otherwise. With the rounding `slack`,
//! `h(q) = r - slack - that bound` is a lower bound of `r - d(q, A)`, and it is 1-Lipschitz,
//! so a point `q` with `h(q) > R` certifies the whole disk `D(q, R)`. The half-disk is split
//! into polar cells (radius `[s0, s1]`, angle `[phi0, phi1]`, every point within
//! `(s1 - s0) / 2 + s1 (phi1 - phi0) / 2` of the cell's centre); a cell is certified by its
//! centre, split when not, and abandoned below a resolution, which caps `L` at its inner
//! radius. Cells are taken by increasing inner radius, so a cap drops every cell beyond it.
//! The disk's centre is `m_c` itself; a cell reaching across the axis is judged at its
//! centre's mirror image, no farther from any of its points in the half-plane.
//!
//! The refinement gathers where the disk's edge meets the region's boundary, at the ball's
//! ways out: the bound it returns is within about the resolution of the exact depth of the
//! ball (the nearest point of the level set `d(., A) >= r`), concave contacts included,
//! where one point's Lipschitz bound `r - d(c, A)` falls short.

use crate::bvh::containment::point_in_profile_capped;
use crate::bvh::offset_solid::{Core, OffsetSolid};
use crate::bvh::QueryTree;
use crate::num::SmallestFirst;
use nalgebra::{Isometry3, Point2, Point3, Vector2, Vector3};
use std::collections::BinaryHeap;
use std::f64::consts::TAU;

/// Most classifications one bound may spend; past it the disk is capped at the inner radius
/// of the next cell (a weaker bound, still certified).
pub const MAX_CELLS: usize = 4000;

/// Angular sectors the disk starts as (each at most a quarter turn keeps the cells' chord
/// bound tight).
const SECTORS: usize = 8;

/// Relative allowance for the rounding of a cell's centre and radius (a few ulps of the
/// disk's coordinates, far below the resolutions asked).
const CELL_ROUNDING_REL: f64 = 1e-12;

/// A polar cell of the disk about the ball's meridian point.
#[derive(Debug, Clone, Copy)]
struct Cell {
    s0: f64,
    s1: f64,
    phi0: f64,
    phi1: f64,
}

impl Cell {
    /// Every point of the cell lies within this of [`Cell::centre`]: half the radial extent
    /// plus the outer arc's half length.
    fn reach(&self) -> f64 {
        0.5 * (self.s1 - self.s0) + 0.5 * self.s1 * (self.phi1 - self.phi0)
    }

    fn centre(&self, m: Point2<f64>) -> Point2<f64> {
        m + self.centre_offset()
    }

    /// The cell's centre as an offset from the disk's centre (radial, axial).
    fn centre_offset(&self) -> Vector2<f64> {
        let s = 0.5 * (self.s0 + self.s1);
        let phi = 0.5 * (self.phi0 + self.phi1);
        Vector2::new(s * phi.cos(), s * phi.sin())
    }

    /// Largest `rho` of the cell's points (cells never reach past a full turn: the disk
    /// starts as sectors of `[0, TAU]`).
    fn max_rho(&self, m: Point2<f64>) -> f64 {
        let cos_max = if self.phi0 <= 0.0 || self.phi1 >= TAU {
            1.0
        } else {
            self.phi0.cos().max(self.phi1.cos())
        };
        let s = if cos_max >= 0.0 { self.s1 } else { self.s0 };
        m.x + s * cos_max
    }

    /// The two halves along the longer of the radial extent and the outer arc.
    fn split(&self) -> [Cell; 2] {
        if self.s1 - self.s0 >= self.s1 * (self.phi1 - self.phi0) {
            let s = 0.5 * (self.s0 + self.s1);
            [Cell { s1: s, ..*self }, Cell { s0: s, ..*self }]
        } else {
            let phi = 0.5 * (self.phi0 + self.phi1);
            [Cell { phi1: phi, ..*self }, Cell { phi0: phi, ..*self }]
        }
    }
}

/// Heap entry: cells are taken by increasing inner radius.
fn by_inner(cell: Cell) -> SmallestFirst<Cell> {
    SmallestFirst {
        key: cell.s0,
        tie: 0.0,
        item: cell,
    }
}

/// What one bound found.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BallDepth {
    /// Certified: `PD >= lower` for the ball inside B against A (module doc).
    pub lower: f64,
    /// Classifications spent.
    pub cells: usize,
    /// The centre of the cell that capped `lower` below the reach, too small to split, as
    /// an offset from the centre's meridian point (radial, axial): where the ball gets out,
    /// within the resolution (`None` when the cells ran out first).
    pub capped_at: Option<Vector2<f64>>,
}

/// Certified lower bound of the depth of the ball `U(centre, radius)` (A's own frame; the
/// ball inside the other solid) against the solid of `tree`, at most `reach` (a known upper
/// bound of the depth, or any radius the search should not pass), resolved to `resolution`:
/// the bound is within about that of the exact depth unless [`MAX_CELLS`] runs out. `slack`
/// is the rounding budget of the pose that placed `centre`.
pub fn ball_depth_lower(
    tree: &QueryTree,
    centre: &Point3<f64>,
    radius: f64,
    reach: f64,
    resolution: f64,
    slack: f64,
) -> BallDepth {
    let e = tree.eps;
    let r = radius - slack;
    if !(r > e && reach > 0.0 && resolution > 0.0 && reach.is_finite()) {
        return BallDepth {
            lower: 0.0,
            cells: 0,
            capped_at: None,
        };
    }
    let m = Point2::new(centre.x.hypot(centre.y), centre.z);
    // r - slack - (an upper bound of the true distance to A) at a meridian point, judged at
    // its mirror image across the axis when rho < 0.
    let h = |q: Point2<f64>| {
        let inside = point_in_profile_capped(tree, Point2::new(q.x.abs(), q.y), r);
        if inside.inside && inside.margin > e {
            r
        } else {
            r - (inside.margin + e)
        }
    };
    let rounding = CELL_ROUNDING_REL * (m.coords.norm() + reach);
    let mut limit = reach;
    let mut heap = BinaryHeap::new();
    for k in 0..SECTORS {
        heap.push(by_inner(Cell {
            s0: 0.0,
            s1: reach,
            phi0: TAU * k as f64 / SECTORS as f64,
            phi1: TAU * (k + 1) as f64 / SECTORS as f64,
        }));
    }
    let mut cells = 0;
    let mut capped_at = None;
    while let Some(SmallestFirst { item: mut cell, .. }) = heap.pop() {
        if cell.s0 >= limit {
            break;
        }
        cell.s1 = cell.s1.min(limit);
        if cell.max_rho(m) < 0.0 {
            continue;
        }
        if cells >= MAX_CELLS {
            // Capped by the budget: the cell left is no way out.
            limit = cell.s0;
            capped_at = None;
            break;
        }
        cells += 1;
        let reach_cell = cell.reach();
        if h(cell.centre(m)) > reach_cell + rounding {
            continue;
        }
        if reach_cell <= resolution {
            limit = cell.s0;
            capped_at = Some(cell.centre_offset());
            continue;
        }
        for half in cell.split() {
            heap.push(by_inner(half));
        }
    }
    BallDepth {
        lower: (limit - rounding).max(0.0),
        cells,
        capped_at,
    }
}

/// A meridian-plane offset (radial, axial) from the point `c` as a 3-D vector: the radial
/// part along `c`'s direction from the axis (the x axis for a point on it).
fn lift(c: &Point3<f64>, offset: Vector2<f64>) -> Vector3<f64> {
    let rho = c.x.hypot(c.y);
    let (ux, uy) = if rho > 0.0 {
        (c.x / rho, c.y / rho)
    } else {
        (1.0, 0.0)
    };
    Vector3::new(offset.x * ux, offset.x * uy, offset.y)
}

/// [`ball_depth_lower`]'s answer for a pair of which one solid is a detected ball.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DetectedBall {
    pub depth: BallDepth,
    /// The ball's centre, A's frame.
    pub centre: Point3<f64>,
    /// B's translation (A's frame) that moves the ball to the cell that capped the bound
    /// ([`BallDepth::capped_at`]): the direction to search for its way out.
    pub capped_translation: Option<Vector3<f64>>,
}

/// The bound of [`ball_depth_lower`] for a pair of which one solid is a detected ball
/// ([`crate::bvh::offset_solid`]: the true solid holds the ball of the detected radius less
/// the detection's error about its core point), with the ball's centre in A's frame; the
/// better of the two when both are balls, `None` when neither is.
pub fn detected_ball_lower(
    ta: &QueryTree,
    tb: &QueryTree,
    pos_ab: &Isometry3<f64>,
    reach: f64,
    resolution: f64,
    slack: f64,
) -> Option<DetectedBall> {
    let inner_ball = |t: &QueryTree| match t.offset {
        Some(OffsetSolid {
            core: Core::Point { z },
            radius,
            error,
        }) => Some((Point3::new(0.0, 0.0, z), radius - error)),
        _ => None,
    };
    // The ball in B, against A: B moves with the ball's centre.
    let in_b = inner_ball(tb).map(|(c, r)| {
        let centre = pos_ab * c;
        let depth = ball_depth_lower(ta, &centre, r, reach, resolution, slack);
        DetectedBall {
            depth,
            centre,
            capped_translation: depth.capped_at.map(|off| lift(&centre, off)),
        }
    });
    // The ball in A, against B (B's frame): moving the ball by `v` relative to B is moving
    // B by `-v`, turned into A's frame.
    let in_a = inner_ball(ta).map(|(c, r)| {
        let centre_in_b = pos_ab.inverse() * c;
        let depth = ball_depth_lower(tb, &centre_in_b, r, reach, resolution, slack);
        DetectedBall {
            depth,
            centre: c,
            capped_translation: depth
                .capped_at
                .map(|off| -(pos_ab.rotation * lift(&centre_in_b, off))),
        }
    });
    match (in_a, in_b) {
        (Some(x), Some(y)) => Some(if x.depth.lower >= y.depth.lower { x } else { y }),
        (x, y) => x.or(y),
    }
}
