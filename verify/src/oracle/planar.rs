//! Distance from a point `(rho, z)` to a profile curve, and point-in-region with a sign.
//!
//! The dense polyline of [`ProfileGeom`] is put in a bounding-box hierarchy over consecutive
//! segments. Three queries:
//!
//! - [`PlanarIndex::poly_distance`]: distance to the polyline. Every curve point is within
//!   `sag` of the polyline and every polyline vertex is a curve point, so
//!   `dist(q, curve) >= poly_distance(q) - sag` (used for lower bounds).
//! - [`PlanarIndex::closest`]: the closest *curve* point. All segments whose polyline distance
//!   is within `2 sag` of the best one are candidates (the true closest point is within `sag`
//!   of a segment, whose distance is then at most `dist(q, curve) + sag <= best + 2 sag`);
//!   on each, the parameter is refined by safeguarded Newton on `(C(t) - q) . C'(t) = 0`
//!   over the segment and its two neighbours, also trying the bracket ends, and by a
//!   derivative-free golden-section search over the segment's own range (Newton stalls where
//!   the speed goes to zero; see [`golden_on_piece`]); the nearer point wins. The answer is
//!   an actual curve point, so its distance is `>=` the true distance up to round-off.
//! - [`PlanarIndex::inside_poly`]: crossing parity of a ray towards `+rho` against the
//!   polygon closed by the axis segment (open chains) or by itself (loops). The axis segment
//!   lies at `rho = 0 <= q.rho` and never crosses the ray, so it needs no edge of its own.
//!
//! [`PlanarIndex::signed`] combines them: the sign is the polygon's unless `q` is within
//! `2 sag` of the polyline, where the side of the tangent at the closest curve point decides
//! (the polygon and the curve bound regions that differ only within `sag` of the polyline).

use super::profile_eval::{cross, dist, dot, norm, seg_distance_sq, sub, ProfileGeom, Sample, P2};

/// Segments per leaf of the hierarchy.
const LEAF_SEGMENTS: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Node {
    min: P2,
    max: P2,
    /// Children, or `u32::MAX` for a leaf.
    left: u32,
    right: u32,
    /// Segment range `[start, end)` (segment `i` joins samples `i` and `i + 1`).
    start: u32,
    end: u32,
}

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

/// Hierarchy over a profile's polyline, with the profile itself for refinement.
#[derive(Debug, Clone)]
pub struct PlanarIndex {
    /// The profile (pieces, polyline, sag).
    pub geom: ProfileGeom,
    nodes: Vec<Node>,
}

#[inline]
fn box_distance_sq(q: P2, min: P2, max: P2) -> f64 {
    let dx = (min[0] - q[0]).max(0.0).max(q[0] - max[0]);
    let dz = (min[1] - q[1]).max(0.0).max(q[1] - max[1]);
    dx * dx + dz * dz
}

impl PlanarIndex {
    /// Builds the hierarchy over `geom`'s polyline.
    pub fn new(geom: ProfileGeom) -> PlanarIndex {
        let nseg = geom.samples.len().saturating_sub(1);
        let mut idx = PlanarIndex {
            geom,
            nodes: Vec::with_capacity(2 * nseg / LEAF_SEGMENTS + 2),
        };
        if nseg > 0 {
            idx.build(0, nseg);
        }
        idx
    }

