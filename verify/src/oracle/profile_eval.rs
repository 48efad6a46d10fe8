//! Own evaluation of a profile's NURBS pieces from their raw data (degree, knots, control
//! points, weights), and a dense polyline of the whole profile with a measured sagitta.
//!
//! Nothing here calls revdist's curve code: the pieces are read through the raw accessors
//! of [`revdist::nurbs::NurbsCurve`] only. A piece is evaluated with de Boor's algorithm in
//! homogeneous coordinates `(w rho, w z, w)`; its first and second derivatives come from the
//! derivative B-splines of the homogeneous curve (control points
//! `p (Q[i+1] - Q[i]) / (u[i+p+1] - u[i+1])` on the knots without their first and last
//! entries) and the quotient rule.

use revdist::profile::{Profile, ProfileKind};

/// A point or vector of the (rho, z) plane.
pub type P2 = [f64; 2];

/// `a - b`.
#[inline]
pub fn sub(a: P2, b: P2) -> P2 {
    [a[0] - b[0], a[1] - b[1]]
}

/// Dot product.
#[inline]
pub fn dot(a: P2, b: P2) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// z-component of the cross product.
#[inline]
pub fn cross(a: P2, b: P2) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Euclidean norm.
#[inline]
pub fn norm(a: P2) -> f64 {
    a[0].hypot(a[1])
}

/// Distance of two points.
#[inline]
pub fn dist(a: P2, b: P2) -> f64 {
    norm(sub(a, b))
}

/// A B-spline in homogeneous coordinates: degree, knots and control points `(w x, w z, w)`.
#[derive(Debug, Clone)]
struct HomSpline {
    degree: usize,
    knots: Vec<f64>,
    ctrl: Vec<[f64; 3]>,
}

impl HomSpline {
    /// The knot span index `k` with `knots[k] <= t < knots[k+1]`, inside the clamped domain;
    /// at the end of the domain the last non-empty span.
    fn span(&self, t: f64) -> usize {
        let p = self.degree;
        let n = self.ctrl.len();
        let (lo, hi) = (self.knots[p], self.knots[n]);
        let t = t.clamp(lo, hi);
        if t >= hi {
            let mut k = n - 1;
            while k > p && self.knots[k] >= hi {
                k -= 1;
            }
            return k;
        }
        // Binary search for the last knot index in [p, n-1] with knots[k] <= t.
        let (mut a, mut b) = (p, n - 1);
        while a < b {
            let m = (a + b).div_ceil(2);
            if self.knots[m] <= t {
                a = m;
            } else {
                b = m - 1;
            }
        }
        a
    }

    /// de Boor's algorithm at `t` (clamped to the domain).
    fn eval(&self, t: f64) -> [f64; 3] {
        let p = self.degree;
        let n = self.ctrl.len();
        let t = t.clamp(self.knots[p], self.knots[n]);
        self.de_boor(self.span(t), |_| t)
    }

    /// The blossom of the polynomial on knot span `k` at the `p` arguments `us` (de Boor's
    /// algorithm with the argument `us[r - 1]` at level `r`): with `p - i` copies of `ta`
    /// and `i` of `tb` it is the `i`-th Bezier control point of the curve on `[ta, tb]`.
    fn blossom(&self, k: usize, us: &[f64]) -> [f64; 3] {
        self.de_boor(k, |r| us[r - 1])
    }

    /// de Boor's triangle on knot span `k` with the argument `arg(r)` at level `r` (the same
    /// argument at every level evaluates the curve; different ones give its blossom).
    fn de_boor(&self, k: usize, arg: impl Fn(usize) -> f64) -> [f64; 3] {
        let p = self.degree;
        let mut d = [[0.0; 3]; 8];
        let mut dv: Vec<[f64; 3]>;
        let buf: &mut [[f64; 3]] = if p < 8 {
            &mut d[..=p]
        } else {
            dv = vec![[0.0; 3]; p + 1];
            &mut dv[..]
        };
        for (j, b) in buf.iter_mut().enumerate() {
            *b = self.ctrl[j + k - p];
        }
        for r in 1..=p {
            let t = arg(r);
            for j in (r..=p).rev() {
                let i = j + k - p;
                let den = self.knots[i + p + 1 - r] - self.knots[i];
                let alpha = if den > 0.0 {
                    (t - self.knots[i]) / den
                } else {
                    0.0
                };
                let prev = buf[j - 1];
                for (v, pv) in buf[j].iter_mut().zip(prev) {
                    *v = (1.0 - alpha) * pv + alpha * *v;
                }
            }
        }
        buf[p]
    }

