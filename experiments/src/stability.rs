//! Numerical stability near degenerate configurations: the error of
//! revdist's answers against exact references as a configuration is moved a distance
//! `delta = 10^-k` (k = 16..1) away from a degenerate one, and at the degenerate
//! configuration itself (`delta = 0`).
//!
//! # Circle level
//!
//! Each family takes entries of the degenerate catalogue of `verify circles`
//! ([`verify::circles::catalogue`], A the unit circle): coaxial (and concentric coplanar),
//! meridian, centre on the other's axis (D1, D1b, D6 and the larger circle's centre on the
//! smaller one's axis), Villarceau, and the two pinned pairs with exactly 8 binormals. A
//! perturbation of size `delta` moves B's centre by `delta` along a random direction, tilts
//! B's plane by an angle of about `delta` about a random axis and changes B's radius by
//! `+-delta`, all in exact rationals (directions are rational points of the unit sphere, the
//! tilt a rational quaternion); the pair is then moved by a random rational rigid motion
//! (translation up to 10 per coordinate). The double-precision solver
//! ([`revdist::circle::min_distance`]) sees the rounded data; the reference is the exact
//! minimum distance of the rational data from the degree-8 polynomial in exact rationals
//! (Sturm isolation, MPFR refinement to ~1e-70: [`verify::circles::run_case`]), or the
//! catalogue's analytic value for the continua at `delta = 0`.
//!
//! The error is relative to the size of the data the solver sees,
//! `size = max(ra, rb, |C_b - C_a|) + |t|` (`t` the rigid motion's translation): rounding the
//! inputs alone moves the answer by a few `2^-53 size` (the distance is 1-Lipschitz in the
//! centres and `r`-Lipschitz in the normals). [`CIRCLE_REL_BOUND`] (`64 * 2^-53`) is the
//! bound checked; the solver's documented guarantee is looser, `1e-12 size`
//! ([`revdist::circle::TIE_REL_TOL`]: below it ties and continua are not resolved).
//!
//! # Solid level
//!
//! Certified queries ([`fn@revdist::query::distance`], default tolerance `eps_a + eps_b`) on
//! pairs whose distance has a closed form, derived beside each constructor in
//! `solid_case`; the closed form is evaluated in 256-bit MPFR from the exact values of the
//! `f64` data (rug), so the cancellation in e.g. `|c_b - c_a| - 1.5` at a gap of 1e-16 costs
//! nothing. The families: coaxial stacks (gap `delta` along a common axis), touching pairs
//! moved `delta` apart along a random direction, nested pairs whose inner surface is `delta`
//! inside the outer one (distance 0: solids, not surfaces), and pairs tangent along a whole
//! circle lifted `delta` apart. The relative pose `P` is built in `f64`; both solids are then
//! moved by a random rigid motion `M` (A at `M`, B at `M P`), so the query also sees the
//! rounding of `M^-1 (M P)`. The reference is the exact distance for `P`. Each answer must
//! satisfy `lower <= exact <= upper` (compared exactly) and `|value - exact| <= eps_a +
//! eps_b`.

use std::sync::Arc;

use indicatif::ProgressBar;
use nalgebra::{Isometry3, Translation3, UnitQuaternion, Vector3};
use rayon::prelude::*;
use revdist::models::primitives::{arc, deg, line, pt};
use revdist::profile::Profile;
use revdist::query::{distance, QueryOptions};
use revdist::rng::SplitMix64;
use revdist::solid::Solid;
use rug::{Float, Rational};
use verify::circles::{catalogue, random_motion, run_case, Case, CatalogueEntry, RCircle};
use verify::exact_circle::{
    rotation_from_quaternion, rotation_from_rational_quaternion, RVec, PREC,
};

use crate::Draw;

/// Error type of this module.
pub type Error = Box<dyn std::error::Error + Send + Sync>;

/// Perturbation exponents: `delta = 10^-k` for k in 1..=16.
pub const DELTA_EXPONENTS: std::ops::RangeInclusive<i32> = 1..=16;

/// Unit roundoff of `f64`, `2^-53`.
pub const UNIT_ROUNDOFF: f64 = f64::EPSILON / 2.0;

