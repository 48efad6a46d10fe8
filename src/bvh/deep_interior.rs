//! The deep interior of a solid as data: interior meridian points with their clearance and
//! the inscribed ball or solid torus they span, kept in the tree once computed. The points
//! are found and certified in [`super::inscribed`]; this file holds only what the tree
//! stores, so that the tree needs nothing of the containment tests that compute it.

use super::offset_solid::OffsetSolid;
use nalgebra::Point2;
use std::sync::OnceLock;

/// The deep interior of one solid (module doc).
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DeepInterior {
    /// Interior meridian points with their clearance from the approximating chain (capped at
    /// a quarter of the root disk's radius), deepest first; among points at the
    /// cap, the nearest to the root disk's centre first.
    pub points: Vec<(Point2<f64>, f64)>,
    /// The ball or solid torus the deepest point spans, when its clearance exceeds the
    /// tree's eps.
    pub inscribed: Option<OffsetSolid>,
}

/// A lazily computed [`DeepInterior`]: a function of the tree, so it takes no part in
/// comparisons (a tree whose cache is filled equals one whose cache is not).
#[derive(Debug, Clone, Default)]
pub struct DeepCache(OnceLock<DeepInterior>);

impl DeepCache {
    /// The cached value, computed by `init` on first use.
    pub fn get_or_init(&self, init: impl FnOnce() -> DeepInterior) -> &DeepInterior {
        self.0.get_or_init(init)
    }
}

impl PartialEq for DeepCache {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}
