//! Independent reference for distances between posed solids of revolution: dense sampling
//! of the exact NURBS surfaces refined by local optimisation. Uses only the NURBS curves
//! and profiles, never the query code.
//!
//! * The distance from a point to a surface of revolution is the planar distance from the
//!   point's meridian coordinates `(rho, z)` to the profile curve; the reference computes it
//!   by a dense polyline sampling of the profile followed by Newton's method on
//!   `(C(t) - m) . C'(t) = 0` (a realised distance to a curve point).
//! * The distance between the two boundaries is the minimum of that point distance over a
//!   dense grid `(t, theta)` on each surface against the other, refined by a pattern search
//!   from the best grid points.
//! * Solids: the distance is 0 when the boundaries meet (reference below
//!   [`REFERENCE_ERROR`]) or when a boundary point of one is inside the other (winding
//!   number of the sampled profile polygon, closed along the axis for open profiles).
//!
//! Every reported value is the distance between two actual surface points, so it is never
//! below the true distance; the grid spacing and the refinement make it exceed the truth by
//! less than [`REFERENCE_ERROR`] when the basin of the global minimum is sampled.

#![allow(dead_code)]

use nalgebra::{Isometry3, Point2, Point3, UnitQuaternion, Vector3};
use revdist::nurbs::NurbsCurve;
use revdist::profile::{Profile, ProfileKind};
use revdist::query::{distance, Distance, QueryOptions};
use revdist::solid::Solid;
use std::f64::consts::TAU;

/// Stated error of the reference (absolute, for models of size about 1): the pattern
/// search stops at steps of 1e-12 and the Newton projection converges to 1e-15, so the
/// value exceeds the local minimum by far less; 1e-7 covers flat minima (parallel faces,
/// coaxial continua) where the grid point and the minimiser differ by up to 1e-4 along a
/// direction of nearly zero curvature.
pub const REFERENCE_ERROR: f64 = 1e-7;

/// Cap on distance evaluations per pattern-search start: in flat valleys (parallel
/// faces, continua) tiny improvements could otherwise continue for very many steps; the
/// value reached is still a realised distance.
const MAX_PATTERN_EVALS: usize = 3000;

/// Samples per profile piece for the polyline.
const POLY_SAMPLES: usize = 64;

/// A profile with its dense polyline (for the inner closest-point search).
pub struct RefProfile<'a> {
    pub profile: &'a Profile,
    /// (piece, t, point)
    samples: Vec<(usize, f64, Point2<f64>)>,
}

impl<'a> RefProfile<'a> {
    pub fn new(profile: &'a Profile) -> Self {
        let mut samples = Vec::new();
        for (i, c) in profile.pieces().iter().enumerate() {
            let (t0, t1) = c.domain();
            for k in 0..=POLY_SAMPLES {
                let t = t0 + (t1 - t0) * k as f64 / POLY_SAMPLES as f64;
                samples.push((i, t, c.eval(t)));
            }
        }
        RefProfile { profile, samples }
    }

    /// Planar distance from `m` to the profile curve (realised at a curve point).
    pub fn curve_distance(&self, m: Point2<f64>) -> f64 {
        // Best sample, and the best one away from it (another local minimum), each refined
        // by Newton on its piece.
        let mut order: Vec<(f64, usize)> = Vec::with_capacity(2);
        let mut best = (f64::INFINITY, 0usize);
        for (k, s) in self.samples.iter().enumerate() {
            let d = (s.2 - m).norm_squared();
            if d < best.0 {
                best = (d, k);
            }
        }
        order.push(best);
        let mut second = (f64::INFINITY, usize::MAX);
        for (k, s) in self.samples.iter().enumerate() {
            let far = s.0 != self.samples[best.1].0 || k.abs_diff(best.1) > 2;
            let d = (s.2 - m).norm_squared();
            if far && d < second.0 {
                second = (d, k);
            }
        }
        if second.1 != usize::MAX {
            order.push(second);
        }
        let mut out = f64::INFINITY;
        for &(_, k) in &order {
            let (i, t, _) = self.samples[k];
            let c = &self.profile.pieces()[i];
            let t = newton(c, m, t);
            out = out.min((c.eval(t) - m).norm());
        }
        out
    }

    /// Distance from a 3-D point (profile frame) to the surface of revolution.
    pub fn surface_distance(&self, x: &Point3<f64>) -> f64 {
        self.curve_distance(Point2::new(x.x.hypot(x.y), x.z))
    }

    /// Winding-number test of the meridian point against the sampled profile region.
    pub fn contains(&self, m: Point2<f64>) -> bool {
        let mut pts: Vec<Point2<f64>> = self.samples.iter().map(|s| s.2).collect();
        if self.profile.kind() == ProfileKind::OpenOnAxis {
            pts.push(Point2::new(0.0, pts.last().unwrap().y));
            pts.push(Point2::new(0.0, pts[0].y));
        }
        let mut w = 0.0;
        for k in 0..pts.len() {
            let (a, b) = (pts[k] - m, pts[(k + 1) % pts.len()] - m);
            w += (a.x * b.y - a.y * b.x).atan2(a.dot(&b));
        }
        (w / TAU).round() != 0.0
    }

