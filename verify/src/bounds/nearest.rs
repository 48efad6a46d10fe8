//! Near-minimising pairs of two revolved chains, in f64: the upper side of the test.
//!
//! For a point `x` of one surface the distance to the other surface of revolution is exact
//! in closed form (the planar distance in `x`'s meridian half-plane of the other frame,
//! [`closest_on_chain`]), so the search is over the two parameters `(s, theta)` of one
//! surface only: a grid on every piece, then a pattern search (steps halved until they are
//! below 1e-16) from the best grid points, then alternating projections between the
//! surfaces. Both directions (A's points against B, B's against A) are searched, and the
//! caller may add seed pairs (a constructed contact, a kernel's witnesses) that are polished
//! the same way. Every pair returned is two actual surface points given by parameters, so
//! its distance is realised whatever the search missed; how close it comes to the minimum
//! is measured against the exact kernel in the report.

use super::chain::{closest_on_chain, point, Pair, SurfacePoint};
use nalgebra::Isometry3;
use revdist::bvh::ProfileArc;
use std::f64::consts::TAU;

/// Grid of one piece: parameter samples (ends included) and revolution angles.
const GRID_S: usize = 20;
const GRID_THETA: usize = 40;
/// Grid points refined per direction.
const STARTS: usize = 3;
/// Alternating projections after the pattern search.
const PROJECTIONS: usize = 12;

/// One search direction: points of `source` (its frame) against `target`, which
/// `to_target` maps into.
struct Direction<'c> {
    source: &'c [ProfileArc],
    target: &'c [ProfileArc],
    to_target: Isometry3<f64>,
}

impl Direction<'_> {
    fn value(&self, x: &SurfacePoint) -> (f64, SurfacePoint) {
        closest_on_chain(self.target, &(self.to_target * point(self.source, x)))
    }

    fn grid(&self) -> Vec<(f64, SurfacePoint)> {
        let mut all = Vec::with_capacity(self.source.len() * (GRID_S + 1) * GRID_THETA);
        for piece in 0..self.source.len() {
            for i in 0..=GRID_S {
                for k in 0..GRID_THETA {
                    let x = SurfacePoint {
                        piece,
                        s: i as f64 / GRID_S as f64,
                        theta: k as f64 * TAU / GRID_THETA as f64,
                    };
                    all.push((self.value(&x).0, x));
                }
            }
        }
        all.sort_by(|a, b| a.0.total_cmp(&b.0));
        all
    }

    /// Pattern search in `(s, theta)` on the start's piece.
    fn descend(&self, start: SurfacePoint) -> SurfacePoint {
        let mut x = start;
        let mut fx = self.value(&x).0;
        let (mut hs, mut ht) = (1.0 / GRID_S as f64, TAU / GRID_THETA as f64);
        for _ in 0..400 {
            if hs < 1e-17 && ht < 1e-17 {
                break;
            }
            let mut moved = false;
            for (ds, dt) in [
                (hs, 0.0),
                (-hs, 0.0),
                (0.0, ht),
                (0.0, -ht),
                (hs, ht),
                (-hs, -ht),
                (hs, -ht),
                (-hs, ht),
            ] {
                let y = SurfacePoint {
                    piece: x.piece,
                    s: (x.s + ds).clamp(0.0, 1.0),
                    theta: x.theta + dt,
                };
                let fy = self.value(&y).0;
                if fy < fx {
                    (x, fx, moved) = (y, fy, true);
                }
            }
            if !moved {
                hs *= 0.5;
                ht *= 0.5;
            }
        }
        x
    }
}

/// The best realised pairs found between chains `a` (frame A) and `b` (placed by
/// `pos_ab`), smallest first, at most `keep`.
pub fn nearest_pairs(
    a: &[ProfileArc],
    b: &[ProfileArc],
    pos_ab: &Isometry3<f64>,
    seeds: &[Pair],
    keep: usize,
) -> Vec<Pair> {
    let pos_ba = pos_ab.inverse();
    let forward = Direction {
        source: a,
        target: b,
        to_target: pos_ba,
    };
    let backward = Direction {
        source: b,
        target: a,
        to_target: *pos_ab,
    };
    let mut found: Vec<Pair> = Vec::new();
    for (dir, a_is_source) in [(&forward, true), (&backward, false)] {
        let grid = dir.grid();
        let mut starts: Vec<SurfacePoint> = Vec::new();
        for (_, x) in grid {
            if starts.len() == STARTS {
                break;
            }
            let near = starts.iter().any(|y| {
                y.piece == x.piece
                    && (y.s - x.s).abs() <= 1.5 / GRID_S as f64
                    && (y.theta - x.theta).abs() <= 1.5 * TAU / GRID_THETA as f64
            });
            if !near {
                starts.push(x);
            }
        }
        for s in starts {
            let x = dir.descend(s);
            let (_, y) = dir.value(&x);
            let pair = if a_is_source {
                Pair::new(a, b, pos_ab, x, y)
            } else {
                Pair::new(a, b, pos_ab, y, x)
            };
            found.push(project(a, b, pos_ab, &pos_ba, pair));
        }
    }
    for s in seeds {
        found.push(*s);
        found.push(project(a, b, pos_ab, &pos_ba, *s));
    }
    found.sort_by(|x, y| x.d.total_cmp(&y.d));
    found.truncate(keep);
    found
}

/// Alternating projections from `pair`: B's point nearest to A's, A's nearest to that, ...;
/// the best pair met.
fn project(
    a: &[ProfileArc],
    b: &[ProfileArc],
    pos_ab: &Isometry3<f64>,
    pos_ba: &Isometry3<f64>,
    pair: Pair,
) -> Pair {
    let mut best = pair;
    let mut p = pair.p;
    for _ in 0..PROJECTIONS {
        let (_, q) = closest_on_chain(b, &(pos_ba * point(a, &p)));
        let c = Pair::new(a, b, pos_ab, p, q);
        if c.d < best.d {
            best = c;
        }
        let (_, p2) = closest_on_chain(a, &(pos_ab * point(b, &q)));
        let c = Pair::new(a, b, pos_ab, p2, q);
        if c.d < best.d {
            best = c;
        }
        p = p2;
    }
    best
}