/// Circle-level bound on `|d - d_exact| / size` (see the module documentation for `size`):
/// `64 u`, `u = 2^-53`.
///
/// Why this value: the solver sees the rounded data. Rounding B's centre (coordinates of
/// magnitude <= size) moves it by <= sqrt(3) u size, rounding the axes moves B's points by
/// <= sqrt(6) u rb, and the distance is 1-Lipschitz in the points: ~5 u size. The solver then
/// maps the pair to a local frame (dot products of 3 terms: ~3 u size per coordinate, both
/// circles) and evaluates the distance at its polished roots (~4 u size): about 16 u size in
/// all, times a margin of 4. The solver's own documented guarantee is far looser,
/// [`revdist::circle::TIE_REL_TOL`] (`1e-12`: ties and continua below it are not resolved);
/// at 64 seeds per family and delta the measured worst is below 3 u.
pub const CIRCLE_REL_BOUND: f64 = 64.0 * UNIT_ROUNDOFF;

/// Runs of the circle solver per case for its time (the fastest is kept).
const CIRCLE_TIMING_RUNS: usize = 5;

/// Default tree accuracy of the solid level.
pub const DEFAULT_EPS: f64 = 1e-5;

/// Which level a sample belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Level {
    Circle,
    Solid,
}

impl Level {
    pub fn name(self) -> &'static str {
        match self {
            Level::Circle => "circle",
            Level::Solid => "solid",
        }
    }
}

/// Circle-level families: (family, catalogue labels cycled over the seeds).
pub const CIRCLE_FAMILIES: [(&str, &[&str]); 5] = [
    ("coaxial", &["coaxial", "concentric coplanar"]),
    ("meridian", &["D2 meridian"]),
    (
        "centre on axis",
        &[
            "D1 centre on axis",
            "D1b centre on axis",
            "D6 centre on axis",
            "larger centre on smaller axis",
        ],
    ),
    ("Villarceau", &["D3 Villarceau"]),
    ("8 binormals", &["8 binormals A", "8 binormals B"]),
];

/// Solid-level families: (family, variants cycled over the seeds).
pub const SOLID_FAMILIES: [(&str, &[&str]); 4] = [
    (
        "coaxial stacks",
        &[
            "sphere on cylinder (off axis)",
            "cylinder on cylinder (tilted)",
            "cylinder on cone apex (tilted)",
            "ring on ring",
        ],
    ),
    (
        "touching",
        &["sphere-sphere", "sphere-torus", "cylinders side by side"],
    ),
    (
        "nested",
        &["ball in sphere", "ball in cylinder", "cone in cylinder"],
    ),
    (
        "tangent along a circle",
        &[
            "sphere in torus hole (off axis)",
            "ring around cone",
            "ring around ring",
        ],
    ),
];

/// What a run covers.
#[derive(Debug, Clone)]
pub struct Config {
    /// Seeds (random perturbation directions and rigid motions) per family and delta.
    pub seeds: usize,
    /// `Some(k)`: `delta = 10^-k`; `None`: the degenerate configuration itself.
    pub deltas: Vec<Option<i32>>,
    /// Tree accuracy of the solid level.
    pub eps: f64,
}

impl Config {
    /// Every delta in [`DELTA_EXPONENTS`] plus `delta = 0`.
    pub fn full(seeds: usize, eps: f64) -> Config {
        let mut deltas = vec![None];
        deltas.extend(DELTA_EXPONENTS.rev().map(Some));
        Config { seeds, deltas, eps }
    }
}

/// `delta` as a number (0 for the degenerate configuration).
pub fn delta_value(d: Option<i32>) -> f64 {
    d.map_or(0.0, |k| 10f64.powi(-k))
}

/// What a sample is grouped by: level, family and perturbation (`None`: delta = 0).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Key {
    pub level: Level,
    pub family: &'static str,
    pub delta: Option<i32>,
}

/// One checked answer.
#[derive(Debug, Clone)]
pub struct Sample {
    pub key: Key,
    pub variant: &'static str,
    pub seed: usize,
    /// Exact reference (rounded to f64).
    pub exact: f64,
    /// The answer revdist gave (the query's `value` for solids).
    pub value: f64,
    /// `|value - exact|`, computed exactly and rounded.
    pub abs_err: f64,
    /// `abs_err / size`.
    pub rel_err: f64,
    /// The absolute error this sample must stay within.
    pub bound: f64,
    /// Certified interval of a solid query (NaN for circles).
    pub lower: f64,
    pub upper: f64,
    /// Solids: `lower <= exact <= upper`, compared exactly (circles: true).
    pub certified: bool,
    /// Wall-clock time of revdist's answer in seconds, the exact reference excluded (circles:
    /// the fastest of a few runs; solids: one query).
    pub seconds: f64,
    /// Solids: the profiles' names and the relative pose the query used, B in A's frame
    /// (`revdist distance A B --eps E --pose-b '...'` reruns it when both are built-ins).
    pub reproducer: Option<String>,
}

