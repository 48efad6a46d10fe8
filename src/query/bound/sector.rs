//! Sectors of a toroidal patch: a sub-piece of the profile revolved over an interval of
//! angles only, with the closed-form support function that bounds two sectors apart.
//!
//! **Support.** A sector's point is `x = (rho cos t, rho sin t, z)` with `(rho, z)` on the
//! sub-piece and `t` in `[t0, t1]`. For a direction `w`,
//! `w . x = rho (w_x cos t + w_y sin t) + w_z z`, and since `rho >= 0` the largest value over
//! the angles is `rho g` with `g` the largest of `w_x cos t + w_y sin t` on `[t0, t1]` (a
//! closed form: `|w_xy|` when the direction's own angle lies in the interval, else an end).
//! The support is then the largest value of the planar linear function `g rho + w_z z` on the
//! sub-piece: an end point, or for an arc the point whose radius points along `(g, w_z)`,
//! written as `L(end) + 2 r |(g, w_z)| sin^2(half the angle between them)` so that an arc of
//! huge radius (a nearly straight piece) loses nothing to cancellation. The support is exact,
//! so `min_B w.y - max_A w.x = -h_B(-w) - h_A(w)` is a valid lower bound of the distance of
//! two sectors for every unit `w`, exact for the convex hulls when `w` is the direction of
//! their closest points.
//!
//! **Why sectors.** The bounds of revolved pieces ([`super::node_pair`], [`mod@super::hull_bound`])
//! revolve every sub-piece a full turn, so their error shrinks at best with the square of
//! the profile length but never with the angle: a piece that wraps around the other solid (a
//! ring about a neck) keeps them useless however fine the profile is cut. A sector's hull
//! shrinks in both directions, and with `w` a surface normal at the sectors' centres its
//! bound's error shrinks with the square of the sectors' size near a contact.

use crate::bvh::patch::ProfileArc;
use crate::num::{cross2, norm2};
use crate::tolerances::BOUND_SLACK;
use nalgebra::{Isometry3, Point2, Point3, Vector2, Vector3};
use std::f64::consts::{PI, TAU};

/// Unit vector at angle `t`.
fn unit(t: f64) -> Vector2<f64> {
    let (s, c) = t.sin_cos();
    Vector2::new(c, s)
}

/// An interval of angles `[lo, lo + span]` (`0 <= span <= 2 pi`) with its end directions, to
/// test whether a direction's angle lies in it without an arc tangent.
#[derive(Debug, Clone, Copy)]
struct AngleRange {
    span: f64,
    first: Vector2<f64>,
    last: Vector2<f64>,
}

impl AngleRange {
    fn new(lo: f64, span: f64) -> Self {
        AngleRange {
            span,
            first: unit(lo),
            last: unit(lo + span),
        }
    }

    /// Whether the angle of the nonzero direction `d` lies in the range (closed). Up to a
    /// rounding of the cross products, whose misjudgement near an end changes a support by
    /// the square of an angle near 1e-16 (far inside [`BOUND_SLACK`]).
    fn holds(&self, d: Vector2<f64>) -> bool {
        if self.span >= TAU {
            true
        } else if self.span <= PI {
            cross2(self.first, d) >= 0.0 && cross2(d, self.last) >= 0.0
        } else {
            // The complement, an open range of less than a half turn.
            !(cross2(self.last, d) > 0.0 && cross2(d, self.first) > 0.0)
        }
    }
}

/// A profile sub-piece with what its support function needs (module doc).
#[derive(Debug, Clone, Copy)]
enum PieceShape {
    Segment,
    /// An arc: its radius and lowest-angle end point, and its range of polar angles.
    Arc {
        radius: f64,
        lo_point: Point2<f64>,
        range: AngleRange,
    },
}

