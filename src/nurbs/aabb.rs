//! The axis-aligned box of the (rho, z) plane that bounds a curve's control points.

use nalgebra::Point2;

/// Axis-aligned box in the (rho, z) plane.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb2 {
    /// Lower-left corner (min rho, min z).
    pub min: Point2<f64>,
    /// Upper-right corner (max rho, max z).
    pub max: Point2<f64>,
}

impl Aabb2 {
    /// The smallest box holding all `points`; `None` when there are none.
    pub fn from_points<'a>(points: impl IntoIterator<Item = &'a Point2<f64>>) -> Option<Self> {
        let mut it = points.into_iter();
        let first = *it.next()?;
        Some(it.fold(
            Aabb2 {
                min: first,
                max: first,
            },
            |b, p| b.including(*p),
        ))
    }

    /// This box grown to hold `p`.
    pub fn including(self, p: Point2<f64>) -> Self {
        Aabb2 {
            min: Point2::new(self.min.x.min(p.x), self.min.y.min(p.y)),
            max: Point2::new(self.max.x.max(p.x), self.max.y.max(p.y)),
        }
    }

    /// The smallest box holding both.
    pub fn union(self, other: Aabb2) -> Self {
        self.including(other.min).including(other.max)
    }

    /// Length of the diagonal.
    pub fn diagonal(&self) -> f64 {
        (self.max - self.min).norm()
    }
}