impl Sample {
    /// Within the error bound and, for solids, with a valid certificate.
    pub fn ok(&self) -> bool {
        self.abs_err <= self.bound && self.certified
    }

    /// `upper - lower` (NaN for circles).
    pub fn width(&self) -> f64 {
        self.upper - self.lower
    }

    /// A one-line description with everything needed to rerun the case.
    pub fn describe(&self) -> String {
        let mut s = format!(
            "{} / {} / {} / delta {} / seed {}: value {:.17e}, exact {:.17e}, error {:.3e} (bound {:.3e})",
            self.key.level.name(),
            self.key.family,
            self.variant,
            self.key.delta.map_or("0".to_string(), |k| format!("1e-{k}")),
            self.seed,
            self.value,
            self.exact,
            self.abs_err,
            self.bound,
        );
        if !self.lower.is_nan() {
            s.push_str(&format!(
                ", interval [{:.17e}, {:.17e}]",
                self.lower, self.upper
            ));
        }
        s.push_str(&format!(", {:.1} us", self.seconds * 1e6));
        if let Some(r) = &self.reproducer {
            s.push_str("; rerun: ");
            s.push_str(r);
        }
        s
    }
}

/// A seed for case (family, variant, delta, seed), independent of the run's order.
fn case_seed(level: Level, family: usize, delta: Option<i32>, seed: usize) -> u64 {
    let mut g = SplitMix64(
        0x0057_ab1e
            ^ ((level as u64) << 56)
            ^ ((family as u64) << 48)
            ^ ((delta.map_or(0, |k| k as u64 + 1)) << 40)
            ^ seed as u64,
    );
    g.next_f64().to_bits()
}

// ---------------------------------------------------------------------------------------
// Circle level
// ---------------------------------------------------------------------------------------

fn catalogue_entry(label: &str) -> Result<CatalogueEntry, Error> {
    catalogue()
        .into_iter()
        .find(|e| e.0 == label)
        .ok_or_else(|| format!("catalogue has no entry '{label}'").into())
}

/// A rational point of the unit sphere (inverse stereographic projection of a random
/// rational point of the plane, then a random sign): exact, and spread over the sphere.
fn rational_unit(rng: &mut SplitMix64) -> RVec {
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

// ---------------------------------------------------------------------------------------
// Solid level
// ---------------------------------------------------------------------------------------

fn exact(x: f64) -> Rational {
    Rational::from_f64(x).expect("finite f64")
}

fn float(x: &Rational) -> Float {
    Float::with_val(PREC, x)
}

/// A rigid motion with exact data: the rotation of the stored quaternion normalised
/// exactly, and the stored translation.
struct ExactPose {
    rot: [RVec; 3],
    t: RVec,
}

impl ExactPose {
    fn of(p: &Isometry3<f64>) -> ExactPose {
        let q = p.rotation.quaternion();
        let rot = rotation_from_rational_quaternion(&[q.w, q.i, q.j, q.k].map(exact));
        let v = p.translation.vector;
        ExactPose {
            rot,
            t: [v.x, v.y, v.z].map(exact),
        }
    }

    /// Image of a local point, exact.
    fn place(&self, local: [f64; 3]) -> RVec {
        let x = local.map(exact);
        let mut out = self.t.clone();
        for (k, o) in out.iter_mut().enumerate() {
            for (j, xj) in x.iter().enumerate() {
                *o += Rational::from(&self.rot[j][k] * xj);
            }
        }
        out
    }
}

/// `sqrt(x^2 + y^2)` in MPFR.
fn hypot(x: &Float, y: &Float) -> Float {
    Float::with_val(PREC, x * x + y * y).sqrt()
}

/// Distance from a ball (centre `p`, radius `rs`) to the solid torus whose tube circle has
/// radius `big_r` at height `zc` on the z axis, tube radius `r`: the distance from `p` to the
/// solid torus is `dist(p, tube circle) - r` when positive, and
/// `dist(p, circle)^2 = (rho - big_r)^2 + (z - zc)^2`, `rho` the distance to the axis
/// (the nearest point of a circle lies in p's meridian half-plane); a ball subtracts its
/// radius.
fn ball_torus_gap(p: &RVec, rs: f64, big_r: f64, zc: f64, r: f64) -> Float {
    let rho = hypot(&float(&p[0]), &float(&p[1]));
    let d_circle = hypot(
        &(rho - float(&exact(big_r))),
        &(float(&p[2]) - float(&exact(zc))),
    );
    d_circle - float(&exact(r)) - float(&exact(rs))
}

fn ball(r: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("ball {r}"),
        vec![arc([0.0, r], r, deg(-90.0), deg(90.0))?],
    )?)
}