    /// Surface point at (piece, t, theta).
    pub fn point(&self, piece: usize, t: f64, theta: f64) -> Point3<f64> {
        let p = self.profile.pieces()[piece].eval(t);
        Point3::new(p.x * theta.cos(), p.x * theta.sin(), p.y)
    }
}

fn newton(c: &NurbsCurve, m: Point2<f64>, mut t: f64) -> f64 {
    let (t0, t1) = c.domain();
    for _ in 0..40 {
        let [p, d1, d2, _] = c.derivatives(t);
        let r = p - m.coords;
        let g = r.dot(&d1);
        let h = d1.dot(&d1) + r.dot(&d2);
        if h <= 0.0 {
            break;
        }
        let tn = (t - g / h).clamp(t0, t1);
        if (tn - t).abs() < 1e-14 * (t1 - t0) {
            return tn;
        }
        t = tn;
    }
    t
}

/// Minimum over the surface of `b` (placed in a's frame by `pos_ab`) of the distance to
/// the surface of `a`, with the best point of `b` (in a's frame).
fn one_side(
    a: &RefProfile,
    b: &RefProfile,
    pos_ab: &Isometry3<f64>,
    n_t: usize,
    n_theta: usize,
) -> (f64, Point3<f64>) {
    let f = |piece: usize, t: f64, th: f64| a.surface_distance(&(pos_ab * b.point(piece, t, th)));
    let mut cands: Vec<(f64, usize, f64, f64)> = Vec::new();
    for (i, c) in b.profile.pieces().iter().enumerate() {
        let (t0, t1) = c.domain();
        for k in 0..=n_t {
            let t = t0 + (t1 - t0) * k as f64 / n_t as f64;
            for j in 0..n_theta {
                let th = j as f64 * TAU / n_theta as f64;
                cands.push((f(i, t, th), i, t, th));
            }
        }
    }
    cands.sort_by(|x, y| x.0.partial_cmp(&y.0).unwrap());
    let mut best = (f64::INFINITY, Point3::origin());
    // Refine the best distinct starts.
    let mut starts: Vec<(f64, usize, f64, f64)> = Vec::new();
    for c in &cands {
        if starts.len() >= 5 {
            break;
        }
        if starts
            .iter()
            .all(|s| s.1 != c.1 || (s.2 - c.2).abs() > 1e-9 || (s.3 - c.3).abs() > 1e-9)
        {
            starts.push(*c);
        }
    }
    for (mut v, i, mut t, mut th) in starts {
        let (t0, t1) = b.profile.pieces()[i].domain();
        let (mut ht, mut hth) = ((t1 - t0) / n_t as f64, TAU / n_theta as f64);
        let mut evals = 0usize;
        while (ht > 1e-13 * (t1 - t0) || hth > 1e-13) && evals < MAX_PATTERN_EVALS {
            evals += 8;
            let mut moved = false;
            for (dt, dth) in [
                (ht, 0.0),
                (-ht, 0.0),
                (0.0, hth),
                (0.0, -hth),
                (ht, hth),
                (-ht, -hth),
                (ht, -hth),
                (-ht, hth),
            ] {
                let t2 = (t + dt).clamp(t0, t1);
                let v2 = f(i, t2, th + dth);
                if v2 < v {
                    (v, t, th) = (v2, t2, th + dth);
                    moved = true;
                    break;
                }
            }
            if !moved {
                ht *= 0.5;
                hth *= 0.5;
            }
        }
        if v < best.0 {
            best = (v, pos_ab * b.point(i, t, th));
        }
    }
    best
}

/// Reference result.
#[derive(Debug, Clone, Copy)]
pub struct Reference {
    /// Distance between the solids (0 when they overlap or nest).
    pub distance: f64,
    /// Distance between the boundary surfaces.
    pub surface_distance: f64,
    /// One solid contains a boundary point of the other.
    pub nested: bool,
    /// Closest point of B's boundary found (A's frame).
    pub point_b: Point3<f64>,
}

/// Reference distance between profile `a` at the identity and `b` placed by `pos_ab`.
pub fn reference(a: &Profile, b: &Profile, pos_ab: &Isometry3<f64>) -> Reference {
    let (ra, rb) = (RefProfile::new(a), RefProfile::new(b));
    let (d1, pb) = one_side(&ra, &rb, pos_ab, 24, 48);
    let (d2, _) = one_side(&rb, &ra, &pos_ab.inverse(), 24, 48);
    let surface = d1.min(d2);
    // Containment of one boundary point of each in the other.
    let pb0 = pos_ab
        * rb.point(
            0,
            b.pieces()[0].domain().0 * 0.5 + b.pieces()[0].domain().1 * 0.5,
            0.3,
        );
    let pa0 = ra.point(
        0,
        a.pieces()[0].domain().0 * 0.5 + a.pieces()[0].domain().1 * 0.5,
        0.3,
    );
    let pa0_in_b = pos_ab.inverse() * pa0;
    let nested = ra.contains(Point2::new(pb0.x.hypot(pb0.y), pb0.z))
        || rb.contains(Point2::new(pa0_in_b.x.hypot(pa0_in_b.y), pa0_in_b.z));
    let distance = if nested || surface <= REFERENCE_ERROR {
        0.0
    } else {
        surface
    };
    Reference {
        distance,
        surface_distance: surface,
        nested,
        point_b: pb,
    }
}

