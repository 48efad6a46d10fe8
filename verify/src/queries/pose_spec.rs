//! A pose of B as `revdist distance` reads it (translation and unit quaternion), the form
//! cases, reproducers and the frozen case list share.

use nalgebra::{Isometry3, Quaternion, Translation3, UnitQuaternion, Vector3};

/// A pose as the CLI reads it: translation and unit quaternion `[w, x, y, z]`.
#[derive(Debug, Clone, Copy)]
pub struct PoseSpec {
    pub translation: [f64; 3],
    pub rotation: [f64; 4],
}

impl PoseSpec {
    /// The pose of an isometry (translation, and its unit quaternion as `[w, x, y, z]`);
    /// [`PoseSpec::isometry`] gives it back.
    pub fn from_isometry(iso: &Isometry3<f64>) -> PoseSpec {
        let t = iso.translation.vector;
        let q = iso.rotation;
        PoseSpec {
            translation: [t.x, t.y, t.z],
            rotation: [q.w, q.i, q.j, q.k],
        }
    }

    /// The isometry exactly as `revdist distance` builds it from JSON.
    pub fn isometry(&self) -> Isometry3<f64> {
        let r = self.rotation;
        Isometry3::from_parts(
            Translation3::from(Vector3::from(self.translation)),
            UnitQuaternion::from_quaternion(Quaternion::new(r[0], r[1], r[2], r[3])),
        )
    }

    /// JSON as `--pose-b` and batch lines take it (shortest round-trip numbers).
    pub fn json(&self) -> String {
        let t = self.translation;
        let r = self.rotation;
        format!(
            "{{\"translation\":[{:?},{:?},{:?}],\"rotation\":[{:?},{:?},{:?},{:?}]}}",
            t[0], t[1], t[2], r[0], r[1], r[2], r[3]
        )
    }
}
