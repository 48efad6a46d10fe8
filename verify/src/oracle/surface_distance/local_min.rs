//! The upper estimate: local minimisations of the distance over a surface's parameters
//! (BFGS, hopping across piece joints) and alternating projections between the surfaces
//! (module documentation of [`super`], "Upper estimate").

use super::cells::Cell;
use super::direction::{surface_foot, BetterThan, Dir, Pair, State};
use super::options::OracleOptions;
use crate::oracle::profile_eval::norm;
use nalgebra::Point3;

impl<'a> Dir<'a> {
    /// Local minimisation of `f` from `(k, t, th)` (see the module documentation).
    pub(super) fn refine(&self, mut k: usize, mut t: f64, mut th: f64, st: &mut State) -> Pair {
        st.refinements += 1;
        let size = self.src.geom.size.max(self.dst.geom.size);
        let (mut pair, mut g) = self.f_grad(k, t, th);
        let mut hops = 0;
        'outer: loop {
            let pc = &self.src.geom.pieces[k];
            let speed = norm(self.src.geom.jet(k, t).d1).max(1e-12 * size);
            let srho = self.src.geom.point(k, t)[0].abs().max(1e-3 * size);
            let scale = [1.0 / speed, 1.0 / srho];
            // Inverse Hessian in scaled variables v = (t * speed, th * srho).
            let mut h = [[0.1 * size, 0.0], [0.0, 0.1 * size]];
            let mut first = true;
            for _ in 0..200 {
                if pair.d == 0.0 {
                    break 'outer;
                }
                let gv = [g[0] * scale[0], g[1] * scale[1]];
                let mut dir = [
                    -(h[0][0] * gv[0] + h[0][1] * gv[1]),
                    -(h[1][0] * gv[0] + h[1][1] * gv[1]),
                ];
                // Bound: an active constraint removes the outward t component.
                let at_lo = t <= pc.t0 && dir[0] < 0.0;
                let at_hi = t >= pc.t1 && dir[0] > 0.0;
                if at_lo || at_hi {
                    let outward_descent = if at_lo { g[0] > 0.0 } else { g[0] < 0.0 };
                    if outward_descent && hops < 6 {
                        let next = if at_lo {
                            self.src.geom.prev_piece(k)
                        } else {
                            self.src.geom.next_piece(k)
                        };
                        if let Some(nk) = next {
                            let npc = &self.src.geom.pieces[nk];
                            let nt = if at_lo { npc.t1 } else { npc.t0 };
                            let (np, ng) = self.f_grad(nk, nt, th);
                            hops += 1;
                            // Move on only if the neighbour's slope continues downhill.
                            let downhill = if at_lo { ng[0] > 0.0 } else { ng[0] < 0.0 };
                            if downhill && np.d <= pair.d * (1.0 + 1e-12) + 1e-300 {
                                k = nk;
                                t = nt;
                                pair = np;
                                g = ng;
                                continue 'outer;
                            }
                        }
                    }
                    dir[0] = 0.0;
                    dir[1] = -h[1][1] * gv[1];
                }
                let slope = dir[0] * gv[0] + dir[1] * gv[1];
                if slope >= 0.0 || (dir[0].abs() + dir[1].abs()) < 1e-16 * size {
                    break 'outer;
                }
                // Armijo backtracking.
                let mut alpha = 1.0;
                let mut accepted = None;
                for _ in 0..40 {
                    let nt = (t + alpha * dir[0] * scale[0]).clamp(pc.t0, pc.t1);
                    let nth = th + alpha * dir[1] * scale[1];
                    let (np, ng) = self.f_grad(k, nt, nth);
                    if np.d <= pair.d + 1e-4 * alpha * slope {
                        accepted = Some((nt, nth, np, ng));
                        break;
                    }
                    alpha *= 0.5;
                }
                let Some((nt, nth, np, ng)) = accepted else {
                    break 'outer;
                };
                let sv = [(nt - t) / scale[0], (nth - th) / scale[1]];
                let yv = [ng[0] * scale[0] - gv[0], ng[1] * scale[1] - gv[1]];
                let improvement = pair.d - np.d;
                t = nt;
                th = nth;
                pair = np;
                g = ng;
                let sy = sv[0] * yv[0] + sv[1] * yv[1];
                if sy > 0.0 {
                    if first {
                        let yy = yv[0] * yv[0] + yv[1] * yv[1];
                        let gamma = sy / yy;
                        h = [[gamma, 0.0], [0.0, gamma]];
                        first = false;
                    }
                    // BFGS inverse update: H = (I - rho s y^T) H (I - rho y s^T) + rho s s^T.
                    let rho = 1.0 / sy;
                    let hy = [
                        h[0][0] * yv[0] + h[0][1] * yv[1],
                        h[1][0] * yv[0] + h[1][1] * yv[1],
                    ];
                    let yhy = yv[0] * hy[0] + yv[1] * hy[1];
                    for a in 0..2 {
                        for b in 0..2 {
                            h[a][b] += -rho * (sv[a] * hy[b] + hy[a] * sv[b])
                                + (rho * rho * yhy + rho) * sv[a] * sv[b];
                        }
                    }
                }
                let step = (sv[0] * sv[0] + sv[1] * sv[1]).sqrt();
                if step < 1e-15 * size || improvement <= 1e-17 * size {
                    break 'outer;
                }
            }
            break;
        }
        self.polish(pair)
    }

    /// Alternating projections: the closest point of the source surface to `x`, then of the
    /// target surface to that, while the distance decreases.
    pub(super) fn polish(&self, mut pair: Pair) -> Pair {
        for _ in 0..6 {
            if pair.d == 0.0 {
                break;
            }
            // Project x (source frame) onto the source surface.
            let x = pair.x;
            let y = surface_foot(self.src, &x);
            // Project y onto the target surface.
            let q = self.to_dst(&y);
            let foot = surface_foot(self.dst, &q);
            let xn = self.to_src(&foot);
            let d = (y - xn).norm();
            if d < pair.d {
                let gain = pair.d - d;
                pair = Pair { d, y, x: xn };
                if gain <= 1e-15 * (1.0 + d) {
                    break;
                }
            } else {
                break;
            }
        }
        pair
    }

    /// Local minimisations from the best, mutually distant cells of the evaluated grid.
    pub(super) fn seed(&self, cells: &[Cell], opts: &OracleOptions, st: &mut State) {
        let l0 = opts.initial_rel * self.src.geom.size;
        // Seeds: best centres, mutually at least 2 l0 apart (in the source frame).
        let mut order: Vec<usize> = (0..cells.len()).collect();
        order.sort_by(|&a, &b| cells[a].f.total_cmp(&cells[b].f));
        let mut chosen: Vec<Point3<f64>> = Vec::new();
        for &i in &order {
            if chosen.len() >= opts.seeds {
                break;
            }
            let c = &cells[i];
            let tm = 0.5 * (c.ta + c.tb);
            let thm = 0.5 * (c.th0 + c.th1);
            let y = self.surface_point(c.k as usize, tm, thm);
            if chosen.iter().any(|z| (z - y).norm() < 2.0 * l0) {
                continue;
            }
            chosen.push(y);
            let p = self.refine(c.k as usize, tm, thm, st);
            self.census_at(&p.y, st);
            if st.best.is_none_or_worse(p.d) {
                st.best = Some(p);
            }
        }
    }

    /// The realised pair at the centre of the grid cell nearest the target.
    pub(super) fn grid_pair(&self, cells: &[Cell]) -> Option<Pair> {
        let c = cells.iter().min_by(|a, b| a.f.total_cmp(&b.f))?;
        Some(
            self.f_grad(c.k as usize, 0.5 * (c.ta + c.tb), 0.5 * (c.th0 + c.th1))
                .0,
        )
    }
}
