//! Criterion benchmarks of circle/circle minimum distance and all-binormals, for random
//! general pairs and each degenerate family (target: median <= 1 us for a general pair's
//! minimum distance; `docs/cost_model.md`).

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use nalgebra::{Isometry3, Point3, Translation3, UnitQuaternion, Vector3};
use revdist::circle::{binormals, min_distance, Circle3};

struct Rng(u64);
impl Rng {
    fn f(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
    }
    fn v(&mut self) -> Vector3<f64> {
        Vector3::new(
            self.f() * 2.0 - 1.0,
            self.f() * 2.0 - 1.0,
            self.f() * 2.0 - 1.0,
        )
    }
    fn motion(&mut self) -> Isometry3<f64> {
        let axis = nalgebra::Unit::new_normalize(self.v() + Vector3::new(0.0, 0.0, 1e-3));
        Isometry3::from_parts(
            Translation3::from(self.v() * 5.0),
            UnitQuaternion::from_axis_angle(&axis, self.f() * std::f64::consts::TAU),
        )
    }
}

fn c(center: [f64; 3], n: [f64; 3], r: f64) -> Circle3 {
    Circle3::new(Point3::from(center), Vector3::from(n), r).unwrap()
}

/// 64 instances of a family: a canonical pair under random rigid motions.
fn family(a: Circle3, b: Circle3, rng: &mut Rng) -> Vec<(Circle3, Circle3)> {
    (0..64)
        .map(|_| {
            let m = rng.motion();
            (a.transformed(&m), b.transformed(&m))
        })
        .collect()
}

fn families() -> Vec<(&'static str, Vec<(Circle3, Circle3)>)> {
    let mut rng = Rng(5);
    let a = c([0.0, 0.0, 0.0], [0.0, 0.0, 1.0], 1.0);
    let general: Vec<_> = (0..256)
        .map(|_| {
            let x = Circle3::new(Point3::from(rng.v()), rng.v(), 0.2 + rng.f()).unwrap();
            let y = Circle3::new(Point3::from(rng.v() * 1.5), rng.v(), 0.2 + rng.f()).unwrap();
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
