//! Distance between the boundary surfaces of two posed solids of revolution, with a realised
//! upper estimate, a lower estimate and an inside/outside census.
//!
//! # The reduction
//! For a point `y` of A's surface, the distance from `y` to B's surface of revolution equals
//! the planar distance from `y`'s `(rho, z)` in B's frame to B's profile curve (the closest
//! point of a surface of revolution lies in the meridian half-plane through `y`). So the
//! surface distance is `min over (t, theta) of f(t, theta)`, with
//! `f(t, theta) = dist_B(y_A(t, theta))`, `y_A` A's surface parametrised by the profile
//! parameter `t` and the revolution angle `theta`. The same is done with A and B swapped.
//!
//! # Lower estimate (branch and bound)
//! A *cell* is a parameter interval `[ta, tb]` of one piece of the source profile times an
//! angle interval `[th0, th1]`. Its surface patch lies within `r_cell` of the centre point
//! `c = y(tm, thm)`:
//! `|y(t, th) - c| <= |C(t) - C(tm)| + |R_th C(tm) - R_thm C(tm)| <= r_param + 2 rho(tm) sin((th1 - th0) / 4)`,
//! where `r_param` bounds the distance from `C(tm)` to the arc `C([ta, tb])` by the arc length
//! of each half, estimated by a two-chord inscribed polygon times [`ARC_SAFETY`] (cells start
//! with a turning angle below [`MAX_TURN`], where the two-chord polygon is within 0.3% of the
//! arc). `dist_B` is 1-Lipschitz in the 3-D point and
//! `dist_B >= poly_distance_B - sag_B` ([`super::planar`]), so every point of the cell is at
//! least `lb = poly_distance_B(c) - sag_B - r_cell` from B's surface. Cells are split (in
//! the dimension contributing more to `r_cell`) best-first by `lb` until the smallest `lb`
//! reaches `upper - tau`, or the budget runs out; the lower estimate is the smallest `lb`
//! left (clamped at 0). It is a lower bound up to the two stated estimates (sagitta and arc
//! length), both taken with a factor of safety. Both directions bound the same surface
//! distance, so the branch and bound runs in one of them only (the one with the smaller
//! initial grid); the other direction's grid still serves the inside census and seeds.
//! With a goal (`OracleOptions::goal`) the search stops as soon as the lower estimate is
//! known to be at least the goal, or cannot exceed it (the realised upper estimate is at or
//! below it): the estimate is then as tight as its user needs, and still a lower bound.
//!
//! # Upper estimate
//! From the best, mutually distant cells (and from any cell found later whose centre beats the
//! current upper by `tau / 2`), a local minimisation of `f` over `(t, theta)`: BFGS on scaled
//! variables with the gradient `n . dy/d(t, theta)` (`n` the unit vector from B's closest
//! point to `y`: envelope theorem), `t` clamped to its piece and hopping to the neighbouring
//! piece at a joint, then a few rounds of alternating projection between the two surfaces.
//! Every value is the distance of two actual surface points (own NURBS evaluation), so the
//! upper estimate is `>=` the true distance up to round-off.
//!
//! # Inside census
//! At every initial grid cell centre of both directions, and at every point a local
//! minimisation ends on, the sign of the planar distance in the other solid is taken
//! (polygon crossing parity, or the tangent side within `2 sag` of the polyline); a point
//! deeper than `poly_distance - sag > margin` (or a realised curve distance `> margin` on
//! the tangent branch) inside the other solid certifies that the solids overlap.
//! Solids overlap exactly when a point of one boundary lies inside the other solid (crossing
//! boundaries or nesting), so with both directions sampled, nesting is always seen; crossing
//! boundaries whose penetration falls between samples show up as `upper ~ 0`.

use super::planar::PlanarIndex;
use super::profile_eval::{dist, norm, P2};
use nalgebra::{Isometry3, Matrix3, Point3, Vector3};
use std::cmp::Ordering;
use std::collections::BinaryHeap;

