//! The oracle's entry points: both directions' grids, seeds and branch and bound combined
//! into an [`OracleResult`], and the polish of a hinted pair (module documentation of
//! [`super`]).

use super::direction::{Dir, Pair, State};
use super::options::OracleOptions;
use super::result::OracleResult;
use super::INSIDE_MARGIN_REL;
use crate::oracle::planar::PlanarIndex;
use nalgebra::{Isometry3, Point3};

/// The oracle: surface distance and inside census of A (at the identity) and B placed by
/// `pos_ab` (a point `x` of B's frame is at `pos_ab * x` in A's frame).
pub fn surface_distance(
    a: &PlanarIndex,
    b: &PlanarIndex,
    pos_ab: &Isometry3<f64>,
    opts: &OracleOptions,
) -> OracleResult {
    let scale = a.geom.size.max(b.geom.size);
    let scene = 1.0 + pos_ab.translation.vector.norm() + a.geom.size + b.geom.size;
    let margin = INSIDE_MARGIN_REL * scene;
    let inv = pos_ab.inverse();
    let ab = Dir::new(a, b, &inv, margin);
    let ba = Dir::new(b, a, pos_ab, margin);
    let new_state = State::new;
    // Pairs move between the two directions' frames: (y on A, x on B) in A's frame is
    // (x, y) mapped by `inv` in B's frame.
    let to_ba = |p: Pair| Pair {
        d: p.d,
        y: inv * p.x,
        x: inv * p.y,
    };
    let to_ab = |p: Pair| Pair {
        d: p.d,
        y: pos_ab * p.x,
        x: pos_ab * p.y,
    };
    // Both grids first (the directions' states are separate, so this order gives the same
    // results as grid, seeds, grid, seeds), then, in quick mode with a goal, the test that
    // makes the local minimisations pointless.
    let mut st_ab = new_state();
    let cells_ab = ab.grid(opts, &mut st_ab);
    let mut st_ba = new_state();
    let cells_ba = ba.grid(opts, &mut st_ba);
    let cleared = !opts.bound && opts.goal.is_finite() && {
        let level = opts.goal.max(0.0);
        if cells_ab.len() <= cells_ba.len() {
            ab.clears(&cells_ab, level, cells_ab.len(), &mut st_ab)
        } else {
            ba.clears(&cells_ba, level, cells_ba.len(), &mut st_ba)
        }
    };
    if cleared {
        // Every realised pair is farther apart than the goal and the boundaries do not
        // meet: one realised pair stands for the upper estimate; the grids' census stands.
        st_ab.best = ab.grid_pair(&cells_ab);
    } else {
        ab.seed(&cells_ab, opts, &mut st_ab);
    }
    st_ba.best = st_ab.best.map(to_ba);
    if !cleared {
        ba.seed(&cells_ba, opts, &mut st_ba);
    }
    let mut budget_hit = false;
    // Branch and bound in one direction (both give lower bounds of the same surface
    // distance): the one with the smaller grid.
    let (lower, best) = if !opts.bound {
        (0.0, st_ba.best.map(to_ab))
    } else if cells_ab.len() <= cells_ba.len() {
        st_ab.best = st_ba.best.map(to_ab);
        let l = ab.branch_and_bound(cells_ab, opts, scale, &mut st_ab, &mut budget_hit);
        (l, st_ab.best)
    } else {
        let l = ba.branch_and_bound(cells_ba, opts, scale, &mut st_ba, &mut budget_hit);
        (l, st_ba.best.map(to_ab))
    };
    let best = best.expect("the grid has cells");
    let (point_a, point_b) = (best.y, best.x);
    let lower = if opts.bound {
        lower.max(0.0).min(best.d)
    } else {
        0.0
    };
    let deep_point = if st_ab.min_signed <= st_ba.min_signed {
        st_ab.deep
    } else {
        st_ba.deep.map(|p| pos_ab * p)
    };
    OracleResult {
        upper: best.d,
        lower,
        point_a,
        point_b,
        min_signed: st_ab.min_signed.min(st_ba.min_signed),
        deep_point,
        a_in_b: st_ab.inside,
        b_in_a: st_ba.inside,
        cells: st_ab.cells + st_ba.cells,
        refinements: st_ab.refinements + st_ba.refinements,
        budget_hit,
    }
}

/// Polishes a hinted pair (e.g. a query's witnesses, in A's frame): projects `pa` onto A's
/// surface and alternates projections. Returns the realised distance and pair in A's frame.
pub fn refine_hint(
    a: &PlanarIndex,
    b: &PlanarIndex,
    pos_ab: &Isometry3<f64>,
    pa: &Point3<f64>,
    pb: &Point3<f64>,
) -> (f64, Point3<f64>, Point3<f64>) {
    let inv = pos_ab.inverse();
    let ab = Dir::new(a, b, &inv, 0.0);
    let mut st = State::new();
    // Start on A at the projection of pa, with pb as the partner; polish, then minimise.
    let rho = pa.x.hypot(pa.y);
    let c = a.closest([rho, pa.z]);
    let th = pa.y.atan2(pa.x);
    let start = ab.polish(Pair {
        d: f64::INFINITY,
        y: *pa,
        x: *pb,
    });
    let p = ab.refine(c.piece, c.t, th, &mut st);
    let best = if start.d < p.d { start } else { p };
    (best.d, best.y, best.x)
}
