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

use nalgebra::{Point3, Vector3};

/// Iteration cap: smooth convex sets converge to rounding in a few dozen iterations.
pub const MAX_ITERATIONS: usize = 64;

/// Relative progress below which a new support point is taken as no progress:
/// `|v|^2 - v . w <= NO_PROGRESS_REL |v|^2` (a few ulps of the squared distance).
const NO_PROGRESS_REL: f64 = 1e-14;

/// One vertex of the simplex: `w = a - b`.
#[derive(Debug, Clone, Copy)]
struct Vertex {
    w: Vector3<f64>,
    a: Point3<f64>,
    b: Point3<f64>,
}

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
    let vertex = |d: &Vector3<f64>| {
        let a = support_a(d);
        let b = support_b(&-d);
        Vertex { w: a - b, a, b }
    };
    let mut v = if initial.norm_squared() > 0.0 {
        initial
    } else {
        Vector3::x()
    };
    let zero = Vertex {
        w: Vector3::zeros(),
        a: Point3::origin(),
        b: Point3::origin(),
    };
    let mut simplex = [zero; 4];
    let mut len = 0;
    let mut lambdas = [0.0; 4];
    let mut lower = f64::NEG_INFINITY;
    let mut upper = f64::INFINITY;
    let mut intersect = false;
    let mut iterations = 0;
    while iterations < MAX_ITERATIONS {
        iterations += 1;
        let vv = v.norm_squared();
        let norm = vv.sqrt();
        let new = vertex(&-v);
        let vw = v.dot(&new.w);
        lower = lower.max(vw / norm);
        if len > 0 && (upper - lower <= target_gap || vv - vw <= NO_PROGRESS_REL * vv) {
            break;
        }
        if simplex[..len].iter().any(|s| s.w == new.w) {
            break;
        }
        simplex[len] = new;
        len += 1;
        let (closest, face) = closest_to_origin(&simplex[..len]);
        let old = simplex;
        len = face.len;
        for k in 0..len {
            simplex[k] = old[face.idx[k]];
            lambdas[k] = face.weight[k];
        }
        v = closest;
        upper = v.norm();
        if upper <= tiny || len == 4 {
            intersect = true;
            break;
        }
    }
    let (mut pa, mut pb) = (Vector3::zeros(), Vector3::zeros());
    for (s, &l) in simplex[..len].iter().zip(&lambdas) {
        pa += s.a.coords * l;
        pb += s.b.coords * l;
    }
    GjkResult {
        lower,
        upper: (pa - pb).norm(),
        point_a: Point3::from(pa),
        point_b: Point3::from(pb),
        intersect,
        iterations,
    }
}

/// The point of the simplex's hull closest to the origin, and the vertices (index, weight)
/// of the face it lies in: the best over all faces whose affine closest point has positive
/// barycentric weights (the closest point of a hull lies in the relative interior of one
/// face; every other such point lies in the hull too). The whole tetrahedron is a face when
/// it contains the origin.
fn closest_to_origin(simplex: &[Vertex]) -> (Vector3<f64>, Face) {
    let n = simplex.len();
    let mut best = (f64::INFINITY, Vector3::zeros(), Face::default());
    for mask in 1u32..(1 << n) {
        let mut face = Face::default();
        for i in 0..n {
            if mask & (1 << i) != 0 {
                face.idx[face.len] = i;
                face.len += 1;
            }
        }
        if !affine_closest(simplex, &mut face) {
            continue;
        }
        let mut p = Vector3::zeros();
        for k in 0..face.len {
            p += simplex[face.idx[k]].w * face.weight[k];
        }
        let d = p.norm_squared();
        if d < best.0 {
            best = (d, p, face);
        }
    }
    (best.1, best.2)
}

/// Vertices of a face of the simplex (indices) and barycentric weights.
#[derive(Debug, Clone, Copy, Default)]
struct Face {
    idx: [usize; 4],
    weight: [f64; 4],
    len: usize,
}

/// Sets the barycentric weights of the point of the face's affine hull closest to the
/// origin; `false` unless they are all positive and the points affinely independent.
fn affine_closest(simplex: &[Vertex], face: &mut Face) -> bool {
    let y0 = simplex[face.idx[0]].w;
    let k = face.len - 1;
    if k == 0 {
        face.weight[0] = 1.0;
        return true;
    }
    // Normal equations G mu = -E^T y0, E = [y_i - y0].
    let mut e = [Vector3::zeros(); 3];
    for i in 0..k {
        e[i] = simplex[face.idx[i + 1]].w - y0;
    }
    let mut g = [[0.0; 3]; 3];
    let mut rhs = [0.0; 3];
    for i in 0..k {
        for j in 0..k {
            g[i][j] = e[i].dot(&e[j]);
        }
        rhs[i] = -e[i].dot(&y0);
    }
    let Some(mu) = solve(&g, &rhs, k) else {
        return false;
    };
    face.weight[0] = 1.0 - mu[..k].iter().sum::<f64>();
    face.weight[1..=k].copy_from_slice(&mu[..k]);
    face.weight[..=k].iter().all(|&l| l > 0.0)
}

/// Solves the `k x k` symmetric system by Cramer's rule; `None` when it is (nearly) singular
/// relative to its entries (affinely dependent points).
fn solve(g: &[[f64; 3]; 3], rhs: &[f64; 3], k: usize) -> Option<[f64; 3]> {
    let scale: f64 = (0..k).map(|i| g[i][i]).fold(0.0, f64::max);
    match k {
        1 => (g[0][0] > 0.0).then(|| [rhs[0] / g[0][0], 0.0, 0.0]),
        2 => {
            let det = g[0][0] * g[1][1] - g[0][1] * g[1][0];
            if !(det > 1e-14 * scale * scale) {
                return None;
            }
            Some([
                (rhs[0] * g[1][1] - g[0][1] * rhs[1]) / det,
                (g[0][0] * rhs[1] - rhs[0] * g[1][0]) / det,
                0.0,
            ])
        }
        _ => {
            let det3 = |m: &[[f64; 3]; 3]| {
                m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                    - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                    + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
            };
            let det = det3(g);
            if !(det > 1e-14 * scale * scale * scale) {
                return None;
            }
            let mut out = [0.0; 3];
            for (c, o) in out.iter_mut().enumerate() {
                let mut m = *g;
                for r in 0..3 {
                    m[r][c] = rhs[r];
                }
                *o = det3(&m) / det;
            }
            Some(out)
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
        assert!(r.lower <= exact + 1e-12 && exact <= r.upper + 1e-12, "{r:?} {exact}");
        assert!(r.upper - r.lower <= 1e-9, "{r:?}");
        let r = gjk(
            cube(Vector3::zeros(), 1.0),
            cube(Vector3::new(2.5, 0.3, 0.2), 1.0),
            Vector3::x(),
            0.0,
            1e-14,
        );
        assert!((r.lower - 0.5).abs() < 1e-12 && (r.upper - 0.5).abs() < 1e-12, "{r:?}");
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
