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
//! **Why sectors.** The bounds of revolved pieces ([`super::node_pair`], [`super::hull_bound`])
//! revolve every sub-piece a full turn, so their error shrinks at best with the square of
//! the profile length but never with the angle: a piece that wraps around the other solid (a
//! ring about a neck) keeps them useless however fine the profile is cut. A sector's hull
//! shrinks in both directions, and with `w` a surface normal at the sectors' centres its
//! bound's error shrinks with the square of the sectors' size near a contact.

use crate::bvh::patch::ProfileArc;
use crate::num::norm2;
use crate::tolerances::BOUND_SLACK;
use nalgebra::{Isometry3, Point2, Point3, Vector2, Vector3};
use std::f64::consts::TAU;

/// A sector of a patch: the profile sub-piece `piece` revolved over `angles = (t0, t1)`,
/// `t0 <= t1 <= t0 + 2 pi`, in the patch's own frame.
#[derive(Debug, Clone, Copy)]
pub struct Sector {
    pub piece: ProfileArc,
    pub angles: (f64, f64),
}

/// Whether the angle `phi` lies in `[lo, lo + span]` modulo a full turn.
fn angle_in(phi: f64, lo: f64, span: f64) -> bool {
    (phi - lo).rem_euclid(TAU) <= span
}

/// Largest value of the planar linear function `c . (rho, z)` on `piece` (module doc).
fn piece_support(piece: &ProfileArc, c: Vector2<f64>) -> f64 {
    let at = |p: Point2<f64>| c.dot(&p.coords);
    let ends = at(piece.start()).max(at(piece.end()));
    match (*piece, piece.ascending_angles()) {
        (ProfileArc::Arc { radius, center, .. }, Some((lo, span))) => {
            let psi = c.y.atan2(c.x);
            if angle_in(psi, lo, span) {
                let lo_point = center + radius * Vector2::new(lo.cos(), lo.sin());
                let half = 0.5 * (psi - lo);
                at(lo_point) + 2.0 * radius * c.norm() * half.sin() * half.sin()
            } else {
                ends
            }
        }
        _ => ends,
    }
}

impl Sector {
    /// The whole patch of `piece` split into `n` sectors of equal angle.
    pub fn full_turn(piece: ProfileArc, n: usize) -> impl Iterator<Item = Sector> {
        (0..n).map(move |i| Sector {
            piece,
            angles: (TAU * i as f64 / n as f64, TAU * (i + 1) as f64 / n as f64),
        })
    }

    /// Largest and smallest of `w_x cos t + w_y sin t` over the sector's angles.
    fn angular_range(&self, w: &Vector3<f64>) -> (f64, f64) {
        let (t0, t1) = self.angles;
        let m = norm2(w.x, w.y);
        if m == 0.0 {
            return (0.0, 0.0);
        }
        let psi = w.y.atan2(w.x);
        let f = |t: f64| w.x * t.cos() + w.y * t.sin();
        let (f0, f1) = (f(t0), f(t1));
        let span = t1 - t0;
        let hi = if angle_in(psi, t0, span) {
            m
        } else {
            f0.max(f1)
        };
        let lo = if angle_in(psi + std::f64::consts::PI, t0, span) {
            -m
        } else {
            f0.min(f1)
        };
        (hi, lo)
    }

    /// `max w . x` over the sector (its own frame; module doc). Profile points have
    /// `rho >= 0` up to rounding (a sphere's pole at `rho ~ 1e-17`), so the largest value
    /// over the angles is `rho` times the largest of the angular factor.
    pub fn support(&self, w: &Vector3<f64>) -> f64 {
        let (hi, _) = self.angular_range(w);
        piece_support(&self.piece, Vector2::new(hi, w.z))
    }

    /// Largest `rho` of the sector.
    pub fn max_rho(&self) -> f64 {
        piece_support(&self.piece, Vector2::new(1.0, 0.0)).max(0.0)
    }

    /// The sector's middle point (middle parameter and middle angle).
    pub fn middle(&self) -> Point3<f64> {
        let m = self.piece.point_at(0.5);
        let t = 0.5 * (self.angles.0 + self.angles.1);
        Point3::new(m.x * t.cos(), m.x * t.sin(), m.y)
    }

    /// The surface normal line's direction at [`Sector::middle`] (unsigned).
    pub fn middle_normal(&self) -> Vector3<f64> {
        let tangent = self.piece.tangent_at(0.5);
        let t = 0.5 * (self.angles.0 + self.angles.1);
        // The profile normal (tangent turned a quarter), lifted to the meridian plane.
        Vector3::new(tangent.y * t.cos(), tangent.y * t.sin(), -tangent.x)
    }

    /// A radius about [`Sector::middle`] that holds the whole sector: half the profile
    /// length (along the meridian) plus half the widest parallel's arc (along it).
    pub fn radius(&self) -> f64 {
        0.5 * (self.piece.length() + self.max_rho() * (self.angles.1 - self.angles.0))
    }

    /// The size of the sector's two extents: (profile length, widest parallel's arc).
    pub fn extents(&self) -> (f64, f64) {
        (
            self.piece.length(),
            self.max_rho() * (self.angles.1 - self.angles.0),
        )
    }

    /// The sector split in two along its profile (`true`) or its angles (`false`).
    pub fn halves(&self, along_profile: bool) -> [Sector; 2] {
        if along_profile {
            [0.0, 0.5].map(|s| Sector {
                piece: self.piece.sub_piece(s, s + 0.5),
                angles: self.angles,
            })
        } else {
            let (t0, t1) = self.angles;
            let m = 0.5 * (t0 + t1);
            [(t0, m), (m, t1)].map(|angles| Sector {
                piece: self.piece,
                angles,
            })
        }
    }

    /// The size used for the rounding slack: the largest coordinate magnitude.
    fn scale(&self) -> f64 {
        let d = self.piece.bounding_disk();
        d.center.coords.norm() + d.radius
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
        Sector {
            piece,
            angles: (t0, t0 + span),
        }
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
