//! The time of impact's link of the chain: the interpolated motion's two bounds checked in
//! MPFR (`src/toi/motion.rs`, `src/toi/speed.rs`).
//!
//! * **Rounding** ([`MOTION_ROUNDING_REL`]): the pose `Motion::pose_at(t)` computes in f64
//!   places a point `x` of the solid within `MOTION_ROUNDING_REL (1 + |p(t)| + |x|)` of where
//!   the motion itself places it. The motion is defined by its f64 start pose `(q0, p0)`,
//!   angular velocity `w` and linear velocity `v`: `(exp(t w) q0, p0 + t v)`, evaluated here
//!   in MPFR (`exp(t w)` the unit quaternion `(cos(t|w|/2), sin(t|w|/2) w/|w|)`); the f64 pose
//!   is applied to `x` in MPFR too, so only the pose's own rounding is measured.
//! * **Speed** ([`speed_bound`]): for points `a` of A and `b` of B within the radii the bound
//!   is given, and times `t0 <= s <= 1`, the exact motions change `|B(t) b - A(t) a|` by at
//!   most `L (s - t0)`, `L = speed_bound(.., t0)` computed in f64.
//!
//! The motions are adversarial: scale log-uniform in [1e-3, 1e3], rotation angles of 0,
//! 1e-12..1e-3 rad, near a half turn (within 1e-9..1e-3 of pi) or random, one solid fixed or
//! both moving, points on the radius spheres (where the speed bound is tight), intervals from
//! 1e-12 to the whole of `[t0, 1]`.

use super::exact::{f, transformed, P3, PREC};
use super::report::Tally;
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;
use revdist::toi::motion::MOTION_ROUNDING_REL;
use revdist::toi::{speed_bound, Motion};
use rug::Float;
use std::f64::consts::PI;

/// A rotation angle from the adversarial families.
fn angle(rng: &mut SplitMix64) -> f64 {
    match rng.below(5) {
        0 => 0.0,
        1 => rng.log_range(1e-12, 1e-3),
        2 => PI - rng.log_range(1e-9, 1e-3),
        _ => rng.range(0.0, PI),
    }
}

fn pose(rng: &mut SplitMix64, scale: f64) -> Isometry3<f64> {
    let q = rng.quaternion();
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
    Isometry3::from_parts(
        Translation3::from(rng.direction() * rng.range(0.0, 3.0) * scale),
        rot,
    )
}

/// A motion from a random start by a rotation of an adversarial angle and a translation.
fn motion(rng: &mut SplitMix64, scale: f64, fixed: bool) -> Motion {
    let start = pose(rng, scale);
    if fixed {
        return Motion::fixed(start).expect("finite pose");
    }
    let turn = UnitQuaternion::from_scaled_axis(rng.direction() * angle(rng));
    let shift = rng.direction() * rng.range(0.0, 3.0) * scale;
    let end = Isometry3::from_parts(
        Translation3::from(start.translation.vector + shift),
        turn * start.rotation,
    );
    Motion::new(start, end).expect("finite poses")
}

/// Where the motion itself places the body point `x` at time `t`, in MPFR.
fn exact_place(m: &Motion, t: f64, x: &Vector3<f64>) -> P3 {
    let w = m.angular_velocity();
    let q0 = m.start().rotation.into_inner();
    let wn = Float::with_val(PREC, f(w.x).square() + f(w.y).square() + f(w.z).square()).sqrt();
    let half = Float::with_val(PREC, &wn * f(t)) / 2u32;
    let (sin, cos) = half.sin_cos(f(0.0));
    // exp(t w) = (cos, sin w / |w|); for w = 0 the identity.
    let axis = |c: f64| {
        if wn.is_zero() {
            f(0.0)
        } else {
            Float::with_val(PREC, &sin * f(c)) / &wn
        }
    };
    let e = [cos, axis(w.x), axis(w.y), axis(w.z)];
    let g = [f(q0.w), f(q0.i), f(q0.j), f(q0.k)];
    // Hamilton product e * g.
    let mul = |a: usize, b: usize| Float::with_val(PREC, &e[a] * &g[b]);
    let r = [
        Float::with_val(PREC, mul(0, 0) - mul(1, 1)) - mul(2, 2) - mul(3, 3),
        Float::with_val(PREC, mul(0, 1) + mul(1, 0)) + mul(2, 3) - mul(3, 2),
        Float::with_val(PREC, mul(0, 2) - mul(1, 3)) + mul(2, 0) + mul(3, 1),
        Float::with_val(PREC, mul(0, 3) + mul(1, 2)) - mul(2, 1) + mul(3, 0),
    ];
    // Rotate x by r (unit to MPFR precision up to the f64 q0's own norm, which
    // `transformed`'s normalisation takes out): r x r^-1 with r normalised.
    let p0 = m.start().translation.vector;
    let v = m.velocity();
    let rotated = rotate(&r, x);
    std::array::from_fn(|k| {
        Float::with_val(PREC, &rotated[k] + f(p0[k])) + Float::with_val(PREC, f(v[k]) * f(t))
    })
}

