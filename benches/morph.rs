//! Cost of producing one frame of the deformable model M_t (section 5): blending the control
//! points, and building the validated profile that the biarc tree is rebuilt from.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use revdist::models::Morph;

fn morph_frames(c: &mut Criterion) {
    let morph = Morph::shared().expect("the keyframes fit");
    let mut points = Vec::new();
    let mut t = 0.0;
    c.bench_function("morph control_points_into", |b| {
        b.iter(|| {
            t = (t + 0.001) % 1.0;
            morph
                .control_points_into(black_box(t), &mut points)
                .unwrap();
        })
    });
    c.bench_function("morph frame (validated profile)", |b| {
        b.iter(|| {
            t = (t + 0.001) % 1.0;
            black_box(morph.frame(black_box(t)).unwrap())
        })
    });
    c.bench_function("morph fit of the five keyframes", |b| {
        b.iter(|| black_box(Morph::fit().unwrap()))
    });
}

criterion_group!(benches, morph_frames);
criterion_main!(benches);
