//! Splitting the profile's spans into spirals (merged across smooth knots) and growing each
//! spiral's binary tree of biarcs, or of chords where rounding cannot establish the spiral
//! property (the module doc of [`super`] says which bound each kind gets).

use super::piece_curve::PieceCurve;
use super::*;
use crate::biarc::fit::{fit_biarc, g1_tolerance, CurveSample, PlanarCurve};
use crate::biarc::spiral::split_span;
use crate::biarc::BiarcError;
use crate::num::cross2;
use crate::nurbs::Aabb2;
use nalgebra::{Point2, Vector2};

impl BiarcTree {
    pub(super) fn segment(&mut self) {
        for si in 0..self.spans.len() {
            let r = self.spans[si];
            let curve = self.span_curve(si);
            // A span whose control points all coincide is a point: skip it.
            let p0 = curve.homogeneous[0];
            let first = Point2::new(p0[0] / p0[2], p0[1] / p0[2]);
            if curve
                .homogeneous
                .iter()
                .all(|p| Point2::new(p[0] / p[2], p[1] / p[2]) == first)
            {
                continue;
            }
            let split = split_span(curve.homogeneous);
            let bound = if split.straight_within_noise {
                SpiralBound::ControlPolygon
            } else if split.spiral_within_noise {
                SpiralBound::ArcDeviation
            } else {
                SpiralBound::Bilens
            };
            let mut u0 = 0.0;
            for u1 in split.splits.iter().map(|s| s.0).chain(std::iter::once(1.0)) {
                let t = |u: f64| r.t0 + (r.t1 - r.t0) * u;
                let info = SpiralInfo {
                    piece: r.piece as usize,
                    param_range: (t(u0), t(u1)),
                    root: 0,
                    aabb: Aabb2 {
                        min: first,
                        max: first,
                    },
                    spans: (si as u32, si as u32),
                    bound,
                };
                let merged = u0 == 0.0
                    && self.spirals.last().is_some_and(|prev| {
                        prev.spans.1 as usize + 1 == si
                            && prev.piece == info.piece
                            && prev.param_range.1 == r.t0
                            && self.joins_as_spiral(prev, &info)
                    });
                if merged {
                    let prev = self.spirals.last_mut().expect("checked above");
                    prev.param_range.1 = info.param_range.1;
                    prev.spans.1 = si as u32;
                    // The merge compared curvatures evaluated at the knot within a tolerance,
                    // so the joined piece is curvature-monotone only to that tolerance: no
                    // bilens (the arc deviation needs no spiral property).
                    prev.bound = prev.bound.max(bound).max(SpiralBound::ArcDeviation);
                } else {
                    self.spirals.push(info);
                }
                u0 = u1;
            }
        }
    }

    /// Whether spiral `b` (starting at a knot) continues spiral `a` (ending there) as one
    /// spiral: G1 at the knot, the same signs of rho', z' and kappa, and kappa monotone in the
    /// same direction on both sides and across the knot (a C1 knot may jump in kappa).
    pub(super) fn joins_as_spiral(&self, a: &SpiralInfo, b: &SpiralInfo) -> bool {
        let ca = self.piece_curve(a);
        let cb = self.piece_curve(b);
        let knot = a.param_range.1;
        let (_, da) = ca.point_and_derivative(knot);
        let (_, db) = cb.point_and_derivative(knot);
        let (na, nb) = (da.norm(), db.norm());
        if !(na > 0.0 && nb > 0.0)
            || cross2(da, db).abs() > MERGE_TANGENT_TOL * na * nb
            || da.dot(&db) <= 0.0
        {
            return false;
        }
        let mid = |s: &SpiralInfo, c: &PieceCurve| {
            c.point_and_derivative(0.5 * (s.param_range.0 + s.param_range.1))
                .1
        };
        let (ma, mb) = (mid(a, &ca), mid(b, &cb));
        let sign = |x: f64, scale: f64| {
            if x.abs() <= MERGE_ZERO_REL * scale {
                0
            } else if x > 0.0 {
                1
            } else {
                -1
            }
        };
        let scale = ma.norm().max(mb.norm());
        if sign(ma.x, scale) != sign(mb.x, scale) || sign(ma.y, scale) != sign(mb.y, scale) {
            return false;
        }
        let ka = [ca.curvature(a.param_range.0), ca.curvature(knot)];
        let kb = [cb.curvature(knot), cb.curvature(b.param_range.1)];
        let k_mid = [
            ca.curvature(0.5 * (a.param_range.0 + knot)),
            cb.curvature(0.5 * (knot + b.param_range.1)),
        ];
        let k_scale = ka.iter().chain(&kb).fold(0.0f64, |m, k| m.max(k.abs()));
        let k_sign = sign(k_mid[0], k_scale);
        if k_sign == 0 || k_sign != sign(k_mid[1], k_scale) {
            return false;
        }
        let dirs = [
            sign(ka[1] - ka[0], k_scale),
            sign(kb[0] - ka[1], k_scale),
            sign(kb[1] - kb[0], k_scale),
        ];
        !(dirs.contains(&1) && dirs.contains(&-1))
    }