/// `q x q^-1` for a quaternion `q = (w, i, j, k)` in MPFR (normalised here).
fn rotate(q: &[Float; 4], x: &Vector3<f64>) -> P3 {
    let n2 = Float::with_val(
        PREC,
        q[0].clone().square()
            + q[1].clone().square()
            + q[2].clone().square()
            + q[3].clone().square(),
    );
    let m = |a: usize, b: usize| Float::with_val(PREC, &q[a] * &q[b]) / &n2;
    let two = |x: Float| x * 2u32;
    let r = [
        [
            Float::with_val(PREC, m(0, 0) + m(1, 1)) - m(2, 2) - m(3, 3),
            two(Float::with_val(PREC, m(1, 2) - m(0, 3))),
            two(Float::with_val(PREC, m(1, 3) + m(0, 2))),
        ],
        [
            two(Float::with_val(PREC, m(1, 2) + m(0, 3))),
            Float::with_val(PREC, m(0, 0) - m(1, 1)) + m(2, 2) - m(3, 3),
            two(Float::with_val(PREC, m(2, 3) - m(0, 1))),
        ],
        [
            two(Float::with_val(PREC, m(1, 3) - m(0, 2))),
            two(Float::with_val(PREC, m(2, 3) + m(0, 1))),
            Float::with_val(PREC, m(0, 0) - m(1, 1)) - m(2, 2) + m(3, 3),
        ],
    ];
    std::array::from_fn(|row| {
        let mut acc = f(0.0);
        for col in 0..3 {
            acc += Float::with_val(PREC, &r[row][col] * f(x[col]));
        }
        acc
    })
}

fn distance(x: &P3, y: &P3) -> Float {
    let mut d2 = f(0.0);
    for k in 0..3 {
        d2 += Float::with_val(PREC, &x[k] - &y[k]).square();
    }
    d2.sqrt()
}

/// A body point on the sphere of radius `r` about the frame origin.
fn body_point(rng: &mut SplitMix64, r: f64) -> Vector3<f64> {
    rng.direction() * r
}

/// One configuration: the rounding check (`rounding`) or the speed check.
pub fn check(rounding: bool, rng: &mut SplitMix64, tally: &mut Tally) {
    let scale = rng.log_range(1e-3, 1e3);
    let both = rng.chance(0.5);
    let ma = motion(rng, scale, !both);
    let mb = motion(rng, scale, false);
    let (ra, rb) = (scale * rng.range(0.1, 2.0), scale * rng.range(0.1, 2.0));
    tally.configs += 1;
    let describe = |what: &str| {
        format!(
            "{what}; motion A start {:?} w {:?} v {:?}; motion B start {:?} w {:?} v {:?}; radii {ra:?}, {rb:?}",
            ma.start(),
            ma.angular_velocity(),
            ma.velocity(),
            mb.start(),
            mb.angular_velocity(),
            mb.velocity()
        )
    };
    if rounding {
        let t = match rng.below(4) {
            0 => 0.0,
            1 => 1.0,
            _ => rng.next_f64(),
        };
        let x = body_point(rng, rb);
        let computed = transformed(&mb.pose_at(t), &[f(x.x), f(x.y), f(x.z)]);
        let exact = exact_place(&mb, t, &x);
        let err = distance(&computed, &exact).to_f64_round(rug::float::Round::Up);
        let p = Point3::from(mb.origin_at(t)).coords.norm();
        let allowed = MOTION_ROUNDING_REL * (1.0 + p + rb);
        tally.record(err, allowed, 0.0, 1.0 + p + rb, || {
            describe(&format!("motion rounding at t = {t:?}, x = {x:?}"))
        });
    } else {
        let t0 = match rng.below(4) {
            0 => 0.0,
            _ => rng.next_f64(),
        };
        let s = if rng.chance(0.5) {
            (t0 + rng.log_range(1e-12, 1.0) * (1.0 - t0)).min(1.0)
        } else {
            1.0
        };
        let (a, b) = (body_point(rng, ra), body_point(rng, rb));
        let gap = |t: f64| distance(&exact_place(&mb, t, &b), &exact_place(&ma, t, &a));
        let change = Float::with_val(PREC, gap(s) - gap(t0))
            .abs()
            .to_f64_round(rug::float::Round::Up);
        let l = speed_bound(&ma, ra, &mb, rb, t0);
        let allowed = l * (s - t0);
        tally.record(change, allowed, 0.0, scale, || {
            describe(&format!("speed bound {l:?} on [{t0:?}, {s:?}]"))
        });
    }
}
