//! The solid level's sample: a case moved by a random rigid motion, queried, and checked
//! against its exact distance; with a `revdist distance` reproducer.

use super::solid_case::{pose, solid_case};
use super::solids::Shapes;
use super::{case_seed, delta_value, Error, Key, Level, Sample, SOLID_FAMILIES};
use crate::Draw;
use nalgebra::Vector3;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use rug::Float;
use verify::exact_circle::PREC;

/// The eps a solid's tree was built at.
fn cfg_eps(s: &Solid) -> f64 {
    s.tree.target_eps
}

/// `revdist distance` arguments of the query between `a` and `b` as the query sees it (B at
/// the relative pose, in full precision).
fn reproducer(a: &Solid, b: &Solid, eps: f64) -> String {
    let rel = a.relative_pose(b);
    let q = rel.rotation.quaternion();
    let t = rel.translation.vector;
    let name = |s: &Solid| {
        s.profile
            .as_ref()
            .map_or("?".to_string(), |p| p.name().to_string())
    };
    format!(
        "revdist distance '{}' '{}' --eps {eps:e} --pose-b '{{\"translation\": [{:?}, {:?}, {:?}], \"rotation\": [{:?}, {:?}, {:?}, {:?}]}}'",
        name(a),
        name(b),
        t.x,
        t.y,
        t.z,
        q.w,
        q.i,
        q.j,
        q.k
    )
}

/// Solid-level sample: family `fi`, perturbation `delta`, seed `seed` (variant `seed mod
/// variants`), queried after a random rigid motion of both solids.
pub fn solid_sample(
    shapes: &Shapes,
    fi: usize,
    delta: Option<i32>,
    seed: usize,
) -> Result<Sample, Error> {
    let (family, variants) = SOLID_FAMILIES[fi];
    let vi = seed % variants.len();
    let mut rng = SplitMix64(case_seed(Level::Solid, fi, delta, seed));
    let c = solid_case(shapes, fi, vi, delta_value(delta), &mut rng)?;
    let exact = c.exact.max(&Float::with_val(PREC, 0));
    let m = pose(
        Vector3::new(
            4.0 * rng.next_f64() - 2.0,
            4.0 * rng.next_f64() - 2.0,
            4.0 * rng.next_f64() - 2.0,
        ),
        rng.rotation(),
    );
    let a = c.a.with_pose(m);
    let b = c.b.with_pose(m * c.rel);
    let start = std::time::Instant::now();
    let q = distance(&a, &b, &QueryOptions::default());
    let seconds = start.elapsed().as_secs_f64();
    let abs_err = Float::with_val(PREC, &exact - q.value).abs().to_f64();
    let certified = exact >= q.lower && exact <= q.upper;
    let size = crate::shapes::diagonal(c.a.profile.as_deref().ok_or("no profile")?)
        + crate::shapes::diagonal(c.b.profile.as_deref().ok_or("no profile")?);
    Ok(Sample {
        key: Key {
            level: Level::Solid,
            family,
            delta,
        },
        variant: c.variant,
        seed,
        exact: exact.to_f64(),
        value: q.value,
        abs_err,
        rel_err: abs_err / size,
        bound: a.tree.target_eps + b.tree.target_eps,
        lower: q.lower,
        upper: q.upper,
        certified,
        seconds,
        reproducer: Some(reproducer(&a, &b, cfg_eps(&a))),
    })
}
