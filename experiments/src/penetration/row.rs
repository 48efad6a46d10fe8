//! One case's answer (a row of `penetration.csv`), its class, and the judgement of coal's depth
//! against the certified interval and the `verify` oracle.

use super::{COAL_EPA_TOLERANCE, TARGET_REL};
use nalgebra::Isometry3;
use revdist::query::penetration::LowerCertificate;
use revdist::rng::SplitMix64;
use verify::oracle::PlanarIndex;
use verify::penetration::oracle::{apart_at, common_point_bound};

/// What kind of contact a case is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Class {
    /// A ball against a model.
    Ball,
    /// Two models, pushed by at most 1 % of the size.
    Shallow,
    /// Two models, pushed deeper.
    Deep,
    /// Two convex models, compared with coal.
    Convex,
}

impl Class {
    pub(super) fn name(self) -> &'static str {
        match self {
            Class::Ball => "ball",
            Class::Shallow => "shallow",
            Class::Deep => "deep",
            Class::Convex => "convex",
        }
    }
    /// Whether the width target applies.
    pub(super) fn targeted(self) -> bool {
        matches!(self, Class::Ball | Class::Shallow)
    }
}

/// One case's answer.
pub(super) struct Row {
    pub(super) pair: String,
    pub(super) class: Class,
    pub(super) eps: f64,
    pub(super) level: f64,
    pub(super) push: f64,
    pub(super) size: f64,
    pub(super) pose: Isometry3<f64>,
    /// The depth interval (NaN when the solids were certified apart).
    pub(super) lower: f64,
    pub(super) upper: f64,
    pub(super) queries: usize,
    pub(super) probes: usize,
    /// Cells of the covering of translations (0 when it did not run).
    pub(super) cover_cells: usize,
    /// What certifies `lower` (`None` when the solids were certified apart).
    pub(super) certificate: Option<LowerCertificate>,
    pub(super) signed_us: f64,
    pub(super) distance_us: f64,
    /// Unit translation of B achieving `upper`, and the point of `lower`'s certificate.
    pub(super) direction: nalgebra::Vector3<f64>,
    pub(super) point: Option<nalgebra::Point3<f64>>,
    /// coal's depth (convex cases).
    pub(super) coal_depth: Option<f64>,
    pub(super) coal_us: Option<f64>,
    /// The oracle's verdict on a coal depth outside the interval.
    pub(super) coal_verdict: Option<CoalVerdict>,
}

/// What the oracle says of coal's depth (convex cases).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum CoalVerdict {
    /// Within `[lower - tol, upper + tol]`.
    Inside,
    /// Below the oracle's certified point bound (this value): coal's error.
    BelowCommonPoint(f64),
    /// Above a translation the oracle confirms separating: coal's error.
    AboveSeparation,
    /// Outside the interval and not refuted by the oracle: a violation.
    Unexplained,
}

impl Row {
    pub(super) fn width(&self) -> f64 {
        self.upper - self.lower
    }
    pub(super) fn target(&self) -> f64 {
        (4.0 * self.eps).max(TARGET_REL * self.lower)
    }
    pub(super) fn met(&self) -> bool {
        self.width() <= self.target()
    }
    pub(super) fn answered(&self) -> bool {
        self.lower.is_finite()
    }
    /// The name of `lower`'s certificate, as the CLI's JSON spells it (empty when apart).
    pub(super) fn certificate_name(&self) -> &'static str {
        self.certificate.map_or("", LowerCertificate::name)
    }
    pub(super) fn coal_tolerance(&self) -> f64 {
        let scene = 1.0 + self.pose.translation.vector.norm() + 2.0 * self.size;
        COAL_EPA_TOLERANCE + 1e-9 * scene
    }
    /// coal's depth outside the interval, by how much (0 inside).
    pub(super) fn coal_excess(&self) -> Option<f64> {
        let c = self.coal_depth?;
        Some((self.lower - c).max(c - self.upper).max(0.0))
    }
    pub(super) fn coal_outside(&self) -> bool {
        self.coal_excess()
            .is_some_and(|e| e > self.coal_tolerance())
    }
    pub(super) fn coal_violates(&self) -> bool {
        self.coal_verdict == Some(CoalVerdict::Unexplained)
    }
    /// The oracle's tolerance (`verify penetration`'s): `1e-9` of the scene.
    pub(super) fn oracle_tolerance(&self) -> f64 {
        1e-9 * (1.0 + self.pose.translation.vector.norm() + 2.0 * self.size)
    }
    /// Judges coal's depth against the interval and, outside it, the oracle on the exact
    /// profiles `ia`, `ib`.
    pub(super) fn judge_coal(&self, ia: &PlanarIndex, ib: &PlanarIndex) -> Option<CoalVerdict> {
        let c = self.coal_depth?;
        if !self.coal_outside() {
            return Some(CoalVerdict::Inside);
        }
        let tol = self.oracle_tolerance();
        if c < self.lower {
            let seeds: Vec<_> = self.point.into_iter().collect();
            let mut rng = SplitMix64(self.pose.translation.vector.x.to_bits());
            let lo = common_point_bound(ia, ib, &self.pose, &seeds, 0.5 * self.size, 200, &mut rng);
            if c < lo - tol {
                return Some(CoalVerdict::BelowCommonPoint(lo));
            }
        } else if self.direction.norm() > 0.0 {
            let t = self.direction * (self.upper + tol);
            if apart_at(ia, ib, &self.pose, &t) == Some(true) {
                return Some(CoalVerdict::AboveSeparation);
            }
        }
        Some(CoalVerdict::Unexplained)
    }
}
