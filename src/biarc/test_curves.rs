//! Analytic curves for tests: clothoids (Euler spirals), ellipse arcs and rational circle arcs.

use nalgebra::{Point2, Vector2};

use super::fit::PlanarCurve;

/// 8-point Gauss-Legendre nodes and weights on [-1, 1].
const GL8: [(f64, f64); 4] = [
    (0.183_434_642_495_649_8, 0.362_683_783_378_362),
    (0.525_532_409_916_329, 0.313_706_645_877_887_3),
    (0.796_666_477_413_626_7, 0.222_381_034_453_374_47),
    (0.960_289_856_497_536_2, 0.101_228_536_290_376_26),
];

/// Table spacing count for the clothoid integral.
const TABLE: usize = 64;

/// Clothoid by arc length: tangent angle `theta0 + k0 s + k1 s^2 / 2`, `s` in `[0, length]`.
pub struct Clothoid {
    pub theta0: f64,
    pub k0: f64,
    pub k1: f64,
    pub length: f64,
    table: Vec<Point2<f64>>,
}

impl Clothoid {
    pub fn new(theta0: f64, k0: f64, k1: f64, length: f64) -> Clothoid {
        let mut c = Clothoid {
            theta0,
            k0,
            k1,
            length,
            table: vec![Point2::origin()],
        };
        let h = length / TABLE as f64;
        for j in 0..TABLE {
            let p = c.table[j] + c.integral(j as f64 * h, (j + 1) as f64 * h);
            c.table.push(p);
        }
        c
    }
    fn theta(&self, s: f64) -> f64 {
        self.theta0 + self.k0 * s + 0.5 * self.k1 * s * s
    }
    fn integral(&self, a: f64, b: f64) -> Vector2<f64> {
        let (m, r) = (0.5 * (a + b), 0.5 * (b - a));
        let mut acc = Vector2::zeros();
        for &(x, w) in &GL8 {
            for s in [m - r * x, m + r * x] {
                let th = self.theta(s);
                acc += Vector2::new(th.cos(), th.sin()) * w;
            }
        }
        acc * r
    }
}

impl PlanarCurve for Clothoid {
    fn point_and_derivative(&self, s: f64) -> (Point2<f64>, Vector2<f64>) {
        let h = self.length / TABLE as f64;
        let j = ((s / h).floor().max(0.0) as usize).min(TABLE - 1);
        let p = self.table[j] + self.integral(j as f64 * h, s);
        let th = self.theta(s);
        (p, Vector2::new(th.cos(), th.sin()))
    }
}

/// Ellipse `(a cos t, b sin t)`: a spiral between its vertices (t in (0, pi/2)).
pub struct Ellipse {
    pub a: f64,
    pub b: f64,
}

impl PlanarCurve for Ellipse {
    fn point_and_derivative(&self, t: f64) -> (Point2<f64>, Vector2<f64>) {
        let (s, c) = t.sin_cos();
        (
            Point2::new(self.a * c, self.b * s),
            Vector2::new(-self.a * s, self.b * c),
        )
    }
}

/// Homogeneous Bezier coefficients `[x w, y w, w]` of the rational quadratic of the circle arc
/// about `c` of radius `r` from angle `a0` to `a1` (`|a1 - a0| < pi`), its middle control point
/// moved outward along the bisector by `bump` (0: the exact arc).
pub fn circle_arc_quadratic(c: Point2<f64>, r: f64, a0: f64, a1: f64, bump: f64) -> Vec<[f64; 3]> {
    let at = |a: f64| c + Vector2::new(a.cos(), a.sin()) * r;
    let half = 0.5 * (a1 - a0);
    let mid_dir = Vector2::new((a0 + half).cos(), (a0 + half).sin());
    let p1 = c + mid_dir * (r / half.cos() + bump);
    let w1 = half.cos();
    let (p0, p2) = (at(a0), at(a1));
    vec![
        [p0.x, p0.y, 1.0],
        [p1.x * w1, p1.y * w1, w1],
        [p2.x, p2.y, 1.0],
    ]
}