    /// The derivative spline (degree `p - 1`), `None` for degree 0.
    fn derivative(&self) -> Option<HomSpline> {
        let p = self.degree;
        if p == 0 {
            return None;
        }
        let n = self.ctrl.len();
        let mut ctrl = Vec::with_capacity(n - 1);
        for i in 0..n - 1 {
            let den = self.knots[i + p + 1] - self.knots[i + 1];
            let f = if den > 0.0 { p as f64 / den } else { 0.0 };
            ctrl.push([
                f * (self.ctrl[i + 1][0] - self.ctrl[i][0]),
                f * (self.ctrl[i + 1][1] - self.ctrl[i][1]),
                f * (self.ctrl[i + 1][2] - self.ctrl[i][2]),
            ]);
        }
        Some(HomSpline {
            degree: p - 1,
            knots: self.knots[1..self.knots.len() - 1].to_vec(),
            ctrl,
        })
    }
}

/// One NURBS piece, evaluated independently of revdist.
#[derive(Debug, Clone)]
pub struct PieceEval {
    curve: HomSpline,
    d1: Option<HomSpline>,
    d2: Option<HomSpline>,
    /// Parameter domain start.
    pub t0: f64,
    /// Parameter domain end.
    pub t1: f64,
    /// Distinct knot values inside and at the ends of the domain (span boundaries).
    pub breaks: Vec<f64>,
}

/// Point, first and second derivative of a piece at a parameter.
#[derive(Debug, Clone, Copy)]
pub struct Jet {
    pub p: P2,
    pub d1: P2,
    pub d2: P2,
}

impl PieceEval {
    /// From raw NURBS data: degree, clamped knots, control points, optional weights.
    pub fn new(degree: usize, knots: &[f64], points: &[P2], weights: Option<&[f64]>) -> Self {
        let ctrl: Vec<[f64; 3]> = points
            .iter()
            .enumerate()
            .map(|(i, q)| {
                let w = weights.map_or(1.0, |w| w[i]);
                [w * q[0], w * q[1], w]
            })
            .collect();
        let curve = HomSpline {
            degree,
            knots: knots.to_vec(),
            ctrl,
        };
        let d1 = curve.derivative();
        let d2 = d1.as_ref().and_then(HomSpline::derivative);
        let (t0, t1) = (knots[degree], knots[knots.len() - 1 - degree]);
        let mut breaks: Vec<f64> = knots
            .iter()
            .copied()
            .filter(|&u| u >= t0 && u <= t1)
            .collect();
        breaks.dedup();
        PieceEval {
            curve,
            d1,
            d2,
            t0,
            t1,
            breaks,
        }
    }

    /// Point at `t` (clamped to the domain).
    pub fn point(&self, t: f64) -> P2 {
        let h = self.curve.eval(t);
        [h[0] / h[2], h[1] / h[2]]
    }

    /// Point and first two derivatives at `t` (quotient rule on the homogeneous curve).
    pub fn jet(&self, t: f64) -> Jet {
        let h = self.curve.eval(t);
        let zero = [0.0; 3];
        let h1 = self.d1.as_ref().map_or(zero, |s| s.eval(t));
        let h2 = self.d2.as_ref().map_or(zero, |s| s.eval(t));
        let w = h[2];
        let p = [h[0] / w, h[1] / w];
        let d1 = [(h1[0] - h1[2] * p[0]) / w, (h1[1] - h1[2] * p[1]) / w];
        let d2 = [
            (h2[0] - 2.0 * h1[2] * d1[0] - h2[2] * p[0]) / w,
            (h2[1] - 2.0 * h1[2] * d1[1] - h2[2] * p[1]) / w,
        ];
        Jet { p, d1, d2 }
    }
}

