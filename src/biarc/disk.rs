//! Disks of the (rho, z) half-plane: the bounding volumes of the profile's pieces. Revolved
//! about the axis a disk is a solid torus (or a ball, when it reaches the axis), the bounding
//! volume of the hierarchy's nodes (paper section 4.1). Both the biarc trees and the
//! solid's hierarchy ([`crate::bvh`]) use this one type.

use nalgebra::Point2;

/// A disk in the (rho, z) half-plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Disk {
    /// Centre.
    pub center: Point2<f64>,
    /// Radius.
    pub radius: f64,
}

impl Disk {
    /// Smallest disk containing both disks.
    pub fn union(&self, o: &Disk) -> Disk {
        let d = (o.center - self.center).norm();
        if d + o.radius <= self.radius {
            return *self;
        }
        if d + self.radius <= o.radius {
            return *o;
        }
        let r = 0.5 * (d + self.radius + o.radius);
        let t = (r - self.radius) / d;
        Disk {
            center: self.center + (o.center - self.center) * t,
            radius: r * (1.0 + 4.0 * f64::EPSILON),
        }
    }

    /// The disk grown by `eps`.
    pub fn inflated(&self, eps: f64) -> Disk {
        Disk {
            center: self.center,
            radius: self.radius + eps,
        }
    }
}