    fn build(&mut self, start: usize, end: usize) -> u32 {
        let s = &self.geom.samples;
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        for smp in &s[start..=end] {
            for c in 0..2 {
                min[c] = min[c].min(smp.p[c]);
                max[c] = max[c].max(smp.p[c]);
            }
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            min,
            max,
            left: u32::MAX,
            right: u32::MAX,
            start: start as u32,
            end: end as u32,
        });
        if end - start > LEAF_SEGMENTS {
            let mid = (start + end) / 2;
            let l = self.build(start, mid);
            let r = self.build(mid, end);
            self.nodes[id as usize].left = l;
            self.nodes[id as usize].right = r;
        }
        id
    }

    fn samples(&self) -> &[Sample] {
        &self.geom.samples
    }

    /// Squared distance to the polyline and the nearest segment.
    pub fn poly_nearest(&self, q: P2) -> (f64, usize) {
        self.poly_nearest_below(q, f64::INFINITY)
            .expect("an unbounded search finds a segment")
    }

    /// Like [`Self::poly_nearest`], searching only below the squared distance `limit_sq`
    /// (`None` when no segment is that close).
    pub fn poly_nearest_below(&self, q: P2, limit_sq: f64) -> Option<(f64, usize)> {
        let s = self.samples();
        let mut best = (limit_sq, usize::MAX);
        if self.nodes.is_empty() {
            return None;
        }
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if box_distance_sq(q, n.min, n.max) >= best.0 {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    let (d2, _) = seg_distance_sq(q, s[i].p, s[i + 1].p);
                    if d2 < best.0 {
                        best = (d2, i);
                    }
                }
            } else {
                let l = &self.nodes[n.left as usize];
                let r = &self.nodes[n.right as usize];
                let dl = box_distance_sq(q, l.min, l.max);
                let dr = box_distance_sq(q, r.min, r.max);
                // Push the farther first so the nearer is visited first.
                let (first, second) = if dl <= dr {
                    (n.right, n.left)
                } else {
                    (n.left, n.right)
                };
                stack[top] = first;
                stack[top + 1] = second;
                top += 2;
            }
        }
        (best.1 != usize::MAX).then_some(best)
    }

    /// Distance from `q` to the polyline.
    pub fn poly_distance(&self, q: P2) -> f64 {
        self.poly_nearest(q).0.sqrt()
    }

    /// Distance from `q` to the polyline, given an upper bound `hint` of it (e.g. a nearby
    /// point's distance plus the distance to that point): the search prunes against the
    /// hint, and falls back to a full search if the hint was wrong.
    pub fn poly_distance_hint(&self, q: P2, hint: f64) -> f64 {
        let h = hint * (1.0 + 1e-9) + 1e-300;
        match self.poly_nearest_below(q, h * h) {
            Some((d2, _)) => d2.sqrt(),
            None => self.poly_distance(q),
        }
    }

    /// Segments whose distance to `q` is at most `r`.
    fn segments_within(&self, q: P2, r: f64, out: &mut Vec<usize>) {
        out.clear();
        if self.nodes.is_empty() {
            return;
        }
        let s = self.samples();
        let r2 = r * r;
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if box_distance_sq(q, n.min, n.max) > r2 {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    if seg_distance_sq(q, s[i].p, s[i + 1].p).0 <= r2 {
                        out.push(i);
                    }
                }
            } else {
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
    }

    /// Whether `q` is inside the polygon (crossing parity of the ray towards `+rho`).
    pub fn inside_poly(&self, q: P2) -> bool {
        let s = self.samples();
        if s.len() < 2 {
            return false;
        }
        let mut inside = false;
        let crosses = |a: P2, b: P2| -> bool {
            if (a[1] <= q[1]) != (b[1] <= q[1]) {
                let x = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                x > q[0]
            } else {
                false
            }
        };
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if n.max[0] <= q[0] || n.min[1] > q[1] || n.max[1] < q[1] {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    if crosses(s[i].p, s[i + 1].p) {
                        inside = !inside;
                    }
                }
            } else {
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
        // Closing edge: the axis segment (never crosses) or the loop's own closure.
        if crosses(s[s.len() - 1].p, s[0].p) {
            inside = !inside;
        }
        inside
    }

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

/// Minimises `|C(t) - q|` over `[lo, hi]` on piece `k`, starting near `t0`: the bracket
/// ends, and safeguarded Newton on `h(t) = (C - q) . C'` when `h` changes sign (else plain
/// Newton steps kept inside the bracket). Returns the best realised parameter and point.
pub fn minimise_on_piece(
    geom: &ProfileGeom,
    k: usize,
    q: P2,
    lo: f64,
    hi: f64,
    t0: f64,
) -> (f64, P2) {
    let pc = &geom.pieces[k];
    let h_of = |t: f64| {
        let j = pc.jet(t);
        let r = sub(j.p, q);
        (dot(r, j.d1), dot(j.d1, j.d1) + dot(r, j.d2), j.p)
    };
    let (hlo, _, plo) = h_of(lo);
    let (hhi, _, phi) = h_of(hi);
    let mut best = if dist(plo, q) <= dist(phi, q) {
        (lo, plo)
    } else {
        (hi, phi)
    };
    let consider = |t: f64, p: P2, best: &mut (f64, P2)| {
        if dist(p, q) < dist(best.1, q) {
            *best = (t, p);
        }
    };
    if hlo < 0.0 && hhi > 0.0 {
        let (mut a, mut b) = (lo, hi);
        let mut t = t0.clamp(a, b);
        for _ in 0..100 {
            let (h, hp, p) = h_of(t);
            consider(t, p, &mut best);
            if h == 0.0 {
                break;
            }
            if h < 0.0 {
                a = t;
            } else {
                b = t;
            }
            let newton = if hp > 0.0 { t - h / hp } else { f64::NAN };
            let next = if newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            if (next - t).abs() <= 2.0 * f64::EPSILON * (t.abs() + (hi - lo)) || b - a <= 0.0 {
                break;
            }
            t = next;
        }
    } else {
        let mut t = t0.clamp(lo, hi);
        for _ in 0..20 {
            let (h, hp, p) = h_of(t);
            consider(t, p, &mut best);
            if hp <= 0.0 || h == 0.0 {
                break;
            }
            let next = (t - h / hp).clamp(lo, hi);
            if (next - t).abs() <= 2.0 * f64::EPSILON * (t.abs() + (hi - lo)) {
                break;
            }
            t = next;
        }
    }
    best
}