/// A sector of a patch: the profile sub-piece `piece` revolved over `angles = (t0, t1)`,
/// `t0 <= t1 <= t0 + 2 pi`, in the patch's own frame, with its end points, angle directions,
/// middle point and normal computed once (every bound of a search reuses them).
#[derive(Debug, Clone, Copy)]
pub struct Sector {
    pub piece: ProfileArc,
    pub angles: (f64, f64),
    start: Point2<f64>,
    end: Point2<f64>,
    shape: PieceShape,
    turn: AngleRange,
    middle: Point3<f64>,
    middle_normal: Vector3<f64>,
    max_rho: f64,
}

impl Sector {
    /// The sector of `piece` over `angles`.
    pub fn new(piece: ProfileArc, angles: (f64, f64)) -> Self {
        let shape = match (piece, piece.ascending_angles()) {
            (ProfileArc::Arc { center, radius, .. }, Some((lo, span))) => PieceShape::Arc {
                radius,
                lo_point: center + radius * unit(lo),
                range: AngleRange::new(lo, span),
            },
            _ => PieceShape::Segment,
        };
        let t_mid = 0.5 * (angles.0 + angles.1);
        let (e_mid, m, tangent) = (unit(t_mid), piece.point_at(0.5), piece.tangent_at(0.5));
        let mut sector = Sector {
            piece,
            angles,
            start: piece.start(),
            end: piece.end(),
            shape,
            turn: AngleRange::new(angles.0, angles.1 - angles.0),
            middle: Point3::new(m.x * e_mid.x, m.x * e_mid.y, m.y),
            // The profile normal (tangent turned a quarter), lifted to the meridian plane.
            middle_normal: Vector3::new(tangent.y * e_mid.x, tangent.y * e_mid.y, -tangent.x),
            max_rho: 0.0,
        };
        sector.max_rho = sector.piece_support(Vector2::new(1.0, 0.0)).max(0.0);
        sector
    }

    /// The whole patch of `piece` split into `n` sectors of equal angle.
    pub fn full_turn(piece: ProfileArc, n: usize) -> impl Iterator<Item = Sector> {
        (0..n).map(move |i| {
            Sector::new(
                piece,
                (TAU * i as f64 / n as f64, TAU * (i + 1) as f64 / n as f64),
            )
        })
    }

    /// Largest value of the planar linear function `c . (rho, z)` on the sub-piece (module
    /// doc): an end, or the arc's point whose radius points along `c`, measured from the
    /// lowest-angle end as `r |c| |u - e_lo|^2 / 2` (`u`, `e_lo` the unit radii), which
    /// does not cancel.
    fn piece_support(&self, c: Vector2<f64>) -> f64 {
        let at = |p: Point2<f64>| c.dot(&p.coords);
        let ends = at(self.start).max(at(self.end));
        match self.shape {
            PieceShape::Arc {
                radius,
                lo_point,
                range,
            } => {
                let norm = c.norm();
                if norm > 0.0 && range.holds(c) {
                    let gap = (c / norm - range.first).norm_squared();
                    at(lo_point) + 0.5 * radius * norm * gap
                } else {
                    ends
                }
            }
            PieceShape::Segment => ends,
        }
    }

    /// Largest `w_x cos t + w_y sin t` over the sector's angles.
    fn angular_max(&self, w: &Vector3<f64>) -> f64 {
        let d = Vector2::new(w.x, w.y);
        let m = norm2(w.x, w.y);
        if m == 0.0 {
            0.0
        } else if self.turn.holds(d) {
            m
        } else {
            d.dot(&self.turn.first).max(d.dot(&self.turn.last))
        }
    }

    /// `max w . x` over the sector (its own frame; module doc). Profile points have
    /// `rho >= 0` up to rounding (a sphere's pole at `rho ~ 1e-17`), so the largest value
    /// over the angles is `rho` times the largest of the angular factor.
    pub fn support(&self, w: &Vector3<f64>) -> f64 {
        self.piece_support(Vector2::new(self.angular_max(w), w.z))
    }

