//! Distance-query benchmarks: per model pair and tree bound eps (1e-3, 1e-4, 1e-5), the
//! time of one query averaged over a fixed set of random separated poses, plus the
//! traversal counters (node pairs and leaf tests per query) printed before each group; and
//! the two node-pair bounds (spheres only vs spheres then solid tori).
//!
//! Run: `cargo bench --bench query -- --warm-up-time 1 --measurement-time 3`.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use revdist::models::model;
use revdist::query::bound::{node_pair_bound, BoundKind};
use revdist::query::{distance, QueryOptions};
use revdist::solid::Solid;
use std::hint::black_box;
use std::sync::Arc;

/// The paper's five solids.
const MODELS: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];
const EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];
/// Poses per measured batch.
const POSES: usize = 16;

/// A deterministic uniform generator on [0, 1) (64-bit LCG, top 53 bits).
fn uniform(mut s: u64) -> impl FnMut() -> f64 {
    move || {
        s = s
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (s >> 11) as f64 / (1u64 << 53) as f64
    }
}

/// Deterministic random separated poses: B's origin 1.6..2.6 from A's, random rotation.
fn poses() -> Vec<Isometry3<f64>> {
    let mut f = uniform(0x9e3779b97f4a7c15);
    (0..POSES)
        .map(|_| {
            let dir = Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5).normalize();
            let t = dir * (1.6 + f()) + Vector3::new(0.0, 0.0, 0.6);
            let r = UnitQuaternion::from_scaled_axis(
                Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 6.0,
            );
            Isometry3::from_parts(Translation3::from(t), r)
        })
        .collect()
}

fn solid(name: &str, eps: f64) -> Solid {
    Solid::from_profile(Arc::new(model(name).expect("built-in model")), eps).expect("tree")
}

fn per_pair(c: &mut Criterion) {
    let poses = poses();
    let opts = QueryOptions::default();
    for eps in EPS {
        let solids: Vec<Solid> = MODELS.iter().map(|n| solid(n, eps)).collect();
        let mut group = c.benchmark_group(format!("query_eps_{eps:e}"));
        group.sample_size(10);
        for i in 0..MODELS.len() {
            for j in i..MODELS.len() {
                let bs: Vec<Solid> = poses.iter().map(|p| solids[j].with_pose(*p)).collect();
                let (mut pairs, mut leaves, mut patches) = (0, 0, 0);
                for b in &bs {
                    let d = distance(&solids[i], b, &opts);
                    pairs += d.stats.node_pairs;
                    leaves += d.stats.leaf_tests;
                    patches += d.stats.patch_tests;
                }
                let n = bs.len() as f64;
                println!(
                    "stats eps {eps:e} {}/{}: {:.1} node pairs, {:.1} leaf tests, {:.1} patch tests per query",
                    MODELS[i],
                    MODELS[j],
                    pairs as f64 / n,
                    leaves as f64 / n,
                    patches as f64 / n
                );
                let id = BenchmarkId::from_parameter(format!("{}-{}", MODELS[i], MODELS[j]));
                group.bench_function(id, |bench| {
                    bench.iter(|| {
                        for b in &bs {
                            black_box(distance(&solids[i], b, &opts));
                        }
                    })
                });
            }
        }
        group.finish();
    }
}

fn bound_kinds(c: &mut Criterion) {
    let poses = poses();
    let a = solid("pawn", 1e-4);
    let b = solid("lightmill", 1e-4);
    let bs: Vec<Solid> = poses.iter().map(|p| b.with_pose(*p)).collect();
    let mut group = c.benchmark_group("bounds_pawn_lightmill_1e-4");
    group.sample_size(10);
    for kind in [BoundKind::Sphere, BoundKind::Torus] {
        let opts = QueryOptions {
            bound: kind,
            ..QueryOptions::default()
        };
        let (mut pairs, mut leaves, mut bounds) = (0, 0, 0);
        for b in &bs {
            let d = distance(&a, b, &opts);
            pairs += d.stats.node_pairs;
            leaves += d.stats.leaf_tests;
            bounds += d.stats.bound_tests;
        }
        println!(
            "stats bound {kind:?}: {:.1} node pairs, {:.1} leaf tests, {:.1} bound tests per query",
            pairs as f64 / POSES as f64,
            leaves as f64 / POSES as f64,
            bounds as f64 / POSES as f64
        );
        group.bench_function(format!("{kind:?}"), |bench| {
            bench.iter(|| {
                for b in &bs {
                    black_box(distance(&a, b, &opts));
                }
            })
        });
    }
    group.finish();
}

