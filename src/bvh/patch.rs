//! Toroidal patches: a profile arc of the (rho, z) half-plane revolved about the z axis
//! (paper section 3.1). Straight pieces give cones, cylinders and flat annuli or disks.
//!
//! Parametrisation (paper 3.1, with a signed major radius): an arc with centre
//! `(c_rho, c_z)` and radius `r` gives the surface
//! `((c_rho + r cos phi) cos theta, (c_rho + r cos phi) sin theta, c_z + r sin phi)`.
//! `c_rho` may be negative or zero (spindle tori, spheres centred on the axis): the formula
//! stays valid because every profile point has `rho >= 0`. The major circle is the circle of
//! radius `c_rho` (signed) at height `c_z`; every surface normal line meets it at a right angle.

use crate::biarc::Disk;
use crate::nearest::NearestPoint;
use crate::tolerances::{ANGLE_SLACK, AXIS_SNAP, FLAT_SNAP, SEGMENT_SLACK};
use nalgebra::{Point2, Point3, Vector2, Vector3};
use std::f64::consts::TAU;

/// A piece of a profile curve in the (rho, z) half-plane: a circular arc or a segment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum ProfileArc {
    /// Arc `center + radius (cos phi, sin phi)` for phi from `phi_start` to
    /// `phi_start + sweep` (`sweep` signed: positive is counter-clockwise, `|sweep| <= 2 pi`).
    Arc {
        center: Point2<f64>,
        radius: f64,
        phi_start: f64,
        sweep: f64,
    },
    /// Straight piece from `start` to `end` (an arc of zero curvature).
    Segment {
        start: Point2<f64>,
        end: Point2<f64>,
    },
}

impl ProfileArc {
    /// Arc through `start` and `end` whose centre is `center` (counter-clockwise when `ccw`).
    pub fn arc_from_center(
        center: Point2<f64>,
        start: Point2<f64>,
        end: Point2<f64>,
        ccw: bool,
    ) -> Self {
        let radius = (start - center).norm();
        let a0 = (start.y - center.y).atan2(start.x - center.x);
        let a1 = (end.y - center.y).atan2(end.x - center.x);
        let mut sweep = (a1 - a0).rem_euclid(TAU);
        if !ccw {
            sweep -= TAU;
        }
        if sweep == 0.0 || sweep == -TAU {
            sweep = if ccw { TAU } else { -TAU };
        }
        ProfileArc::Arc {
            center,
            radius,
            phi_start: a0,
            sweep,
        }
    }

    /// First point of the piece.
    pub fn start(&self) -> Point2<f64> {
        match *self {
            ProfileArc::Segment { start, .. } => start,
            ProfileArc::Arc { .. } => self.point_at(0.0),
        }
    }

    /// Last point of the piece.
    pub fn end(&self) -> Point2<f64> {
        match *self {
            ProfileArc::Segment { end, .. } => end,
            ProfileArc::Arc { .. } => self.point_at(1.0),
        }
    }

    /// An arc's polar angles about its centre as `(lowest, unsigned sweep)`, whichever way
    /// it runs; `None` for a segment.
    pub fn ascending_angles(&self) -> Option<(f64, f64)> {
        match *self {
            ProfileArc::Arc {
                phi_start, sweep, ..
            } if sweep >= 0.0 => Some((phi_start, sweep)),
            ProfileArc::Arc {
                phi_start, sweep, ..
            } => Some((phi_start + sweep, -sweep)),
            ProfileArc::Segment { .. } => None,
        }
    }

