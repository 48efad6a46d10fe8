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
        if g.len > 0 && g.gap() <= target_gap {
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
    simplex: [Vertex; 4],
    lambdas: [f64; 4],
    len: usize,
    /// The support point for the current `v` (after a probe).
    new: Option<Vertex>,
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
        let zero = Vertex {
            w: Vector3::zeros(),
            a: Point3::origin(),
            b: Point3::origin(),
        };
        Gjk {
            support_a,
            support_b,
            v: if initial.norm_squared() > 0.0 {
                initial
            } else {
                Vector3::x()
            },
            simplex: [zero; 4],
            lambdas: [0.0; 4],
            len: 0,
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
        let new = Vertex { w: a - b, a, b };
        let vv = self.v.norm_squared();
        self.lower = self.lower.max(self.v.dot(&new.w) / vv.sqrt());
        self.new = Some(new);
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
        let new = self.new.expect("probed");
        if self.iterations >= MAX_ITERATIONS {
            return Status::Stalled;
        }
        let vv = self.v.norm_squared();
        let vw = self.v.dot(&new.w);
        let len = self.len;
        if (len > 0 && vv - vw <= NO_PROGRESS_REL * vv)
            || self.simplex[..len].iter().any(|s| s.w == new.w)
        {
            return Status::Stalled;
        }
        self.iterations += 1;
        self.new = None;
        self.simplex[len] = new;
        let (closest, face) = closest_to_origin(&self.simplex[..len + 1]);
        let old = self.simplex;
        self.len = face.len;
        for k in 0..face.len {
            self.simplex[k] = old[face.idx[k]];
            self.lambdas[k] = face.weight[k];
        }
        self.v = closest;
        self.upper = closest.norm();
        if self.upper <= self.tiny || self.len == 4 {
            self.intersect = true;
            return Status::Intersect;
        }
        Status::Running
    }

    /// The simplex's support points of A and of B (as many as its vertices).
    pub fn support_points(&self) -> impl Iterator<Item = (Point3<f64>, Point3<f64>)> + '_ {
        self.simplex[..self.len].iter().map(|s| (s.a, s.b))
    }

    /// The closest points so far and the bounds.
    pub fn result(&self) -> GjkResult {
        let simplex = &self.simplex[..self.len];
        let (mut pa, mut pb) = (Vector3::zeros(), Vector3::zeros());
        for (s, &l) in simplex.iter().zip(&self.lambdas) {
            pa += s.a.coords * l;
            pb += s.b.coords * l;
        }
        let single = |f: fn(&Vertex) -> Point3<f64>| {
            !simplex.is_empty() && simplex.iter().all(|s| f(s) == f(&simplex[0]))
        };
        let (single_a, single_b) = (single(|s| s.a), single(|s| s.b));
        if single_a {
            pa = simplex[0].a.coords;
        }
        if single_b {
            pb = simplex[0].b.coords;
        }
        GjkResult {
            lower: self.lower,
            upper: (pa - pb).norm(),
            point_a: Point3::from(pa),
            point_b: Point3::from(pb),
            intersect: self.intersect,
            single_a,
            single_b,
            iterations: self.iterations,
        }
    }
}

/// The point of the simplex's hull closest to the origin, and the face (vertex indices and
/// barycentric weights) it lies in; the whole tetrahedron when it contains the origin.
/// Region tests after Ericson, *Real-Time Collision Detection*, 5.1.
fn closest_to_origin(simplex: &[Vertex]) -> (Vector3<f64>, Face) {
    let w = |i: usize| simplex[i].w;
    match simplex.len() {
        1 => (w(0), Face::of(&[(0, 1.0)])),
        2 => segment(w(0), w(1), [0, 1]),
        3 => triangle(w(0), w(1), w(2), [0, 1, 2]),
        _ => tetrahedron(simplex),
    }
}

/// Vertices of a face of the simplex (indices) and barycentric weights.
#[derive(Debug, Clone, Copy, Default)]
struct Face {
    idx: [usize; 4],
    weight: [f64; 4],
    len: usize,
}

impl Face {
    fn of(entries: &[(usize, f64)]) -> Face {
        let mut f = Face::default();
        for &(i, l) in entries {
            f.idx[f.len] = i;
            f.weight[f.len] = l;
            f.len += 1;
        }
        f
    }
}

