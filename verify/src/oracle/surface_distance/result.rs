//! What the oracle found for a pair of posed solids: the realised upper estimate, the lower
//! estimate and the inside census (module documentation of [`super`]).

use nalgebra::Point3;

/// What the oracle found for a pair of posed solids (points in A's frame).
#[derive(Debug, Clone)]
pub struct OracleResult {
    /// Distance of a realised pair of surface points (>= the surface distance).
    pub upper: f64,
    /// Lower estimate of the surface distance (>= 0).
    pub lower: f64,
    /// The realised pair: on A's surface and on B's surface, in A's frame.
    pub point_a: Point3<f64>,
    pub point_b: Point3<f64>,
    /// Most negative conservative signed distance found (a sample of one surface inside the
    /// other solid at depth `-min_signed`); `+inf` when none was inside.
    pub min_signed: f64,
    /// That deepest sample, in A's frame: a point on one boundary inside the other solid (a
    /// certificate of overlap when deeper than the margin).
    pub deep_point: Option<Point3<f64>>,
    /// Some sample of A's surface is certainly inside B.
    pub a_in_b: bool,
    /// Some sample of B's surface is certainly inside A.
    pub b_in_a: bool,
    /// Cells evaluated (both directions).
    pub cells: usize,
    /// Local minimisations run.
    pub refinements: usize,
    /// The branch and bound stopped on its budget.
    pub budget_hit: bool,
}

impl OracleResult {
    /// The solids certainly overlap (a boundary sample inside the other solid).
    pub fn overlap(&self) -> bool {
        self.a_in_b || self.b_in_a
    }

    /// Upper estimate of the distance between the *solids* (0 when overlapping).
    pub fn solid_upper(&self) -> f64 {
        if self.overlap() {
            0.0
        } else {
            self.upper
        }
    }

    /// Lower estimate of the distance between the solids.
    pub fn solid_lower(&self) -> f64 {
        if self.overlap() {
            0.0
        } else {
            self.lower
        }
    }

    /// Signed gap: the surface distance when apart, minus the penetration depth found when
    /// overlapping.
    pub fn gap(&self) -> f64 {
        if self.overlap() {
            self.min_signed.min(0.0)
        } else {
            self.upper
        }
    }
}
