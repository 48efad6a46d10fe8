//! The Rust side of the Python package's overhead measurement (python/bench/overhead.py):
//! the core's batch API (`revdist::query::distances`) on N poses of two
//! far-apart spheres (a closed-form answer of well under a microsecond, so that the time is
//! almost all per-pose overhead), pairs built from the poses included, on 1 and 2 threads.
//! Prints the best of `REPS` runs in microseconds per pose.
//!
//!     cargo run --release --manifest-path python/Cargo.toml --example rust_batch [N]

use std::sync::Arc;
use std::time::Instant;

use nalgebra::{Isometry3, Translation3, UnitQuaternion};
use revdist::models::model;
use revdist::query::distances;
use revdist::query::QueryOptions;
use revdist::solid::Solid;

/// Repetitions; the minimum is reported (the least disturbed by other processes).
const REPS: usize = 30;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let n: usize = std::env::args().nth(1).map_or(Ok(10_000), |s| s.parse())?;
    let sphere = Solid::from_profile(Arc::new(model("sphere")?), 1e-4)?;
    // The poses python/bench/overhead.py uses: x = 10 + i 1e-4, identity rotation.
    let poses: Vec<Isometry3<f64>> = (0..n)
        .map(|i| {
            Isometry3::from_parts(
                Translation3::new(10.0 + i as f64 * 1e-4, 0.0, 0.0),
                UnitQuaternion::identity(),
            )
        })
        .collect();
    let opts = QueryOptions::default();
    for threads in [1, 2] {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let mut best = f64::INFINITY;
        let mut checksum = 0.0;
        for _ in 0..REPS {
            let t = Instant::now();
            let pairs: Vec<(Solid, Solid)> = poses
                .iter()
                .map(|p| (sphere.clone(), sphere.with_pose(*p)))
                .collect();
            let d = pool.install(|| distances(&pairs, &opts));
            best = best.min(t.elapsed().as_secs_f64());
            checksum += d[n / 2].value;
        }
        println!(
            "rust batch API, N = {n}, {threads} thread(s): {:.3} us/pose (checksum {checksum})",
            best / n as f64 * 1e6
        );
    }
    Ok(())
}