/// Whether `t` is a knot of the piece up to [`KNOT_ULPS`] ulps (a foot found by a search may
/// stop a few ulps off the corner it belongs to).
fn near_break(breaks: &[f64], t: f64) -> bool {
    breaks
        .iter()
        .any(|&k| (t - k).abs() <= KNOT_ULPS * f64::EPSILON * k.abs().max(1.0))
}

/// Tolerance of [`near_break`], in ulps of the knot: the searches stop within 4 ulps
/// ([`GOLDEN_TOL_ULPS`]); twice that for margin.
const KNOT_ULPS: f64 = 8.0;

/// Golden-section search for the minimum of `|C(t) - q|` over `[ta, tb]` on piece `k`,
/// using curve points only (no derivatives, so a zero speed does not disturb it); the
/// iterates never leave `[ta, tb]`. Returns the best realised parameter and point seen,
/// the two ends included.
///
/// [`PlanarIndex::refine_segment`] calls it on one polyline segment's parameter range. That
/// range lies inside one knot span (every knot is a polyline vertex), and the closest curve
/// point lies in the range of some candidate segment (see the module documentation), so a
/// search confined to each candidate's own range loses nothing. The search finds the
/// minimum whenever `|C(t) - q|` is unimodal on the range, e.g. on a straight run however its
/// speed varies (`verify/regressions/near-stationary/zero-speed-knot.toml`: speed going to zero
/// at a knot); otherwise it still returns an actual curve point, a local minimum or an end,
/// i.e. an upper bound like every answer of [`PlanarIndex::closest`], and the caller keeps
/// the Newton answer when that is nearer.
///
/// It stops when the bracket is within [`GOLDEN_TOL_ULPS`] ulps of `t` (or after
/// [`GOLDEN_MAX_ITER`] steps): near the minimum `|C(t) - q|` changes by a second-order
/// amount only, so the realised distance is then exact to round-off even where the
/// comparisons can no longer order the iterates.
pub fn golden_on_piece(geom: &ProfileGeom, k: usize, q: P2, ta: f64, tb: f64) -> (f64, P2) {
    let pc = &geom.pieces[k];
    let g = |t: f64| {
        let p = pc.point(t);
        (dist(p, q), p)
    };
    let (ga, pa) = g(ta);
    let (gb, pb) = g(tb);
    let mut best = if ga <= gb { (ga, ta, pa) } else { (gb, tb, pb) };
    if tb <= ta {
        return (best.1, best.2);
    }
    // 1 / phi: the interior points split the bracket in the golden ratio, so one of them is
    // reused at every step.
    const INV_PHI: f64 = 0.618_033_988_749_894_9;
    let (mut a, mut b) = (ta, tb);
    let mut x1 = b - INV_PHI * (b - a);
    let mut x2 = a + INV_PHI * (b - a);
    let (mut g1, mut p1) = g(x1);
    let (mut g2, mut p2) = g(x2);
    for _ in 0..GOLDEN_MAX_ITER {
        for (gx, x, px) in [(g1, x1, p1), (g2, x2, p2)] {
            if gx < best.0 {
                best = (gx, x, px);
            }
        }
        if b - a <= GOLDEN_TOL_ULPS * f64::EPSILON * (a.abs().max(b.abs()) + (tb - ta)) {
            break;
        }
        if g1 <= g2 {
            // The minimum is in [a, x2].
            (b, x2, g2, p2) = (x2, x1, g1, p1);
            x1 = b - INV_PHI * (b - a);
            (g1, p1) = g(x1);
        } else {
            (a, x1, g1, p1) = (x1, x2, g2, p2);
            x2 = a + INV_PHI * (b - a);
            (g2, p2) = g(x2);
        }
    }
    (best.1, best.2)
}

