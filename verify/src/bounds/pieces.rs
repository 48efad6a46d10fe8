//! Adversarial pairs of revolved piece chains: the configurations of the piece, leaf and
//! node bounds.
//!
//! A configuration is two short chains (one to three pieces each, joined end to start) in
//! their own frames and the pose of B in A's frame. The families are the places where a
//! lower bound is most easily wrong ([`Family`]); every family is drawn at a scale
//! log-uniform in [1e-3, 1e3]. Most poses put the chains in contact: a point `p` of A (often
//! a piece end, a kink) and a point `q` of B are chosen with normals `n_A`, `n_B` (at a kink
//! any unit vector of the normal cone between the two pieces' normals), B is rotated so that
//! `n_B` becomes `-n_A` (with a random twist about `n_A`) and moved so that `q` lands at
//! `p + g n_A`, the gap `g` being 0, `+-1e-13..1e-5` of the scale, or a free distance. The
//! constructed pair `(p, q)` is then a realised pair at distance `|g|` (to rounding).

use super::chain::{lift_vector, planar_normal, Pair, SurfacePoint};
use crate::contact;
use nalgebra::{Isometry3, Point2, Translation3, UnitQuaternion, Vector2, Vector3};
use revdist::bvh::ProfileArc;
use revdist::rng::SplitMix64;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// The adversarial families.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Family {
    /// Random arcs and segments, joined smoothly or not.
    Generic,
    /// Chains with G0 corners (kinks inside a chain), convex and reflex, touched at the kink.
    Corner,
    /// Arcs starting or ending at a parallel or an equator (`phi` a multiple of pi/2).
    ParallelEquator,
    /// Pieces with an end on the axis (`rho = 0`): cone tips, sphere poles, tori touching the
    /// axis.
    Axis,
    /// Coaxial solids (B's axis is A's, possibly flipped), with B's arc tangent to A's
    /// profile (externally or internally tangent circles).
    CoaxialTangent,
    /// B is A's chain moved by 1e-12..1e-6 of the scale (nearly coincident patches).
    Coincident,
    /// Nearly flat or nearly cylindrical cones (slope 1e-9..1e-5), the family of the
    /// meridian-line cluster bug.
    FlatCone,
}

pub const FAMILIES: [Family; 7] = [
    Family::Generic,
    Family::Corner,
    Family::ParallelEquator,
    Family::Axis,
    Family::CoaxialTangent,
    Family::Coincident,
    Family::FlatCone,
];

impl Family {
    pub fn name(self) -> &'static str {
        match self {
            Family::Generic => "generic",
            Family::Corner => "corner",
            Family::ParallelEquator => "parallel-equator",
            Family::Axis => "axis",
            Family::CoaxialTangent => "coaxial-tangent",
            Family::Coincident => "coincident",
            Family::FlatCone => "flat-cone",
        }
    }
}

/// One configuration of two chains.
#[derive(Debug, Clone)]
pub struct PieceConfig {
    pub family: Family,
    pub scale: f64,
    pub a: Vec<ProfileArc>,
    pub b: Vec<ProfileArc>,
    pub pos_ab: Isometry3<f64>,
    /// The constructed contact pair, when the pose was made by one.
    pub contact: Option<Pair>,
}

/// A gap of a contact, relative to the scale: 0, a tiny one of either sign, or a free one.
pub(super) fn gap(rng: &mut SplitMix64) -> f64 {
    match rng.below(10) {
        0..=2 => 0.0,
        3..=5 => rng.log_range(1e-13, 1e-5),
        6..=7 => -rng.log_range(1e-13, 1e-5),
        _ => rng.range(0.0, 0.5),
    }
}

/// An arc starting at `start` with unit tangent angle `alpha`, radius `r`, signed sweep.
fn arc_from(start: Point2<f64>, alpha: f64, r: f64, sweep: f64) -> ProfileArc {
    let left = Vector2::new(-alpha.sin(), alpha.cos());
    let center = start + left * (r * sweep.signum());
    let d = start - center;
    ProfileArc::Arc {
        center,
        radius: r,
        phi_start: d.y.atan2(d.x),
        sweep,
    }
}

