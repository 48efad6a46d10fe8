//! The circle level: perturbed entries of `verify circles`' degenerate catalogue, the
//! double-precision solver against the exact rational reference.

use super::{case_seed, Error, Key, Level, Sample, CIRCLE_FAMILIES, CIRCLE_REL_BOUND};
use revdist::rng::SplitMix64;
use rug::Rational;
use verify::circles::{catalogue, random_motion, run_case, Case, CatalogueEntry, RCircle};
use verify::exact_circle::{rotation_from_quaternion, rotation_from_rational_quaternion, RVec};

/// Runs of the circle solver per case for its time (the fastest is kept).
const CIRCLE_TIMING_RUNS: usize = 5;

/// The entry of `verify circles`' catalogue labelled `label`.
fn catalogue_entry(label: &str) -> Result<CatalogueEntry, Error> {
    catalogue()
        .into_iter()
        .find(|e| e.0 == label)
        .ok_or_else(|| format!("catalogue has no entry '{label}'").into())
}

/// A rational point of the unit sphere (inverse stereographic projection of a random
/// rational point of the plane, then a random sign): exact, and spread over the sphere.
pub(super) fn rational_unit(rng: &mut SplitMix64) -> RVec {
    let s = Rational::from((rng.signed_int(-1000, 1000), 500));
    let t = Rational::from((rng.signed_int(-1000, 1000), 500));
    let n2 = Rational::from(&s * &s) + Rational::from(&t * &t);
    let den = Rational::from(&n2 + 1u32);
    let sign = if rng.signed_int(0, 1) == 0 { 1 } else { -1 };
    [
        Rational::from(&s * 2u32) * sign / &den,
        Rational::from(&t * 2u32) * sign / &den,
        (n2 - 1u32) * sign / den,
    ]
}

/// Circle-level sample: family `fi`, perturbation `delta`, seed `seed`.
pub fn circle_sample(fi: usize, delta: Option<i32>, seed: usize) -> Result<Sample, Error> {
    let (family, labels) = CIRCLE_FAMILIES[fi];
    let variant = labels[seed % labels.len()];
    let (_, c, quat, r, analytic) = catalogue_entry(variant)?;
    let mut rng = SplitMix64(case_seed(Level::Circle, fi, delta, seed));
    let rot = rotation_from_quaternion(quat);
    let (b, analytic) = match delta {
        None => (RCircle::rotated(c, &rot, r), analytic),
        Some(k) => {
            let d = Rational::from((1, 10i64.pow(k as u32)));
            // Centre moved by d along a random direction.
            let offset = rational_unit(&mut rng);
            let centre: RVec = [0, 1, 2].map(|j| Rational::from(&offset[j] * &d) + &c[j]);
            // Plane tilted by 2 atan(d / 2) ~ d about a random axis: the quaternion
            // (2 / d, n) with |n| = 1.
            let n = rational_unit(&mut rng);
            let w = Rational::from(2u32) / &d;
            let [nx, ny, nz] = n;
            let tilt = rotation_from_rational_quaternion(&[w, nx, ny, nz]);
            // Radius changed by +-d.
            let r = if rng.signed_int(0, 1) == 0 {
                r + &d
            } else {
                r - &d
            };
            let zero = [Rational::new(), Rational::new(), Rational::new()];
            (RCircle::rotated(zero, &rot, r).moved(&tilt, &centre), None)
        }
    };
    let motion = random_motion(&mut rng);
    let case = Case {
        family,
        label: variant.to_string(),
        ra: Rational::from(1),
        b,
        motion: Some(motion.clone()),
        analytic,
    };
    let out = run_case(&case);
    // Time the double-precision solver alone on the inputs it saw (deterministic: the same
    // answer as inside `run_case`); the fastest of a few runs, since one call of a few
    // microseconds is at the mercy of the scheduler.
    let mut seconds = f64::INFINITY;
    let mut again = None;
    for _ in 0..CIRCLE_TIMING_RUNS {
        let start = std::time::Instant::now();
        again = Some(revdist::circle::min_distance(&out.inputs.0, &out.inputs.1));
        seconds = seconds.min(start.elapsed().as_secs_f64());
    }
    let again = again.expect("timed at least once");
    debug_assert_eq!(again.distance, out.float);
    if !out.exact.is_finite() {
        return Err(format!("no exact reference for {variant} at delta {delta:?}").into());
    }
    let norm = |x: &RVec| x.iter().map(|c| c.to_f64().powi(2)).sum::<f64>().sqrt();
    let size = 1f64.max(case.b.r.to_f64()).max(norm(&case.b.c)) + norm(&motion.1);
    let abs_err = (out.float - out.exact).abs();
    Ok(Sample {
        key: Key {
            level: Level::Circle,
            family,
            delta,
        },
        variant,
        seed,
        exact: out.exact,
        value: out.float,
        abs_err,
        rel_err: abs_err / size,
        bound: CIRCLE_REL_BOUND * size,
        lower: f64::NAN,
        upper: f64::NAN,
        certified: true,
        seconds,
        reproducer: None,
    })
}
