//! Seeded random freeform profiles for the query campaign, built only through the public
//! constructors `NurbsCurve::new` and `Profile::new`.
//!
//! A profile starts from a star-shaped control skeleton (radius a smooth random function of
//! the angle about a centre): a half turn from the axis back to the axis for chains open on
//! the axis, a full turn about a centre at `rho > radius` for closed loops. The skeleton is
//! cut into pieces (corners at the joints), each a B-spline of degree 3 (sometimes 2 or 1,
//! sometimes rational) with uniform or random interior knots, sometimes a repeated interior
//! knot (a corner inside a piece). Runs of consecutive control points are made exactly
//! collinear (axis-parallel, axis-perpendicular or oblique: straight spans) or nearly
//! collinear (long near-straight spans); open chains sometimes start or end with a flat disk.
//! A candidate is kept only when `Profile::new` accepts it and its own dense polyline is
//! simple with a clearance between non-adjacent parts; otherwise it is drawn again.

use crate::oracle::profile_eval::{cross, dist, sub, PieceEval, P2};
use nalgebra::Point2;
use revdist::nurbs::NurbsCurve;
use revdist::profile::{Profile, ProfileKind};
use revdist::rng::SplitMix64;
use std::f64::consts::{PI, TAU};

/// What a generated profile contains (for reports).
#[derive(Debug, Clone, Default)]
pub struct Features {
    pub closed: bool,
    pub clockwise: bool,
    pub pieces: usize,
    pub control_points: usize,
    pub straight_spans: usize,
    pub near_straight: usize,
    pub repeated_knots: usize,
    pub rational: usize,
    pub flat_ends: usize,
}

/// Draws attempts until a valid simple profile of about `size` comes out.
pub fn random_profile(rng: &mut SplitMix64, name: &str, size: f64) -> (Profile, Features) {
    loop {
        if let Some(r) = attempt(rng, name, size) {
            return r;
        }
    }
}

/// Radius function: 1 + a small random Fourier series, kept in [0.35, 1.6].
fn radius_fn(rng: &mut SplitMix64) -> impl Fn(f64) -> f64 {
    let terms: Vec<(f64, f64, f64)> = (1..=5)
        .map(|k| {
            let amp = rng.range(0.0, 0.35) / k as f64;
            (k as f64, amp, rng.range(0.0, TAU))
        })
        .collect();
    move |phi: f64| {
        let r: f64 = 1.0
            + terms
                .iter()
                .map(|(k, a, b)| a * (k * phi + b).cos())
                .sum::<f64>();
        r.clamp(0.35, 1.6)
    }
}