/// The direction angle of a piece's tangent at its end.
fn end_angle(p: &ProfileArc) -> f64 {
    let t = p.tangent_at(1.0);
    t.y.atan2(t.x)
}

/// Smallest rho over a piece (sampled densely and at the arc's leftmost angle).
fn min_rho(p: &ProfileArc) -> f64 {
    let mut m = f64::INFINITY;
    for i in 0..=64 {
        m = m.min(p.point_at(i as f64 / 64.0).x);
    }
    if let ProfileArc::Arc { center, radius, .. } = *p {
        if let Some(s) = p.arc_param(PI) {
            m = m.min(p.point_at(s).x).min(center.x - radius);
        }
    }
    m
}

/// Moves a chain right so that no point has `rho < margin`.
fn keep_off_axis(chain: &mut [ProfileArc], margin: f64) {
    let m = chain.iter().map(min_rho).fold(f64::INFINITY, f64::min);
    if m < margin {
        let dx = Vector2::new(margin - m, 0.0);
        for p in chain.iter_mut() {
            *p = shifted(p, dx);
        }
    }
}

fn shifted(p: &ProfileArc, d: Vector2<f64>) -> ProfileArc {
    match *p {
        ProfileArc::Arc {
            center,
            radius,
            phi_start,
            sweep,
        } => ProfileArc::Arc {
            center: center + d,
            radius,
            phi_start,
            sweep,
        },
        ProfileArc::Segment { start, end } => ProfileArc::Segment {
            start: start + d,
            end: end + d,
        },
    }
}

fn scaled(p: &ProfileArc, k: f64) -> ProfileArc {
    match *p {
        ProfileArc::Arc {
            center,
            radius,
            phi_start,
            sweep,
        } => ProfileArc::Arc {
            center: Point2::from(center.coords * k),
            radius: radius * k,
            phi_start,
            sweep,
        },
        ProfileArc::Segment { start, end } => ProfileArc::Segment {
            start: Point2::from(start.coords * k),
            end: Point2::from(end.coords * k),
        },
    }
}

/// A random chain of `n` pieces from a random start; `kink` is the G0 turn at each joint
/// (0 for smooth joints; its sign against the pieces' turning makes it convex or reflex).
fn chain(
    rng: &mut SplitMix64,
    n: usize,
    kink: &mut dyn FnMut(&mut SplitMix64) -> f64,
) -> Vec<ProfileArc> {
    let mut start = Point2::new(rng.range(0.3, 1.5), rng.range(-1.0, 1.0));
    let mut alpha = rng.range(0.0, TAU);
    let mut out = Vec::with_capacity(n);
    for _ in 0..n {
        let piece = if rng.chance(0.35) {
            let l = rng.range(0.1, 1.0);
            let end = start + l * Vector2::new(alpha.cos(), alpha.sin());
            ProfileArc::Segment { start, end }
        } else {
            let r = rng.log_range(0.05, 2.0);
            let sweep =
                rng.range(0.05, 2.0_f64.min(1.2 / r)) * if rng.chance(0.5) { 1.0 } else { -1.0 };
            arc_from(start, alpha, r, sweep)
        };
        alpha = end_angle(&piece) + kink(rng);
        start = piece.end();
        out.push(piece);
    }
    out
}

fn generic_chain(rng: &mut SplitMix64) -> Vec<ProfileArc> {
    let n = rng.int(1, 3);
    let smooth = rng.chance(0.5);
    let mut c = chain(rng, n, &mut |r| {
        if smooth {
            0.0
        } else {
            r.range(-1.0, 1.0)
        }
    });
    keep_off_axis(&mut c, 0.01);
    c
}

fn corner_chain(rng: &mut SplitMix64) -> Vec<ProfileArc> {
    let n = rng.int(2, 3);
    let mut c = chain(rng, n, &mut |r| {
        // Convex or reflex, from nearly smooth to a hairpin.
        let k = match r.below(3) {
            0 => r.log_range(1e-9, 1e-3),
            1 => r.range(0.1, 1.5),
            _ => r.range(2.5, 3.1),
        };
        if r.chance(0.5) {
            k
        } else {
            -k
        }
    });
    keep_off_axis(&mut c, 0.01);
    c
}

