//! Case (d) of [`super`]: crossings of the two patches, found as sign changes of the other
//! patch's implicit halves ([`implicit_halves`]) along one patch's meridians, each point
//! measured with the exact point-to-patch distance (zero at a crossing).

use super::*;

/// Meridians always scanned for crossings (an intersection loop that winds around a
/// patch's axis meets every meridian of that patch).
pub(super) const FIXED_MERIDIANS: [f64; 4] = [
    0.0,
    std::f64::consts::FRAC_PI_2,
    std::f64::consts::PI,
    3.0 * std::f64::consts::FRAC_PI_2,
];

/// Samples along a meridian for the crossing scan.
const MERIDIAN_SAMPLES: usize = 32;

/// Implicit functions of the two mirror halves of the extended surface of `o` at `x`
/// (o's frame): each is zero exactly on one half of the revolved full circle (or line) of
/// the piece, so that their union is the extended surface. The halves are kept apart: their
/// product, zero on the same set, becomes a square with no sign change when the halves
/// nearly coincide (an arc centred near the axis, a segment within rounding of flat), and a
/// crossing scan on it missed a cone tip poking through a flat disk (campaign seed 1206).
fn implicit_halves(o: &Patch, x: &Point3<f64>) -> [f64; 2] {
    let rho = norm2(x.x, x.y);
    match o.core() {
        Core::Circle {
            r_major,
            z,
            r_minor,
        } => [
            norm2(rho - r_major, x.z - z) - r_minor,
            norm2(rho + r_major, x.z - z) - r_minor,
        ],
        Core::Line { n, c } => [n.x * rho + n.y * x.z - c, -n.x * rho + n.y * x.z - c],
    }
}

/// Points of `g`'s meridians (at angles `thetas`, frame G) where an implicit function of
/// `o`'s halves changes sign ([`implicit_halves`]), each emitted with its closest point on
/// `o` (O's frame): a crossing of the two patches when that distance is zero. Every
/// emitted pair is two real points of the patches, so extra candidates never undercut the
/// distance. `pos_og` places G in O.
pub(super) fn meridian_crossings(
    g: &Patch,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    thetas: &[f64],
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let n = MERIDIAN_SAMPLES;
    // The meridian's profile samples do not depend on the meridian: computed once.
    let mut samples = [Point2::origin(); MERIDIAN_SAMPLES + 1];
    for (i, m) in samples.iter_mut().enumerate() {
        *m = g.arc.point_at(i as f64 / n as f64);
    }
    for &th in thetas {
        let e = e_rho(th);
        let at = |s: f64| pos_og * lift(g.arc.point_at(s), &e);
        let mut prev = implicit_halves(o, &(pos_og * lift(samples[0], &e)));
        for (i, m) in samples.iter().enumerate().skip(1) {
            let (s0, s1) = ((i - 1) as f64 / n as f64, i as f64 / n as f64);
            let cur = implicit_halves(o, &(pos_og * lift(*m, &e)));
            for half in 0..2 {
                if prev[half] != 0.0 && prev[half].signum() == cur[half].signum() {
                    continue;
                }
                let f = |s: f64| implicit_halves(o, &at(s))[half];
                let (mut lo, mut hi, mut flo) = (s0, s1, prev[half]);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    let fm = f(mid);
                    if fm == 0.0 {
                        lo = mid;
                        hi = mid;
                        break;
                    }
                    if fm.signum() == flo.signum() {
                        lo = mid;
                        flo = fm;
                    } else {
                        hi = mid;
                    }
                }
                let x = at(0.5 * (lo + hi));
                let (_, c) = o.point_distance(&x);
                emit(x, c);
            }
            prev = cur;
        }
    }
}