/// Leaf-sized toroidal patch pairs (sweep <= 0.1 rad, as at eps 1e-4) slid to 1e-4 of
/// contact: the exact patch distance with the sampled kernel, the binormal kernel, and the
/// binormal kernel with the Gauss-map restriction (paper 3.3).
fn patch_kernels(c: &mut Criterion) {
    use revdist::bvh::{Patch, ProfileArc};
    use revdist::query::patch_distance::{patch_distance_with, Kernel, PatchOptions};
    let mut f = uniform(0x2545f4914f6cdd1d);
    let arc = |f: &mut dyn FnMut() -> f64| loop {
        let a = ProfileArc::Arc {
            center: nalgebra::Point2::new(0.2 + f(), f() - 0.5),
            radius: 0.05 + 0.5 * f(),
            phi_start: f() * std::f64::consts::TAU,
            sweep: (2.0 * f() - 1.0) * 0.1,
        };
        if a.start().x > 0.0 && a.end().x > 0.0 {
            return Patch::new(a);
        }
    };
    let opts = |kernel, gauss_restriction| PatchOptions {
        kernel,
        gauss_restriction,
        ..PatchOptions::default()
    };
    let mut cases = Vec::new();
    while cases.len() < 64 {
        let (a, b) = (arc(&mut f), arc(&mut f));
        let pose = Isometry3::from_parts(
            Translation3::new(f() - 0.5, f() - 0.5, f() - 0.5),
            UnitQuaternion::from_scaled_axis(Vector3::new(f() - 0.5, f() - 0.5, f() - 0.5) * 6.0),
        );
        let r = patch_distance_with(&a, &b, &pose, opts(Kernel::Binormals, true));
        if r.distance > 1e-3 {
            let shift = (r.point_a - r.point_b) * ((r.distance - 1e-4) / r.distance);
            cases.push((a, b, Translation3::from(shift) * pose));
        }
    }
    let mut group = c.benchmark_group("patch_distance_64_leaf_pairs");
    group.sample_size(20);
    for (name, o) in [
        ("sampled_scan", opts(Kernel::Sweep, false)),
        ("binormals", opts(Kernel::Binormals, false)),
        ("binormals_gauss", opts(Kernel::Binormals, true)),
    ] {
        group.bench_function(name, |bench| {
            bench.iter(|| {
                for (a, b, pose) in &cases {
                    black_box(patch_distance_with(a, b, pose, o));
                }
            })
        });
    }
    // Stage 1 of a leaf pair (`docs/cost_model.md`): the cheap lower bound and realised upper
    // bound.
    group.bench_function("stage1_bounds", |bench| {
        bench.iter(|| {
            let mut memo = revdist::query::search::leaf::patch_lower::CoreMemo::default();
            for (a, b, pose) in &cases {
                black_box(revdist::query::search::leaf::patch_upper::patch_bounds(
                    a, b, pose, &mut memo,
                ));
            }
        })
    });
    // The node-pair bound of the same pairs' disks (spheres, then solid tori).
    group.bench_function("node_pair_bound", |bench| {
        bench.iter(|| {
            for (a, b, pose) in &cases {
                black_box(node_pair_bound(
                    &a.arc.bounding_disk(),
                    &b.arc.bounding_disk(),
                    pose,
                    BoundKind::Torus,
                    f64::INFINITY,
                    None,
                ));
            }
        })
    });
    group.finish();
}

criterion_group!(benches, patch_kernels, bound_kinds, per_pair);
criterion_main!(benches);