/// An arc whose start or end angle is exactly a multiple of pi/2.
fn parallel_arc(rng: &mut SplitMix64) -> ProfileArc {
    let k = rng.int(0, 3) as f64;
    let phi = k * FRAC_PI_2 - if rng.chance(0.3) { PI } else { 0.0 };
    let r = rng.range(0.1, 1.0);
    let sweep = rng.range(0.1, PI) * if rng.chance(0.5) { 1.0 } else { -1.0 };
    let (phi_start, sweep) = if rng.chance(0.5) {
        (phi, sweep)
    } else {
        (phi - sweep, sweep)
    };
    let on_axis = rng.chance(0.3);
    let c = if on_axis {
        0.0
    } else {
        r + rng.range(0.0, 1.0)
    };
    let mut a = ProfileArc::Arc {
        center: Point2::new(c, rng.range(-1.0, 1.0)),
        radius: r,
        phi_start,
        sweep,
    };
    if on_axis && min_rho(&a) < 0.0 {
        // A sphere patch: keep the side of rho >= 0 (a quarter from a pole to the equator).
        let (lo, hi) = if rng.chance(0.5) {
            (-FRAC_PI_2, 0.0)
        } else {
            (0.0, FRAC_PI_2)
        };
        a = ProfileArc::Arc {
            center: Point2::new(0.0, rng.range(-1.0, 1.0)),
            radius: r,
            phi_start: lo,
            sweep: hi - lo,
        };
    }
    a
}

/// A piece with an end on the axis: a cone to its tip, a sphere cap to its pole, a torus
/// arc touching the axis.
fn axis_piece(rng: &mut SplitMix64) -> ProfileArc {
    let z = rng.range(-1.0, 1.0);
    let p = match rng.below(3) {
        0 => ProfileArc::Segment {
            start: Point2::new(0.0, z),
            end: Point2::new(rng.range(0.1, 1.0), z + rng.range(-1.0, 1.0)),
        },
        1 => {
            let pole = if rng.chance(0.5) {
                FRAC_PI_2
            } else {
                -FRAC_PI_2
            };
            let sweep = rng.range(0.1, FRAC_PI_2) * -pole.signum();
            ProfileArc::Arc {
                center: Point2::new(0.0, z),
                radius: rng.range(0.1, 1.0),
                phi_start: pole,
                sweep,
            }
        }
        _ => {
            // Centre at rho = r: the arc reaches the axis at phi = pi.
            let r = rng.range(0.1, 1.0);
            ProfileArc::Arc {
                center: Point2::new(r, z),
                radius: r,
                phi_start: PI,
                sweep: rng.range(0.1, 1.5) * if rng.chance(0.5) { 1.0 } else { -1.0 },
            }
        }
    };
    if rng.chance(0.5) {
        p.reversed()
    } else {
        p
    }
}

fn flat_cone(rng: &mut SplitMix64) -> ProfileArc {
    let slope = rng.log_range(1e-9, 1e-5) * if rng.chance(0.5) { 1.0 } else { -1.0 };
    let (r0, z0, l) = (
        rng.range(0.0, 1.0),
        rng.range(-1.0, 1.0),
        rng.range(0.2, 1.0),
    );
    let r0 = if rng.chance(0.2) { 0.0 } else { r0 };
    if rng.chance(0.7) {
        ProfileArc::Segment {
            start: Point2::new(r0, z0),
            end: Point2::new(r0 + l, z0 + slope * l),
        }
    } else {
        let r0 = r0 + 0.1;
        ProfileArc::Segment {
            start: Point2::new(r0, z0),
            end: Point2::new(r0 + slope * l, z0 + l),
        }
    }
}

