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

/// Normalised parameter of the meridian point `m` on `g`'s piece (`m` on the piece), for
/// sampling a meridian at an interior candidate's own point.
pub(super) fn piece_param(g: &Patch, m: Point2<f64>) -> Option<f64> {
    match g.arc {
        ProfileArc::Arc { center, .. } => {
            let d = m - center;
            g.arc.arc_param(d.y.atan2(d.x))
        }
        ProfileArc::Segment { start, end } => {
            let e = end - start;
            let l2 = e.norm_squared();
            (l2 > 0.0).then(|| ((m - start).dot(&e) / l2).clamp(0.0, 1.0))
        }
    }
}

/// A meridian of the crossing scan: its revolution angle, and the parameters of interior
/// candidates on it (sampled too, so that the scan starts from each candidate: the
/// extremum of a crossing lens, [`super::second_order`], sees the loop around it as a sign
/// change between itself and a neighbouring sample).
#[derive(Debug, Clone)]
pub(super) struct Meridian {
    pub theta: f64,
    pub through: Vec<f64>,
}

impl Meridian {
    /// A meridian scanned at the uniform samples only.
    pub fn fixed(theta: f64) -> Self {
        Meridian {
            theta,
            through: Vec::new(),
        }
    }

    /// The meridian of `g` through its surface point `x` (g's frame), sampled at `x` too.
    pub fn through(g: &Patch, x: &Point3<f64>) -> Self {
        let rho = norm2(x.x, x.y);
        Meridian {
            theta: x.y.atan2(x.x),
            through: piece_param(g, Point2::new(rho, x.z)).into_iter().collect(),
        }
    }

    /// The meridians sorted by angle, those within [`MERIDIAN_DEDUP`] of each other merged
    /// into one that keeps every candidate's parameter (the four sign combinations of a
    /// common normal share its meridians).
    pub fn merged(mut list: Vec<Meridian>) -> Vec<Meridian> {
        list.sort_by(|x, y| x.theta.total_cmp(&y.theta));
        let mut out: Vec<Meridian> = Vec::with_capacity(list.len());
        for m in list {
            match out.last_mut() {
                Some(last) if (m.theta - last.theta).abs() <= MERIDIAN_DEDUP => {
                    last.through.extend(m.through)
                }
                _ => out.push(m),
            }
        }
        out
    }
}

/// Points of `g`'s meridians where an implicit function of `o`'s halves changes sign
/// ([`implicit_halves`]), each emitted with its closest point on `o` (O's frame): a
/// crossing of the two patches when that distance is zero. Every emitted pair is two real
/// points of the patches, so extra candidates never undercut the distance. `pos_og` places
/// G in O.
pub(super) fn meridian_crossings(
    g: &Patch,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    meridians: &[Meridian],
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let n = MERIDIAN_SAMPLES;
    // The meridian's profile samples do not depend on the meridian: computed once.
    let uniform: Vec<(f64, Point2<f64>)> = (0..=n)
        .map(|i| {
            let s = i as f64 / n as f64;
            (s, g.arc.point_at(s))
        })
        .collect();
    let mut samples = Vec::with_capacity(n + 2);
    for m in meridians {
        samples.clear();
        samples.extend_from_slice(&uniform);
        for &s in m.through.iter().filter(|s| (0.0..=1.0).contains(*s)) {
            let k = samples.partition_point(|x| x.0 < s);
            if samples.get(k).is_none_or(|x| x.0 != s) {
                samples.insert(k, (s, g.arc.point_at(s)));
            }
        }
        let e = e_rho(m.theta);
        let at = |s: f64| pos_og * lift(g.arc.point_at(s), &e);
        let mut prev = implicit_halves(o, &(pos_og * lift(samples[0].1, &e)));
        for k in 1..samples.len() {
            let (s0, s1) = (samples[k - 1].0, samples[k].0);
            let cur = implicit_halves(o, &(pos_og * lift(samples[k].1, &e)));
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