    /// Largest `rho` of the sector.
    pub fn max_rho(&self) -> f64 {
        self.max_rho
    }

    /// The sector's middle point (middle parameter and middle angle).
    pub fn middle(&self) -> Point3<f64> {
        self.middle
    }

    /// The surface normal line's direction at [`Sector::middle`] (unsigned).
    pub fn middle_normal(&self) -> Vector3<f64> {
        self.middle_normal
    }

    /// A radius about [`Sector::middle`] that holds the whole sector: half the profile
    /// length (along the meridian) plus half the widest parallel's arc (along it).
    pub fn radius(&self) -> f64 {
        let (profile, parallel) = self.extents();
        0.5 * (profile + parallel)
    }

    /// The size of the sector's two extents: (profile length, widest parallel's arc).
    pub fn extents(&self) -> (f64, f64) {
        (
            self.piece.length(),
            self.max_rho * (self.angles.1 - self.angles.0),
        )
    }

    /// The sector split in two along its profile (`true`) or its angles (`false`).
    pub fn halves(&self, along_profile: bool) -> [Sector; 2] {
        if along_profile {
            [0.0, 0.5].map(|s| Sector::new(self.piece.sub_piece(s, s + 0.5), self.angles))
        } else {
            let (t0, t1) = self.angles;
            let m = 0.5 * (t0 + t1);
            [(t0, m), (m, t1)].map(|angles| Sector::new(self.piece, angles))
        }
    }

    /// The size used for the rounding slack: the largest coordinate magnitude.
    fn scale(&self) -> f64 {
        self.start.coords.norm().max(self.end.coords.norm()) + self.piece.length()
    }
}

/// Lower bound of the distance between sector `a` (frame A) and sector `b` (placed by
/// `pos_ab`) for the direction `w` (from A towards B, unit length up to rounding):
/// `min_B w.y - max_A w.x`, less [`BOUND_SLACK`] of the configuration's scale.
pub fn sector_bound(a: &Sector, b: &Sector, pos_ab: &Isometry3<f64>, w: &Vector3<f64>) -> f64 {
    let t = pos_ab.translation.vector;
    let w_b = pos_ab.rotation.inverse_transform_vector(w);
    let min_b = w.dot(&t) - b.support(&-w_b);
    let scale = 1.0 + t.norm() + a.scale() + b.scale();
    min_b - a.support(w) - BOUND_SLACK * scale
}