/// A random point of a chain, at a piece end (often a kink) with probability 0.4.
pub(super) fn surface_point(rng: &mut SplitMix64, chain: &[ProfileArc]) -> SurfacePoint {
    let piece = rng.below(chain.len());
    let s = match rng.below(5) {
        0 => 0.0,
        1 => 1.0,
        _ => rng.next_f64(),
    };
    SurfacePoint {
        piece,
        s,
        theta: rng.range(0.0, TAU),
    }
}

/// The planar normal of the neighbouring piece when `x` is a joint of the chain (a piece's
/// start after another piece, or its end before one).
pub(super) fn neighbour_normal(chain: &[ProfileArc], x: &SurfacePoint) -> Option<Vector2<f64>> {
    if x.s == 0.0 && x.piece > 0 {
        Some(planar_normal(&chain[x.piece - 1], 1.0))
    } else if x.s == 1.0 && x.piece + 1 < chain.len() {
        Some(planar_normal(&chain[x.piece + 1], 0.0))
    } else {
        None
    }
}

/// A random unit vector between two unit normals of a joint (its normal cone), or `n` when
/// they nearly cancel.
pub(super) fn blend_normals(
    rng: &mut SplitMix64,
    n: Vector2<f64>,
    m: Vector2<f64>,
) -> Vector2<f64> {
    let w = rng.next_f64();
    let blend = n * w + m * (1.0 - w);
    if blend.norm() > 1e-3 {
        blend.normalize()
    } else {
        n
    }
}

/// A unit normal of the chain at `x`: at a joint, a random unit vector between the two
/// pieces' normals (the normal cone of a kink); random sign.
fn normal(rng: &mut SplitMix64, chain: &[ProfileArc], x: &SurfacePoint) -> Vector3<f64> {
    let mut n = planar_normal(&chain[x.piece], x.s);
    if let Some(m) = neighbour_normal(chain, x) {
        n = blend_normals(rng, n, m);
    }
    let n3 = lift_vector(n, x.theta);
    if rng.chance(0.5) {
        n3
    } else {
        -n3
    }
}

/// The contact pose: `q` of B at `p + g n_A`, `n_B` turned to `-n_A` (module doc).
fn contact_pose(rng: &mut SplitMix64, cfg: &mut PieceConfig, g: f64) {
    let p = surface_point(rng, &cfg.a);
    let q = surface_point(rng, &cfg.b);
    let na = normal(rng, &cfg.a, &p);
    let nb = normal(rng, &cfg.b, &q);
    let spin = rng.range(0.0, TAU);
    let (pa, qb) = (
        super::chain::point(&cfg.a, &p),
        super::chain::point(&cfg.b, &q),
    );
    cfg.pos_ab = contact::contact_pose((pa.coords, na), (qb.coords, nb), g, spin);
    cfg.contact = Some(Pair::new(&cfg.a, &cfg.b, &cfg.pos_ab, p, q));
}

/// A random pose at a distance of a few sizes (no contact).
pub(super) fn free_pose(rng: &mut SplitMix64, scale: f64) -> Isometry3<f64> {
    let q = rng.quaternion();
    let rot = UnitQuaternion::from_quaternion(nalgebra::Quaternion::new(q[0], q[1], q[2], q[3]));
    let t = rng.direction() * rng.range(0.0, 3.0) * scale;
    Isometry3::from_parts(Translation3::from(t), rot)
}