/// Unit vector helper for pose generation.
pub fn unit(v: Vector3<f64>) -> Vector3<f64> {
    v / v.norm()
}

/// Small deterministic generator for test poses (no external crates).
pub struct Rng(pub u64);
impl Rng {
    pub fn f(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    pub fn rotation(&mut self) -> UnitQuaternion<f64> {
        let v = Vector3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5);
        UnitQuaternion::from_scaled_axis(v * 7.0)
    }
    pub fn unit(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(self.f() - 0.5, self.f() - 0.5, self.f() - 0.5);
            if v.norm() > 0.1 && v.norm() < 0.5 {
                return v.normalize();
            }
        }
    }
}

/// Exact rational circle profile (a ring) of radius `r` around `(c_rho, c_z)`.
pub fn ring_profile(c_rho: f64, c_z: f64, r: f64) -> Profile {
    let w = std::f64::consts::FRAC_1_SQRT_2;
    let pts = [
        (1.0, 0.0),
        (1.0, 1.0),
        (0.0, 1.0),
        (-1.0, 1.0),
        (-1.0, 0.0),
        (-1.0, -1.0),
        (0.0, -1.0),
        (1.0, -1.0),
        (1.0, 0.0),
    ]
    .iter()
    .map(|&(x, y)| Point2::new(c_rho + r * x, c_z + r * y))
    .collect();
    let knots = vec![
        0.0, 0.0, 0.0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1.0, 1.0, 1.0,
    ];
    let weights = vec![1.0, w, 1.0, w, 1.0, w, 1.0, w, 1.0];
    let circle = NurbsCurve::new(2, knots, pts, Some(weights)).unwrap();
    Profile::new("ring", vec![circle]).unwrap()
}

/// Closest point of the surface of `prof` (its frame) to `x`.
pub fn closest_point(prof: &RefProfile, x: &Point3<f64>) -> Point3<f64> {
    let rho = x.x.hypot(x.y);
    let m = Point2::new(rho, x.z);
    let mut best = (f64::INFINITY, m);
    for &(i, t, _) in &prof.samples {
        let c = &prof.profile.pieces()[i];
        let p = c.eval(newton(c, m, t));
        let d = (p - m).norm();
        if d < best.0 {
            best = (d, p);
        }
    }
    let e = if rho > 0.0 {
        Vector3::new(x.x / rho, x.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    Point3::new(best.1.x * e.x, best.1.x * e.y, best.1.y)
}

/// Rounding slack of the lower-bound check: the reference's surface distance is realised by
/// two actual surface points, so it is never below the truth and `lower` may exceed it only
/// by rounding (1e-12 of the scene, far below the smallest gap tested, 1e-9).
pub const ROUNDING: f64 = 1e-12;

/// Whether `d`'s interval holds the reference distance `r`: `lower <= r` up to [`ROUNDING`]
/// (the reference is realised, never below the truth), `r <= upper` up to
/// [`REFERENCE_ERROR`].
pub fn brackets(d: &Distance, r: f64) -> bool {
    d.lower <= r + ROUNDING && r <= d.upper + REFERENCE_ERROR
}

/// Query `a` against `b` with default options and compare with the reference:
/// `lower <= reference` up to [`ROUNDING`] only (the reference is an upper estimate of the
/// truth), `reference <= upper` and `|value - reference| <= upper - lower` up to
/// [`REFERENCE_ERROR`]; an overlap claim needs a zero reference.
pub fn check_query(
    a: &Solid,
    b: &Solid,
    opts: &QueryOptions,
    label: &str,
) -> Result<(Distance, Reference), String> {
    let pos = a.relative_pose(b);
    let r = reference(
        a.profile.as_deref().unwrap(),
        b.profile.as_deref().unwrap(),
        &pos,
    );
    let d = distance(a, b, opts);
    let e = REFERENCE_ERROR;
    // Upper estimate of the truth: 0 when nested, else the realised surface distance.
    let truth_above = if r.nested { 0.0 } else { r.surface_distance };
    if d.lower > truth_above + ROUNDING {
        return Err(format!(
            "{label}: lower {} above the reference's realised distance {truth_above}",
            d.lower
        ));
    }
    if r.distance.is_nan() || r.distance > d.upper + e {
        return Err(format!(
            "{label}: reference {} (surface {}, nested {}) outside [{}, {}]",
            r.distance, r.surface_distance, r.nested, d.lower, d.upper
        ));
    }
    if (d.value - r.distance).abs() > d.upper - d.lower + e {
        return Err(format!(
            "{label}: value {} vs reference {}",
            d.value, r.distance
        ));
    }
    if d.overlap && r.distance > e {
        return Err(format!(
            "{label}: overlap claimed, reference {}",
            r.distance
        ));
    }
    Ok((d, r))
}
