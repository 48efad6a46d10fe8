//! The oracle's check of one time-of-impact answer, sharing no code with the query or with
//! `revdist::toi`: its own interpolation of the motion (nalgebra's slerp on the shortest
//! arc, linear translation) and `verify`'s independent surface distance
//! ([`mod@crate::oracle::surface_distance`]).
//!
//! * Before `t_lower`: at every sampled time (uniform on `[0, t_lower)` and accumulating
//!   towards `t_lower`; `[0, 1]` for "apart") the oracle's realised upper estimate (the
//!   distance of two actual surface points, so `>=` the true distance) must not be below
//!   `D - tol`, and its inside census must not certify an overlap.
//! * At `t_upper`: the oracle's lower estimate of the solids' distance must not exceed
//!   `D + tol`.
//!
//! `tol` ([`ORACLE_TOL_REL`]) is the oracle's own error: its lower estimate rests on two
//! estimates (sagitta and arc length, taken with factors of safety) and its inside census on
//! a margin of `1e-13` of the scene's scale; both far below it.
//!
//! **What decides a check sooner, without deciding it differently.** Before `t_lower` the
//! question is only whether the solids come within `D - tol` or overlap. (1) When the
//! oracle's own bounding spheres of the two solids ([`bounding_sphere`]: the profile's box,
//! which contains the curve, revolved) are more than `D + tol` apart, neither can happen and
//! the oracle is not called. (2) Otherwise the oracle gets the goal `D - tol`
//! ([`OracleOptions::goal`]): when its grid's cell bounds prove the surfaces farther apart
//! than that (and than 0), its local minimisations could not realise a closer pair and are
//! skipped; its inside census, which sees nesting, runs as before. At `t_upper` the question
//! is whether the lower estimate exceeds `D + tol`, the branch and bound's goal: it stops
//! once that is decided either way.

use crate::oracle::{surface_distance, OracleOptions, OracleResult, PlanarIndex};
use nalgebra::{Isometry3, Point3};

/// Allowed error of the oracle relative to the scene's scale (`1 + |translations| +
/// sizes`): 1e4 times the inside census's margin, and far below every eps of the campaign
/// (1e-4 and up), so a certificate off by the query's own accuracy still fails.
pub const ORACLE_TOL_REL: f64 = 1e-9;

/// Uniform samples on `[0, t_lower)`.
pub const UNIFORM_SAMPLES: usize = 40;
/// Samples accumulating towards `t_lower`: `t_lower (1 - 2^-j)`, `j = 3 ..` this.
pub const LAST_HALVING: i32 = 16;

/// The pose at time `t` of the motion from `p0` to `p1` (own interpolation).
pub fn pose_at(p0: &Isometry3<f64>, p1: &Isometry3<f64>, t: f64) -> Isometry3<f64> {
    let tr = p0.translation.vector * (1.0 - t) + p1.translation.vector * t;
    let r = p0
        .rotation
        .try_slerp(&p1.rotation, t, 1e-12)
        .unwrap_or(p0.rotation);
    Isometry3::from_parts(tr.into(), r)
}

/// A sphere containing the solid of `index` in its own frame: the profile's box (the
/// polyline's box grown by its sagitta bound, which contains the curve, and so the region the
/// curve and the axis enclose), revolved about the z axis. Centre on the axis.
pub fn bounding_sphere(index: &PlanarIndex) -> (Point3<f64>, f64) {
    let (lo, hi) = (index.geom.min, index.geom.max);
    let rho = lo[0].abs().max(hi[0].abs());
    let half = 0.5 * (hi[1] - lo[1]);
    (
        Point3::new(0.0, 0.0, 0.5 * (lo[1] + hi[1])),
        rho.hypot(half),
    )
}

/// Oracle calls a check made, and times it decided by the bounding spheres alone.
#[derive(Debug, Clone, Copy, Default)]
pub struct Calls {
    pub oracle: usize,
    pub spheres: usize,
    /// Oracle calls whose grid proved the solids apart (no local minimisation ran).
    pub grid: usize,
}

/// What decided one sampled time of [`Scene::breach_apart`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Decided {
    /// The bounding spheres alone (no oracle call).
    Spheres,
    /// The oracle's grid (its cell bounds cleared the goal; no local minimisation).
    Grid,
    /// The oracle with its local minimisations.
    Oracle,
}

/// One violation of a check.
#[derive(Debug, Clone)]
pub struct Breach {
    pub what: &'static str,
    pub t: f64,
    pub oracle_lower: f64,
    pub oracle_upper: f64,
    pub overlap: bool,
}

/// The two solids' oracle views and the motions.
pub struct Scene<'a> {
    pub a: &'a PlanarIndex,
    pub b: &'a PlanarIndex,
    pub pose_a: [Isometry3<f64>; 2],
    pub pose_b: [Isometry3<f64>; 2],
}