fn cylinder(radius: f64, height: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("cylinder {radius}x{height}"),
        vec![
            line(pt(0.0, 0.0), pt(radius, 0.0))?,
            line(pt(radius, 0.0), pt(radius, height))?,
            line(pt(radius, height), pt(0.0, height))?,
        ],
    )?)
}

fn ring(big_r: f64, r: f64, zc: f64) -> Result<Profile, Error> {
    Ok(Profile::new(
        format!("ring {big_r}/{r}"),
        vec![arc([big_r, zc], r, deg(-90.0), deg(270.0))?],
    )?)
}

/// The fixed solids of the solid level, built once at the run's eps.
pub struct Shapes {
    eps: f64,
    /// Built-in `sphere`: radius 0.75, centre (0, 0, 0.75).
    sphere: Solid,
    /// Built-in `cylinder`: radius 0.5, z in [0, 1.5].
    cylinder: Solid,
    /// Built-in `cone`: base radius 0.6 at z = 0, apex (0, 0, 1.5).
    cone: Solid,
    /// Built-in `ring`: tube circle radius 0.9 at z = 0.6, tube radius 0.6.
    ring: Solid,
    /// Balls of radius 0.5 and 0.4 resting on z = 0.
    ball_05: Solid,
    ball_04: Solid,
}

impl Shapes {
    pub fn new(eps: f64) -> Result<Shapes, Error> {
        let built = |p: Profile| Solid::from_profile(Arc::new(p), eps);
        let model =
            |name: &str| -> Result<Solid, Error> { Ok(built(revdist::models::model(name)?)?) };
        Ok(Shapes {
            eps,
            sphere: model("sphere")?,
            cylinder: model("cylinder")?,
            cone: model("cone")?,
            ring: model("ring")?,
            ball_05: built(ball(0.5)?)?,
            ball_04: built(ball(0.4)?)?,
        })
    }

    fn build(&self, p: Profile) -> Result<Solid, Error> {
        Ok(Solid::from_profile(Arc::new(p), self.eps)?)
    }
}

/// A pair at its relative pose `P` (B in A's frame) with the exact distance for `P`.
struct SolidCase {
    variant: &'static str,
    a: Solid,
    b: Solid,
    rel: Isometry3<f64>,
    exact: Float,
}

fn spin(rng: &mut SplitMix64) -> UnitQuaternion<f64> {
    UnitQuaternion::from_axis_angle(&Vector3::z_axis(), std::f64::consts::TAU * rng.next_f64())
}

/// A random horizontal unit vector.
fn horizontal(rng: &mut SplitMix64) -> Vector3<f64> {
    let phi = std::f64::consts::TAU * rng.next_f64();
    Vector3::new(phi.cos(), phi.sin(), 0.0)
}

/// A random spin about z followed by a tilt of `angle` about a random horizontal axis.
fn tilted(rng: &mut SplitMix64, angle: f64) -> UnitQuaternion<f64> {
    let axis = nalgebra::Unit::new_normalize(horizontal(rng));
    UnitQuaternion::from_axis_angle(&axis, angle) * spin(rng)
}

/// The pose with rotation `r` that puts the local axis point (0, 0, `z`) (a ball's centre) at
/// `c`.
fn centred_at(c: Vector3<f64>, r: UnitQuaternion<f64>, z: f64) -> Isometry3<f64> {
    pose(c - r * Vector3::new(0.0, 0.0, z), r)
}

fn pose(t: Vector3<f64>, r: UnitQuaternion<f64>) -> Isometry3<f64> {
    Isometry3::from_parts(Translation3::from(t), r)
}