    /// The biarc of the curve piece between samples `a` and `b` with its certified bound, for
    /// the spiral kinds that fit biarcs: the bilens bound plus the flat arcs' chord distance
    /// and `stationary_slack` ([`SpiralBound::Bilens`]), or each arc's certified deviation
    /// from its part of the piece ([`SpiralBound::ArcDeviation`], no spiral property).
    fn fitted(
        &self,
        curve: &PieceCurve<'_>,
        (a, b): (&CurveSample, &CurveSample),
        kind: SpiralBound,
        piece: usize,
        stationary_slack: f64,
    ) -> Result<([Arc; 2], f64), TreeError> {
        let fit = fit_biarc(curve, a, b).map_err(|source| TreeError::Fit { piece, source })?;
        // On a short spiral the J-circle crosses the curve and the joint is G1 to rounding; a
        // larger defect means no crossing was found, so rounding made the piece something
        // else and its bilens bound is not certain. The arc deviation bound needs no spiral:
        // there the joint is G1 only to the piece's departure from one
        // (ARC_DEVIATION_G1_TOL).
        let g1 = g1_tolerance(&fit, self.coordinate_scale);
        let allowed = match kind {
            SpiralBound::Bilens => g1,
            _ => g1.max(ARC_DEVIATION_G1_TOL),
        };
        let not_a_spiral = |t0: f64, t1: f64| TreeError::Fit {
            piece,
            source: BiarcError::NotASpiral { t0, t1 },
        };
        if fit.joint_defect() > allowed {
            return Err(not_a_spiral(a.t, b.t));
        }
        if kind != SpiralBound::ArcDeviation {
            // Bound of the curve piece against the biarc as the query revolves it (flat arcs
            // as chords): bilens bound plus the largest chord/arc distance.
            let flat = fit.arcs[0]
                .flattening_error(self.flat_radius)
                .max(fit.arcs[1].flattening_error(self.flat_radius));
            return Ok((fit.arcs, fit.eps + flat + stationary_slack));
        }
        let mut bound = 0.0f64;
        for (arc, (t0, t1)) in fit
            .arcs
            .iter()
            .zip([(a.t, fit.t_joint), (fit.t_joint, b.t)])
        {
            let d = curve
                .arc_deviation(t0, t1, arc, self.flat_radius)
                .ok_or_else(|| not_a_spiral(t0, t1))?;
            bound = bound.max(d);
        }
        Ok((fit.arcs, bound))
    }

    /// Joins consecutive spirals of a piece where one biarc fits their union within the
    /// tree's `eps` under the arc deviation bound, which needs no spiral property: a single
    /// leaf then covers what was one leaf per spiral.
    ///
    /// Why: a B-spline's curvature has an extremum in most knot spans, and each extremum
    /// starts a spiral, so a freeform profile's tree had at least one leaf per spiral however
    /// coarse `eps` was (`pawn_ff`: 69 spirals, 71 leaves at eps 1e-3 against `pawn`'s 17),
    /// and its queries popped four times the node pairs. Spirals whose ends meet at the same
    /// parameter of one piece are candidates (a crease or a skipped point span ends a run);
    /// the joined spiral's tree is then grown with [`SpiralBound::ArcDeviation`], which
    /// refits the same biarc as a leaf. Chord spirals ([`SpiralBound::ControlPolygon`]) and
    /// ends at stationary points (where the end sample drops a first-order term) stay apart.
    pub(super) fn merge_spirals(&mut self) {
        let spirals = std::mem::take(&mut self.spirals);
        let mut merged: Vec<SpiralInfo> = Vec::with_capacity(spirals.len());
        for s in spirals {
            if let Some(joined) = merged.last().and_then(|prev| self.joined(prev, &s)) {
                *merged.last_mut().expect("checked above") = joined;
            } else {
                merged.push(s);
            }
        }
        self.spirals = merged;
    }