/// A polyline vertex: an actual curve point with its piece and parameter.
#[derive(Debug, Clone, Copy)]
pub struct Sample {
    pub piece: usize,
    pub t: f64,
    pub p: P2,
}

/// Relative chord sagitta the polyline is refined to (times the profile size).
pub const SAG_REL: f64 = 1e-6;
/// Longest polyline segment, relative to the profile size.
pub const MAX_SEGMENT_REL: f64 = 0.02;
/// Interior points per accepted segment at which the curve's deviation from the chord is
/// measured to estimate the sagitta bound.
const SAG_PROBES: usize = 7;
/// The measured deviation is multiplied by this before it is used as a bound: between the
/// probes (1/8 of the segment apart) the deviation of a nearly straight arc is a smooth bump
/// whose maximum exceeds the best probe by a few percent at most; 2 also covers uneven
/// parametric speed.
pub const SAG_SAFETY: f64 = 2.0;

/// The whole profile, ready for evaluation: pieces, kind, a dense polyline and its bounds.
#[derive(Debug, Clone)]
pub struct ProfileGeom {
    /// Name (for reports).
    pub name: String,
    /// The pieces in chain order.
    pub pieces: Vec<PieceEval>,
    /// Closed loop or open chain closed by the axis.
    pub kind: ProfileKind,
    /// Polyline through curve points, in chain order; consecutive pieces share the joint
    /// (the joint appears twice: as the last sample of one piece and the first of the next).
    pub samples: Vec<Sample>,
    /// Bound on the distance from any curve point to the polyline (measured sagitta times
    /// [`SAG_SAFETY`]).
    pub sag: f64,
    /// Box of the polyline, grown by `sag`: contains the curve.
    pub min: P2,
    pub max: P2,
    /// Diagonal of the box.
    pub size: f64,
    /// +1 when the region (closed by the axis for open chains) is counter-clockwise.
    pub orientation: f64,
    /// Largest distance from the origin of the profile's frame to a curve point (bounding
    /// sphere of the solid about its origin, up to `sag`).
    pub radius: f64,
}

impl ProfileGeom {
    /// Reads the raw data of `profile` and builds the polyline.
    pub fn new(profile: &Profile) -> ProfileGeom {
        let pieces: Vec<PieceEval> = profile
            .pieces()
            .iter()
            .map(|c| {
                let pts: Vec<P2> = c.points().iter().map(|q| [q.x, q.y]).collect();
                PieceEval::new(c.degree(), c.knots(), &pts, c.weights())
            })
            .collect();
        Self::from_pieces(profile.name().to_string(), pieces, profile.kind())
    }