/// Builds variant `vi` of solid family `fi` at perturbation `d` (0 for the degenerate
/// configuration). Every closed form is stated next to its construction; `max(0, .)` is
/// applied by the caller (solids that touch or overlap have distance 0).
fn solid_case(
    shapes: &Shapes,
    fi: usize,
    vi: usize,
    d: f64,
    rng: &mut SplitMix64,
) -> Result<SolidCase, Error> {
    let (family, variants) = SOLID_FAMILIES[fi];
    let variant = variants[vi];
    let s = shapes;
    let zero = || Float::with_val(PREC, 0);
    let case = |a: &Solid, b: &Solid, rel: Isometry3<f64>, exact: Float| SolidCase {
        variant,
        a: a.clone(),
        b: b.clone(),
        rel,
        exact,
    };
    // The built-in sphere (radius 0.75) centred at `c`, turned by `rot`, against the ring:
    // the exact gap of [`ball_torus_gap`].
    let sphere_at = |c: Vector3<f64>, rot: UnitQuaternion<f64>| {
        let rel = centred_at(c, rot, 0.75);
        let p = ExactPose::of(&rel).place([0.0, 0.0, 0.75]);
        let gap = ball_torus_gap(&p, 0.75, 0.9, 0.6, 0.6);
        case(&s.ring, &s.sphere, rel, gap)
    };
    Ok(match (family, variant) {
        // Coaxial stacks, moved d off the coaxial configuration: B above A with a gap d.
        // Sphere on the cylinder (top disk z = 1.5, radius 0.5), its centre c d off the axis,
        // B turned at random (a ball is invariant): every point of B has z >= c_z - 0.75,
        // every point of A z <= 1.5, and the sphere's lowest point lies above the disk
        // (|c_xy| = d < 0.5), so d_exact = c_z - 2.25.
        ("coaxial stacks", "sphere on cylinder (off axis)") => {
            let rot = rng.rotation();
            let c = d * horizontal(rng) + Vector3::new(0.0, 0.0, 2.25 + d);
            let rel = centred_at(c, rot, 0.75);
            let cz = float(&ExactPose::of(&rel).place([0.0, 0.0, 0.75])[2]);
            case(&s.cylinder, &s.sphere, rel, cz - 2.25)
        }
        // A cylinder (radius 0.5) on the cylinder's top disk, B's axis tilted by d about a
        // random horizontal axis. B's lowest point is on its bottom rim: the height of
        // R (x, y, 0) + t over the rim x^2 + y^2 = 0.25 is at least t_z - 0.5 |((R e_x)_z,
        // (R e_y)_z)|, and that point is within 0.5 of the axis, above A's top disk, while A
        // stays below z = 1.5: d_exact = t_z - 0.5 |((R e_x)_z, (R e_y)_z)| - 1.5. The gap is
        // d by construction (t_z = 1.5 + d + 0.5 sin d).
        ("coaxial stacks", "cylinder on cylinder (tilted)") => {
            let rel = pose(
                Vector3::new(0.0, 0.0, 1.5 + d + 0.5 * d.sin()),
                tilted(rng, d),
            );
            let e = ExactPose::of(&rel);
            let drop = hypot(&float(&e.rot[0][2]), &float(&e.rot[1][2])) * 0.5f64;
            case(&s.cylinder, &s.cylinder, rel, float(&e.t[2]) - drop - 1.5)
        }
        // A cylinder tilted by d, its bottom centre d above the cone's apex p = (0, 0, 1.5).
        // The apex is the cone's extreme point in every direction within 68 degrees of its
        // axis (half-angle atan(0.6 / 1.5)), so the cone's nearest point to B's bottom plane
        // (normal n = R e_z) is p, at height (t - p) . n below it, and its foot lies inside
        // B's bottom disk (d off centre): d_exact = (t - p) . n.
        ("coaxial stacks", "cylinder on cone apex (tilted)") => {
            let rel = pose(Vector3::new(0.0, 0.0, 1.5 + d), tilted(rng, d));
            let e = ExactPose::of(&rel);
            let mut h = Float::with_val(PREC, 0);
            for (k, apex) in [0.0, 0.0, 1.5].into_iter().enumerate() {
                let dk: Rational = &e.t[k] - exact(apex);
                h += float(&Rational::from(&dk * &e.rot[2][k]));
            }
            case(&s.cone, &s.cylinder, rel, h)
        }
        // Ring on ring, exactly coaxial (a spin about z keeps B's axis exactly z): equal
        // tubes one above the other, tube circles of radius 0.9 at z = 0.6 and t_z + 0.6:
        // d_exact = t_z - 2 * 0.6 (a continuum of closest pairs along a circle).
        ("coaxial stacks", _) => {
            let rel = pose(Vector3::new(0.0, 0.0, 1.2 + d), spin(rng));
            let tz = float(&ExactPose::of(&rel).t[2]);
            case(&s.ring, &s.ring, rel, tz - float(&exact(2.0 * 0.6)))
        }
        // Touching spheres (radius 0.75, centres (0, 0, 0.75) in their frames): B's centre
        // at (0, 0, 0.75) + (1.5 + d) u, u random: d = |c_b - c_a| - 1.5.
        ("touching", "sphere-sphere") => {
            let (rot, u) = (rng.rotation(), rng.unit_vector());
            let c_a = Vector3::new(0.0, 0.0, 0.75);
            let t = c_a + (1.5 + d) * u - rot * c_a;
            let rel = pose(t, rot);
            let c_b = ExactPose::of(&rel).place([0.0, 0.0, 0.75]);
            let dx = |k: usize| float(&(&c_b[k] - exact(c_a[k])));
            let dist = Float::with_val(PREC, dx(0).square() + dx(1).square() + dx(2).square());
            case(&s.sphere, &s.sphere, rel, dist.sqrt() - 1.5)
        }
        // The sphere's centre at distance 0.6 + 0.75 + d from the ring's tube circle, in a
        // random meridian half-plane at a random angle a in [-90, 90] degrees from the
        // outward radial direction: d = gap of [`ball_torus_gap`].
        ("touching", "sphere-torus") => {
            let rot = rng.rotation();
            let (phi, a) = (
                std::f64::consts::TAU * rng.next_f64(),
                std::f64::consts::PI * (rng.next_f64() - 0.5),
            );
            let reach = 0.6 + 0.75 + d;
            let (rho, z) = (0.9 + reach * a.cos(), 0.6 + reach * a.sin());
            sphere_at(Vector3::new(rho * phi.cos(), rho * phi.sin(), z), rot)
        }
        // Two cylinders (radius 0.5, height 1.5) with parallel axes 1 + d apart and heights
        // offset by at most 1 (their sides overlap in z): the closest points are on the two
        // sides, d = |axis offset| - 2 * 0.5 (a continuum along a segment).
        ("touching", _) => {
            let phi = std::f64::consts::TAU * rng.next_f64();
            let dz = 2.0 * rng.next_f64() - 1.0;
            let t = Vector3::new((1.0 + d) * phi.cos(), (1.0 + d) * phi.sin(), dz);
            let rel = pose(t, spin(rng));
            let e = ExactPose::of(&rel);
            let off = hypot(&float(&e.t[0]), &float(&e.t[1]));
            case(&s.cylinder, &s.cylinder, rel, off - 1.0)
        }
        // Nested: the inner surface d inside the outer one; the solids' distance is 0.
        // Ball of radius 0.5 in the sphere of radius 0.75, centres 0.25 - d apart.
        ("nested", "ball in sphere") => {
            let (rot, u) = (rng.rotation(), rng.unit_vector());
            let c = Vector3::new(0.0, 0.0, 0.75) + (0.25 - d) * u;
            let rel = centred_at(c, rot, 0.5);
            case(&s.sphere, &s.ball_05, rel, zero())
        }
        // Ball of radius 0.4 in the cylinder (radius 0.5, height 1.5), its centre 0.1 - d
        // from the axis at height 0.5..1.0: d from the side, >= 0.1 from the disks.
        ("nested", "ball in cylinder") => {
            let rot = rng.rotation();
            let phi = std::f64::consts::TAU * rng.next_f64();
            let z = 0.5 + 0.5 * rng.next_f64();
            let c = Vector3::new((0.1 - d) * phi.cos(), (0.1 - d) * phi.sin(), z);
            let rel = centred_at(c, rot, 0.4);
            case(&s.cylinder, &s.ball_04, rel, zero())
        }
        // The cone (base radius 0.6, height 1.5) in a cylinder of radius 0.6 + d and height
        // 1.5 + 2 d, its base d above the cylinder's bottom: the base rim is d from the side
        // and the bottom all along a circle.
        ("nested", _) => {
            let outer = s.build(cylinder(0.6 + d, 1.5 + 2.0 * d)?)?;
            let rel = pose(Vector3::new(0.0, 0.0, d), spin(rng));
            case(&outer, &s.cone, rel, zero())
        }
        // Tangent along a circle, moved d off it. The sphere (radius 0.75) in the ring's
        // hole, its centre d off the ring's axis and at height h above the tube circle's
        // plane with sqrt((0.9 - d)^2 + h^2) = 0.6 + 0.75 + d, above or below: at d = 0 it
        // touches the tube along a circle; d_exact = gap of [`ball_torus_gap`] (= d).
        ("tangent along a circle", "sphere in torus hole (off axis)") => {
            let sign = if rng.next_f64() < 0.5 { -1.0 } else { 1.0 };
            let h = sign * ((1.35 + d).powi(2) - (0.9 - d).powi(2)).sqrt();
            let rot = rng.rotation();
            sphere_at(d * horizontal(rng) + Vector3::new(0.0, 0.0, 0.6 + h), rot)
        }
        // The ring (tube circle radius 0.9 at local height 0.6, tube radius 0.6) coaxial with
        // the cone, resting on its slant. Coaxial solids are closest in a common meridian
        // half-plane (|p - q|^2 >= (rho_p - rho_q)^2 + (z_p - z_q)^2, equality at equal
        // azimuth), so d = dist((0.9, zc), slant line) - 0.6, the slant through (0.6, 0) and
        // (0, 1.5): dist = |(-0.6, 1.5) x (0.3, zc)| / |(-0.6, 1.5)| = (0.6 zc + 0.45) /
        // sqrt(2.61). Its foot (0.9, zc) - dist n, n = (1.5, 0.6) / sqrt(2.61), lies inside
        // the slant for every d <= 0.1, and the base disk (z = 0) and rim are farther.
        ("tangent along a circle", "ring around cone") => {
            let zc = ((0.6 + d) * 2.61f64.sqrt() - 0.45) / 0.6;
            let rel = pose(Vector3::new(0.0, 0.0, zc - 0.6), spin(rng));
            let zc = float(&ExactPose::of(&rel).place([0.0, 0.0, 0.6])[2]);
            let (rim, apex) = ((0.6, 0.0), (0.0, 1.5));
            let (dx, dz) = (
                float(&exact(apex.0)) - float(&exact(rim.0)),
                float(&exact(apex.1)) - float(&exact(rim.1)),
            );
            let (px, pz) = (float(&exact(0.9)) - float(&exact(rim.0)), zc);
            let cross = Float::with_val(PREC, &dx * &pz - &dz * &px).abs();
            let dist = cross / hypot(&dx, &dz);
            case(&s.cone, &s.ring, rel, dist - float(&exact(0.6)))
        }
        // A ring of tube radius 0.3 coaxial and coplanar with the ring (0.9, 0.6), its tube
        // circle radius 1.8 + d: the inner equator (radius 1.8 + d - 0.3) faces the outer
        // equator (0.9 + 0.6) all along a circle: d = (R_b - 0.3) - (0.9 + 0.6).
        ("tangent along a circle", _) => {
            let big_r = 1.8 + d;
            let outer = s.build(ring(big_r, 0.3, 0.6)?)?;
            let rel = pose(Vector3::zeros(), spin(rng));
            let gap = (float(&exact(big_r)) - float(&exact(0.3)))
                - (float(&exact(0.9)) + float(&exact(0.6)));
            case(&s.ring, &outer, rel, gap)
        }
        _ => return Err(format!("unknown solid family {family} / {variant}").into()),
    })
}

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