/// Factor on the two-chord estimate of a half-cell's arc length.
pub const ARC_SAFETY: f64 = 1.02;
/// Largest turning angle (radians) between the two chords of an initial parameter interval.
pub const MAX_TURN: f64 = 0.35;
/// In quick mode with a goal, cells are not split below this radius (relative to the source
/// profile's size) to prove the surfaces apart; the local minimisations decide instead.
pub const QUICK_GOAL_MIN_CELL_REL: f64 = 1e-4;

/// How hard the oracle works.
#[derive(Debug, Clone, Copy)]
pub struct OracleOptions {
    /// Cell evaluations per direction in the branch and bound (after the initial grid).
    pub max_cells: usize,
    /// Stop splitting when `upper - lower <= tau_rel * scale` (scale: the larger profile).
    pub tau_rel: f64,
    /// Initial cell size relative to the source profile's size.
    pub initial_rel: f64,
    /// Local minimisations from the initial grid per direction.
    pub seeds: usize,
    /// Further local minimisations allowed during the branch and bound per direction.
    pub max_refinements: usize,
    /// Run the branch and bound at all (the quick mode only wants the upper estimate).
    pub bound: bool,
    /// The level the lower estimate must reach for its user (a campaign's check b needs it
    /// only up to the query's upper bound plus the slack): the branch and bound stops once
    /// every cell's bound reaches it, or once the realised upper estimate is at or below it
    /// (then no lower estimate can exceed it). Infinite: run to `upper - tau`.
    ///
    /// Without the branch and bound (quick mode) the goal is the level the realised upper
    /// estimate is compared with (a time-of-impact check asks whether some pair is closer
    /// than it, or the solids overlap): when the grid's cells, split best-first up to the
    /// grid's own size, prove the surfaces farther apart than `max(goal, 0)`, no local
    /// minimisation can realise a pair below the goal and the boundaries do not meet, so
    /// the minimisations are skipped; the grids' inside census (which sees nesting) stands.
    pub goal: f64,
}

impl OracleOptions {
    /// Thorough: tight lower estimate (used for the checks).
    pub fn full() -> Self {
        OracleOptions {
            max_cells: 30_000,
            tau_rel: 1e-4,
            initial_rel: 1.0 / 24.0,
            seeds: 6,
            max_refinements: 24,
            bound: true,
            goal: f64::INFINITY,
        }
    }

    /// Cheap: coarse grid and local minimisation only (used to place poses).
    pub fn quick() -> Self {
        OracleOptions {
            max_cells: 0,
            tau_rel: 1e-2,
            initial_rel: 1.0 / 12.0,
            seeds: 4,
            max_refinements: 0,
            bound: false,
            goal: f64::INFINITY,
        }
    }
}

/// What the oracle found for a pair of posed solids (points in A's frame).
#[derive(Debug, Clone)]
pub struct OracleResult {
    /// Distance of a realised pair of surface points (>= the surface distance).
    pub upper: f64,
    /// Lower estimate of the surface distance (>= 0).
    pub lower: f64,
    /// The realised pair: on A's surface and on B's surface, in A's frame.
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Most negative conservative signed distance found (a sample of one surface inside the
    /// other solid at depth `-min_signed`); `+inf` when none was inside.
    pub min_signed: f64,
    /// That deepest sample, in A's frame: a point on one boundary inside the other solid (a
    /// certificate of overlap when deeper than the margin).
    pub deep_point: Option<Point3<f64>>,
    /// Some sample of A's surface is certainly inside B.
    pub a_in_b: bool,
    /// Some sample of B's surface is certainly inside A.
    pub b_in_a: bool,
    /// Cells evaluated (both directions).
    pub cells: usize,
    /// Local minimisations run.
    pub refinements: usize,
    /// The branch and bound stopped on its budget.
    pub budget_hit: bool,
}

impl OracleResult {
    /// The solids certainly overlap (a boundary sample inside the other solid).
    pub fn overlap(&self) -> bool {
        self.a_in_b || self.b_in_a
    }

    /// Upper estimate of the distance between the *solids* (0 when overlapping).
    pub fn solid_upper(&self) -> f64 {
        if self.overlap() {
            0.0
        } else {
            self.upper
        }
    }

