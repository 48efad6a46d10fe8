//! Case (a) of [`super`] for two straight pieces (cones): common normals from the Gauss
//! images' latitude circles, parallel axes and flat disks (annuli) handled explicitly.
//!
//! **Conditioning.** The solve is exact up to rounding only away from three degenerate
//! configurations, where a rounding error of the direction is amplified until a common
//! normal is missed or measured off its place (campaign cases: two nearly flat annuli, a
//! nearly flat cone against one with an axis 4.6e-6 rad off, the kernel 6e-10 above a
//! crossing). There the answer is marked sampled and the caller subdivides
//! (`docs/verification.md`, "Crossing lenses"):
//! * axes nearly parallel but not coaxial-parallel: the latitude equations divide by
//!   `1 - k^2` ([`CONE_AXES_CONDITION`]);
//! * latitude circles nearly tangent: the direction moves by `sqrt` of the rounding of
//!   `rem` ([`CONE_TANGENCY`]);
//! * a nearly flat cone: the radial direction of a normal divides by `n_rho`
//!   ([`CONE_FLATNESS`]).

use super::*;

/// `1 - k^2` (`k` the cosine between the axes) below which non-parallel axes count as
/// nearly parallel: the latitude solve loses `eps / (1 - k^2)`, 1e-10 at this value.
const CONE_AXES_CONDITION: f64 = 1e-6;

/// `|1 - |base|^2|` below which the latitude circles count as nearly tangent: the direction
/// then moves by about `sqrt(eps / rem)`-amplified rounding, 1e-12 at this value.
const CONE_TANGENCY: f64 = 1e-8;

/// `|n_rho|` below which a straight piece that is not exactly flat counts as nearly flat:
/// its radial direction for a normal divides rounding by `n_rho`, 1e-12 at this value.
const CONE_FLATNESS: f64 = 1e-4;

/// Interior common normals of two straight pieces (cones, cylinders, annuli) via their
/// Gauss images (circles of latitude). Emits (point on a, point on b) in A's frame; returns
/// whether the configuration is ill-conditioned (module docs, "Conditioning"): the pairs
/// are then realised but not proven complete.
pub(super) fn cone_cone(
    a: &Patch,
    b: &Patch,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let (ProfileArc::Segment { start: a0, end: a1 }, ProfileArc::Segment { start: b0, end: b1 }) =
        (a.arc, b.arc)
    else {
        return false;
    };
    let Core::Line { n: na, .. } = a.core() else {
        return false;
    };
    let Core::Line { n: nb, .. } = b.core() else {
        return false;
    };
    let nearly_flat = |n: nalgebra::Vector2<f64>| n.x != 0.0 && n.x.abs() < CONE_FLATNESS;
    let mut ill_conditioned = nearly_flat(na) || nearly_flat(nb);
    let ez = Vector3::z();
    let axis_b = pos_ab.rotation * ez;
    let k = axis_b.z;
    // Generator of a straight piece at radial direction e (frame-local), as a 3-D segment.
    let gen = |p0: Point2<f64>, p1: Point2<f64>, e: &Vector3<f64>| (lift(p0, e), lift(p1, e));
    let mut try_dir = |dir: Vector3<f64>| {
        // Radial directions where a's (resp. b's) normal is +-dir.
        let ea = radial_for_normal(na, &dir);
        let dir_b = pos_ab.inverse_transform_vector(&dir);
        let eb = radial_for_normal(nb, &dir_b);
        for e1 in ea.iter().flatten() {
            for e2 in eb.iter().flatten() {
                let (p0, p1) = gen(a0, a1, e1);
                let (q0, q1) = gen(b0, b1, e2);
                let (q0, q1) = (pos_ab * q0, pos_ab * q1);
                segment_common_normal(p0, p1, q0, q1, &dir, emit);
            }
        }
    };
    if 1.0 - k.abs() > AXIS_TOLERANCE {
        // Latitudes: dir . ez = sa * na.y, dir . axis_b = sb * nb.y.
        let m = ez.cross(&axis_b);
        let det = 1.0 - k * k;
        ill_conditioned |= det < CONE_AXES_CONDITION;
        for sa in [1.0, -1.0] {
            for sb in [1.0, -1.0] {
                let (al, be) = (sa * na.y, sb * nb.y);
                let lam = (al - be * k) / det;
                let mu = (be - al * k) / det;
                let base = ez * lam + axis_b * mu;
                let rem = 1.0 - base.norm_squared();
                ill_conditioned |= rem.abs() < CONE_TANGENCY;
                if rem < -1e-12 {
                    continue;
                }
                let nu = rem.max(0.0).sqrt() / det.sqrt();
                for sn in [1.0, -1.0] {
                    try_dir(base + m * (sn * nu));
                    if nu == 0.0 {
                        break;
                    }
                }
            }
        }
    } else {
        // Parallel axes: common normals lie in the plane of both axes (or are the axis
        // direction for two flat annuli, handled by the annulus overlap below).
        let off = pos_ab.translation.vector;
        let w = Vector3::new(off.x, off.y, 0.0);
        if w.norm() > 0.0 {
            let w = w.normalize();
            for sw in [1.0, -1.0] {
                for sz in [1.0, -1.0] {
                    let dir = w * (sw * na.x) + ez * (sz * na.y);
                    if dir.norm() > 0.0 {
                        try_dir(dir.normalize());
                    }
                }
            }
        }
        if na.x.abs() < 1e-15 && nb.x.abs() < 1e-15 {
            annulus_overlap(a0, a1, b0, b1, pos_ab, emit);
        }
    }
    // A flat annulus of one piece against a generator parallel to its plane.
    if na.x.abs() < 1e-15 {
        disk_vs_generators(a0, a1, b0, b1, pos_ab, emit);
    }
    if nb.x.abs() < 1e-15 {
        let pos_ba = pos_ab.inverse();
        disk_vs_generators(b0, b1, a0, a1, &pos_ba, &mut |q, p| {
            emit(pos_ab * p, pos_ab * q)
        });
    }
    ill_conditioned
}