/// A job: family, perturbation (`None`: delta = 0) and seed.
type Job = (usize, Option<i32>, usize);

/// The jobs of a level with `families` families, numbered in this order (a job's number is
/// its work unit within the level for `--shard`).
fn jobs(families: usize, cfg: &Config) -> Vec<Job> {
    (0..families)
        .flat_map(|fi| {
            cfg.deltas
                .iter()
                .flat_map(move |&d| (0..cfg.seeds).map(move |s| (fi, d, s)))
        })
        .collect()
}

/// Runs `sample(family, delta, seed)` for the jobs ([`jobs`]) whose number `keep` accepts,
/// in parallel, advancing `bar`; each sample with its job's number.
fn run_all<F>(
    families: usize,
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
    sample: F,
) -> Result<Vec<(usize, Sample)>, Error>
where
    F: Fn(usize, Option<i32>, usize) -> Result<Sample, Error> + Sync,
{
    let jobs: Vec<(usize, Job)> = jobs(families, cfg)
        .into_iter()
        .enumerate()
        .filter(|(k, _)| keep(*k))
        .collect();
    if let Some(b) = bar {
        b.set_length(jobs.len() as u64);
    }
    jobs.par_iter()
        .map(|&(k, (fi, d, s))| {
            let r = sample(fi, d, s);
            if let Some(b) = bar {
                b.inc(1);
            }
            r.map(|r| (k, r))
        })
        .collect()
}

