//! Circle B expressed in circle A's frame (A at the origin, normal +z, angle 0 along +x),
//! scaled so the configuration has unit size.

use super::Circle3;
use nalgebra::Vector3;

/// Circle B in A's normalised frame. Lengths are divided by `scale`.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LocalPair {
    /// A's radius / scale.
    pub ra: f64,
    /// B's centre, u-axis, v-axis and radius / scale in A's frame.
    pub c: Vector3<f64>,
    pub u: Vector3<f64>,
    pub v: Vector3<f64>,
    pub rb: f64,
    /// max(ra, rb, |Cb - Ca|) in world units (> 0).
    pub scale: f64,
}

impl LocalPair {
    /// Expresses `b` in `a`'s frame. Returns `None` when the configuration has zero size
    /// (both circles are the same point).
    pub fn new(a: &Circle3, b: &Circle3) -> Option<Self> {
        let ua = a.u_axis.into_inner();
        let va = a.v_axis();
        let na = a.normal.into_inner();
        let to_local = |w: Vector3<f64>| Vector3::new(w.dot(&ua), w.dot(&va), w.dot(&na));
        let dc = b.center - a.center;
        let scale = a.radius.max(b.radius).max(dc.norm());
        if scale == 0.0 || !scale.is_finite() {
            return None;
        }
        let inv = 1.0 / scale;
        Some(Self {
            ra: a.radius * inv,
            c: to_local(dc) * inv,
            u: to_local(b.u_axis.into_inner()),
            v: to_local(b.v_axis()),
            rb: b.radius * inv,
            scale,
        })
    }

    /// A(phi) in the local frame.
    #[inline]
    pub fn pa(&self, phi: f64) -> Vector3<f64> {
        let (s, c) = phi.sin_cos();
        Vector3::new(self.ra * c, self.ra * s, 0.0)
    }

    /// B(theta) in the local frame.
    #[inline]
    pub fn pb(&self, theta: f64) -> Vector3<f64> {
        let (s, c) = theta.sin_cos();
        self.c + self.rb * (c * self.u + s * self.v)
    }

    /// Distance from B(theta) to circle A (local units) and the angle of the nearest point.
    #[inline]
    pub fn dist_b_to_a(&self, theta: f64) -> (f64, f64) {
        let q = self.pb(theta);
        let rho = q.x.hypot(q.y);
        let phi = if rho == 0.0 { 0.0 } else { q.y.atan2(q.x) };
        (q.z.hypot(rho - self.ra), phi)
    }
}

impl LocalPair {
    /// A unit-scale placeholder frame (for configurations of zero size).
    pub fn unit() -> Self {
        Self {
            ra: 0.0,
            c: Vector3::zeros(),
            u: Vector3::x(),
            v: Vector3::y(),
            rb: 0.0,
            scale: 1.0,
        }
    }
}
