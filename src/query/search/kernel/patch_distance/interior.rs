//! Case (a) of [`super`] for a toroidal patch: common normals through the major circle's
//! critical points against the other patch's core ([`crate::query::angles::radial_field`]), their feet and
//! the signs `l +- r1 +- r2` (paper section 3), with the continua that have closed forms (a
//! sphere centre on the other axis).

use super::*;

/// Field of the distance to the core of `patch` for mirror branch `s` (see `sweep`).
pub(super) fn core_field(patch: &Patch, s: f64) -> RadialField {
    match patch.core() {
        Core::Circle { r_major, z, .. } => RadialField {
            a: -2.0 * s * r_major,
            b: 1.0,
            c1: -2.0 * z,
            c2: 1.0,
        },
        Core::Line { n, .. } => RadialField {
            a: s * n.x,
            b: 0.0,
            c1: n.y,
            c2: 0.0,
        },
    }
}

/// Interior common normals with `t` a toroidal patch (frame T) and `o` any patch placed in
/// T's frame by `pos_to`. Emits (point on t, point on o) in T's frame; returns whether the
/// critical angles came from the sampled scan.
pub(super) fn interior_via_core(
    t: &Patch,
    o: &Patch,
    pos_to: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let Core::Circle { r_major, z, .. } = t.core() else {
        return false;
    };
    let mut sampled = false;
    let pos_ot = pos_to.inverse();
    // Major circle of t in o's frame.
    let major = ParamCircle::parallel(r_major, z, &pos_ot);
    let mut thetas = Vec::with_capacity(32);
    if r_major == 0.0 {
        thetas.push(0.0);
    } else {
        let exact = match (kernel, o.core()) {
            (Kernel::Binormals, Core::Line { n, .. }) => {
                let critical = line_field_critical(&major, n, &mut thetas);
                // Clustered angles are measured, but the answer is an upper bound only
                // (`angles::meridian_line`, "Clusters").
                sampled |= critical == FieldAngles::Clustered;
                critical != FieldAngles::Constant
                    || (n.x == 0.0 && {
                        // A horizontal major circle over a flat annulus: every angle is
                        // critical, and the common normals are vertical; the one whose
                        // foot is in the annulus (if any) comes from the closed form.
                        flat_annulus_angle(&major, o, &mut thetas);
                        true
                    })
            }
            _ => false,
        };
        if !exact {
            sampled = true;
            for s in [1.0, -1.0] {
                critical_angles(&major, &core_field(o, s), &mut thetas);
            }
        }
    }
    let mut feet = Vec::with_capacity(8);
    let mut pts = Vec::with_capacity(4);
    for &th in &thetas {
        let core_t = lift(Point2::new(r_major, z), &e_rho(th)); // in t's frame
        let core_o = pos_ot * core_t;
        feet.clear();
        o.critical_feet(&core_o, &mut feet);
        if r_major == 0.0 {
            sphere_centre_feet(t, pos_to, &core_o, &mut feet);
        }
        for f in &feet {
            let q = pos_to * f;
            let w = q - core_t;
            let n = w.norm();
            let dir = if n > 1e-300 {
                w / n
            } else {
                // q on the major circle: the common normal is the surface normal of o at q.
                pos_to.rotation * surface_normal(o, f)
            };
            pts.clear();
            t.points_on_normal_line(&core_t, &dir, &mut pts);
            for p in &pts {
                emit(*p, q);
            }
        }
    }
    sampled
}

/// Feet on `o` seen from the centre of the sphere patch `t` when that centre (`x`, o's
/// frame) lies on o's axis (`pos_to` places O in T's frame).
///
/// **Exactness.** Each critical foot `f` of `o` from a point on its axis lies on a parallel
/// of `o`, all of whose points are feet at the same distance `|f - x|`; the common normal
/// through a foot is the line from the sphere centre, and `t` keeps it when the direction's
/// latitude in T's frame lies in t's arc range (`sin phi` in `[s_lo, s_hi]`). Along the
/// parallel the direction's z component in T's frame is `(A + K cos(psi - psi0)) / |w|`,
/// so for each sign of the direction the kept feet form an interval of `psi`, found in
/// closed form; the foot at its middle is emitted (every kept foot gives the same
/// distance). No meridian is sampled.
fn sphere_centre_feet(
    t: &Patch,
    pos_to: &Isometry3<f64>,
    x: &Point3<f64>,
    feet: &mut Vec<Point3<f64>>,
) {
    if x.x.hypot(x.y) > 1e-13 * (1.0 + x.coords.norm()) {
        return;
    }
    let ProfileArc::Arc {
        phi_start, sweep, ..
    } = t.arc
    else {
        return;
    };
    let half_pi = std::f64::consts::FRAC_PI_2;
    let latitude = |phi: f64| phi.sin().atan2(phi.cos()).clamp(-half_pi, half_pi).sin();
    let (l0, l1) = (latitude(phi_start), latitude(phi_start + sweep));
    let (s_lo, s_hi) = (l0.min(l1), l0.max(l1));
    let core_t = pos_to * x;
    let (ex, ey) = (
        pos_to.rotation * Vector3::x(),
        pos_to.rotation * Vector3::y(),
    );
    let base: Vec<Point3<f64>> = feet.clone();
    for f in &base {
        let rho_f = f.x.hypot(f.y);
        let alpha = f.y.atan2(f.x);
        let w_len = (f - x).norm();
        let a = (pos_to * Point3::new(0.0, 0.0, f.z)).z - core_t.z;
        let (p, q) = (ex.z * rho_f, ey.z * rho_f);
        let k = p.hypot(q);
        let psi0 = q.atan2(p);
        for sgn in [1.0, -1.0] {
            // Direction sgn * w / |w| has z in [s_lo, s_hi]  <=>  w_z in [lo, hi].
            let (b0, b1) = (sgn * s_lo * w_len, sgn * s_hi * w_len);
            let (lo, hi) = (b0.min(b1).max(a - k), b0.max(b1).min(a + k));
            if lo > hi {
                continue;
            }
            let target = 0.5 * (lo + hi);
            let psi = if k > 0.0 {
                psi0 + ((target - a) / k).clamp(-1.0, 1.0).acos()
            } else {
                psi0
            };
            let rot = nalgebra::Rotation3::from_axis_angle(&Vector3::z_axis(), psi - alpha);
            feet.push(rot * f);
        }
    }
}

/// Unit surface normal (from the core side) of patch `o` at its point `f` (o's frame).
fn surface_normal(o: &Patch, f: &Point3<f64>) -> Vector3<f64> {
    let rho = f.x.hypot(f.y);
    let e = if rho > 0.0 {
        Vector3::new(f.x / rho, f.y / rho, 0.0)
    } else {
        Vector3::x()
    };
    let n2 = o.planar_normal(Point2::new(rho, f.z));
    e * n2.x + Vector3::z() * n2.y
}
