//! Case (b) of [`super`]: a boundary parallel of one patch against the other patch: a cheap
//! lower bound first ([`parallel_lower_bound`], closed forms outside a torus), then the
//! critical angles along the parallel and their feet, with the flat-annulus and sampled
//! continua.

use super::*;

/// Fast exact path of [`boundary_vs_patch`] for a toroidal patch `o` (no degree-8
/// solve in the common case). Let `m` be the minimum distance between the parallel `G` and
/// the patch's major circle `M` (the circle module's certified minimum) and `x` its point
/// on `G`. When `m` exceeds the tube radius `r`, `G` lies outside the solid torus (no
/// crossing), every point of `G` is at least `m - r` from the torus surface, hence from
/// the patch; if the patch's closest point `c` to `x` is at distance `m - r` (up to
/// [`FAST_PATH_REL`] of the scale), `(x, c)` realises that bound and is the exact answer.
/// Otherwise `None`: the minimum lies where the torus' closest point is off the patch.
fn parallel_torus_fast(
    e: Point2<f64>,
    o: &Patch,
    pos_og: &Isometry3<f64>,
) -> Option<(Point3<f64>, Point3<f64>)> {
    let Core::Circle {
        r_major,
        z,
        r_minor,
    } = o.core()
    else {
        return None;
    };
    if r_major == 0.0 {
        return None;
    }
    let g = parallel_circle(e.x, e.y, pos_og);
    let core = parallel_circle(r_major, z, &Isometry3::identity());
    let m = min_distance(&g, &core);
    let scale = 1.0 + g.center.coords.norm() + g.radius + r_major.abs() + z.abs() + r_minor;
    let tol = FAST_PATH_REL * scale;
    let bound = m.distance - r_minor;
    if bound <= tol {
        return None;
    }
    let (d, c) = o.point_distance(&m.point_a);
    (d <= bound + tol).then_some((m.point_a, c))
}

/// A lower bound of the distance from the boundary parallel `e` (frame G, placed in O's
/// frame by `pos_og`) to the patch `o`, from circle/circle minima only: the parallel against
/// the solid torus of the disk around `o`'s piece and, for an arc, of the arc's own circle
/// (both contain the patch; [`crate::query::bound::node_pair`] and [`crate::query::search::leaf::patch_lower`] give the proofs),
/// after the closed-form hull bound of [`crate::query::bound::hull_bound::hull_bound`].
/// Returns early once a bound reaches `enough`. A parallel that is a point gets no bound
/// (its exact distance is cheaper).
pub(super) fn parallel_lower_bound(
    e: Point2<f64>,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    enough: f64,
) -> f64 {
    if e.x.abs() <= POINT_SNAP * (1.0 + e.y.abs()) {
        return f64::NEG_INFINITY;
    }
    // The convex-hull bound first (closed form): the parallel against the hull of the
    // patch's chord frustum grown by its sagitta.
    let m = o.arc.point_at(0.5);
    let dir = pos_og * Point3::new(0.0, 0.0, e.y) - Point3::new(0.0, 0.0, m.y);
    let parallel = ProfileArc::Segment { start: e, end: e };
    let hull = hull_bound_until(&o.arc, &parallel, pos_og, &dir, enough);
    if hull >= enough {
        return hull;
    }
    let parallel = Disk {
        center: e,
        radius: 0.0,
    };
    let around = hull.max(node_pair_bound(
        &o.arc.bounding_disk(),
        &parallel,
        pos_og,
        BoundKind::Torus,
        enough,
        None,
    ));
    match o.arc {
        ProfileArc::Arc { center, radius, .. } if around < enough => {
            let tube = Disk { center, radius };
            around.max(node_pair_bound(
                &tube,
                &parallel,
                pos_og,
                BoundKind::Torus,
                enough,
                None,
            ))
        }
        _ => around,
    }
}