fn attempt(rng: &mut SplitMix64, name: &str, size: f64) -> Option<(Profile, Features)> {
    let mut f = Features {
        closed: rng.chance(0.4),
        ..Features::default()
    };
    let half = 0.5 * size;
    let rfun = radius_fn(rng);
    let total = rng.int(4, 60);
    let mut pts: Vec<P2> = Vec::with_capacity(total + 1);
    if f.closed {
        let rmax = 1.6 * half;
        let rho_c = rmax * rng.range(1.05, 2.0);
        let zc = rng.range(-half, half);
        let phi0 = rng.range(0.0, TAU);
        for i in 0..total {
            let phi = phi0 + TAU * i as f64 / total as f64;
            let r = half * rfun(phi);
            pts.push([rho_c + r * phi.cos(), zc + r * phi.sin()]);
        }
        pts.push(pts[0]);
    } else {
        let zc = rng.range(-half, half);
        for i in 0..=total {
            let phi = -0.5 * PI + PI * i as f64 / total as f64;
            let r = half * rfun(phi);
            let rho = if i == 0 || i == total {
                0.0
            } else {
                r * phi.cos()
            };
            pts.push([rho, zc + r * phi.sin()]);
        }
        // Flat disks at the ends: the end moves along z = const to the axis.
        if rng.chance(0.35) && pts.len() > 3 {
            let z0 = pts[0][1];
            let a = pts[1][0] * rng.range(0.3, 0.9);
            pts[1] = [a, z0];
            f.flat_ends += 1;
        }
        if rng.chance(0.35) && pts.len() > 3 {
            let n = pts.len() - 1;
            let z1 = pts[n][1];
            let a = pts[n - 1][0] * rng.range(0.3, 0.9);
            pts[n - 1] = [a, z1];
            f.flat_ends += 1;
        }
    }
    // Straight and near-straight runs.
    let runs = rng.int(0, 3);
    for _ in 0..runs {
        let n = pts.len();
        if n < 8 {
            break;
        }
        let len = rng.int(4, 8.min(n - 3));
        let i = rng.int(1, n - 2 - len);
        let j = i + len - 1;
        let (mut a, mut b) = (pts[i], pts[j]);
        let kind = rng.int(0, 3);
        match kind {
            0 if a[0] > 0.0 && b[0] > 0.0 => {
                // Axis-parallel (a cylinder band): constant rho.
                let rho = 0.5 * (a[0] + b[0]);
                a[0] = rho;
                b[0] = rho;
            }
            1 => {
                // Axis-perpendicular (a flat annulus): constant z.
                let z = 0.5 * (a[1] + b[1]);
                a[1] = z;
                b[1] = z;
            }
            _ => {}
        }
        let near = kind == 3;
        let nrm = {
            let d = sub(b, a);
            let l = d[0].hypot(d[1]).max(1e-300);
            [-d[1] / l, d[0] / l]
        };
        let delta = if near {
            size * [1e-3, 1e-5, 1e-7][rng.int(0, 2)]
        } else {
            0.0
        };
        for (m, k) in (i..=j).enumerate() {
            let s = m as f64 / (len - 1) as f64;
            let off = if near && m > 0 && m + 1 < len {
                delta * rng.range(-1.0, 1.0)
            } else {
                0.0
            };
            pts[k] = [
                a[0] + s * (b[0] - a[0]) + off * nrm[0],
                a[1] + s * (b[1] - a[1]) + off * nrm[1],
            ];
        }
        if near {
            f.near_straight += 1;
        } else {
            f.straight_spans += 1;
        }
    }
    if pts.iter().any(|q| q[0] < 0.0) {
        return None;
    }
    // Runs drawn over runs can collapse control points: keep the legs of the control polygon
    // clear of zero length (a zero leg at a piece end is a zero end tangent).
    if pts.windows(2).any(|w| dist(w[0], w[1]) < 1e-4 * size) {
        return None;
    }
    if rng.chance(0.2) {
        pts.reverse();
        f.clockwise = true;
    }
    // Cut into pieces at random joints (each piece >= 2 skeleton points).
    let n = pts.len();
    let npieces = rng.int(1, 5).min((n - 1) / 2).max(1);
    let mut cuts: Vec<usize> = vec![0, n - 1];
    while cuts.len() < npieces + 1 {
        let c = rng.int(1, n - 2);
        if !cuts.contains(&c) {
            cuts.push(c);
        }
    }
    cuts.sort_unstable();
    let mut pieces = Vec::new();
    for w in cuts.windows(2) {
        let mut ctrl: Vec<P2> = pts[w[0]..=w[1]].to_vec();
        let degree = match rng.int(0, 9) {
            0 => 1,
            1 => 2,
            _ => 3,
        };
        // Too few points for the degree: insert midpoints of the longest edges.
        while ctrl.len() < degree + 1 {
            let (k, _) = ctrl
                .windows(2)
                .enumerate()
                .map(|(k, e)| (k, dist(e[0], e[1])))
                .max_by(|x, y| x.1.total_cmp(&y.1))?;
            let m = [
                0.5 * (ctrl[k][0] + ctrl[k + 1][0]),
                0.5 * (ctrl[k][1] + ctrl[k + 1][1]),
            ];
            ctrl.insert(k + 1, m);
        }
        let knots = random_knots(rng, degree, ctrl.len(), &mut f);
        let weights = if degree >= 2 && rng.chance(0.2) {
            f.rational += 1;
            let mut w: Vec<f64> = (0..ctrl.len()).map(|_| rng.log_range(0.5, 2.0)).collect();
            w[0] = 1.0;
            *w.last_mut().unwrap() = 1.0;
            Some(w)
        } else {
            None
        };
        f.control_points += ctrl.len();
        pieces.push((degree, knots, ctrl, weights));
    }
    f.pieces = pieces.len();
    // Own simplicity check on a dense polyline.
    let evals: Vec<PieceEval> = pieces
        .iter()
        .map(|(d, k, c, w)| PieceEval::new(*d, k, c, w.as_deref()))
        .collect();
    if !is_simple(&evals, f.closed, size) {
        return None;
    }
    let curves = pieces
        .into_iter()
        .map(|(d, k, c, w)| {
            NurbsCurve::new(d, k, c.iter().map(|q| Point2::new(q[0], q[1])).collect(), w)
        })
        .collect::<Result<Vec<_>, _>>()
        .ok()?;
    let profile = Profile::new(name, curves).ok()?;
    let want = if f.closed {
        ProfileKind::Closed
    } else {
        ProfileKind::OpenOnAxis
    };
    (profile.kind() == want).then_some((profile, f))
}