impl Scene<'_> {
    /// The poses at `t`, the relative pose of B in A's frame, and `tol`.
    fn at(&self, t: f64) -> (Isometry3<f64>, Isometry3<f64>, f64) {
        let pa = pose_at(&self.pose_a[0], &self.pose_a[1], t);
        let pb = pose_at(&self.pose_b[0], &self.pose_b[1], t);
        let scale = 1.0
            + pa.translation.vector.norm()
            + pb.translation.vector.norm()
            + self.a.geom.size
            + self.b.geom.size;
        (pa, pb, scale * ORACLE_TOL_REL)
    }

    fn oracle(
        &self,
        pa: &Isometry3<f64>,
        pb: &Isometry3<f64>,
        opts: &OracleOptions,
    ) -> OracleResult {
        surface_distance(self.a, self.b, &(pa.inverse() * pb), opts)
    }

    /// Whether the bounding spheres at these poses are more than `gap` apart.
    fn spheres_apart(&self, pa: &Isometry3<f64>, pb: &Isometry3<f64>, gap: f64) -> bool {
        let (ca, ra) = bounding_sphere(self.a);
        let (cb, rb) = bounding_sphere(self.b);
        (pa * ca - pb * cb).norm() - ra - rb > gap
    }

    /// The sampled times before `t_lower` (with `t_lower` itself when `inclusive`).
    pub fn times_before(t_lower: f64, inclusive: bool) -> Vec<f64> {
        let mut ts: Vec<f64> = (0..UNIFORM_SAMPLES)
            .map(|k| t_lower * k as f64 / UNIFORM_SAMPLES as f64)
            .collect();
        ts.extend((3..=LAST_HALVING).map(|j| t_lower * (1.0 - 0.5f64.powi(j))));
        // Only times strictly before t_lower (t_lower = 0 certifies nothing).
        ts.retain(|&t| t < t_lower);
        ts.dedup();
        if inclusive {
            ts.push(t_lower);
        }
        ts
    }

    /// Check "apart before t_lower" (see the module doc for what decides it).
    pub fn check_apart(
        &self,
        t_lower: f64,
        inclusive: bool,
        d: f64,
        out: &mut Vec<Breach>,
    ) -> Calls {
        let mut calls = Calls::default();
        for t in Self::times_before(t_lower, inclusive) {
            let (breach, decided) = self.breach_apart(t, d);
            match decided {
                Decided::Spheres => calls.spheres += 1,
                Decided::Grid => {
                    calls.oracle += 1;
                    calls.grid += 1;
                }
                Decided::Oracle => calls.oracle += 1,
            }
            out.extend(breach);
        }
        calls
    }

    /// Whether the solids come within `D - tol` or overlap at `t` (a breach of "apart"),
    /// and what decided it.
    pub fn breach_apart(&self, t: f64, d: f64) -> (Option<Breach>, Decided) {
        let (pa, pb, tol) = self.at(t);
        if self.spheres_apart(&pa, &pb, d + tol) {
            return (None, Decided::Spheres);
        }
        let opts = OracleOptions {
            goal: d - tol,
            ..OracleOptions::quick()
        };
        let r = self.oracle(&pa, &pb, &opts);
        let breach = (r.overlap() || r.upper < d - tol).then(|| Breach {
            what: "within D before t_lower",
            t,
            oracle_lower: r.solid_lower(),
            oracle_upper: r.solid_upper(),
            overlap: r.overlap(),
        });
        let decided = if r.refinements == 0 {
            Decided::Grid
        } else {
            Decided::Oracle
        };
        (breach, decided)
    }

    /// The same question asked of the quick oracle without a goal or the spheres (as the
    /// check was first written): for tests that the shortcuts decide it the same way.
    pub fn breach_apart_unaided(&self, t: f64, d: f64) -> bool {
        let (pa, pb, tol) = self.at(t);
        let r = self.oracle(&pa, &pb, &OracleOptions::quick());
        r.overlap() || r.upper < d - tol
    }

    /// Check "within D at t_upper".
    pub fn check_contact(&self, t_upper: f64, d: f64, out: &mut Vec<Breach>) {
        let (pa, pb, tol) = self.at(t_upper);
        let opts = OracleOptions {
            goal: d + tol,
            ..OracleOptions::full()
        };
        let r = self.oracle(&pa, &pb, &opts);
        if r.solid_lower() > d + tol {
            out.push(Breach {
                what: "apart at t_upper",
                t: t_upper,
                oracle_lower: r.solid_lower(),
                oracle_upper: r.solid_upper(),
                overlap: r.overlap(),
            });
        }
    }
}
