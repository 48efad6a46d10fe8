//! Shared pieces of the research drivers (the binaries under `src/bin/`).

pub mod args;
pub mod baseline_mesh;
pub mod cli;
pub mod driver;
pub mod peers;
pub mod plot;
pub mod poses;
pub mod progress;
/// Provenance lines of every CSV (lives in `verify`, which writes reports too).
pub use verify::provenance;
pub mod shapes;
/// `--shard I/N` and `--merge DIR...` of the long drivers (lives in `verify`, whose
/// `crosscheck` has them too).
pub use verify::shard;
pub use verify::shard_record;
pub mod stability;
pub mod stats;
pub mod table;

use nalgebra::{UnitQuaternion, Vector3};

/// SplitMix64: a tiny deterministic generator, so runs are reproducible without a crate.
pub struct SplitMix(pub u64);

impl SplitMix {
    pub fn next_f64(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^= z >> 31;
        (z >> 11) as f64 / (1u64 << 53) as f64
    }

    pub fn unit_vector(&mut self) -> Vector3<f64> {
        loop {
            let v = Vector3::new(
                2.0 * self.next_f64() - 1.0,
                2.0 * self.next_f64() - 1.0,
                2.0 * self.next_f64() - 1.0,
            );
            let n = v.norm();
            if n > 1e-3 && n <= 1.0 {
                return v / n;
            }
        }
    }

    pub fn rotation(&mut self) -> UnitQuaternion<f64> {
        let axis = nalgebra::Unit::new_normalize(self.unit_vector());
        UnitQuaternion::from_axis_angle(&axis, std::f64::consts::PI * (2.0 * self.next_f64() - 1.0))
    }
}