    /// `a` and `b` as one spiral bounded by the arc deviation, when its one biarc is within
    /// `eps` of it ([`Self::merge_spirals`]).
    fn joined(&self, a: &SpiralInfo, b: &SpiralInfo) -> Option<SpiralInfo> {
        let chords = SpiralBound::ControlPolygon;
        if a.piece != b.piece
            || a.param_range.1 != b.param_range.0
            || a.bound == chords
            || b.bound == chords
        {
            return None;
        }
        let union = SpiralInfo {
            param_range: (a.param_range.0, b.param_range.1),
            spans: (a.spans.0, b.spans.1),
            bound: SpiralBound::ArcDeviation,
            ..*a
        };
        let curve = self.piece_curve(&union);
        let (t0, t1) = union.param_range;
        let (start, slack_start) = curve.end_sample(t0, true, t1 - t0);
        let (end, slack_end) = curve.end_sample(t1, false, t1 - t0);
        if slack_start != 0.0 || slack_end != 0.0 {
            return None;
        }
        let kind = SpiralBound::ArcDeviation;
        let (_, bound) = self
            .fitted(&curve, (&start, &end), kind, a.piece, 0.0)
            .ok()?;
        (bound <= self.eps).then_some(union)
    }

    pub(super) fn piece_curve(&self, s: &SpiralInfo) -> PieceCurve<'_> {
        PieceCurve {
            spans: &self.spans[s.spans.0 as usize..=s.spans.1 as usize],
            coeffs: &self.coeffs,
        }
    }

    /// Builds the node tree of spiral `s`: with biarcs and the bilens bound or the arc
    /// deviation bound, or, when the spiral is marked [`SpiralBound::ControlPolygon`] or the
    /// biarc build fails on it (no biarc fits, a zero tangent, a joint that is not G1, or the
    /// bound stalls: rounding made a piece that is not a short spiral), with chords and the
    /// control-polygon bound.
    pub(super) fn build_spiral(&mut self, s: usize) -> Result<(), TreeError> {
        let (root, max_depth) = (self.nodes.len(), self.max_depth);
        let kind = self.spirals[s].bound;
        if kind != SpiralBound::ControlPolygon {
            if self.grow_spiral(s, kind).is_ok() {
                return Ok(());
            }
            self.nodes.truncate(root);
            self.max_depth = max_depth;
            self.spirals[s].bound = SpiralBound::ControlPolygon;
        }
        self.grow_spiral(s, SpiralBound::ControlPolygon)
    }

    pub(super) fn grow_spiral(&mut self, s: usize, kind: SpiralBound) -> Result<(), TreeError> {
        let info = self.spirals[s];
        let piece = info.piece;
        let root = self.nodes.len() as u32;
        self.spirals[s].root = root;
        self.nodes.push(placeholder());
        let (a, b, stationary_slack) = {
            let c = self.piece_curve(&info);
            let (t0, t1) = info.param_range;
            let (a, slack_a) = c.end_sample(t0, true, t1 - t0);
            let (b, slack_b) = c.end_sample(t1, false, t1 - t0);
            (a, b, slack_a + slack_b)
        };
        self.stack.clear();
        self.stack.push(Job {
            node: root,
            a,
            b,
            depth: 0,
        });
        let (s0, s1) = (info.spans.0 as usize, info.spans.1 as usize);
        while let Some(job) = self.stack.pop() {
            let curve = PieceCurve {
                spans: &self.spans[s0..=s1],
                coeffs: &self.coeffs,
            };
            let (arcs, bound) = match kind {
                SpiralBound::Bilens | SpiralBound::ArcDeviation => {
                    self.fitted(&curve, (&job.a, &job.b), kind, piece, stationary_slack)?
                }
                SpiralBound::ControlPolygon => {
                    let (a, b) = (job.a.point, job.b.point);
                    let deviation = curve.hull_deviation(job.a.t, job.b.t, a, b);
                    chord_arcs(a, b, deviation)
                }
            };
            let leaf = bound <= self.eps;
            if !leaf && job.depth >= MAX_DEPTH {
                return Err(TreeError::BoundNotReached {
                    piece,
                    reached: bound,
                });
            }
            let mut node = make_node(arcs, bound, s as u32, job.depth);
            node.t0 = job.a.t;
            node.t1 = job.b.t;
            self.max_depth = self.max_depth.max(job.depth);
            if !leaf {
                let first = self.nodes.len() as u32;
                node.first_child = first;
                self.nodes.push(placeholder());
                self.nodes.push(placeholder());
                let mid = CurveSample::off_stationary(&curve, 0.5 * (job.a.t + job.b.t), job.b.t);
                self.stack.push(Job {
                    node: first + 1,
                    a: mid,
                    b: job.b,
                    depth: job.depth + 1,
                });
                self.stack.push(Job {
                    node: first,
                    a: job.a,
                    b: mid,
                    depth: job.depth + 1,
                });
            }
            self.nodes[job.node as usize] = node;
        }
        let r = self.nodes[root as usize];
        let mut aabb = arc_aabb(&r.arcs[0]).union(arc_aabb(&r.arcs[1]));
        aabb.min -= Vector2::new(r.eps, r.eps);
        aabb.max += Vector2::new(r.eps, r.eps);
        self.spirals[s].aabb = aabb;
        Ok(())
    }
}