/// The boundary parallel `e` (meridian coordinates of frame G) against patch `o` (frame O);
/// `pos_og` places G in O. Emits (point on the parallel, point on o) in O's frame.
pub(super) fn boundary_vs_patch(
    e: Point2<f64>,
    o: &Patch,
    pos_og: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let mut feet = Vec::with_capacity(8);
    // The closest point of `o` to `x` and every critical foot.
    let mut emit_feet = |x: Point3<f64>| {
        let (_, c) = o.point_distance(&x);
        emit(x, c);
        feet.clear();
        o.critical_feet(&x, &mut feet);
        for f in &feet {
            emit(x, *f);
        }
    };
    if e.x.abs() <= POINT_SNAP * (1.0 + e.y.abs()) {
        emit_feet(pos_og * Point3::new(0.0, 0.0, e.y));
        return false;
    }
    if kernel == Kernel::Binormals {
        if let Some((x, c)) = parallel_torus_fast(e, o, pos_og) {
            emit(x, c);
            return false;
        }
    }
    let mut thetas = Vec::with_capacity(48);
    let circle = ParamCircle::parallel(e.x, e.y, pos_og);
    // A cone's angles that the solver could only resolve as clusters: measured like the
    // rest, but the answer is then an upper bound only (`angles::meridian_line`, "Clusters").
    let mut clustered = false;
    let exact = match (kernel, o.core()) {
        (Kernel::Binormals, Core::Circle { .. }) if circle.is_coaxial() => {
            // Coaxial with the torus: the distance to the patch is the same at every angle.
            thetas.push(0.0);
            true
        }
        (Kernel::Binormals, Core::Circle { r_major, z, .. }) => {
            circle_torus_critical(&circle, r_major, z, &mut thetas) && {
                // Crossings of the torus lie between consecutive critical angles.
                let level = surface_level(o);
                let n_crit = thetas.len();
                let mut crossings = Vec::new();
                for s in [1.0, -1.0] {
                    let f = core_field(o, s);
                    level_crossings(&circle, &f, level, &thetas[..n_crit], &mut crossings);
                }
                thetas.extend(crossings);
                true
            }
        }
        (Kernel::Binormals, Core::Line { n, c }) => {
            let solve = match line_field_critical(&circle, n, &mut thetas) {
                FieldAngles::Constant => FieldAngles::Constant,
                critical => critical.and(line_field_levels(&circle, n, c, &mut thetas)),
            };
            clustered = solve == FieldAngles::Clustered;
            if solve == FieldAngles::Constant {
                thetas.clear();
                // The line field is constant along the circle: a flat annulus and a circle
                // in a parallel plane (closed form), else a circle coaxial with the cone or
                // cylinder, whose distance to the patch is the same at every angle.
                if n.x == 0.0 {
                    flat_annulus_angle(&circle, o, &mut thetas);
                } else {
                    thetas.push(0.0);
                }
            }
            true
        }
        _ => false,
    };
    if !exact {
        sampled_boundary_angles(&circle, o, &mut thetas);
    }
    for &th in &thetas {
        emit_feet(circle.point(th));
    }
    !exact || clustered
}

/// The closest angle of a circle lying in a plane `z = const` (frame O) to the flat annulus
/// `o` (a horizontal segment revolved: `z = z_o`, `rho` in `[r0, r1]`).
///
/// **Exactness.** The squared distance from a point to the annulus is
/// `(z - z_o)^2 + dist(rho, [r0, r1])^2`; along the circle `z` is constant and
/// `rho(theta)^2 = d^2 + r^2 + 2 d r cos(theta - theta0)` (`d` the centre's distance to the
/// axis, `r` the radius) sweeps `[|d - r|, d + r]` continuously. The minimum is at the
/// `rho` of that interval nearest to `[r0, r1]` (the middle of their overlap when they
/// overlap), whose angle is solved in closed form.
pub(super) fn flat_annulus_angle(circle: &ParamCircle, o: &Patch, out: &mut Vec<f64>) {
    let (a, b) = (o.arc.start(), o.arc.end());
    let (r0, r1) = (a.x.min(b.x), a.x.max(b.x));
    let (ox, oy) = (circle.o.x, circle.o.y);
    let (pu, pv) = (
        ox * circle.u.x + oy * circle.u.y,
        ox * circle.v.x + oy * circle.v.y,
    );
    let amp = pu.hypot(pv); // d r
    let base = ox * ox + oy * oy + circle.radius() * circle.radius(); // d^2 + r^2
    if amp == 0.0 {
        out.push(0.0);
        return;
    }
    let (lo, hi) = (
        (base - 2.0 * amp).max(0.0).sqrt(),
        (base + 2.0 * amp).sqrt(),
    );
    let target = if hi < r0 {
        hi
    } else if lo > r1 {
        lo
    } else {
        0.5 * (lo.max(r0) + hi.min(r1))
    };
    let theta0 = pv.atan2(pu);
    let c = ((target * target - base) / (2.0 * amp)).clamp(-1.0, 1.0);
    out.push(theta0 + c.acos());
}

/// Critical and crossing angles of the parallel `circle` against `o` by the sampled scan.
fn sampled_boundary_angles(circle: &ParamCircle, o: &Patch, thetas: &mut Vec<f64>) {
    for s in [1.0, -1.0] {
        critical_angles(circle, &core_field(o, s), thetas);
    }
    // Crossings of the extended surface: F = level.
    let level = surface_level(o);
    for s in [1.0, -1.0] {
        level_angles(circle, &core_field(o, s), level, thetas);
    }
}

/// The value of [`core_field`] (either branch) on the extended surface of `o`.
fn surface_level(o: &Patch) -> f64 {
    match o.core() {
        Core::Circle {
            r_major,
            z,
            r_minor,
        } => r_minor * r_minor - r_major * r_major - z * z,
        Core::Line { c, .. } => c,
    }
}