    /// Lower estimate of the distance between the solids.
    pub fn solid_lower(&self) -> f64 {
        if self.overlap() {
            0.0
        } else {
            self.lower
        }
    }

    /// Signed gap: the surface distance when apart, minus the penetration depth found when
    /// overlapping.
    pub fn gap(&self) -> f64 {
        if self.overlap() {
            self.min_signed.min(0.0)
        } else {
            self.upper
        }
    }
}

/// A map from the source solid's frame to the target's, with both profiles.
struct Dir<'a> {
    src: &'a PlanarIndex,
    dst: &'a PlanarIndex,
    rot: Matrix3<f64>,
    trans: Vector3<f64>,
    /// Inside-census margin.
    margin: f64,
}

impl<'a> Dir<'a> {
    /// Search over `src`'s surface against `dst`, `src_to_dst` mapping src's frame into dst's.
    fn new(
        src: &'a PlanarIndex,
        dst: &'a PlanarIndex,
        src_to_dst: &Isometry3<f64>,
        margin: f64,
    ) -> Dir<'a> {
        Dir {
            src,
            dst,
            rot: *src_to_dst.rotation.to_rotation_matrix().matrix(),
            trans: src_to_dst.translation.vector,
            margin,
        }
    }
}

/// A realised pair in the source frame.
#[derive(Debug, Clone, Copy)]
struct Pair {
    d: f64,
    y: Point3<f64>,
    /// Target surface point, in the *source* frame.
    x: Point3<f64>,
}

#[derive(Debug, Clone, Copy)]
struct Cell {
    k: u32,
    ta: f64,
    tb: f64,
    th0: f64,
    th1: f64,
    r_param: f64,
    lb: f64,
    r: f64,
    f: f64,
    rho: f64,
}

#[derive(PartialEq)]
struct HeapKey(f64, usize);
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

/// Running state of one direction.
struct State {
    best: Option<Pair>,
    min_signed: f64,
    /// Where `min_signed` was found (source frame).
    deep: Option<Point3<f64>>,
    inside: bool,
    cells: usize,
    refinements: usize,
}

impl State {
    /// Nothing found yet.
    fn new() -> State {
        State {
            best: None,
            min_signed: f64::INFINITY,
            deep: None,
            inside: false,
            cells: 0,
            refinements: 0,
        }
    }
}