/// Radial directions `e` (horizontal unit vectors) where the normal line of a straight piece
/// with planar normal `n` is parallel to `dir` (frame-local); none for flat annuli.
fn radial_for_normal(n: nalgebra::Vector2<f64>, dir: &Vector3<f64>) -> [Option<Vector3<f64>>; 2] {
    let mut out = [None, None];
    if n.x.abs() < 1e-15 {
        return out;
    }
    for (i, s) in [1.0, -1.0].into_iter().enumerate() {
        // s * dir = n.x e + n.y ez  =>  e = (s dir - n.y ez) / n.x
        if (s * dir.z - n.y).abs() > 1e-9 {
            continue;
        }
        let e = Vector3::new(s * dir.x / n.x, s * dir.y / n.x, 0.0);
        let en = e.norm();
        if en > 0.0 {
            out[i] = Some(e / en);
        }
    }
    out
}

/// Closest points of two segments when both are interior and the connecting vector is
/// parallel to `dir`; for parallel segments, the middle of their overlap.
fn segment_common_normal(
    p0: Point3<f64>,
    p1: Point3<f64>,
    q0: Point3<f64>,
    q1: Point3<f64>,
    dir: &Vector3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (d1, d2, r) = (p1 - p0, q1 - q0, p0 - q0);
    let (a, e, f) = (d1.dot(&d1), d2.dot(&d2), d2.dot(&r));
    let (b, c) = (d1.dot(&d2), d1.dot(&r));
    let den = a * e - b * b;
    if den > 1e-14 * a * e {
        let s = (b * f - c * e) / den;
        let t = (a * f - b * c) / den;
        if (-1e-9..=1.0 + 1e-9).contains(&s) && (-1e-9..=1.0 + 1e-9).contains(&t) {
            emit(p0 + d1 * s.clamp(0.0, 1.0), q0 + d2 * t.clamp(0.0, 1.0));
        }
    } else if a > 0.0 {
        // Parallel generators: offset orthogonal to the lines must be parallel to dir.
        let u = d1 / a.sqrt();
        let (t0, t1) = ((q0 - p0).dot(&u), (q1 - p0).dot(&u));
        let (lo, hi) = (t0.min(t1).max(0.0), t0.max(t1).min(a.sqrt()));
        if lo <= hi {
            let tm = 0.5 * (lo + hi);
            let p = p0 + u * tm;
            let s = if (t1 - t0).abs() > 0.0 {
                (tm - t0) / (t1 - t0)
            } else {
                0.0
            };
            let q = q0 + d2 * s.clamp(0.0, 1.0);
            let _ = dir;
            emit(p, q);
        }
    }
}