    /// From already converted pieces.
    pub fn from_pieces(name: String, pieces: Vec<PieceEval>, kind: ProfileKind) -> ProfileGeom {
        // Size from a coarse sampling (control boxes would also do).
        let mut lo = [f64::INFINITY; 2];
        let mut hi = [f64::NEG_INFINITY; 2];
        for pc in &pieces {
            for i in 0..=64 {
                let q = pc.point(pc.t0 + (pc.t1 - pc.t0) * i as f64 / 64.0);
                for c in 0..2 {
                    lo[c] = lo[c].min(q[c]);
                    hi[c] = hi[c].max(q[c]);
                }
            }
        }
        let size0 = norm(sub(hi, lo)).max(f64::MIN_POSITIVE);
        let tol = SAG_REL * size0;
        let max_len = MAX_SEGMENT_REL * size0;
        let mut samples: Vec<Sample> = Vec::new();
        let mut sag_meas: f64 = 0.0;
        for (k, pc) in pieces.iter().enumerate() {
            for w in pc.breaks.windows(2) {
                let (a, b) = (w[0], w[1]);
                if b <= a {
                    continue;
                }
                let first = match samples.last() {
                    Some(s) => s.piece != k,
                    None => true,
                };
                if first {
                    samples.push(Sample {
                        piece: k,
                        t: a,
                        p: pc.point(a),
                    });
                }
                // Four uniform starts per knot span, then adaptive bisection.
                for i in 0..4 {
                    let ta = a + (b - a) * i as f64 / 4.0;
                    let tb = if i == 3 {
                        b
                    } else {
                        a + (b - a) * (i + 1) as f64 / 4.0
                    };
                    subdivide(pc, k, ta, tb, tol, max_len, 0, &mut samples, &mut sag_meas);
                }
            }
        }
        let sag = SAG_SAFETY * sag_meas + 4.0 * f64::EPSILON * size0;
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        let mut radius: f64 = 0.0;
        for s in &samples {
            for c in 0..2 {
                min[c] = min[c].min(s.p[c]);
                max[c] = max[c].max(s.p[c]);
            }
            radius = radius.max(norm(s.p));
        }
        min = [min[0] - sag, min[1] - sag];
        max = [max[0] + sag, max[1] + sag];
        // Shoelace area of the closed polygon (the axis closure for open chains is the
        // implicit edge from the last sample back to the first).
        let mut area2 = 0.0;
        for i in 0..samples.len() {
            let a = samples[i].p;
            let b = samples[(i + 1) % samples.len()].p;
            area2 += cross(a, b);
        }
        ProfileGeom {
            name,
            pieces,
            kind,
            samples,
            sag,
            min,
            max,
            size: norm(sub(max, min)),
            orientation: if area2 >= 0.0 { 1.0 } else { -1.0 },
            radius: radius + sag,
        }
    }

    /// Point of piece `k` at `t`.
    pub fn point(&self, k: usize, t: f64) -> P2 {
        self.pieces[k].point(t)
    }

    /// Jet of piece `k` at `t`.
    pub fn jet(&self, k: usize, t: f64) -> Jet {
        self.pieces[k].jet(t)
    }

    /// The piece after `k` in chain order (wrapping for closed loops).
    pub fn next_piece(&self, k: usize) -> Option<usize> {
        if k + 1 < self.pieces.len() {
            Some(k + 1)
        } else if self.kind == ProfileKind::Closed {
            Some(0)
        } else {
            None
        }
    }

    /// The piece before `k` in chain order (wrapping for closed loops).
    pub fn prev_piece(&self, k: usize) -> Option<usize> {
        if k > 0 {
            Some(k - 1)
        } else if self.kind == ProfileKind::Closed {
            Some(self.pieces.len() - 1)
        } else {
            None
        }
    }
}

/// Deviation of the curve from the chord `[pa, pb]` at `SAG_PROBES` interior points.
fn chord_deviation(pc: &PieceEval, ta: f64, tb: f64, pa: P2, pb: P2) -> f64 {
    let mut dev: f64 = 0.0;
    for i in 1..=SAG_PROBES {
        let t = ta + (tb - ta) * i as f64 / (SAG_PROBES + 1) as f64;
        dev = dev.max(point_segment_distance(pc.point(t), pa, pb));
    }
    dev.max(pc.hull_deviation(ta, tb, pa, pb))
}

impl PieceEval {
    /// A bound on the distance from the curve on `[ta, tb]` (inside one knot span) to the
    /// chord `[pa, pb]`: the curve lies in the convex hull of its Bezier control points on
    /// that interval (positive weights), and the distance to a segment is convex, so the
    /// largest control point distance bounds it. Unlike probes, it sees features between
    /// samples, such as a piece that runs back along itself for a few micrometres (a
    /// retrace) near a sample; `+inf` (subdivide) for non-positive weights.
    fn hull_deviation(&self, ta: f64, tb: f64, pa: P2, pb: P2) -> f64 {
        let c = &self.curve;
        let p = c.degree;
        if p < 2 {
            return 0.0;
        }
        let k = c.span(0.5 * (ta + tb));
        let mut us = vec![ta; p];
        let mut dev: f64 = 0.0;
        for i in 1..p {
            us[p - i] = tb;
            let h = c.blossom(k, &us);
            if h[2].is_nan() || h[2] <= 0.0 {
                return f64::INFINITY;
            }
            dev = dev.max(point_segment_distance([h[0] / h[2], h[1] / h[2]], pa, pb));
        }
        dev
    }
}

