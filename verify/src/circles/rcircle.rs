//! Circles with exact rational data, their rigid motions, and the rational helpers the
//! cases are built with.

use crate::exact_circle::RVec;
use nalgebra::{Point3, Vector3};
use revdist::circle::Circle3;
use rug::Rational;

/// A circle with exact rational data.
#[derive(Debug, Clone)]
pub struct RCircle {
    pub c: RVec,
    pub u: RVec,
    pub v: RVec,
    pub r: Rational,
}

fn rv(x: [Rational; 3]) -> RVec {
    x
}

pub(super) fn rat(n: i64, d: i64) -> Rational {
    Rational::from((n, d))
}

pub(super) fn apply(rot: &[RVec; 3], x: &RVec) -> RVec {
    // rot holds the images of e_x, e_y, e_z.
    let mut out = [Rational::new(), Rational::new(), Rational::new()];
    for (k, o) in out.iter_mut().enumerate() {
        for j in 0..3 {
            *o += Rational::from(&rot[j][k] * &x[j]);
        }
    }
    out
}

impl RCircle {
    /// Circle A: centre 0, axes x, y, radius r.
    pub fn canonical(r: Rational) -> Self {
        Self {
            c: rv([Rational::new(), Rational::new(), Rational::new()]),
            u: rv([Rational::from(1), Rational::new(), Rational::new()]),
            v: rv([Rational::new(), Rational::from(1), Rational::new()]),
            r,
        }
    }

    /// Circle with centre `c`, radius `r`, axes = rotation of x, y by `rot`.
    pub fn rotated(c: RVec, rot: &[RVec; 3], r: Rational) -> Self {
        Self {
            c,
            u: rot[0].clone(),
            v: rot[1].clone(),
            r,
        }
    }

    /// Rigid motion x -> rot x + t.
    pub fn moved(&self, rot: &[RVec; 3], t: &RVec) -> Self {
        let mut c = apply(rot, &self.c);
        for k in 0..3 {
            c[k] += &t[k];
        }
        Self {
            c,
            u: apply(rot, &self.u),
            v: apply(rot, &self.v),
            r: self.r.clone(),
        }
    }

    /// The double-precision circle (data rounded to nearest).
    pub fn to_f64(&self) -> Circle3 {
        let f = |x: &RVec| Vector3::new(x[0].to_f64(), x[1].to_f64(), x[2].to_f64());
        let (u, v) = (f(&self.u), f(&self.v));
        Circle3::with_u_axis(Point3::from(f(&self.c)), u.cross(&v), u, self.r.to_f64())
            .expect("valid rational circle")
    }
}

pub(super) fn pow10(k: i32) -> Rational {
    if k >= 0 {
        Rational::from(10).pow_ref_int(k)
    } else {
        Rational::from(1) / Rational::from(10).pow_ref_int(-k)
    }
}

trait PowInt {
    fn pow_ref_int(&self, k: i32) -> Rational;
}
impl PowInt for Rational {
    fn pow_ref_int(&self, k: i32) -> Rational {
        let mut out = Rational::from(1);
        for _ in 0..k {
            out *= self;
        }
        out
    }
}
