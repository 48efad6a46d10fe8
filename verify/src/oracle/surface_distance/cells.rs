//! Cells of the branch and bound: their radius bound, evaluation with the inside census, the
//! initial grid and the split (module documentation of [`super`], "Lower estimate").

use super::direction::{Dir, State};
use super::options::OracleOptions;
use super::{ARC_SAFETY, MAX_TURN};
use crate::oracle::profile_eval::{dist, P2};
use std::cmp::Ordering;

#[derive(Debug, Clone, Copy)]
pub(super) struct Cell {
    pub(super) k: u32,
    pub(super) ta: f64,
    pub(super) tb: f64,
    pub(super) th0: f64,
    pub(super) th1: f64,
    pub(super) r_param: f64,
    pub(super) lb: f64,
    pub(super) r: f64,
    pub(super) f: f64,
    pub(super) rho: f64,
}

#[derive(PartialEq)]
pub(super) struct HeapKey(pub(super) f64, pub(super) usize);
impl Eq for HeapKey {}
impl PartialOrd for HeapKey {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for HeapKey {
    fn cmp(&self, o: &Self) -> Ordering {
        // Min-heap on the bound.
        o.0.total_cmp(&self.0).then(o.1.cmp(&self.1))
    }
}

impl<'a> Dir<'a> {
    /// Bound on the distance from `C(tm)` to the arc `C([ta, tb])` (two-chord arc lengths).
    pub(super) fn r_param(&self, k: usize, ta: f64, tb: f64) -> (f64, P2) {
        let g = &self.src.geom;
        let tm = 0.5 * (ta + tb);
        let p0 = g.point(k, ta);
        let p1 = g.point(k, 0.5 * (ta + tm));
        let p2 = g.point(k, tm);
        let p3 = g.point(k, 0.5 * (tm + tb));
        let p4 = g.point(k, tb);
        let left = dist(p0, p1) + dist(p1, p2);
        let right = dist(p2, p3) + dist(p3, p4);
        (ARC_SAFETY * left.max(right), p2)
    }

    pub(super) fn make_cell(
        &self,
        k: usize,
        ta: f64,
        tb: f64,
        th0: f64,
        th1: f64,
        r_param: f64,
    ) -> Cell {
        let tm = 0.5 * (ta + tb);
        let p = self.src.geom.point(k, tm);
        Cell {
            k: k as u32,
            ta,
            tb,
            th0,
            th1,
            r_param,
            lb: 0.0,
            r: r_param + 2.0 * p[0].abs() * ((th1 - th0) / 4.0).sin(),
            f: 0.0,
            rho: p[0],
        }
    }

    /// Evaluates a cell's centre: polyline distance, bound, and (with `census`) the inside
    /// census.
    /// `parent` is the enclosing cell's (distance, radius) when known: the centre is within
    /// the parent's radius of the parent's centre, which bounds the search.
    pub(super) fn eval_cell(
        &self,
        c: &mut Cell,
        st: &mut State,
        census: bool,
        parent: Option<(f64, f64)>,
    ) {
        st.cells += 1;
        let tm = 0.5 * (c.ta + c.tb);
        let thm = 0.5 * (c.th0 + c.th1);
        let y = self.surface_point(c.k as usize, tm, thm);
        let q = self.to_dst(&y);
        let q2 = [q.x.hypot(q.y), q.z];
        let dpoly = match parent {
            Some((f, r)) => self.dst.poly_distance_hint(q2, f + r),
            None => self.dst.poly_distance(q2),
        };
        let sag = self.dst.geom.sag;
        c.f = dpoly;
        c.lb = dpoly - sag - c.r;
        if !census {
            return;
        }
        let inside_depth = if dpoly > 2.0 * sag {
            if self.dst.inside_poly(q2) {
                Some(dpoly - sag)
            } else {
                None
            }
        } else {
            let s = self.dst.signed(q2);
            (s.value < 0.0).then_some(-s.value)
        };
        if let Some(depth) = inside_depth {
            if -depth < st.min_signed {
                st.min_signed = -depth;
                st.deep = Some(y);
            }
            if depth > self.margin {
                st.inside = true;
            }
        }
    }

    /// Initial cells: parameter intervals with turning below [`MAX_TURN`] and arc radius
    /// below `l0 / 2`, times angle intervals of length about `l0`.
    pub(super) fn initial_cells(&self, l0: f64) -> Vec<Cell> {
        let g = &self.src.geom;
        let mut out = Vec::new();
        let mut stack = Vec::new();
        for (k, pc) in g.pieces.iter().enumerate() {
            for w in pc.breaks.windows(2) {
                if w[1] <= w[0] {
                    continue;
                }
                stack.push((w[0], w[1], 0));
                while let Some((ta, tb, depth)) = stack.pop() {
                    let (rp, _) = self.r_param(k, ta, tb);
                    let tm = 0.5 * (ta + tb);
                    let p0 = g.point(k, ta);
                    let p2 = g.point(k, tm);
                    let p4 = g.point(k, tb);
                    let c1 = [p2[0] - p0[0], p2[1] - p0[1]];
                    let c2 = [p4[0] - p2[0], p4[1] - p2[1]];
                    let turn = (c1[0] * c2[1] - c1[1] * c2[0])
                        .atan2(c1[0] * c2[0] + c1[1] * c2[1])
                        .abs();
                    if depth < 24 && (rp > 0.5 * l0 || turn > MAX_TURN) {
                        stack.push((tm, tb, depth + 1));
                        stack.push((ta, tm, depth + 1));
                        continue;
                    }
                    let rho = p0[0].max(p2[0]).max(p4[0]).max(0.0);
                    let n_th = ((std::f64::consts::TAU * rho / l0).ceil() as usize).clamp(4, 4096);
                    let dth = std::f64::consts::TAU / n_th as f64;
                    for i in 0..n_th {
                        out.push(self.make_cell(
                            k,
                            ta,
                            tb,
                            i as f64 * dth,
                            (i + 1) as f64 * dth,
                            rp,
                        ));
                    }
                }
            }
        }
        out
    }

    /// One direction's initial grid, evaluated (with the inside census).
    pub(super) fn grid(&self, opts: &OracleOptions, st: &mut State) -> Vec<Cell> {
        let l0 = opts.initial_rel * self.src.geom.size;
        let mut cells = self.initial_cells(l0);
        for c in cells.iter_mut() {
            self.eval_cell(c, st, true, None);
        }
        cells
    }

    /// The two halves of a cell, split in the dimension contributing more to its radius.
    pub(super) fn split(&self, c: &Cell) -> [Cell; 2] {
        let th_part = 2.0 * c.rho.abs() * ((c.th1 - c.th0) / 4.0).sin();
        let k = c.k as usize;
        if th_part > c.r_param {
            let thm = 0.5 * (c.th0 + c.th1);
            [
                self.make_cell(k, c.ta, c.tb, c.th0, thm, c.r_param),
                self.make_cell(k, c.ta, c.tb, thm, c.th1, c.r_param),
            ]
        } else {
            let tm = 0.5 * (c.ta + c.tb);
            let (r1, _) = self.r_param(k, c.ta, tm);
            let (r2, _) = self.r_param(k, tm, c.tb);
            [
                self.make_cell(k, c.ta, tm, c.th0, c.th1, r1),
                self.make_cell(k, tm, c.tb, c.th0, c.th1, r2),
            ]
        }
    }
}
