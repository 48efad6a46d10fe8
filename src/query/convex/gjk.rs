//! Distance between two convex sets given by their support functions: GJK (Gilbert,
//! Johnson and Keerthi 1988) with both bounds of the duality gap.
//!
//! The Minkowski difference `M = A - B` has support `s_M(d) = s_A(d) - s_B(-d)`. Each
//! iteration adds the support point `w = s_M(-v)` to a simplex of at most four points of `M`
//! and moves `v` to the simplex's point closest to the origin.
//! * **Upper bound**: `v = p_A - p_B` with `p_A`, `p_B` the same convex combination of the
//!   simplex's support points of `A` and `B`; they lie in the sets, so `|p_A - p_B|` is a
//!   realised distance.
//! * **Lower bound**: every point `m` of `M` has `v . m >= v . w` (`w` is the support in
//!   `-v`), so `|m| >= v . w / |v|`: the separation of the sets along `v`. The largest over
//!   the iterations is kept; it needs only that the supports are exact, not that `v` is.
//!
//! The iteration stops when the gap is within the caller's target, when a support point
//! brings no progress (the gap is at rounding level), or after [`MAX_ITERATIONS`].

use crate::query::simplex::{PointPair, Simplex};
use nalgebra::{Point3, Vector3};

/// Iteration cap: smooth convex sets converge to rounding in a few dozen iterations.
pub const MAX_ITERATIONS: usize = 64;

/// Relative progress below which a new support point is taken as no progress:
/// `|v|^2 - v . w <= NO_PROGRESS_REL |v|^2` (a few ulps of the squared distance).
const NO_PROGRESS_REL: f64 = 1e-14;

/// What GJK established.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct GjkResult {
    /// Certified lower bound of the distance between the sets (exact supports assumed;
    /// may be negative: no separation found).
    pub lower: f64,
    /// `|point_a - point_b|`.
    pub upper: f64,
    /// A point of A (convex combination of support points of A).
    pub point_a: Point3<f64>,
    /// A point of B; `point_a = point_b` (up to rounding) when the origin is in `M`.
    pub point_b: Point3<f64>,
    /// The simplex reached the origin: the sets intersect (up to rounding) at `point_a`.
    pub intersect: bool,
    /// `point_a` is a single support point of A (every vertex of the final simplex has the
    /// same point of A), so it lies on A's boundary where the supports do; likewise
    /// `single_b`.
    pub single_a: bool,
    pub single_b: bool,
    pub iterations: usize,
}

/// GJK between `A` and `B` given their supports (`support_a(d)` maximises `d . x` over A),
/// starting from direction `initial` (a guess of `p_A - p_B`), until `upper - lower <=
/// target_gap`. `tiny` is the length below which `v` counts as the origin (rounding of the
/// configuration's coordinates).
pub fn gjk(
    support_a: impl Fn(&Vector3<f64>) -> Point3<f64>,
    support_b: impl Fn(&Vector3<f64>) -> Point3<f64>,
    initial: Vector3<f64>,
    target_gap: f64,
    tiny: f64,
) -> GjkResult {
    let mut g = Gjk::new(support_a, support_b, initial, tiny);
    loop {
        g.probe();
        if g.simplex.len() > 0 && g.gap() <= target_gap {
            break;
        }
        if g.advance() != Status::Running {
            break;
        }
    }
    g.result()
}

/// Where a [`Gjk`] run stands after [`Gjk::advance`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// The simplex moved closer to the origin; another probe may narrow the gap.
    Running,
    /// The last support point brought no progress (the gap is at rounding level), repeated
    /// a vertex, or the run reached [`MAX_ITERATIONS`].
    Stalled,
    /// The simplex reached the origin: the sets intersect up to rounding.
    Intersect,
}

/// GJK one step at a time, so that the caller can test its own acceptance between steps
/// (the convex path moves the closest points to the surfaces and stops as soon as they fit).
/// [`Gjk::probe`] evaluates the support point for the current `v` and raises the lower
/// bound; [`Gjk::advance`] adds that point to the simplex and moves `v`.
pub struct Gjk<SA, SB> {
    support_a: SA,
    support_b: SB,
    v: Vector3<f64>,
    simplex: Simplex,
    /// The support point for the current `v` (after a probe): `w = a - b` and `(a, b)`.
    new: Option<(Vector3<f64>, PointPair)>,
    lower: f64,
    upper: f64,
    tiny: f64,
    iterations: usize,
    intersect: bool,
}

