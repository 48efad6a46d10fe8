//! Biarc-tree build times (paper section 5, Figure 9): every built-in model, and rebuilds of the
//! deformable model M_t over a cycle of frames, at eps = 1e-3, 1e-4, 1e-5.
//!
//! `cargo bench --bench tree -- --warm-up-time 1 --measurement-time 3`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use revdist::biarc::BiarcTree;
use revdist::models;

/// The paper's precisions.
const EPS: [f64; 3] = [1e-3, 1e-4, 1e-5];
/// M_t frames cycled through by the rebuild benchmark (profiles prepared outside the timing).
const MORPH_FRAMES: usize = 32;

fn build(c: &mut Criterion) {
    let mut group = c.benchmark_group("build");
    for name in models::model_names() {
        let profile = models::model(name).expect("built-in model");
        for eps in EPS {
            group.bench_with_input(BenchmarkId::new(*name, eps), &eps, |b, &eps| {
                b.iter(|| BiarcTree::build(&profile, eps).expect("tree"))
            });
        }
    }
    group.finish();
}

fn morph_rebuild(c: &mut Criterion) {
    let frames: Vec<_> = (0..MORPH_FRAMES)
        .map(|i| models::morph(i as f64 / MORPH_FRAMES as f64).expect("morph frame"))
        .collect();
    let mut group = c.benchmark_group("morph_rebuild");
    for eps in EPS {
        let mut tree = BiarcTree::build(&frames[0], eps).expect("tree");
        let mut i = 0;
        group.bench_with_input(BenchmarkId::from_parameter(eps), &eps, |b, &eps| {
            b.iter(|| {
                i = (i + 1) % MORPH_FRAMES;
                tree.rebuild(&frames[i], eps).expect("tree");
                tree.nodes().len()
            })
        });
    }
    group.finish();
}

criterion_group!(benches, build, morph_rebuild);
criterion_main!(benches);