/// Every circle-level sample of `cfg`, in parallel.
pub fn circle_samples(cfg: &Config, bar: Option<&ProgressBar>) -> Result<Vec<Sample>, Error> {
    circle_samples_where(cfg, bar, &|_| true).map(without_numbers)
}

/// Every solid-level sample of `cfg`, in parallel.
pub fn solid_samples(cfg: &Config, bar: Option<&ProgressBar>) -> Result<Vec<Sample>, Error> {
    solid_samples_where(cfg, bar, &|_| true).map(without_numbers)
}

fn without_numbers(v: Vec<(usize, Sample)>) -> Vec<Sample> {
    v.into_iter().map(|(_, s)| s).collect()
}

/// Jobs of the circle level ([`circle_samples_where`] numbers them `0..` this).
pub fn circle_jobs(cfg: &Config) -> usize {
    jobs(CIRCLE_FAMILIES.len(), cfg).len()
}

/// Jobs of the solid level.
pub fn solid_jobs(cfg: &Config) -> usize {
    jobs(SOLID_FAMILIES.len(), cfg).len()
}

/// The circle-level samples whose job number `keep` accepts, with their numbers.
pub fn circle_samples_where(
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Vec<(usize, Sample)>, Error> {
    run_all(CIRCLE_FAMILIES.len(), cfg, bar, keep, circle_sample)
}

/// The solid-level samples whose job number `keep` accepts, with their numbers (the shapes
/// are built only when a job is kept).
pub fn solid_samples_where(
    cfg: &Config,
    bar: Option<&ProgressBar>,
    keep: &(dyn Fn(usize) -> bool + Sync),
) -> Result<Vec<(usize, Sample)>, Error> {
    if !(0..solid_jobs(cfg)).any(keep) {
        return Ok(Vec::new());
    }
    let shapes = Shapes::new(cfg.eps)?;
    run_all(SOLID_FAMILIES.len(), cfg, bar, keep, |fi, d, s| {
        solid_sample(&shapes, fi, d, s)
    })
}

/// Statistics of the samples of one (level, family, delta).
#[derive(Debug, Clone)]
pub struct Row {
    pub key: Key,
    pub cases: usize,
    pub max_abs: f64,
    pub median_abs: f64,
    pub max_rel: f64,
    pub median_rel: f64,
    /// Largest absolute bound of the group.
    pub bound: f64,
    /// Largest `abs_err / bound`.
    pub max_over_bound: f64,
    /// Largest certified width (NaN for circles).
    pub max_width: f64,
    /// Samples with `lower <= exact <= upper` violated.
    pub certificate_violations: usize,
    /// Samples above their error bound.
    pub bound_exceeded: usize,
    /// Slowest answer (seconds).
    pub max_seconds: f64,
}

/// Groups samples by (level, family, delta) in the order of first appearance.
pub fn summarise(samples: &[Sample]) -> Vec<Row> {
    let mut keys: Vec<Key> = Vec::new();
    for s in samples {
        if !keys.contains(&s.key) {
            keys.push(s.key);
        }
    }
    keys.into_iter()
        .map(|key| {
            let g: Vec<&Sample> = samples.iter().filter(|s| s.key == key).collect();
            let col = |f: fn(&Sample) -> f64| g.iter().map(|s| f(s)).collect::<Vec<f64>>();
            let max = |v: &[f64]| v.iter().copied().fold(f64::NAN, f64::max);
            let (abs, rel) = (col(|s| s.abs_err), col(|s| s.rel_err));
            Row {
                key,
                cases: g.len(),
                max_abs: max(&abs),
                median_abs: crate::stats::median(&abs),
                max_rel: max(&rel),
                median_rel: crate::stats::median(&rel),
                bound: max(&col(|s| s.bound)),
                max_over_bound: max(&col(|s| s.abs_err / s.bound)),
                max_width: max(&col(|s| s.width())),
                certificate_violations: g.iter().filter(|s| !s.certified).count(),
                bound_exceeded: g.iter().filter(|s| s.abs_err > s.bound).count(),
                max_seconds: max(&col(|s| s.seconds)),
            }
        })
        .collect()
}

mod raw;

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rational_units_are_unit() {
        let mut rng = SplitMix64(3);
        for _ in 0..20 {
            let u = rational_unit(&mut rng);
            let n: Rational = u.iter().map(|c| Rational::from(c * c)).sum();
            assert_eq!(n, 1);
        }
    }

    #[test]
    fn a_wrong_answer_fails_the_check() {
        let s = Sample {
            key: Key {
                level: Level::Solid,
                family: "touching",
                delta: Some(3),
            },
            variant: "sphere-sphere",
            seed: 0,
            exact: 1e-3,
            value: 1e-3 + 3e-5,
            abs_err: 3e-5,
            rel_err: 1e-5,
            bound: 2e-5,
            lower: 9e-4,
            upper: 1.1e-3,
            certified: true,
            seconds: 0.0,
            reproducer: None,
        };
        assert!(!s.ok());
        assert!(Sample {
            abs_err: 1e-6,
            ..s.clone()
        }
        .ok());
        assert!(!Sample {
            abs_err: 1e-6,
            certified: false,
            ..s
        }
        .ok());
    }
}