    /// Point at normalised parameter `s` in [0, 1].
    pub fn point_at(&self, s: f64) -> Point2<f64> {
        match *self {
            ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            } => {
                let phi = phi_start + s * sweep;
                center + radius * Vector2::new(phi.cos(), phi.sin())
            }
            ProfileArc::Segment { start, end } => start + s * (end - start),
        }
    }

    /// Unit tangent at normalised parameter `s` in the direction of travel.
    pub fn tangent_at(&self, s: f64) -> Vector2<f64> {
        match *self {
            ProfileArc::Arc {
                phi_start, sweep, ..
            } => {
                let phi = phi_start + s * sweep;
                sweep.signum() * Vector2::new(-phi.sin(), phi.cos())
            }
            ProfileArc::Segment { start, end } => (end - start).normalize(),
        }
    }

    /// Bound on how far the stored piece's points, evaluated in floating point, are from the
    /// piece it was made from: for an arc, `centre + r (cos phi, sin phi)` with `phi` from
    /// `atan2` of `start - centre` moves a point by at most about
    /// `4 eps_mach (|centre| + r + |start|) <= 8 eps_mach (|centre| + r)`; doubled for the
    /// kernels' own use of the centre form. Segments store their end points exactly (0).
    pub fn representation_error(&self) -> f64 {
        match *self {
            ProfileArc::Arc { center, radius, .. } => {
                16.0 * f64::EPSILON * (center.coords.norm() + radius)
            }
            ProfileArc::Segment { .. } => 0.0,
        }
    }

    /// Length of the piece.
    pub fn length(&self) -> f64 {
        match *self {
            ProfileArc::Arc { radius, sweep, .. } => radius * sweep.abs(),
            ProfileArc::Segment { start, end } => (end - start).norm(),
        }
    }

    /// A disk containing the piece: the chord's Thales disk for arcs of sweep at most
    /// pi (every point of such an arc sees the chord under an angle of at least pi/2), else
    /// the arc's full circle; the segment's Thales disk for segments.
    pub fn bounding_disk(&self) -> Disk {
        match *self {
            ProfileArc::Arc {
                center,
                radius,
                sweep,
                ..
            } if sweep.abs() > std::f64::consts::PI => Disk { center, radius },
            _ => {
                let (a, b) = (self.start(), self.end());
                Disk {
                    center: nalgebra::center(&a, &b),
                    radius: 0.5 * (b - a).norm() * (1.0 + 4.0 * f64::EPSILON),
                }
            }
        }
    }

    /// Whether the arc angle `phi` lies in the arc's range (inclusive, [`ANGLE_SLACK`]).
    /// Returns the normalised parameter in [0, 1] (clamped) when it does.
    pub fn arc_param(&self, phi: f64) -> Option<f64> {
        let ProfileArc::Arc {
            phi_start,
            sweep,
            radius,
            ..
        } = *self
        else {
            return None;
        };
        let slack = ANGLE_SLACK.max(1e-12 / radius.max(1e-300));
        let d = if sweep >= 0.0 {
            (phi - phi_start).rem_euclid(TAU)
        } else {
            (phi_start - phi).rem_euclid(TAU)
        };
        let span = sweep.abs();
        if d <= span + slack {
            Some((d / span).min(1.0))
        } else if d >= TAU - slack {
            Some(0.0)
        } else {
            None
        }
    }

    /// The sub-piece between normalised parameters `s0` and `s1`.
    pub fn sub_piece(&self, s0: f64, s1: f64) -> Self {
        match *self {
            ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            } => ProfileArc::Arc {
                center,
                radius,
                phi_start: phi_start + s0 * sweep,
                sweep: (s1 - s0) * sweep,
            },
            ProfileArc::Segment { .. } => ProfileArc::Segment {
                start: self.point_at(s0),
                end: self.point_at(s1),
            },
        }
    }

    /// The same piece traversed backwards.
    pub fn reversed(&self) -> Self {
        match *self {
            ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            } => ProfileArc::Arc {
                center,
                radius,
                phi_start: phi_start + sweep,
                sweep: -sweep,
            },
            ProfileArc::Segment { start, end } => ProfileArc::Segment {
                start: end,
                end: start,
            },
        }
    }

    /// Image under the planar map `(rho, z) -> (rho, sign z + offset)` (`sign = +-1`), used
    /// for coaxial solids.
    pub fn mapped_z(&self, sign: f64, offset: f64) -> Self {
        let m = |p: Point2<f64>| Point2::new(p.x, sign * p.y + offset);
        match *self {
            ProfileArc::Arc {
                center,
                radius,
                phi_start,
                sweep,
            } => ProfileArc::Arc {
                center: m(center),
                radius,
                phi_start: if sign > 0.0 { phi_start } else { -phi_start },
                sweep: sign * sweep,
            },
            ProfileArc::Segment { start, end } => ProfileArc::Segment {
                start: m(start),
                end: m(end),
            },
        }
    }
}

