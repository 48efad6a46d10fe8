//! The promises of a certified distance query, checked against the oracle.
//!
//! A query between solids A and B with trees of bounds `eps_a`, `eps_b` promises:
//! `lower <= true distance <= upper`, `value` in `[lower, upper]`, witness points on the
//! approximating surfaces (so within `eps` of the true ones), `|point_a - point_b| = value`,
//! and `overlap` exactly when the solids intersect or nest (distance 0). The oracle gives a
//! realised upper estimate `U` (two actual surface points, so `U >= truth`), a lower estimate
//! `L <= truth`, and a census of boundary samples inside the other solid. The checks
//! (letters as in `docs/verification.md`, section 1, and in the campaign's reports):
//!
//! - **a** `lower <= U_solid + slack` (a lower bound above a realised pair is a lie);
//! - **b** `upper >= L_solid - slack`;
//! - **c** `value - U_solid <= eps_a + eps_b + slack`, and unless the query reports overlap,
//!   `U_solid - value <= eps_a + eps_b + slack` (the value is a distance of the
//!   approximations, within `eps_a + eps_b` of the truth);
//! - **d** witness points within `eps + slack` of their own true surfaces (not for overlap
//!   answers, whose witnesses are interior points);
//! - **e** `| |point_a - point_b| - value | <= slack` (not for overlap answers);
//! - **f** all numbers finite and `lower <= value <= upper`, exactly;
//! - **g** `overlap` agrees with the oracle unless the oracle's gap (distance, or depth of the
//!   deepest inside sample) is within `band = 2 (eps_a + eps_b) + slack` of touching;
//! - **h** a non-overlap answer with an oracle gap above `2 (eps_a + eps_b) + slack` has
//!   `lower > 0`.
//!
//! `U_solid` and `L_solid` are 0 when the oracle certifies overlap. A query asked for a
//! tolerance `T > 0` may stop once `upper - lower <= T`, so its value is then only within
//! `eps_a + eps_b + T` of the truth: `T` is added to the allowance of **c** and to the bands
//! of **g** and **h**.

use super::planar::PlanarIndex;
use super::surface_distance::OracleResult;
use nalgebra::{Isometry3, Point3};
use revdist::query::Distance;

/// Round-off slack relative to the scene scale `1 + |translation| + size_a + size_b`.
///
/// Coordinates of magnitude `S` carry an absolute rounding of `2^-52 S ~ 2.2e-16 S` per
/// operation; a rigid motion, the evaluation of a NURBS point (de Boor: a few dozen
/// operations), a closest-point solve and a square root of a sum of squares accumulate a few
/// hundred such errors in either program. `1e-12` is about 4500 ulps of the scale: far above
/// that accumulation, far below the smallest eps checked (1e-6) at scene scales up to 1e5
/// (at 1e6 it is 1e-6: far poses only test gross errors).
pub const SLACK_REL: f64 = 1e-12;

/// Which promise a violation breaks.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Check {
    /// a: lower above a realised distance.
    Lower,
    /// b: upper below the oracle's lower estimate.
    Upper,
    /// c: value farther than `eps_a + eps_b` from the truth.
    Value,
    /// d: a witness point farther than its eps from its own true surface.
    Witness,
    /// e: witness pair distance differs from the value.
    PairDistance,
    /// f: non-finite numbers or `lower <= value <= upper` broken.
    Order,
    /// g: overlap flag disagrees with the oracle outside the touching band.
    Overlap,
    /// h: separated by more than `2 (eps_a + eps_b)` but `lower = 0`.
    PositiveLower,
}

impl Check {
    /// All checks in report order.
    pub const ALL: [Check; 8] = [
        Check::Lower,
        Check::Upper,
        Check::Value,
        Check::Witness,
        Check::PairDistance,
        Check::Order,
        Check::Overlap,
        Check::PositiveLower,
    ];

    /// Short name with the check's letter.
    pub fn name(self) -> &'static str {
        match self {
            Check::Lower => "a:lower<=truth",
            Check::Upper => "b:upper>=truth",
            Check::Value => "c:value~truth",
            Check::Witness => "d:witness-on-surface",
            Check::PairDistance => "e:|pa-pb|=value",
            Check::Order => "f:lower<=value<=upper",
            Check::Overlap => "g:overlap-flag",
            Check::PositiveLower => "h:lower>0-when-apart",
        }
    }
}

/// One broken promise: by how much (beyond the allowance) and the numbers.
#[derive(Debug, Clone)]
pub struct Violation {
    pub check: Check,
    /// Amount beyond the allowed bound (always > 0; `inf` for non-finite or flag errors).
    pub excess: f64,
    pub detail: String,
}

/// Everything a check needs.
pub struct CheckInput<'a> {
    pub d: &'a Distance,
    /// World poses of A and B (the oracle result is in A's frame).
    pub pose_a: &'a Isometry3<f64>,
    pub pose_b: &'a Isometry3<f64>,
    /// The trees' eps (`solid.tree.eps`).
    pub eps_a: f64,
    pub eps_b: f64,
    /// The tolerance the query was asked for (`QueryOptions::tolerance`).
    pub tolerance: f64,
    /// The rounding slack the library declares for this query
    /// ([`revdist::query::query_slack`], `POSE_SLACK_REL` and `SIZE_SLACK_REL` of the
    /// scale): it widens the certified interval by that much on each side, so the value
    /// (check **c**) and the touching band of the overlap flag (**g**, **h**) may be off by
    /// it too. Checks **a** and **b** do not get it: the interval already contains it.
    pub declared_slack: f64,
    pub oracle: &'a OracleResult,
    pub a: &'a PlanarIndex,
    pub b: &'a PlanarIndex,
}