/// The best of [`sector_bound`] over a few directions: the line of the sectors' middles,
/// each sector's middle normal (turned towards the other middle), and `hint`.
pub fn sector_pair_bound(
    a: &Sector,
    b: &Sector,
    pos_ab: &Isometry3<f64>,
    hint: Option<&Vector3<f64>>,
) -> f64 {
    let (ma, mb) = (a.middle(), pos_ab * b.middle());
    let between = mb - ma;
    let mut best = f64::NEG_INFINITY;
    let mut try_dir = |v: Vector3<f64>| {
        let n = v.norm();
        if n > 0.0 && n.is_finite() {
            best = best.max(sector_bound(a, b, pos_ab, &(v / n)));
        }
    };
    try_dir(between);
    let toward = |n: Vector3<f64>| if n.dot(&between) < 0.0 { -n } else { n };
    try_dir(toward(a.middle_normal()));
    try_dir(toward(pos_ab.rotation * b.middle_normal()));
    if let Some(h) = hint {
        try_dir(*h);
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;
    use nalgebra::{Translation3, UnitQuaternion};

    fn random_piece(f: &mut dyn FnMut() -> f64, arc: bool) -> ProfileArc {
        if arc {
            let radius = if f() < 0.2 {
                1e3 * (1.0 + f())
            } else {
                0.05 + f()
            };
            // Keep the arc in the half-plane: a short sweep about a point at rho >= 0.1.
            let sweep = (2.0 * f() - 1.0) * (0.3 / radius).min(3.0);
            let phi = TAU * f();
            let p = Point2::new(0.1 + f(), f() - 0.5);
            let center = p - radius * Vector2::new(phi.cos(), phi.sin());
            let arc = ProfileArc::Arc {
                center,
                radius,
                phi_start: phi,
                sweep,
            };
            if (0..=8).all(|i| arc.point_at(i as f64 / 8.0).x >= 0.0) {
                arc
            } else {
                ProfileArc::Segment {
                    start: p,
                    end: Point2::new(0.1 + f(), f()),
                }
            }
        } else {
            ProfileArc::Segment {
                start: Point2::new(f(), f() - 0.5),
                end: Point2::new(f(), f() - 0.5),
            }
        }
    }

    fn random_sector(f: &mut dyn FnMut() -> f64) -> Sector {
        let is_arc = f() < 0.7;
        let piece = random_piece(f, is_arc);
        let t0 = TAU * f();
        let span = if f() < 0.3 { TAU } else { TAU * f() * f() };
        Sector::new(piece, (t0, t0 + span))
    }

    fn sample(s: &Sector, u: f64, v: f64) -> Point3<f64> {
        let m = s.piece.point_at(u);
        let t = s.angles.0 + v * (s.angles.1 - s.angles.0);
        Point3::new(m.x * t.cos(), m.x * t.sin(), m.y)
    }

    /// The support is attained (a dense sampling comes within its resolution of it) and
    /// never exceeded by a sampled point.
    #[test]
    fn support_is_exact() {
        let mut s = Lcg(5);
        let mut f = move || s.f();
        for case in 0..300 {
            let sec = random_sector(&mut f);
            let w = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5).normalize();
            let h = sec.support(&w);
            let n = 200;
            let mut best = f64::NEG_INFINITY;
            for i in 0..=n {
                for k in 0..=n {
                    let x = sample(&sec, i as f64 / n as f64, k as f64 / n as f64);
                    best = best.max(w.dot(&x.coords));
                }
            }
            assert!(best <= h + 1e-12, "case {case}: sampled {best} above {h}");
            // Resolution: the samples are at most (length + rho arc) / 200 apart.
            let (l, t) = sec.extents();
            assert!(
                h - best <= (l + t) / n as f64 + 1e-12,
                "case {case}: support {h} far above samples {best}"
            );
            // The radius holds every sample.
            let m = sec.middle();
            let r = sec.radius();
            for i in 0..=20 {
                for k in 0..=20 {
                    let x = sample(&sec, i as f64 / 20.0, k as f64 / 20.0);
                    assert!((x - m).norm() <= r * (1.0 + 1e-12) + 1e-15, "case {case}");
                }
            }
        }
    }

    /// The pair bound never exceeds the distance between sampled points of the sectors.
    #[test]
    fn pair_bound_is_valid() {
        let mut s = Lcg(9);
        let mut f = move || s.f();
        for case in 0..200 {
            let (a, b) = (random_sector(&mut f), random_sector(&mut f));
            let rot = UnitQuaternion::from_scaled_axis(Vector3::new(f(), f(), f()) * 3.0);
            let t = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 3.0;
            let pos = Isometry3::from_parts(Translation3::from(t), rot);
            let hint = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5);
            let bound = sector_pair_bound(&a, &b, &pos, Some(&hint));
            let n = 16;
            let mut closest = f64::INFINITY;
            for i in 0..=n {
                for k in 0..=n {
                    let x = sample(&a, i as f64 / n as f64, k as f64 / n as f64);
                    for j in 0..=n {
                        for l in 0..=n {
                            let y = pos * sample(&b, j as f64 / n as f64, l as f64 / n as f64);
                            closest = closest.min((y - x).norm());
                        }
                    }
                }
            }
            assert!(
                bound <= closest,
                "case {case}: bound {bound} above {closest}"
            );
        }
    }
}
