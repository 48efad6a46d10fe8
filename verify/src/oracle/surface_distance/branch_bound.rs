//! The lower estimate: best-first branch and bound over the cells, and the quick mode's test
//! that the surfaces are farther apart than a goal (module documentation of [`super`],
//! "Lower estimate").

use super::cells::{Cell, HeapKey};
use super::direction::{BetterThan, Dir, State};
use super::options::OracleOptions;
use super::QUICK_GOAL_MIN_CELL_REL;
use std::collections::BinaryHeap;

impl<'a> Dir<'a> {
    /// Whether every point of the source surface is farther than `level` from the target
    /// surface: a best-first split of the grid's cells whose bound `lb` is at most `level`,
    /// until none is left (`true`) or `budget` cells were evaluated or a cell cannot shrink
    /// further (`false`). Without the census: the grid's census already ran.
    pub(super) fn clears(&self, cells: &[Cell], level: f64, budget: usize, st: &mut State) -> bool {
        let mut open: BinaryHeap<HeapKey> = BinaryHeap::new();
        let mut pool: Vec<Cell> = Vec::new();
        for c in cells.iter().filter(|c| c.lb <= level) {
            pool.push(*c);
            open.push(HeapKey(c.lb, pool.len() - 1));
        }
        let mut evals = 0;
        while let Some(HeapKey(_, i)) = open.pop() {
            let c = pool[i];
            if evals >= budget || c.r <= QUICK_GOAL_MIN_CELL_REL * self.src.geom.size {
                return false;
            }
            for mut kid in self.split(&c) {
                self.eval_cell(&mut kid, st, false, Some((c.f, c.r)));
                evals += 1;
                if kid.lb <= level {
                    pool.push(kid);
                    open.push(HeapKey(kid.lb, pool.len() - 1));
                }
            }
        }
        true
    }

    /// Branch and bound from the evaluated grid `cells`; returns the lower estimate.
    pub(super) fn branch_and_bound(
        &self,
        mut cells: Vec<Cell>,
        opts: &OracleOptions,
        scale: f64,
        st: &mut State,
        budget_hit: &mut bool,
    ) -> f64 {
        let tau = opts.tau_rel * scale;
        let mut heap: BinaryHeap<HeapKey> = cells
            .iter()
            .enumerate()
            .map(|(i, c)| HeapKey(c.lb, i))
            .collect();
        let mut leaf_min = f64::INFINITY;
        let mut evals = 0usize;
        let mut refinements = 0usize;
        let lower;
        loop {
            let Some(HeapKey(lb, i)) = heap.pop() else {
                lower = leaf_min;
                break;
            };
            let upper = st.best.map_or(f64::INFINITY, |p| p.d);
            let reached_goal = opts.goal.is_finite() && upper <= opts.goal;
            if lb.max(0.0) >= (upper - tau).min(opts.goal) || reached_goal {
                lower = lb.min(leaf_min);
                break;
            }
            if evals >= opts.max_cells {
                *budget_hit = true;
                lower = lb.min(leaf_min);
                break;
            }
            let c = cells[i];
            if c.r <= tau / 8.0 {
                leaf_min = leaf_min.min(lb);
                continue;
            }
            let k = c.k as usize;
            let mut kids = self.split(&c);
            for kid in kids.iter_mut() {
                self.eval_cell(kid, st, false, Some((c.f, c.r)));
                evals += 1;
                let upper = st.best.map_or(f64::INFINITY, |p| p.d);
                if kid.f - self.dst.geom.sag < upper - 0.5 * tau
                    && refinements < opts.max_refinements
                {
                    refinements += 1;
                    let p = self.refine(k, 0.5 * (kid.ta + kid.tb), 0.5 * (kid.th0 + kid.th1), st);
                    self.census_at(&p.y, st);
                    if st.best.is_none_or_worse(p.d) {
                        st.best = Some(p);
                    }
                }
                cells.push(*kid);
                heap.push(HeapKey(kid.lb, cells.len() - 1));
            }
        }
        lower
    }
}