/// Stopping width of [`golden_on_piece`], in ulps of the parameter (plus the range): a few
/// ulps, where the search cannot order its points any more.
pub const GOLDEN_TOL_ULPS: f64 = 4.0;
/// Step cap of [`golden_on_piece`], a guard only: each step shrinks the bracket by 0.618 and
/// the stopping width is at least [`GOLDEN_TOL_ULPS`] ulps of the range, which about 73 steps
/// reach; the cap ends the loop should a non-finite value keep the test from holding.
pub const GOLDEN_MAX_ITER: usize = 100;

#[cfg(test)]
mod tests {
    use super::super::profile_eval::{PieceEval, ProfileGeom};
    use super::*;
    use revdist::profile::ProfileKind;

    fn line(a: P2, b: P2) -> PieceEval {
        PieceEval::new(1, &[0.0, 0.0, 1.0, 1.0], &[a, b], None)
    }

    #[test]
    fn square_ring_inside_and_distance() {
        let (a, b, c, d) = ([1.0, 0.0], [2.0, 0.0], [2.0, 1.0], [1.0, 1.0]);
        let g = ProfileGeom::from_pieces(
            "sq".into(),
            vec![line(a, b), line(b, c), line(c, d), line(d, a)],
            ProfileKind::Closed,
        );
        let idx = PlanarIndex::new(g);
        let s = idx.signed([1.5, 0.5]);
        assert!((s.value + 0.5).abs() < 1e-14);
        let s = idx.signed([1.2, 0.5]);
        assert!((s.value + 0.2).abs() < 1e-14);
        let s = idx.signed([3.0, 2.0]);
        assert!((s.value - 2f64.sqrt()).abs() < 1e-14);
        let s = idx.signed([0.0, 0.5]);
        assert!((s.value - 1.0).abs() < 1e-14);
        assert!(!idx.inside_poly([0.5, 0.5]));
        assert!(idx.inside_poly([1.999, 0.999]));
    }

    /// A cubic that leaves a corner backwards along its own line for 4e-6 and returns (a
    /// retrace, found by the stationary-point property test): the polyline's probes at 1/8
    /// of a chord missed the fin's tip, and the oracle put a point of the tip 3.9e-6 from
    /// the curve. The control-polygon bound of the sagitta refines the polyline around it.
    #[test]
    fn retrace_fin_at_a_corner_is_on_the_curve() {
        let (c, d) = (
            [0.6149755885599717, 0.90542182387424],
            [1.5437466728434721, 0.90542182387424],
        );
        let fin = PieceEval::new(
            3,
            &[0.0, 0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0],
            &[c, [0.6137585056521959, c[1]], [0.8929366780727052, c[1]], d],
            None,
        );
        let (a, e) = (
            [0.5041220461639593, 1.4047918639542627],
            [1.6780510783507863, 1.4047918639542627],
        );
        let g = ProfileGeom::from_pieces(
            "retrace".into(),
            vec![line(a, c), fin, line(d, e), line(e, a)],
            ProfileKind::Closed,
        );
        let idx = PlanarIndex::new(g);
        // The tip: x(t) = c + 3 t (x1 - c) + ... has its minimum at t = 0.0021695...
        let tip = [0.6149716273419957, c[1]];
        let hit = idx.closest(tip);
        assert!(hit.dist < 1e-12, "tip {:e} from the curve", hit.dist);
        let beyond = idx.closest([tip[0] - 1e-6, c[1]]);
        assert!((beyond.dist - 1e-6).abs() < 1e-12, "{:e}", beyond.dist);
    }