fn snapped(arc: ProfileArc) -> ProfileArc {
    match arc {
        ProfileArc::Arc {
            center,
            radius,
            phi_start,
            sweep,
        } if center.x != 0.0 && center.x.abs() <= AXIS_SNAP * radius => ProfileArc::Arc {
            center: Point2::new(0.0, center.y),
            radius,
            phi_start,
            sweep,
        },
        ProfileArc::Segment { start, end } => {
            let (rise, run, length) = (end.y - start.y, end.x - start.x, (end - start).norm());
            let slight = |d: f64| d != 0.0 && d.abs() <= FLAT_SNAP * length;
            if slight(rise) {
                let z = 0.5 * (start.y + end.y);
                ProfileArc::Segment {
                    start: Point2::new(start.x, z),
                    end: Point2::new(end.x, z),
                }
            } else if slight(run) {
                let rho = 0.5 * (start.x + end.x);
                ProfileArc::Segment {
                    start: Point2::new(rho, start.y),
                    end: Point2::new(rho, end.y),
                }
            } else {
                arc
            }
        }
        a => a,
    }
}

/// Meridian frame of the local z axis at revolution angle `theta`: `e_rho(theta)`.
pub(crate) fn e_rho(theta: f64) -> Vector3<f64> {
    Vector3::new(theta.cos(), theta.sin(), 0.0)
}

/// Point of the surface of revolution with meridian coordinates `(rho, z)` (rho signed)
/// in the meridian plane with radial direction `e` (unit, horizontal).
pub(crate) fn lift(q: Point2<f64>, e: &Vector3<f64>) -> Point3<f64> {
    Point3::new(q.x * e.x, q.x * e.y, q.y)
}

/// A profile piece revolved about the local z axis (a full revolution).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    pub arc: ProfileArc,
}

/// Where the normal lines of a patch pass: the arc's centre (a circle after revolution) or
/// the segment's line (a cone after revolution). Paper 3.2: every normal line of a toroidal
/// patch meets its major circle at a right angle.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Core {
    /// Major circle: signed radius `r_major`, height `z`, profile radius `r_minor`.
    Circle { r_major: f64, z: f64, r_minor: f64 },
    /// Meridian line `n . (rho, z) = c`, unit `n`.
    Line { n: Vector2<f64>, c: f64 },
}

impl Patch {
    /// A patch of `arc`, with an arc centre closer to the axis than [`AXIS_SNAP`] times the
    /// radius moved onto the axis (a sphere patch), and a segment within [`FLAT_SNAP`] of
    /// flat or cylindrical made exactly so. The surface moves by at most
    /// [`Patch::snap_error`]; callers that certify bounds add it to their eps.
    pub fn new(arc: ProfileArc) -> Self {
        Patch { arc: snapped(arc) }
    }

    /// How far [`Patch::new`] moved the surface of `arc` (0 unless snapped): the centre's
    /// move for an arc (every point moves with it), the larger end's move for a segment (its
    /// points move by the interpolated amount).
    pub fn snap_error(arc: &ProfileArc) -> f64 {
        match (*arc, snapped(*arc)) {
            (ProfileArc::Arc { center: a, .. }, ProfileArc::Arc { center: b, .. }) => {
                (a - b).norm()
            }
            (ProfileArc::Segment { start, end }, ProfileArc::Segment { start: s2, end: e2 }) => {
                (start - s2).norm().max((end - e2).norm())
            }
            _ => 0.0,
        }
    }

    /// The core (major circle or cone line) of the patch.
    pub fn core(&self) -> Core {
        match self.arc {
            ProfileArc::Arc { center, radius, .. } => Core::Circle {
                r_major: center.x,
                z: center.y,
                r_minor: radius,
            },
            ProfileArc::Segment { start, end } => {
                let d = (end - start).normalize();
                let n = Vector2::new(-d.y, d.x);
                Core::Line {
                    n,
                    c: n.dot(&start.coords),
                }
            }
        }
    }

    /// Boundary parallels (rho, z) of the patch: the revolved end points of the arc. A point
    /// with `rho = 0` is a single point on the axis.
    pub fn boundary(&self) -> [Point2<f64>; 2] {
        [self.arc.start(), self.arc.end()]
    }

