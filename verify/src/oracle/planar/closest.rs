//! The closest curve point to a point `(rho, z)` and the signed distance to the region
//! (module documentation of [`super`]).

use super::hierarchy::PlanarIndex;
use super::piece_search::{golden_on_piece, minimise_on_piece};
use crate::oracle::profile_eval::{cross, dist, norm, seg_distance_sq, sub, P2};

/// A closest curve point.
#[derive(Debug, Clone, Copy)]
pub struct CurvePoint {
    /// Distance from the query point (realised: `|q - p|`).
    pub dist: f64,
    /// Piece and parameter.
    pub piece: usize,
    pub t: f64,
    /// The curve point.
    pub p: P2,
    /// Tangent `C'(t)`, zero when unknown.
    pub tangent: P2,
    /// Whether `t` is at an end of its piece or at a knot inside it (a joint or a possible
    /// corner: the tangent does not give the side).
    pub at_joint: bool,
}

/// A signed distance: negative inside the region.
#[derive(Debug, Clone, Copy)]
pub struct Signed {
    /// Signed distance to the curve (realised magnitude).
    pub value: f64,
    /// The closest curve point.
    pub closest: CurvePoint,
}

impl PlanarIndex {
    /// The closest curve point to `q` (see the module documentation).
    pub fn closest(&self, q: P2) -> CurvePoint {
        let (d2, _) = self.poly_nearest(q);
        let r = d2.sqrt() + 2.0 * self.geom.sag + 1e-15 * (1.0 + norm(q));
        let mut cand = Vec::with_capacity(4);
        self.segments_within(q, r, &mut cand);
        let mut best = CurvePoint {
            dist: f64::INFINITY,
            piece: 0,
            t: 0.0,
            p: [f64::NAN; 2],
            tangent: [0.0; 2],
            at_joint: false,
        };
        for &i in &cand {
            let c = self.refine_segment(q, i);
            if c.dist < best.dist {
                best = c;
            }
        }
        best
    }

    /// Closest point of the curve near segment `i`: Newton on the parameter over the
    /// segment and its neighbours within the same piece.
    fn refine_segment(&self, q: P2, i: usize) -> CurvePoint {
        let s = self.samples();
        let (a, b) = (s[i], s[i + 1]);
        if a.piece != b.piece {
            // The zero-length joint segment: both pieces' end points.
            let pa = self.point_at(a.piece, a.t);
            let pb = self.point_at(b.piece, b.t);
            return if pa.dist(q) <= pb.dist(q) {
                pa.with_dist(q)
            } else {
                pb.with_dist(q)
            };
        }
        let k = a.piece;
        let lo = if i > 0 && s[i - 1].piece == k {
            s[i - 1].t
        } else {
            a.t
        };
        let hi = if i + 2 < s.len() && s[i + 2].piece == k {
            s[i + 2].t
        } else {
            b.t
        };
        let (_, frac) = seg_distance_sq(q, a.p, b.p);
        let t0 = a.t + frac * (b.t - a.t);
        let (mut t, mut p) = minimise_on_piece(&self.geom, k, q, lo, hi, t0);
        // Newton needs `h' = |C'|^2 + (C - q) . C''` well away from zero, which fails where
        // the speed goes to zero (a stationary point, often on a knot): there `h'` can vanish
        // or turn negative far from the minimum and the iteration stalls (regression f11 of
        // `verify/regressions/near-stationary/zero-speed-knot.toml`). The derivative-free search over the
        // segment's own parameter range does not use `C'` at all; keep the nearer point.
        let (tg, pg) = golden_on_piece(&self.geom, k, q, a.t, b.t);
        if dist(pg, q) < dist(p, q) {
            (t, p) = (tg, pg);
        }
        let pc = &self.geom.pieces[k];
        let j = pc.jet(t);
        CurvePoint {
            dist: dist(p, q),
            piece: k,
            t,
            p,
            tangent: j.d1,
            // A knot inside the piece may be a corner (a degree-1 polyline, a repeated knot):
            // there the tangent of one side says nothing about the other, so it counts as a
            // joint like the piece's ends (the side of `q` comes from the crossing parity).
            at_joint: t <= pc.t0 || t >= pc.t1 || near_break(&pc.breaks, t),
        }
    }

    fn point_at(&self, k: usize, t: f64) -> CurvePoint {
        let pc = &self.geom.pieces[k];
        let j = pc.jet(t);
        CurvePoint {
            dist: f64::INFINITY,
            piece: k,
            t,
            p: j.p,
            tangent: j.d1,
            at_joint: true,
        }
    }

    /// Signed distance of `q` to the region (negative inside).
    pub fn signed(&self, q: P2) -> Signed {
        let c = self.closest(q);
        let dpoly = self.poly_distance(q);
        let inside = if dpoly > 2.0 * self.geom.sag || c.at_joint || norm(c.tangent) == 0.0 {
            self.inside_poly(q)
        } else {
            // The region lies to the left of travel when counter-clockwise.
            cross(c.tangent, sub(q, c.p)) * self.geom.orientation > 0.0
        };
        Signed {
            value: if inside { -c.dist } else { c.dist },
            closest: c,
        }
    }
}

trait WithDist {
    fn dist(&self, q: P2) -> f64;
    fn with_dist(self, q: P2) -> Self;
}

impl WithDist for CurvePoint {
    fn dist(&self, q: P2) -> f64 {
        dist(self.p, q)
    }
    fn with_dist(mut self, q: P2) -> Self {
        self.dist = dist(self.p, q);
        self
    }
}

/// Whether `t` is a knot of the piece up to [`KNOT_ULPS`] ulps (a foot found by a search may
/// stop a few ulps off the corner it belongs to).
fn near_break(breaks: &[f64], t: f64) -> bool {
    breaks
        .iter()
        .any(|&k| (t - k).abs() <= KNOT_ULPS * f64::EPSILON * k.abs().max(1.0))
}

/// Tolerance of [`near_break`], in ulps of the knot: the searches stop within 4 ulps
/// ([`GOLDEN_TOL_ULPS`](super::GOLDEN_TOL_ULPS)); twice that for margin.
const KNOT_ULPS: f64 = 8.0;