    /// Case f11 of the stationary-point property test (`verify/regressions/near-stationary/zero-speed-knot.toml`): piece 2 is a cubic
    /// B-spline whose speed vanishes at its knot 0.99834504835 (a stationary point on a knot)
    /// and slows down towards it over the span before. `q` is that piece's point at
    /// t = 0.8914, so its distance to the curve is zero up to the round-off of one curve
    /// evaluation (a few ulps of coordinates of size ~1, i.e. ~1e-16). The tolerance is
    /// [`SLACK_REL`](crate::oracle::checks::SLACK_REL) = 1e-12 times `1 + |q|`, the round-off
    /// slack the checks grant witness points: four orders above that round-off and nine
    /// below the wrong answer the Newton iteration on `(C - q) . C'` gave (6.45e-3 at
    /// t = 0.93584, where `h'` nearly vanishes as the curve decelerates).
    #[test]
    fn closest_next_to_zero_speed_knot_is_on_the_curve() {
        let profile = revdist::profile_file::from_toml_str_allowing_self_contact(include_str!(
            "../../regressions/near-stationary/zero-speed-knot.toml"
        ))
        .expect("the f11 profile builds");
        let idx = crate::oracle::index(&profile);
        let q = [1.1755570567281444, 0.11530362878890313];
        let on_curve = idx.geom.point(2, 0.8914);
        assert!(dist(on_curve, q) < 1e-15, "q is piece 2 at t = 0.8914");
        let hit = idx.closest(q);
        let tol = crate::oracle::checks::SLACK_REL * (1.0 + norm(q));
        assert!(
            hit.dist < tol,
            "closest: dist {:e} (piece {}, t {}, p {:?}) above {tol:e}",
            hit.dist,
            hit.piece,
            hit.t,
            hit.p
        );
    }

    /// A corner at a knot inside a piece (a degree-1 polyline turning at (1, 0), from a slanted
    /// side to the top): a point just beyond the corner and 1e-15 below its height is outside,
    /// 1e-6 from the corner, which is its closest point. (A curved piece elsewhere gives the
    /// polyline a sagitta above that distance, so the side comes from the closest point.) The
    /// tangent of the span after the corner (pointing along the top edge) put it inside, since
    /// the corner counted as a joint only at a piece's ends (campaign 1803, case 17213: a
    /// random profile against the bottle, reported overlapping at 1.27e-6 apart).
    #[test]
    fn corner_inside_a_piece_gives_no_side_from_its_tangent() {
        let profile = revdist::profile_file::from_toml_str_allowing_self_contact(
            r#"
name = "quad-with-inner-corner"
[[piece]]
degree = 1
knots = [0.0, 0.0, 1.0, 1.0]
points = [[0.0, -1.0], [0.9, -1.0]]
[[piece]]
degree = 1
knots = [0.0, 0.0, 0.5, 1.0, 1.0]
points = [[0.9, -1.0], [1.0, 0.0], [0.5, 0.0]]
[[piece]]
degree = 2
knots = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0]
points = [[0.5, 0.0], [0.25, 0.4], [0.0, 0.0]]
"#,
        )
        .expect("the profile builds");
        let idx = crate::oracle::index(&profile);
        let beyond = idx.signed([1.0 + 1e-6, -1e-15]);
        assert!(
            (beyond.value - 1e-6).abs() < 1e-12,
            "signed {:e}, expected +1e-6 (outside)",
            beyond.value
        );
        let within = idx.signed([1.0 - 1e-6, -1e-6]);
        assert!(
            within.value < 0.0,
            "signed {:e}, expected inside",
            within.value
        );
    }

    #[test]
    fn open_chain_closed_by_axis() {
        // Half of a square [0, 1] x [0, 1] around the axis: bottom, side, top.
        let g = ProfileGeom::from_pieces(
            "cyl".into(),
            vec![
                line([0.0, 0.0], [1.0, 0.0]),
                line([1.0, 0.0], [1.0, 1.0]),
                line([1.0, 1.0], [0.0, 1.0]),
            ],
            ProfileKind::OpenOnAxis,
        );
        let idx = PlanarIndex::new(g);
        // On the axis, inside: distance to the curve, not to the axis.
        let s = idx.signed([0.0, 0.5]);
        assert!((s.value + 0.5).abs() < 1e-14, "{}", s.value);
        let s = idx.signed([0.1, 0.5]);
        assert!((s.value + 0.5).abs() < 1e-14);
        let s = idx.signed([0.0, 1.5]);
        assert!((s.value - 0.5).abs() < 1e-14);
        let s = idx.signed([0.9, 0.95]);
        assert!((s.value + 0.05).abs() < 1e-14);
        assert!(!idx.inside_poly([0.0, -0.1]));
    }
}
