//! Criterion benchmarks of circle/circle minimum distance and all-binormals, for random
//! general pairs and each degenerate family (target: median <= 1 us for a general pair's
//! minimum distance; `docs/cost_model.md`).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::circle::{binormals, min_distance, Circle3};
use revdist::rng::SplitMix64;

/// A vector with coordinates uniform in [-1, 1).
fn vector(rng: &mut SplitMix64) -> Vector3<f64> {
    Vector3::new(
        rng.next_f64() * 2.0 - 1.0,
        rng.next_f64() * 2.0 - 1.0,
        rng.next_f64() * 2.0 - 1.0,
    )
}

/// A rigid motion: a rotation about a random axis, a shift of up to 5 per coordinate.
fn motion(rng: &mut SplitMix64) -> Isometry3<f64> {
    let axis = nalgebra::Unit::new_normalize(vector(rng) + Vector3::new(0.0, 0.0, 1e-3));
    Isometry3::from_parts(
        Translation3::from(vector(rng) * 5.0),
        UnitQuaternion::from_axis_angle(&axis, rng.next_f64() * std::f64::consts::TAU),
    )
}

fn c(center: [f64; 3], n: [f64; 3], r: f64) -> Circle3 {
    Circle3::new(Point3::from(center), Vector3::from(n), r).unwrap()
}

/// 64 instances of a family: a canonical pair under random rigid motions.
fn family(a: Circle3, b: Circle3, rng: &mut SplitMix64) -> Vec<(Circle3, Circle3)> {
    (0..64)
        .map(|_| {
            let m = motion(rng);
            (a.transformed(&m), b.transformed(&m))
        })
        .collect()
}

fn families() -> Vec<(&'static str, Vec<(Circle3, Circle3)>)> {
    let mut rng = SplitMix64(5);
    let a = c([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0);
    let general: Vec<_> = (0..256)
        .map(|_| {
            let x = Circle3::new(
                Point3::from(vector(&mut rng)),
                vector(&mut rng),
                0.2 + rng.next_f64(),
            )
            .unwrap();
            let y = Circle3::new(
                Point3::from(vector(&mut rng) * 1.5),
                vector(&mut rng),
                0.2 + rng.next_f64(),
            )
            .unwrap();
            (x, y)
        })
        .collect();
    vec![
        ("general", general),
        (
            "centre_on_axis",
            family(a, c([0.0, 0.0, 1.0 / 3.0], [0.0, 0.8, 0.6], 0.9), &mut rng),
        ),
        (
            "meridian",
            family(a, c([0.0, 1.0, 0.0], [1.0, 0.0, 0.0], 0.5), &mut rng),
        ),
        (
            "villarceau",
            family(a, c([0.0, 0.6, 0.0], [-0.6, 0.0, 0.8], 1.0), &mut rng),
        ),
        (
            "coaxial",
            family(a, c([0.0, 0.0, 2.0], [0.0, 0.0, 1.0], 0.5), &mut rng),
        ),
        (
            "coplanar",
            family(a, c([1.0, 0.0, 0.0], [0.0, 0.0, 1.0], 0.5), &mut rng),
        ),
        (
            "nearly_parallel_1e-9",
            family(a, c([0.3, 0.0, 0.5], [1e-9, 0.0, 1.0], 0.7), &mut rng),
        ),
        (
            "through_centre",
            family(a, c([0.5, 0.0, 0.0], [0.0, 1.0, 0.0], 0.5), &mut rng),
        ),
        (
            "radius_ratio_1e-6",
            family(a, c([1.0, 0.5, 0.2], [0.3, 0.4, 0.5], 1e-6), &mut rng),
        ),
    ]
}

fn bench(cr: &mut Criterion) {
    for (name, pairs) in families() {
        let mut i = 0;
        cr.bench_function(&format!("min_distance/{name}"), |bch| {
            bch.iter(|| {
                i = (i + 1) % pairs.len();
                let (x, y) = &pairs[i];
                black_box(min_distance(black_box(x), black_box(y)))
            })
        });
        let mut j = 0;
        cr.bench_function(&format!("binormals/{name}"), |bch| {
            bch.iter(|| {
                j = (j + 1) % pairs.len();
                let (x, y) = &pairs[j];
                black_box(binormals(black_box(x), black_box(y), None, None))
            })
        });
    }
}

criterion_group!(benches, bench);
criterion_main!(benches);