impl<'a> Dir<'a> {
    fn to_dst(&self, y: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rot * y.coords + self.trans)
    }

    fn to_src(&self, x: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rot.transpose() * (x.coords - self.trans))
    }

    fn surface_point(&self, k: usize, t: f64, th: f64) -> Point3<f64> {
        let p = self.src.geom.point(k, t);
        Point3::new(p[0] * th.cos(), p[0] * th.sin(), p[1])
    }

    /// Bound on the distance from `C(tm)` to the arc `C([ta, tb])` (two-chord arc lengths).
    fn r_param(&self, k: usize, ta: f64, tb: f64) -> (f64, P2) {
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

    fn make_cell(&self, k: usize, ta: f64, tb: f64, th0: f64, th1: f64, r_param: f64) -> Cell {
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
    fn eval_cell(&self, c: &mut Cell, st: &mut State, census: bool, parent: Option<(f64, f64)>) {
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

    /// `f` and its gradient at `(k, t, th)`: the realised pair and `(df/dt, df/dth)`.
    fn f_grad(&self, k: usize, t: f64, th: f64) -> (Pair, [f64; 2]) {
        let j = self.src.geom.jet(k, t);
        let (c, s) = (th.cos(), th.sin());
        let y = Point3::new(j.p[0] * c, j.p[0] * s, j.p[1]);
        let dy_dt = Vector3::new(j.d1[0] * c, j.d1[0] * s, j.d1[1]);
        let dy_dth = Vector3::new(-j.p[0] * s, j.p[0] * c, 0.0);
        let q = self.to_dst(&y);
        let x = surface_foot(self.dst, &q);
        let v = q - x;
        let d = v.norm();
        let grad = if d > 0.0 {
            let n = self.rot.transpose() * (v / d);
            [n.dot(&dy_dt), n.dot(&dy_dth)]
        } else {
            [0.0, 0.0]
        };
        (
            Pair {
                d,
                y,
                x: self.to_src(&x),
            },
            grad,
        )
    }

    /// Signed census at a realised source point.
    fn census_at(&self, y: &Point3<f64>, st: &mut State) {
        let q = self.to_dst(y);
        let s = self.dst.signed([q.x.hypot(q.y), q.z]);
        if s.value < 0.0 {
            if s.value < st.min_signed {
                st.min_signed = s.value;
                st.deep = Some(*y);
            }
            if -s.value > self.margin {
                st.inside = true;
            }
        }
    }

    /// Local minimisation of `f` from `(k, t, th)` (see the module documentation).
    fn refine(&self, mut k: usize, mut t: f64, mut th: f64, st: &mut State) -> Pair {
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
    fn polish(&self, mut pair: Pair) -> Pair {
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

    /// Initial cells: parameter intervals with turning below [`MAX_TURN`] and arc radius
    /// below `l0 / 2`, times angle intervals of length about `l0`.
    fn initial_cells(&self, l0: f64) -> Vec<Cell> {
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
    fn grid(&self, opts: &OracleOptions, st: &mut State) -> Vec<Cell> {
        let l0 = opts.initial_rel * self.src.geom.size;
        let mut cells = self.initial_cells(l0);
        for c in cells.iter_mut() {
            self.eval_cell(c, st, true, None);
        }
        cells
    }

    /// Local minimisations from the best, mutually distant cells of the evaluated grid.
    fn seed(&self, cells: &[Cell], opts: &OracleOptions, st: &mut State) {
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

    /// Whether every point of the source surface is farther than `level` from the target
    /// surface: a best-first split of the grid's cells whose bound `lb` is at most `level`,
    /// until none is left (`true`) or `budget` cells were evaluated or a cell cannot shrink
    /// further (`false`). Without the census: the grid's census already ran.
    fn clears(&self, cells: &[Cell], level: f64, budget: usize, st: &mut State) -> bool {
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

    /// The realised pair at the centre of the grid cell nearest the target.
    fn grid_pair(&self, cells: &[Cell]) -> Option<Pair> {
        let c = cells.iter().min_by(|a, b| a.f.total_cmp(&b.f))?;
        Some(
            self.f_grad(c.k as usize, 0.5 * (c.ta + c.tb), 0.5 * (c.th0 + c.th1))
                .0,
        )
    }

    /// The two halves of a cell, split in the dimension contributing more to its radius.
    fn split(&self, c: &Cell) -> [Cell; 2] {
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

    /// Branch and bound from the evaluated grid `cells`; returns the lower estimate.
    fn branch_and_bound(
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

trait BetterThan {
    fn is_none_or_worse(&self, d: f64) -> bool;
}

impl BetterThan for Option<Pair> {
    fn is_none_or_worse(&self, d: f64) -> bool {
        match self {
            None => true,
            Some(p) => d < p.d,
        }
    }
}

/// The closest point of `idx`'s surface of revolution to `q` (its frame): the planar closest
/// point of `q`'s meridian coordinates, lifted into `q`'s meridian plane.
fn surface_foot(idx: &PlanarIndex, q: &Point3<f64>) -> Point3<f64> {
    let rho = q.x.hypot(q.y);
    let cp = idx.closest([rho, q.z]);
    let (c, s) = if rho > 0.0 {
        (q.x / rho, q.y / rho)
    } else {
        (1.0, 0.0)
    };
    Point3::new(cp.p[0] * c, cp.p[0] * s, cp.p[1])
}

/// Relative margin for the inside census: a sample must be deeper than this times the scene
/// scale (1 + |translation| + sizes) to count as inside; a few hundred ulps of the scene's
/// coordinates, far below any eps a query uses.
pub const INSIDE_MARGIN_REL: f64 = 1e-13;

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