/// Two flat annuli with parallel axes: a point in the overlap of their projections.
fn annulus_overlap(
    a0: Point2<f64>,
    a1: Point2<f64>,
    b0: Point2<f64>,
    b1: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (ra0, ra1) = (a0.x.min(a1.x), a0.x.max(a1.x));
    let (rb0, rb1) = (b0.x.min(b1.x), b0.x.max(b1.x));
    let cb = pos_ab * Point3::new(0.0, 0.0, b0.y);
    let w = nalgebra::Vector2::new(cb.x, cb.y);
    let d = w.norm();
    let u = if d > 0.0 {
        w / d
    } else {
        nalgebra::Vector2::x()
    };
    // Points on the line of centres: x = t u, |x| = |t|, |x - w| = |t - d|.
    let cands = [
        ra0,
        ra1,
        -ra0,
        -ra1,
        d + rb0,
        d - rb0,
        d + rb1,
        d - rb1,
        0.5 * d,
    ];
    for t in cands {
        let ta = t.abs();
        let tb = (t - d).abs();
        if ta >= ra0 - 1e-12 && ta <= ra1 + 1e-12 && tb >= rb0 - 1e-12 && tb <= rb1 + 1e-12 {
            let p = Point3::new(t * u.x, t * u.y, a0.y);
            let q = Point3::new(t * u.x, t * u.y, cb.z);
            emit(p, q);
            return;
        }
    }
}

/// A flat annulus `(a0, a1)` (frame A, horizontal) against the generators of the straight
/// piece `(b0, b1)` whose normal is the annulus normal: such a generator is parallel to the
/// annulus plane, so each of its points over the annulus is on a common normal.
/// Emits (point on annulus, point on generator) in A's frame.
fn disk_vs_generators(
    a0: Point2<f64>,
    a1: Point2<f64>,
    b0: Point2<f64>,
    b1: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) {
    let (ra0, ra1) = (a0.x.min(a1.x), a0.x.max(a1.x));
    let db = b1 - b0;
    let nb = nalgebra::Vector2::new(-db.y, db.x).normalize();
    let ez_b = pos_ab.inverse_transform_vector(&Vector3::z());
    for e in radial_for_normal(nb, &ez_b).iter().flatten() {
        let (q0, q1) = (pos_ab * lift(b0, e), pos_ab * lift(b1, e));
        let d = q1 - q0;
        let (p0h, dh) = (
            nalgebra::Vector2::new(q0.x, q0.y),
            nalgebra::Vector2::new(d.x, d.y),
        );
        let a2 = dh.norm_squared();
        let tmin = if a2 > 0.0 {
            (-p0h.dot(&dh) / a2).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let mut ts = vec![tmin, 0.0, 1.0, 0.5];
        // Radius crossings ra0, ra1 along the segment.
        for rr in [ra0, ra1] {
            let (qa, qb, qc) = (a2, 2.0 * p0h.dot(&dh), p0h.norm_squared() - rr * rr);
            let disc = qb * qb - 4.0 * qa * qc;
            if qa > 0.0 && disc >= 0.0 {
                ts.push((-qb - disc.sqrt()) / (2.0 * qa));
                ts.push((-qb + disc.sqrt()) / (2.0 * qa));
            }
        }
        for t in ts {
            if !(0.0..=1.0).contains(&t) {
                continue;
            }
            let x = q0 + d * t;
            let r = x.x.hypot(x.y);
            if r >= ra0 * (1.0 - 1e-12) && r <= ra1 * (1.0 + 1e-12) + 1e-300 {
                emit(Point3::new(x.x, x.y, a0.y), x);
            }
        }
    }
}