    /// Exact distance from a point (patch frame) to the patch, with the closest point.
    /// The surface is the set of circles through the profile points, so the distance is the
    /// planar distance from `(rho, z)` of the point to the profile piece.
    pub fn point_distance(&self, x: &Point3<f64>) -> (f64, Point3<f64>) {
        let rho = crate::num::norm2(x.x, x.y);
        let (d, c) = self.arc.nearest(Point2::new(rho, x.z));
        let e = if rho > 0.0 {
            Vector3::new(x.x / rho, x.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        (d, lift(c, &e))
    }

    /// All critical feet of `x` (patch frame) on the patch interior: points `y` of the patch,
    /// with the patch parameter inside its range, where `x - y` is normal to the surface.
    /// In the meridian plane of `x` the surface is the profile piece and its mirror image
    /// (`rho -> -rho`, the half at `theta + pi`); feet are the intersections of the piece with
    /// the line through `x` and the arc centre, or the perpendicular foot on a segment.
    /// `x` on the axis gives a continuum; then `extra_dirs` gives the radial directions tried.
    pub fn critical_feet(&self, x: &Point3<f64>, out: &mut Vec<Point3<f64>>) {
        let rho = crate::num::norm2(x.x, x.y);
        if rho > 1e-13 * (1.0 + x.coords.norm()) {
            let e = Vector3::new(x.x / rho, x.y / rho, 0.0);
            self.critical_feet_in_plane(Point2::new(rho, x.z), &e, out);
        } else {
            // On the axis every meridian plane is equivalent: the feet form circles. One
            // meridian plane gives every distinct distance.
            let e = Vector3::x();
            self.critical_feet_in_plane(Point2::new(0.0, x.z), &e, out);
        }
    }

    /// Critical feet from the meridian-plane point `xm` (rho >= 0) in the plane with radial
    /// direction `e`, covering the piece and its mirror image.
    fn critical_feet_in_plane(
        &self,
        xm: Point2<f64>,
        e: &Vector3<f64>,
        out: &mut Vec<Point3<f64>>,
    ) {
        for mirror in [1.0, -1.0] {
            // Work with the mirrored point instead of the mirrored piece.
            let xs = Point2::new(mirror * xm.x, xm.y);
            match self.arc {
                ProfileArc::Arc { center, .. } => {
                    let d = xs - center;
                    let n = d.norm();
                    if n <= 1e-300 {
                        // x at the arc centre: every arc point is a foot; take the ends and
                        // the middle (all at the same distance `radius`).
                        for s in [0.0, 0.5, 1.0] {
                            let p = self.arc.point_at(s);
                            out.push(lift(Point2::new(mirror * p.x, p.y), e));
                        }
                        continue;
                    }
                    let w = d / n;
                    for sgn in [1.0, -1.0] {
                        let phi = (sgn * w.y).atan2(sgn * w.x);
                        if let Some(s) = self.arc.arc_param(phi) {
                            let p = self.arc.point_at(s);
                            out.push(lift(Point2::new(mirror * p.x, p.y), e));
                        }
                    }
                }
                ProfileArc::Segment { start, end } => {
                    let ev = end - start;
                    let l2 = ev.norm_squared();
                    if l2 == 0.0 {
                        continue;
                    }
                    let t = (xs - start).dot(&ev) / l2;
                    if (-SEGMENT_SLACK..=1.0 + SEGMENT_SLACK).contains(&t) {
                        let p = start + t.clamp(0.0, 1.0) * ev;
                        out.push(lift(Point2::new(mirror * p.x, p.y), e));
                    }
                }
            }
        }
    }

    /// Surface points of the patch on the normal line through the core point `core_pt`
    /// (patch frame; a point of the major circle) with direction `dir` (unit, normal to the
    /// major circle there). Returns the points whose arc angle is in range.
    /// Only meaningful for arcs.
    pub fn points_on_normal_line(
        &self,
        core_pt: &Point3<f64>,
        dir: &Vector3<f64>,
        out: &mut Vec<Point3<f64>>,
    ) {
        let ProfileArc::Arc { center, .. } = self.arc else {
            return;
        };
        let h = Vector2::new(core_pt.x, core_pt.y);
        let hn = h.norm();
        for sgn in [1.0, -1.0] {
            let d = dir * sgn;
            // Radial direction of the meridian plane of the surface point: the one in which
            // the core point has signed coordinate `center.x`, or (major circle a point:
            // sphere centred on the axis) the one containing the direction itself.
            let e = if center.x.abs() > 1e-300 && hn > 0.0 {
                let s = center.x.signum();
                Vector3::new(s * h.x / hn, s * h.y / hn, 0.0)
            } else {
                let dh = Vector2::new(d.x, d.y);
                let dn = dh.norm();
                if dn > 1e-300 {
                    Vector3::new(dh.x / dn, dh.y / dn, 0.0)
                } else {
                    Vector3::x()
                }
            };
            let phi = d.z.atan2(d.dot(&e));
            if let Some(s) = self.arc.arc_param(phi) {
                let p = self.arc.point_at(s);
                out.push(lift(p, &e));
            }
        }
    }

    /// Outward-from-core unit normal used by orientation tests: the planar unit vector from
    /// the arc centre (or the segment's left normal) at the planar point `m`.
    pub fn planar_normal(&self, m: Point2<f64>) -> Vector2<f64> {
        match self.arc {
            ProfileArc::Arc { center, .. } => {
                let d = m - center;
                let n = d.norm();
                if n > 0.0 {
                    d / n
                } else {
                    Vector2::x()
                }
            }
            ProfileArc::Segment { start, end } => {
                let d = (end - start).normalize();
                Vector2::new(-d.y, d.x)
            }
        }
    }
}

impl NearestPoint for ProfileArc {
    /// Closest point of the piece to `x` (planar), with its distance.
    fn nearest(&self, x: Point2<f64>) -> (f64, Point2<f64>) {
        match *self {
            ProfileArc::Arc { center, radius, .. } => {
                let d = x - center;
                let n = d.norm();
                if n > 0.0 {
                    let phi = d.y.atan2(d.x);
                    if self.arc_param(phi).is_some() {
                        let p = center + d * (radius / n);
                        return ((n - radius).abs(), p);
                    }
                }
                let (a, b) = (self.start(), self.end());
                let (da, db) = ((x - a).norm(), (x - b).norm());
                if da <= db {
                    (da, a)
                } else {
                    (db, b)
                }
            }
            ProfileArc::Segment { start, end } => {
                let e = end - start;
                let l2 = e.norm_squared();
                let t = if l2 > 0.0 {
                    ((x - start).dot(&e) / l2).clamp(0.0, 1.0)
                } else {
                    0.0
                };
                let p = start + t * e;
                ((x - p).norm(), p)
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A segment whose rise or run is rounding (an M_t frame's bottom at `z = -1.4e-18`) is
    /// made exactly flat or cylindrical, and its snap error bounds how far every point moved;
    /// a real slope, however small, is kept.
    #[test]
    fn slight_segments_snap_flat_or_cylindrical() {
        let flat = ProfileArc::Segment {
            start: Point2::new(0.1575, -1.3611220880147127e-18),
            end: Point2::new(0.315, 0.0),
        };
        let cylinder = ProfileArc::Segment {
            start: Point2::new(0.5, 0.2),
            end: Point2::new(0.5 + 2e-15, 0.9),
        };
        let real = ProfileArc::Segment {
            start: Point2::new(0.1575, -1e-9),
            end: Point2::new(0.315, 0.0),
        };
        for piece in [flat, cylinder] {
            let p = Patch::new(piece);
            let ProfileArc::Segment { start, end } = p.arc else {
                panic!("a segment stays a segment");
            };
            assert!(start.y == end.y || start.x == end.x, "{:?}", p.arc);
            let err = Patch::snap_error(&piece);
            assert!(err > 0.0 && err <= 1e-15, "{err}");
            for k in 0..=8 {
                let s = k as f64 / 8.0;
                let moved = (piece.point_at(s) - p.arc.point_at(s)).norm();
                assert!(moved <= err, "{moved} > {err}");
            }
        }
        assert_eq!(Patch::new(real).arc, real);
        assert_eq!(Patch::snap_error(&real), 0.0);
    }
}