impl CheckInput<'_> {
    /// The round-off slack of this scene.
    pub fn slack(&self) -> f64 {
        scene_slack(self.a, self.b, &(self.pose_a.inverse() * self.pose_b))
    }
}

/// The round-off slack of the checks for B placed by `pos_ab` in A's frame: [`SLACK_REL`]
/// of the scene's size.
pub fn scene_slack(a: &PlanarIndex, b: &PlanarIndex, pos_ab: &Isometry3<f64>) -> f64 {
    let t = pos_ab.translation.vector.norm();
    SLACK_REL * (1.0 + t + a.geom.size + b.geom.size)
}

/// Distance from a world point to a solid's true surface (realised closest point).
fn surface_gap(pose: &Isometry3<f64>, idx: &PlanarIndex, p: &Point3<f64>) -> f64 {
    let l = pose.inverse() * p;
    idx.closest([l.x.hypot(l.y), l.z]).dist
}

/// All violations of one answer.
pub fn check(inp: &CheckInput) -> Vec<Violation> {
    let d = inp.d;
    let o = inp.oracle;
    let slack = inp.slack();
    let eps_sum = inp.eps_a + inp.eps_b + inp.tolerance;
    let band = 2.0 * (inp.eps_a + inp.eps_b) + inp.tolerance + slack + inp.declared_slack;
    // The value's allowance (check c) includes the library's declared rounding.
    let value_slack = slack + inp.declared_slack;
    let (u, l) = (o.solid_upper(), o.solid_lower());
    let mut out = Vec::new();
    let mut push = |check: Check, excess: f64, detail: String| {
        out.push(Violation {
            check,
            excess,
            detail,
        })
    };
    let finite = [d.value, d.lower, d.upper]
        .iter()
        .chain(d.point_a.coords.iter())
        .chain(d.point_b.coords.iter())
        .all(|v| v.is_finite());
    if !(finite && d.lower <= d.value && d.value <= d.upper) {
        push(
            Check::Order,
            f64::INFINITY,
            format!(
                "lower {:e} value {:e} upper {:e} finite {finite}",
                d.lower, d.value, d.upper
            ),
        );
    }
    // a
    if d.lower > u + slack {
        push(
            Check::Lower,
            d.lower - u - slack,
            format!("lower {:e} > oracle upper {:e}", d.lower, u),
        );
    }
    // b
    if d.upper < l - slack {
        push(
            Check::Upper,
            l - slack - d.upper,
            format!("upper {:e} < oracle lower {:e}", d.upper, l),
        );
    }
    // c
    if d.value - u > eps_sum + value_slack {
        push(
            Check::Value,
            d.value - u - eps_sum - value_slack,
            format!(
                "value {:e} > oracle upper {:e} + eps_a + eps_b {:e}",
                d.value, u, eps_sum
            ),
        );
    }
    if !d.overlap && u - d.value > eps_sum + value_slack {
        push(
            Check::Value,
            u - d.value - eps_sum - value_slack,
            format!(
                "value {:e} < oracle distance {:e} - eps_a - eps_b {:e} (oracle lower {:e})",
                d.value, u, eps_sum, l
            ),
        );
    }
    if !d.overlap {
        // d
        for (name, pose, idx, p, eps) in [
            ("a", inp.pose_a, inp.a, &d.point_a, inp.eps_a),
            ("b", inp.pose_b, inp.b, &d.point_b, inp.eps_b),
        ] {
            if !p.coords.iter().all(|v| v.is_finite()) {
                continue;
            }
            // The library's declared rounding (every snap may move a candidate off the
            // exact surfaces by up to it, `revdist::tolerances`), as for c, g and h: the
            // closed form of two solid tori crossing by 7e-13 put its witness 3.1e-11 off
            // both surfaces, the circle solver's error (seed 27027, case 5335).
            let g = surface_gap(pose, idx, p);
            if g > eps + value_slack {
                push(
                    Check::Witness,
                    g - eps - value_slack,
                    format!("point_{name} is {g:e} from its surface (eps {eps:e})"),
                );
            }
        }
        // e
        let pd = (d.point_a - d.point_b).norm();
        if (pd - d.value).abs() > slack {
            push(
                Check::PairDistance,
                (pd - d.value).abs() - slack,
                format!("|pa - pb| = {pd:e}, value {:e}", d.value),
            );
        }
    }
    // g
    let gap = o.gap();
    if o.overlap() && !d.overlap && -gap > band {
        push(
            Check::Overlap,
            -gap - band,
            format!(
                "oracle: overlap (a boundary sample {:e} deep in the other solid, at {}), query: overlap=false (value {:e})",
                -gap,
                o.deep_point
                    .map(|p| format!("[{:?}, {:?}, {:?}]", p.x, p.y, p.z))
                    .unwrap_or_default(),
                d.value
            ),
        );
    }
    if !o.overlap() && d.overlap && gap > band {
        push(
            Check::Overlap,
            gap - band,
            format!("oracle: apart by {gap:e}, query: overlap=true"),
        );
    }
    // h
    if !d.overlap && !o.overlap() && gap > band && d.lower <= 0.0 {
        push(
            Check::PositiveLower,
            gap - band,
            format!(
                "oracle gap {gap:e} > 2 (eps_a + eps_b), lower {:e}",
                d.lower
            ),
        );
    }
    out
}
