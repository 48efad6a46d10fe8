//! The cases of `verify circles`: random, scaled and near-touching pairs, and the perturbed,
//! rigidly moved catalogue entries.

use super::catalogue::catalogue;
use super::rcircle::{apply, pow10, rat, RCircle};
use crate::exact_circle::{
    rotation_from_quaternion, rotation_from_rational_quaternion, ExactPair, RVec,
};
use revdist::rng::SplitMix64;
use rug::Rational;

/// One verification case: circle B in the canonical frame of A, plus the rigid motion the
/// float solver sees, and an analytic answer for continua where P vanishes identically.
#[derive(Debug, Clone)]
pub struct Case {
    pub family: &'static str,
    pub label: String,
    pub ra: Rational,
    pub b: RCircle,
    pub motion: Option<([RVec; 3], RVec)>,
    pub analytic: Option<f64>,
}

impl Case {
    /// The exact pair in A's canonical frame (before the rigid motion).
    pub fn exact_pair(&self) -> ExactPair {
        ExactPair {
            ra: self.ra.clone(),
            c: self.b.c.clone(),
            u: self.b.u.clone(),
            v: self.b.v.clone(),
            rb: self.b.r.clone(),
        }
    }
}

/// A random integer quaternion with entries in `[-m, m]`, not all zero.
fn integer_quaternion(rng: &mut SplitMix64, m: i64) -> [i64; 4] {
    loop {
        let q = [0, 1, 2, 3].map(|_| rng.signed_int(-m, m));
        if q.iter().any(|&x| x != 0) {
            return q;
        }
    }
}

/// A random rigid motion: a rational rotation (integer quaternion with entries up to 50) and a
/// translation with components in [-10, 10] (multiples of 1/8).
pub fn random_motion(rng: &mut SplitMix64) -> ([RVec; 3], RVec) {
    let rot = rotation_from_quaternion(integer_quaternion(rng, 50));
    let t = [0, 1, 2].map(|_| rat(rng.signed_int(-80, 80), 8));
    (rot, t)
}

/// A random general pair.
pub fn random_case(rng: &mut SplitMix64) -> Case {
    let ra = rat(rng.signed_int(8, 128), 64);
    let c = [0, 1, 2].map(|_| rat(rng.signed_int(-128, 128), 64));
    let rot = rotation_from_quaternion(integer_quaternion(rng, 9));
    let rb = rat(rng.signed_int(8, 128), 64);
    Case {
        family: "random",
        label: String::from("random"),
        ra,
        b: RCircle::rotated(c, &rot, rb),
        motion: Some(random_motion(rng)),
        analytic: None,
    }
}

/// Radius ratios 1e-6..1e6 and distance scales up to 1e6, or near-touching pairs with gaps
/// 1e-12..1.
pub fn scaled_case(rng: &mut SplitMix64) -> Case {
    let ra = Rational::from(1);
    let rot = rotation_from_quaternion(integer_quaternion(rng, 9));
    if rng.signed_int(0, 1) == 0 {
        let kr = rng.signed_int(-6, 6) as i32;
        let kc = rng.signed_int(-3, 6) as i32;
        let rb = rat(rng.signed_int(8, 128), 64) * pow10(kr);
        let c = [0, 1, 2].map(|_| rat(rng.signed_int(-128, 128), 64) * pow10(kc));
        Case {
            family: "scaled",
            label: format!("rb~1e{kr} |c|~1e{kc}"),
            ra,
            b: RCircle::rotated(c, &rot, rb),
            motion: Some(random_motion(rng)),
            analytic: None,
        }
    } else {
        // B(0) = (1 + gap, 0, 0): B passes within `gap` of A's point (1, 0, 0).
        let kg = rng.signed_int(-12, 0) as i32;
        let kr = rng.signed_int(-6, 6) as i32;
        let rb = rat(rng.signed_int(8, 128), 64) * pow10(kr);
        let gap = pow10(kg);
        let p = [Rational::from(1) + &gap, Rational::new(), Rational::new()];
        let c = [0, 1, 2].map(|k| &p[k] - Rational::from(&rb * &rot[0][k]));
        Case {
            family: "near-touching",
            label: format!("gap 1e{kg} rb~1e{kr}"),
            ra,
            b: RCircle::rotated(c, &rot, rb),
            motion: Some(random_motion(rng)),
            analytic: None,
        }
    }
}

/// Catalogued configurations, perturbed (eps 0, 1e-14..1e-2 on centre x, centre y, tilt,
/// radius) and rigidly moved.
pub fn catalogue_cases(rng: &mut SplitMix64, motions: usize) -> Vec<Case> {
    let mut out = Vec::new();
    for (label, c, q, r, analytic) in catalogue() {
        for kind in 0..4 {
            for k in [0, 14, 12, 10, 8, 6, 4, 2] {
                if k == 0 && kind > 0 {
                    continue;
                }
                let eps = if k == 0 { Rational::new() } else { pow10(-k) };
                let (mut c, mut r) = (c.clone(), r.clone());
                let mut rot = rotation_from_quaternion(q);
                match kind {
                    0 => c[0] += &eps,
                    1 => c[1] += &eps,
                    2 => {
                        // Tilt: compose with a rational rotation of angle ~2 eps about x.
                        if k != 0 {
                            let m = Rational::from(1) / &eps;
                            let tilt = rotation_from_quaternion_rat(m);
                            rot = [0, 1, 2].map(|j| apply(&tilt, &rot[j]));
                        }
                    }
                    _ => r += &eps,
                }
                for _ in 0..motions {
                    out.push(Case {
                        family: "catalogue",
                        label: format!("{label} kind {kind} eps 1e-{k}"),
                        ra: Rational::from(1),
                        b: RCircle::rotated(c.clone(), &rot, r.clone()),
                        motion: Some(random_motion(rng)),
                        analytic: if k == 0 { analytic } else { None },
                    });
                }
            }
        }
    }
    out
}

/// Rotation from the quaternion (m, 1, 0, 0) with a big rational m: angle ~2/m about x.
pub(super) fn rotation_from_quaternion_rat(m: Rational) -> [RVec; 3] {
    rotation_from_rational_quaternion(&[m, Rational::from(1), Rational::new(), Rational::new()])
}