impl<SA, SB> Gjk<SA, SB>
where
    SA: Fn(&Vector3<f64>) -> Point3<f64>,
    SB: Fn(&Vector3<f64>) -> Point3<f64>,
{
    /// A run from direction `initial` (a guess of `p_A - p_B`); `tiny` as for [`gjk`].
    pub fn new(support_a: SA, support_b: SB, initial: Vector3<f64>, tiny: f64) -> Self {
        Gjk {
            support_a,
            support_b,
            v: if initial.norm_squared() > 0.0 {
                initial
            } else {
                Vector3::x()
            },
            simplex: Simplex::default(),
            new: None,
            lower: f64::NEG_INFINITY,
            upper: f64::INFINITY,
            tiny,
            iterations: 0,
            intersect: false,
        }
    }

    /// The support point of `A - B` in direction `-v` (once per `v`), and the separation
    /// along `v` it proves.
    pub fn probe(&mut self) {
        if self.new.is_some() {
            return;
        }
        let d = -self.v;
        let a = (self.support_a)(&d);
        let b = (self.support_b)(&-d);
        let w = a - b;
        let vv = self.v.norm_squared();
        self.lower = self.lower.max(self.v.dot(&w) / vv.sqrt());
        self.new = Some((w, (a, b)));
    }

    /// `upper - lower` (infinite before the first [`Gjk::advance`]).
    pub fn gap(&self) -> f64 {
        self.upper - self.lower
    }

    /// Simplex updates so far.
    pub fn iterations(&self) -> usize {
        self.iterations
    }

    /// The certified lower bound so far (may be negative).
    pub fn lower(&self) -> f64 {
        self.lower
    }

    /// Adds the probed support point to the simplex and moves `v` to the simplex's point
    /// nearest the origin (probes first if needed).
    pub fn advance(&mut self) -> Status {
        if self.intersect {
            return Status::Intersect;
        }
        self.probe();
        let (w, pair) = self.new.expect("probed");
        if self.iterations >= MAX_ITERATIONS {
            return Status::Stalled;
        }
        let vv = self.v.norm_squared();
        let vw = self.v.dot(&w);
        // No progress, or a vertex repeated (the simplex refuses it).
        if (self.simplex.len() > 0 && vv - vw <= NO_PROGRESS_REL * vv)
            || !self.simplex.push(w, pair)
        {
            return Status::Stalled;
        }
        self.iterations += 1;
        self.new = None;
        let closest = self.simplex.closest_to_origin();
        self.v = closest;
        self.upper = closest.norm();
        if self.upper <= self.tiny || self.simplex.len() == 4 {
            self.intersect = true;
            return Status::Intersect;
        }
        Status::Running
    }

    /// The simplex's support points of A and of B (as many as its vertices).
    pub fn support_points(&self) -> impl Iterator<Item = (Point3<f64>, Point3<f64>)> + '_ {
        self.simplex.pairs().iter().copied()
    }

    /// The closest points so far and the bounds.
    pub fn result(&self) -> GjkResult {
        let pairs = self.simplex.pairs();
        let (mut pa, mut pb) = self
            .simplex
            .combination()
            .unwrap_or((Point3::origin(), Point3::origin()));
        let single = |f: fn(&PointPair) -> Point3<f64>| {
            !pairs.is_empty() && pairs.iter().all(|s| f(s) == f(&pairs[0]))
        };
        let (single_a, single_b) = (single(|s| s.0), single(|s| s.1));
        if single_a {
            pa = pairs[0].0;
        }
        if single_b {
            pb = pairs[0].1;
        }
        GjkResult {
            lower: self.lower,
            upper: (pa - pb).norm(),
            point_a: pa,
            point_b: pb,
            intersect: self.intersect,
            single_a,
            single_b,
            iterations: self.iterations,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ball(c: Vector3<f64>, r: f64) -> impl Fn(&Vector3<f64>) -> Point3<f64> {
        move |d: &Vector3<f64>| Point3::from(c + d.normalize() * r)
    }

    fn cube(c: Vector3<f64>, h: f64) -> impl Fn(&Vector3<f64>) -> Point3<f64> {
        move |d: &Vector3<f64>| Point3::from(c + d.map(|x| if x >= 0.0 { h } else { -h }))
    }

    #[test]
    fn balls_and_cubes() {
        let r = gjk(
            ball(Vector3::zeros(), 1.0),
            ball(Vector3::new(3.0, 1.0, -0.5), 0.5),
            Vector3::x(),
            1e-10,
            1e-14,
        );
        let exact = Vector3::new(3.0, 1.0, -0.5).norm() - 1.5;
        assert!(
            r.lower <= exact + 1e-12 && exact <= r.upper + 1e-12,
            "{r:?} {exact}"
        );
        assert!(r.upper - r.lower <= 1e-9, "{r:?}");
        let r = gjk(
            cube(Vector3::zeros(), 1.0),
            cube(Vector3::new(2.5, 0.3, 0.2), 1.0),
            Vector3::x(),
            0.0,
            1e-14,
        );
        assert!(
            (r.lower - 0.5).abs() < 1e-12 && (r.upper - 0.5).abs() < 1e-12,
            "{r:?}"
        );
        let r = gjk(
            cube(Vector3::zeros(), 1.0),
            ball(Vector3::new(0.5, 0.3, 0.2), 1.0),
            Vector3::x(),
            0.0,
            1e-14,
        );
        assert!(r.intersect && r.lower <= 0.0, "{r:?}");
    }
}
