//! Case (c) of [`super`]: two boundary parallels, the critical points of the distance from
//! one circle to the other.

use super::*;

/// Closest points between the parallel `ea` of A and the parallel `eb` of B.
pub(super) fn parallel_pair(
    ea: Point2<f64>,
    eb: Point2<f64>,
    pos_ab: &Isometry3<f64>,
    kernel: Kernel,
    emit: &mut dyn FnMut(Point3<f64>, Point3<f64>),
) -> bool {
    let closest_on_a = |x: &Point3<f64>| {
        let rho = x.x.hypot(x.y);
        let e = if rho > 0.0 {
            Vector3::new(x.x / rho, x.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        lift(ea, &e)
    };
    if eb.x.abs() <= POINT_SNAP * (1.0 + eb.y.abs()) {
        let x = pos_ab * Point3::new(0.0, 0.0, eb.y);
        emit(closest_on_a(&x), x);
        return false;
    }
    let circle = ParamCircle::parallel(eb.x, eb.y, pos_ab);
    if ea.x.abs() <= POINT_SNAP * (1.0 + ea.y.abs()) {
        // A's parallel is a point: closest point of B's circle to it.
        let pa = Point3::new(0.0, 0.0, ea.y);
        let pos_ba = pos_ab.inverse();
        let local = pos_ba * pa;
        let rho = local.x.hypot(local.y);
        let e = if rho > 0.0 {
            Vector3::new(local.x / rho, local.y / rho, 0.0)
        } else {
            Vector3::x()
        };
        emit(pa, pos_ab * lift(eb, &e));
        return false;
    }
    if kernel == Kernel::Binormals {
        let (p, q) = parallel_pair_closest((ea.x, ea.y), (eb.x, eb.y), pos_ab);
        emit(p, q);
        return false;
    }
    let field = RadialField {
        a: -2.0 * ea.x,
        b: 1.0,
        c1: -2.0 * ea.y,
        c2: 1.0,
    };
    let mut thetas = Vec::with_capacity(24);
    critical_angles(&circle, &field, &mut thetas);
    for &th in &thetas {
        let x = circle.point(th);
        emit(closest_on_a(&x), x);
    }
    true
}