fn segment(a: Vector3<f64>, b: Vector3<f64>, id: [usize; 2]) -> (Vector3<f64>, Face) {
    let ab = b - a;
    let len2 = ab.norm_squared();
    let t = if len2 > 0.0 { -a.dot(&ab) / len2 } else { 0.0 };
    if t <= 0.0 {
        (a, Face::of(&[(id[0], 1.0)]))
    } else if t >= 1.0 {
        (b, Face::of(&[(id[1], 1.0)]))
    } else {
        (a + ab * t, Face::of(&[(id[0], 1.0 - t), (id[1], t)]))
    }
}

fn triangle(
    a: Vector3<f64>,
    b: Vector3<f64>,
    c: Vector3<f64>,
    id: [usize; 3],
) -> (Vector3<f64>, Face) {
    let (ab, ac) = (b - a, c - a);
    let ap = -a;
    let (d1, d2) = (ab.dot(&ap), ac.dot(&ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Face::of(&[(id[0], 1.0)]));
    }
    let bp = -b;
    let (d3, d4) = (ab.dot(&bp), ac.dot(&bp));
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Face::of(&[(id[1], 1.0)]));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return segment(a, b, [id[0], id[1]]);
    }
    let cp = -c;
    let (d5, d6) = (ab.dot(&cp), ac.dot(&cp));
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Face::of(&[(id[2], 1.0)]));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return segment(a, c, [id[0], id[2]]);
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return segment(b, c, [id[1], id[2]]);
    }
    let denom = va + vb + vc;
    if denom.is_nan() || denom <= 0.0 {
        // Degenerate (collinear) triangle: the best of its edges.
        return best([
            segment(a, b, [id[0], id[1]]),
            segment(a, c, [id[0], id[2]]),
            segment(b, c, [id[1], id[2]]),
        ]);
    }
    let (v, w) = (vb / denom, vc / denom);
    let u = 1.0 - v - w;
    (
        a + ab * v + ac * w,
        Face::of(&[(id[0], u), (id[1], v), (id[2], w)]),
    )
}

fn best<const N: usize>(options: [(Vector3<f64>, Face); N]) -> (Vector3<f64>, Face) {
    let mut out = options[0];
    for o in &options[1..] {
        if o.0.norm_squared() < out.0.norm_squared() {
            out = *o;
        }
    }
    out
}

fn tetrahedron(s: &[Vertex]) -> (Vector3<f64>, Face) {
    let p = [s[0].w, s[1].w, s[2].w, s[3].w];
    // Faces with the opposite vertex; the origin is outside a face when it and the opposite
    // vertex lie on different sides of the face's plane. Only the faces through the newest
    // vertex (3) are tested: the old triangle's closest point `v` was inside it, so its
    // plane is orthogonal to `v`, and the origin and the new support point (`v . w < |v|^2`,
    // [`Gjk::advance`] checks progress) lie on the same side of it. (Should rounding put the
    // origin outside that face, the run reports an intersection, which the convex path
    // certifies independently or declines.)
    let faces = [([0, 1, 3], 2), ([0, 2, 3], 1), ([1, 2, 3], 0)];
    let mut out: Option<(Vector3<f64>, Face)> = None;
    let mut inside = true;
    for (f, opposite) in faces {
        let (a, b, c) = (p[f[0]], p[f[1]], p[f[2]]);
        let n = (b - a).cross(&(c - a));
        let side_origin = -a.dot(&n);
        let side_opposite = (p[opposite] - a).dot(&n);
        if side_origin * side_opposite >= 0.0 && side_opposite != 0.0 {
            continue;
        }
        inside = false;
        let cand = triangle(a, b, c, f);
        match out {
            Some(o) if o.0.norm_squared() <= cand.0.norm_squared() => {}
            _ => out = Some(cand),
        }
    }
    if inside {
        // Barycentric weights of the origin: signed volumes.
        let vol = |a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>, d: Vector3<f64>| {
            (b - a).dot(&(c - a).cross(&(d - a)))
        };
        let total = vol(p[0], p[1], p[2], p[3]);
        let o = Vector3::zeros();
        let l = [
            vol(o, p[1], p[2], p[3]) / total,
            vol(p[0], o, p[2], p[3]) / total,
            vol(p[0], p[1], o, p[3]) / total,
            vol(p[0], p[1], p[2], o) / total,
        ];
        return (
            Vector3::zeros(),
            Face::of(&[(0, l[0]), (1, l[1]), (2, l[2]), (3, l[3])]),
        );
    }
    out.expect("a face is outside when the origin is not inside")
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