/// Distance from `q` to the segment `[a, b]`.
pub fn point_segment_distance(q: P2, a: P2, b: P2) -> f64 {
    seg_distance_sq(q, a, b).0.sqrt()
}

/// Squared distance from `q` to the segment `[a, b]` and the parameter of the closest point.
#[inline]
pub fn seg_distance_sq(q: P2, a: P2, b: P2) -> (f64, f64) {
    let ab = sub(b, a);
    let l2 = dot(ab, ab);
    let s = if l2 > 0.0 {
        (dot(sub(q, a), ab) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let dx = a[0] + s * ab[0] - q[0];
    let dz = a[1] + s * ab[1] - q[1];
    (dx * dx + dz * dz, s)
}

/// Appends samples for `(ta, tb]` of piece `k`, bisecting until the chord deviation is below
/// `tol` and the chord is shorter than `max_len` (depth at most 40).
#[allow(clippy::too_many_arguments)]
fn subdivide(
    pc: &PieceEval,
    k: usize,
    ta: f64,
    tb: f64,
    tol: f64,
    max_len: f64,
    depth: usize,
    out: &mut Vec<Sample>,
    sag: &mut f64,
) {
    let pa = pc.point(ta);
    let pb = pc.point(tb);
    let dev = chord_deviation(pc, ta, tb, pa, pb);
    if depth < 40 && (dev > tol || dist(pa, pb) > max_len) {
        let tm = 0.5 * (ta + tb);
        subdivide(pc, k, ta, tm, tol, max_len, depth + 1, out, sag);
        subdivide(pc, k, tm, tb, tol, max_len, depth + 1, out, sag);
        return;
    }
    *sag = sag.max(dev);
    out.push(Sample {
        piece: k,
        t: tb,
        p: pb,
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarter_circle_is_exact() {
        let w = std::f64::consts::FRAC_1_SQRT_2;
        let pc = PieceEval::new(
            2,
            &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0],
            &[[1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
            Some(&[1.0, w, 1.0]),
        );
        for i in 0..=20 {
            let t = i as f64 / 20.0;
            let j = pc.jet(t);
            assert!((norm(j.p) - 1.0).abs() < 1e-15);
            // Tangent orthogonal to the radius.
            assert!(dot(j.p, j.d1).abs() < 1e-14 * norm(j.d1));
            // Curvature 1: |p' x p''| / |p'|^3.
            let k = cross(j.d1, j.d2).abs() / norm(j.d1).powi(3);
            assert!((k - 1.0).abs() < 1e-12, "{k}");
        }
    }

    #[test]
    fn cubic_derivative_matches_differences() {
        let pc = PieceEval::new(
            3,
            &[0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 1.0, 1.0, 1.0, 1.0],
            &[
                [0.0, 0.0],
                [1.0, 0.2],
                [1.5, 1.0],
                [0.7, 1.4],
                [0.4, 2.0],
                [0.0, 2.2],
            ],
            None,
        );
        let h = 1e-6;
        for i in 1..20 {
            let t = i as f64 / 20.0;
            let j = pc.jet(t);
            let a = pc.point(t - h);
            let b = pc.point(t + h);
            let fd = [(b[0] - a[0]) / (2.0 * h), (b[1] - a[1]) / (2.0 * h)];
            assert!(dist(fd, j.d1) < 1e-6, "{t}");
            let ja = pc.jet(t - h);
            let jb = pc.jet(t + h);
            let fd2 = [
                (jb.d1[0] - ja.d1[0]) / (2.0 * h),
                (jb.d1[1] - ja.d1[1]) / (2.0 * h),
            ];
            assert!(dist(fd2, j.d2) < 1e-4, "{t}");
        }
        assert_eq!(pc.point(0.0), [0.0, 0.0]);
        assert_eq!(pc.point(1.0), [0.0, 2.2]);
    }
}