/// Coaxial tangent circles: B is one arc tangent to A's profile at a chosen point, in a
/// frame shifted along A's axis and possibly flipped.
fn coaxial_tangent(
    rng: &mut SplitMix64,
    a: &[ProfileArc],
    scale: f64,
) -> (Vec<ProfileArc>, Isometry3<f64>) {
    let piece = rng.below(a.len());
    let s = if rng.chance(0.3) {
        rng.below(2) as f64
    } else {
        rng.next_f64()
    };
    let m = a[piece].point_at(s);
    let n = planar_normal(&a[piece], s) * if rng.chance(0.5) { 1.0 } else { -1.0 };
    let g = gap(rng) * scale;
    let r = rng.log_range(0.05, 2.0) * scale;
    // External tangency: centre beyond the contact; internal: B's circle encloses A's
    // near the contact (centre on A's side, farther than A's curvature centre).
    let c = if rng.chance(0.6) {
        m + n * (g + r)
    } else {
        m + n * g - n * r
    };
    let (c, contact) = if (m + n * g).x > 0.0 {
        (c, m + n * g)
    } else {
        (c - n * g, m)
    };
    let d = contact - c;
    let phi = d.y.atan2(d.x);
    let mut half = rng.range(0.05, 1.0);
    let mut arc = ProfileArc::Arc {
        center: c,
        radius: r,
        phi_start: phi - half,
        sweep: 2.0 * half,
    };
    // Only the part of B's circle with rho >= 0 around the contact.
    while min_rho(&arc) < 0.0 && half > 1e-6 {
        half *= 0.5;
        arc = ProfileArc::Arc {
            center: c,
            radius: r,
            phi_start: phi - half,
            sweep: 2.0 * half,
        };
    }
    let tz = rng.range(-2.0, 2.0) * scale;
    let flip = rng.chance(0.5);
    // B's frame: z_B = sign (z_A - tz); the pose maps B's frame into A's.
    let sign = if flip { -1.0 } else { 1.0 };
    let arc = arc.mapped_z(sign, -sign * tz);
    let rot = if flip {
        UnitQuaternion::from_axis_angle(&Vector3::x_axis(), PI)
    } else {
        UnitQuaternion::identity()
    };
    let spin = UnitQuaternion::from_axis_angle(&Vector3::z_axis(), rng.range(0.0, TAU));
    let pos = Isometry3::from_parts(Translation3::new(0.0, 0.0, tz), spin * rot);
    (vec![arc], pos)
}

/// A configuration of `family` (module doc).
pub fn draw(rng: &mut SplitMix64, family: Family) -> PieceConfig {
    let scale = rng.log_range(1e-3, 1e3);
    let unit = |rng: &mut SplitMix64| -> Vec<ProfileArc> {
        match family {
            Family::Generic | Family::Coincident | Family::CoaxialTangent => generic_chain(rng),
            Family::Corner => corner_chain(rng),
            Family::ParallelEquator => {
                let mut c = vec![parallel_arc(rng)];
                if rng.chance(0.4) {
                    let first = c[0];
                    let next = chain(rng, 1, &mut |_| 0.0);
                    let n = shifted(&next[0], first.end() - next[0].start());
                    c.push(n);
                    keep_off_axis(&mut c, 0.0);
                }
                c
            }
            Family::Axis => vec![axis_piece(rng)],
            Family::FlatCone => {
                if rng.chance(0.7) {
                    vec![flat_cone(rng)]
                } else {
                    generic_chain(rng)
                }
            }
        }
    };
    let a: Vec<ProfileArc> = unit(rng).iter().map(|p| scaled(p, scale)).collect();
    let mut cfg = PieceConfig {
        family,
        scale,
        a: a.clone(),
        b: Vec::new(),
        pos_ab: Isometry3::identity(),
        contact: None,
    };
    match family {
        Family::CoaxialTangent => {
            let (b, pos) = coaxial_tangent(rng, &a, scale);
            cfg.b = b;
            cfg.pos_ab = pos;
        }
        Family::Coincident => {
            cfg.b = a;
            let off = rng.log_range(1e-12, 1e-6);
            cfg.pos_ab = if rng.chance(0.5) {
                Isometry3::from_parts(
                    Translation3::from(rng.direction() * off * scale),
                    UnitQuaternion::identity(),
                )
            } else {
                let rot = UnitQuaternion::from_scaled_axis(rng.direction() * off);
                Isometry3::from_parts(Translation3::identity(), rot)
            };
        }
        _ => {
            cfg.b = unit(rng).iter().map(|p| scaled(p, scale)).collect();
            if rng.chance(0.85) {
                let g = gap(rng) * scale;
                contact_pose(rng, &mut cfg, g);
            } else {
                cfg.pos_ab = free_pose(rng, scale);
            }
        }
    }
    cfg
}