/// Clamped knots on [0, 1]: uniform or jittered interior knots, sometimes one repeated
/// `degree` times (a corner) or `degree - 1` times.
fn random_knots(rng: &mut SplitMix64, degree: usize, npts: usize, f: &mut Features) -> Vec<f64> {
    let interior = npts - degree - 1;
    let mut inner: Vec<f64> = if rng.chance(0.5) {
        (1..=interior)
            .map(|i| i as f64 / (interior + 1) as f64)
            .collect()
    } else {
        let mut acc = 0.0;
        let steps: Vec<f64> = (0..=interior).map(|_| rng.range(0.3, 1.7)).collect();
        let total: f64 = steps.iter().sum();
        steps[..interior]
            .iter()
            .map(|s| {
                acc += s;
                acc / total
            })
            .collect()
    };
    if degree >= 2 && interior >= degree && rng.chance(0.25) {
        // Repeat one interior knot: multiplicity `degree` (C0 corner) or `degree - 1`.
        let mult = if rng.chance(0.6) { degree } else { degree - 1 };
        let i = rng.int(0, interior - mult);
        let v = inner[i];
        for k in 0..mult {
            inner[i + k] = v;
        }
        f.repeated_knots += 1;
    }
    let mut knots = vec![0.0; degree + 1];
    knots.extend(inner);
    knots.resize(knots.len() + degree + 1, 1.0);
    knots
}

/// Samples per knot span of the simplicity check.
const SIMPLE_SAMPLES: usize = 12;
/// Clearance required between non-adjacent parts of the curve, relative to the size.
const CLEARANCE_REL: f64 = 2e-3;

/// Whether the chain (closed, or open with the axis closing it) is simple: no two
/// non-adjacent polyline segments intersect or come closer than the clearance, and open
/// chains stay off the axis between their ends.
fn is_simple(pieces: &[PieceEval], closed: bool, size: f64) -> bool {
    let mut poly: Vec<P2> = Vec::new();
    for pc in pieces {
        for w in pc.breaks.windows(2) {
            for i in 0..SIMPLE_SAMPLES {
                let t = w[0] + (w[1] - w[0]) * i as f64 / SIMPLE_SAMPLES as f64;
                poly.push(pc.point(t));
            }
        }
    }
    poly.push(pieces.last().unwrap().point(pieces.last().unwrap().t1));
    poly.dedup_by(|a, b| dist(*a, *b) <= 1e-12 * size);
    let n = poly.len();
    if n < 4 {
        return false;
    }
    if !closed && poly[1..n - 1].iter().any(|q| q[0] <= 1e-6 * size) {
        return false;
    }
    let clearance = CLEARANCE_REL * size;
    // Arc length along the polyline: parts closer than a few clearances along the chain are
    // neighbours (naturally close); farther parts must keep the clearance. No two
    // non-adjacent segments may cross.
    let mut cum = vec![0.0; n];
    for i in 1..n {
        cum[i] = cum[i - 1] + dist(poly[i - 1], poly[i]);
    }
    let total = cum[n - 1];
    let nseg = n - 1;
    for i in 0..nseg {
        for j in i + 2..nseg {
            if closed && i == 0 && j == nseg - 1 {
                continue;
            }
            let (a, b, c, d) = (poly[i], poly[i + 1], poly[j], poly[j + 1]);
            if a[0].min(b[0]) > c[0].max(d[0]) + clearance
                || c[0].min(d[0]) > a[0].max(b[0]) + clearance
                || a[1].min(b[1]) > c[1].max(d[1]) + clearance
                || c[1].min(d[1]) > a[1].max(b[1]) + clearance
            {
                continue;
            }
            if segments_intersect(a, b, c, d) {
                return false;
            }
            let mut along = cum[j] - cum[i + 1];
            if closed {
                along = along.min(total - (cum[j + 1] - cum[i]));
            }
            if along > 4.0 * clearance && segment_gap(a, b, c, d) < clearance {
                return false;
            }
        }
    }
    true
}

fn orient(a: P2, b: P2, c: P2) -> f64 {
    cross(sub(b, a), sub(c, a))
}

fn segments_intersect(a: P2, b: P2, c: P2, d: P2) -> bool {
    let (o1, o2) = (orient(a, b, c), orient(a, b, d));
    let (o3, o4) = (orient(c, d, a), orient(c, d, b));
    o1 * o2 < 0.0 && o3 * o4 < 0.0
}

fn segment_gap(a: P2, b: P2, c: P2, d: P2) -> f64 {
    use crate::oracle::profile_eval::point_segment_distance as psd;
    psd(a, c, d)
        .min(psd(b, c, d))
        .min(psd(c, a, b))
        .min(psd(d, a, b))
}

/// The profile in the README's TOML format (revdist's writer, used for output only).
pub fn to_toml(profile: &Profile) -> String {
    revdist::profile_file::to_toml_string(profile)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn many_profiles_are_valid_and_varied() {
        let mut rng = SplitMix64(7);
        let mut closed = 0;
        let mut straight = 0;
        for i in 0..200 {
            let (p, f) = random_profile(&mut rng, &format!("r{i}"), 1.0);
            assert!(!p.pieces().is_empty());
            closed += f.closed as usize;
            straight += f.straight_spans;
            let back = revdist::profile_file::from_toml_str(&to_toml(&p)).unwrap();
            assert_eq!(back, p);
        }
        assert!(closed > 40 && closed < 120, "{closed}");
        assert!(straight > 50, "{straight}");
    }
}
