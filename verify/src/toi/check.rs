//! The oracle's check of one time-of-impact answer, sharing no code with the query or with
//! `revdist::toi`: its own interpolation of the motion (nalgebra's slerp on the shortest
//! arc, linear translation) and `verify`'s independent surface distance
//! ([`crate::oracle::surface_distance`]).
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

use crate::oracle::{surface_distance, OracleOptions, OracleResult, PlanarIndex};
use nalgebra::Isometry3;

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
    fn oracle(&self, t: f64, opts: &OracleOptions) -> (OracleResult, f64) {
        let pa = pose_at(&self.pose_a[0], &self.pose_a[1], t);
        let pb = pose_at(&self.pose_b[0], &self.pose_b[1], t);
        let pos_ab = pa.inverse() * pb;
        let scale = 1.0
            + pa.translation.vector.norm()
            + pb.translation.vector.norm()
            + self.a.geom.size
            + self.b.geom.size;
        (
            surface_distance(self.a, self.b, &pos_ab, opts),
            scale * ORACLE_TOL_REL,
        )
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

    /// Check "apart before t_lower"; returns the oracle calls made.
    pub fn check_apart(
        &self,
        t_lower: f64,
        inclusive: bool,
        d: f64,
        out: &mut Vec<Breach>,
    ) -> usize {
        let ts = Self::times_before(t_lower, inclusive);
        for &t in &ts {
            let (r, tol) = self.oracle(t, &OracleOptions::quick());
            if r.overlap() || r.upper < d - tol {
                out.push(Breach {
                    what: "within D before t_lower",
                    t,
                    oracle_lower: r.solid_lower(),
                    oracle_upper: r.solid_upper(),
                    overlap: r.overlap(),
                });
            }
        }
        ts.len()
    }

    /// Check "within D at t_upper".
    pub fn check_contact(&self, t_upper: f64, d: f64, out: &mut Vec<Breach>) {
        let (r, tol) = self.oracle(t_upper, &OracleOptions::full());
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
