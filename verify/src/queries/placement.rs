//! Poses that aim at a gap: B placed along a random direction and the translation solved
//! for with the oracle's quick mode (Newton steps with the witness slope from the far side,
//! secant or bisection once the target is passed; a touching target never accepts a
//! realised 0, which would be a crossing).

use super::pool::Shape;
use super::pose_spec::PoseSpec;
use crate::oracle::{surface_distance, OracleOptions};
use nalgebra::{Isometry3, Quaternion, UnitQuaternion, Vector3};
use revdist::rng::SplitMix64;

/// The quick oracle at a pose: `(signed gap, unsigned surface distance, d gap / d s)` for
/// B moved along `u` (the slope is `u . n`, `n` the unit vector from A's witness to B's).
pub(super) fn quick_eval(
    a: &Shape,
    b: &Shape,
    pos: &Isometry3<f64>,
    u: &Vector3<f64>,
) -> (f64, f64, f64) {
    let r = surface_distance(&a.index, &b.index, pos, &OracleOptions::quick());
    let v = r.point_b - r.point_a;
    let slope = if r.upper > 0.0 {
        u.dot(&v) / r.upper
    } else {
        f64::NAN
    };
    (r.gap(), r.upper, slope)
}

/// Finds `s` with `g(s) = target` starting from `s0` where `g(s0) > target`: Newton steps
/// with the witness slope from the side above the target, secant or bisection once the
/// target has been passed (the bracket keeps every step inside). `f` returns `(g, slope)`.
/// Returns the best `(s, g)` when it is within `accept` of the target.
pub(super) fn newton_gap(
    f: impl Fn(f64) -> (f64, f64),
    s0: f64,
    target: f64,
    tol: f64,
    accept: f64,
) -> Option<(f64, f64)> {
    let (mut g, mut slope) = f(s0);
    if g.is_nan() || g <= target {
        return None;
    }
    let mut s = s0;
    let (mut good, mut g_good) = (s0, g);
    let mut bad: Option<(f64, f64)> = None;
    let mut best = (s0, g);
    // Aiming at 0 (touching), a realised 0 means crossing surfaces: not accepted.
    let hit = |g: f64| (g - target).abs() <= tol && (target != 0.0 || g > 0.0);
    for _ in 0..80 {
        if hit(g) {
            return Some((s, g));
        }
        if g > target {
            good = s;
            g_good = g;
        } else {
            bad = Some((s, g));
        }
        let inside = |x: f64| match bad {
            Some((b, _)) => x > good.min(b) && x < good.max(b),
            None => true,
        };
        let newton = if g > target && slope.is_finite() && slope != 0.0 {
            let sl = if slope.abs() < 0.2 {
                0.2 * slope.signum()
            } else {
                slope
            };
            s - (g - target) / sl
        } else {
            f64::NAN
        };
        let next = if newton.is_finite() && inside(newton) && newton != s {
            newton
        } else if let Some((b, gb)) = bad {
            let sec = good + (target - g_good) * (b - good) / (gb - g_good);
            let mid = 0.5 * (good + b);
            if sec.is_finite()
                && inside(sec)
                && (sec - good).abs() > 0.01 * (b - good).abs()
                && (sec - b).abs() > 0.01 * (b - good).abs()
            {
                sec
            } else {
                mid
            }
        } else {
            break;
        };
        if next == s {
            break;
        }
        s = next;
        (g, slope) = f(s);
        let better = if target == 0.0 {
            g > 0.0 && (best.1 <= 0.0 || g < best.1)
        } else {
            (g - target).abs() < (best.1 - target).abs()
        };
        if better {
            best = (s, g);
        }
    }
    ((best.1 - target).abs() <= accept && (target != 0.0 || best.1 > 0.0)).then_some(best)
}

pub(super) fn spec(translation: Vector3<f64>, q: [f64; 4]) -> PoseSpec {
    PoseSpec {
        translation: [translation.x, translation.y, translation.z],
        rotation: q,
    }
}

/// A rotation for B: random (most), about z only (coaxial with A), flipped, or none.
pub(super) fn draw_rotation(rng: &mut SplitMix64) -> ([f64; 4], bool) {
    let u = rng.next_f64();
    if u < 0.65 {
        (rng.quaternion(), false)
    } else if u < 0.85 {
        let a = rng.range(0.0, std::f64::consts::TAU);
        ([(0.5 * a).cos(), 0.0, 0.0, (0.5 * a).sin()], true)
    } else if u < 0.92 {
        ([0.0, 1.0, 0.0, 0.0], true)
    } else {
        ([1.0, 0.0, 0.0, 0.0], true)
    }
}

/// Axis midpoint of a shape (its box centre on the axis).
pub(super) fn axis_centre(s: &Shape) -> Vector3<f64> {
    Vector3::new(0.0, 0.0, 0.5 * (s.index.geom.min[1] + s.index.geom.max[1]))
}

/// Places B along a random direction from A's centre at translation parameter `s`.
fn along(a: &Shape, b: &Shape, q: [f64; 4], u: Vector3<f64>, s: f64) -> PoseSpec {
    let rot = UnitQuaternion::from_quaternion(Quaternion::new(q[0], q[1], q[2], q[3]));
    let t = axis_centre(a) + u * s - rot * axis_centre(b);
    spec(t, q)
}

/// Solves for a pose of B with signed gap `target` along a random direction (Newton on the
/// translation from far away); `None` when no direction reached it.
pub(super) fn place_at_gap(
    rng: &mut SplitMix64,
    a: &Shape,
    b: &Shape,
    target: f64,
) -> Option<(PoseSpec, f64)> {
    for _ in 0..6 {
        let (q, coaxial) = draw_rotation(rng);
        let u = if coaxial && rng.chance(0.5) {
            Vector3::new(0.0, 0.0, if rng.chance(0.5) { 1.0 } else { -1.0 })
        } else {
            rng.direction()
        };
        let far = a.index.geom.radius + b.index.geom.radius + a.size + b.size;
        let scale = a.size.max(b.size);
        let f = |s: f64| {
            let (g, _, slope) = quick_eval(a, b, &along(a, b, q, u, s).isometry(), &u);
            (g, slope)
        };
        let tol = (1e-3 * target.abs()).max(1e-13 * scale);
        let accept = (0.05 * target.abs()).max(1e-10 * scale);
        if let Some((s, got)) = newton_gap(f, far, target, tol, accept) {
            return Some((along(a, b, q, u, s), got));
        }
    }
    None
}

/// A point of A's solid at depth at least `depth` (by the oracle's signed distance).
pub(super) fn interior_point(rng: &mut SplitMix64, a: &Shape, depth: f64) -> Option<Vector3<f64>> {
    let g = &a.index.geom;
    for _ in 0..400 {
        let rho = rng.range(0.0, g.max[0]);
        let z = rng.range(g.min[1], g.max[1]);
        let s = a.index.signed([rho, z]);
        if s.value < -depth {
            let th = rng.range(0.0, std::f64::consts::TAU);
            return Some(Vector3::new(rho * th.cos(), rho * th.sin(), z));
        }
    }
    None
}
