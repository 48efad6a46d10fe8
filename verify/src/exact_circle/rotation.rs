//! Exact rational rotations from integer and rational quaternions.

use super::RVec;
use rug::Rational;

/// Rotation matrix columns (as rows of the result) from an integer quaternion (w, x, y, z):
/// exact rationals with denominator w^2 + x^2 + y^2 + z^2.
pub fn rotation_from_quaternion(q: [i64; 4]) -> [RVec; 3] {
    rotation_from_rational_quaternion(&q.map(Rational::from))
}

/// Rotation matrix columns (as rows of the result) from a non-zero rational quaternion
/// (w, x, y, z), exact: the rotation of q / |q|, entries divided by |q|^2. Rational
/// quaternions reach rotations of any small angle, e.g. (2 / delta, 1, 0, 0) turns by about
/// `delta` about x.
pub fn rotation_from_rational_quaternion(q: &[Rational; 4]) -> [RVec; 3] {
    let [w, x, y, z] = q;
    let m = |a: &Rational, b: &Rational| Rational::from(a * b);
    let (ww, xx, yy, zz) = (m(w, w), m(x, x), m(y, y), m(z, z));
    let n = Rational::from(&ww + &xx) + &yy + &zz;
    let e = |num: Rational| num / &n;
    let two = |a: Rational, b: Rational| (a + b) * 2u32;
    let (r00, r11, r22) = (
        e(Rational::from(&ww + &xx) - &yy - &zz),
        e(Rational::from(&ww - &xx) + &yy - &zz),
        e(Rational::from(&ww - &xx) - &yy + &zz),
    );
    let (r01, r10) = (e(two(m(x, y), -m(w, z))), e(two(m(x, y), m(w, z))));
    let (r02, r20) = (e(two(m(x, z), m(w, y))), e(two(m(x, z), -m(w, y))));
    let (r12, r21) = (e(two(m(y, z), -m(w, x))), e(two(m(y, z), m(w, x))));
    // Columns: images of e_x, e_y, e_z.
    [[r00, r10, r20], [r01, r11, r21], [r02, r12, r22]]
}
