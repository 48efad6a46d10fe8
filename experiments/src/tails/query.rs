//! The queries: their configuration kinds, their draws before placement, a placed query with
//! its reproducer command line, and a timed query.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

/// The configurations.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub(super) enum Kind {
    Random,
    Coaxial,
    Flipped,
    Identical,
    CupRest,
    Nested,
}

pub(super) const DEGENERATE_KINDS: [Kind; 5] = [
    Kind::Coaxial,
    Kind::Flipped,
    Kind::Identical,
    Kind::CupRest,
    Kind::Nested,
];

impl Kind {
    pub(super) fn name(self) -> &'static str {
        match self {
            Kind::Random => "random",
            Kind::Coaxial => "coaxial",
            Kind::Flipped => "flipped",
            Kind::Identical => "identical",
            Kind::CupRest => "cup_rest",
            Kind::Nested => "nested",
        }
    }
}

/// A query before placement.
#[derive(Debug, Clone)]
pub(super) struct Spec {
    pub(super) index: usize,
    pub(super) kind: Kind,
    pub(super) eps: f64,
    pub(super) tol0: bool,
    pub(super) seed: u64,
}

/// A placed query.
#[derive(Debug, Clone)]
pub(super) struct Placed {
    pub(super) spec: Spec,
    pub(super) a: String,
    pub(super) b: String,
    /// The gap (random, stacks, cup, nested: placed distance; identical: the offset).
    pub(super) gap: f64,
    /// B's pose as the reproducer writes it: translation and quaternion [w, x, y, z].
    pub(super) translation: [f64; 3],
    pub(super) rotation: [f64; 4],
}

impl Placed {
    /// The pose as `revdist distance` builds it from the reproducer's numbers (printed in
    /// full, so they parse back to the same bits).
    pub(super) fn pose(&self) -> Isometry3<f64> {
        let [w, x, y, z] = self.rotation;
        Isometry3::from_parts(
            Translation3::from(Vector3::from(self.translation)),
            UnitQuaternion::from_quaternion(Quaternion::new(w, x, y, z)),
        )
    }

    pub(super) fn reproducer(&self) -> String {
        let [tx, ty, tz] = self.translation;
        let [w, x, y, z] = self.rotation;
        format!(
            "revdist distance {} {} --eps {:e}{} --json --pose-b \
             '{{\"translation\":[{tx:?},{ty:?},{tz:?}],\"rotation\":[{w:?},{x:?},{y:?},{z:?}]}}'",
            self.a,
            self.b,
            self.spec.eps,
            if self.spec.tol0 { " --tolerance 0" } else { "" },
        )
    }

    /// Exact models, freeform, M_t (either model), or degenerate (any kind but random).
    pub(super) fn family(&self) -> &'static str {
        let any = |f: fn(&str) -> bool| f(&self.a) || f(&self.b);
        if self.spec.kind != Kind::Random {
            "degenerate"
        } else if any(|n| n.starts_with(revdist::models::MORPH_PREFIX)) {
            "M_t"
        } else if any(|n| n.ends_with("_ff")) {
            "freeform"
        } else {
            "exact"
        }
    }
}

/// A timed query.
pub(super) struct Row {
    pub(super) q: Placed,
    pub(super) time_us: f64,
    pub(super) node_pairs: usize,
    pub(super) leaf_tests: usize,
    pub(super) lower: f64,
    pub(super) upper: f64,
    pub(super) overlap: bool,
    pub(super) budget_exhausted: bool,
}
