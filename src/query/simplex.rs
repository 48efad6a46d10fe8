//! The simplex of GJK (Gilbert, Johnson and Keerthi 1988), the one step both GJK iterations
//! of the query share: the convex path's ([`crate::query::convex`]) and the hull bounds'
//! ([`mod@crate::query::bound::hull_bound`]). Up to four points of two sets' Minkowski
//! difference and the point of their convex hull closest to the origin, by Voronoi regions
//! (Ericson 2005, sections 5.1.5 and 9.5.2), with the pair of set points behind each.

use nalgebra::{Point3, Vector3};

/// A point of A's hull and a point of B's (A's frame).
pub type PointPair = (Point3<f64>, Point3<f64>);

/// Up to four points `w = q - p` of the Minkowski difference, each with its points `p` on
/// hull A and `q` on hull B, and the barycentric coordinates of the closest point found
/// last.
#[derive(Default)]
pub(crate) struct Simplex {
    points: [Vector3<f64>; 4],
    pairs: [PointPair; 4],
    weights: [f64; 4],
    len: usize,
}

impl Simplex {
    /// Adds a vertex; `false` when it repeats one already there (no progress possible).
    pub(crate) fn push(&mut self, w: Vector3<f64>, pair: PointPair) -> bool {
        if self.points[..self.len].contains(&w) || self.len == 4 {
            return false;
        }
        self.points[self.len] = w;
        self.pairs[self.len] = pair;
        self.len += 1;
        true
    }

    /// How many vertices the simplex keeps.
    pub(crate) fn len(&self) -> usize {
        self.len
    }

    /// The pairs of set points behind the vertices kept.
    pub(crate) fn pairs(&self) -> &[PointPair] {
        &self.pairs[..self.len]
    }

    /// The same convex combination of each set's points as the last closest point of the
    /// difference (the origin's, when the simplex holds it); `None` before the first.
    pub(crate) fn combination(&self) -> Option<PointPair> {
        if self.len == 0 {
            return None;
        }
        let (mut p, mut q) = (Vector3::zeros(), Vector3::zeros());
        for i in 0..self.len {
            p += self.pairs[i].0.coords * self.weights[i];
            q += self.pairs[i].1.coords * self.weights[i];
        }
        Some((Point3::from(p), Point3::from(q)))
    }

    /// The sets' points whose difference is the last closest point (`None` before the
    /// first one, or when it was the origin).
    pub(crate) fn witness(&self) -> Option<PointPair> {
        if self.len == 4 {
            return None;
        }
        self.combination()
    }

    /// The point of the simplex's hull closest to the origin; the simplex keeps only the
    /// vertices of the face that holds it, with their barycentric weights.
    ///
    /// The closest point of a segment, triangle or tetrahedron to a point follows from its
    /// Voronoi regions (Ericson, *Real-Time Collision Detection*, 5.1.2-5.1.6): a handful
    /// of dot products decide which vertex, edge or face holds it, and only that feature's
    /// coordinates are computed. A tetrahedron's faces through the newest vertex are the
    /// candidates (the opposite face was the previous simplex, whose closest point `v` the
    /// new vertex beats: `v . w < |v|^2`); when the origin lies inside all of them the
    /// hulls overlap and the point is the origin. Rounding can only move `v` within the
    /// simplex's hull of support points: every bound the iteration reports comes from a
    /// support function, never from `v`, so this decides how fast it converges, not
    /// whether its bounds hold.
    pub(crate) fn closest_to_origin(&mut self) -> Vector3<f64> {
        let mut f = match self.len {
            1 => Feature::vertex(0),
            2 => segment_feature(&self.points, 1, 0),
            3 => triangle_feature(&self.points, 2, 0, 1),
            _ => self.tetrahedron_feature(),
        };
        if f.len == 4 {
            // The origin is inside: the caller stops on `|v| = 0`; the weights are the
            // origin's barycentric coordinates ([`Simplex::combination`]).
            self.weights = f.weight;
            return Vector3::zeros();
        }
        let v = f.point(&self.points);
        // Keep the feature's vertices in insertion order, the newest last: with increasing
        // indices, copying down in place never overwrites a vertex still to be read.
        f.sort();
        for k in 0..f.len {
            let i = f.index[k] as usize;
            self.points[k] = self.points[i];
            self.pairs[k] = self.pairs[i];
            self.weights[k] = f.weight[k];
        }
        self.len = f.len;
        v
    }

    /// The closest feature of a tetrahedron (newest vertex last) among its faces through
    /// the newest vertex whose plane separates the origin from the opposite vertex; the
    /// whole tetrahedron when there is none.
    fn tetrahedron_feature(&self) -> Feature {
        let p = &self.points;
        let mut best: Option<(f64, Feature)> = None;
        for (b, c, opposite) in [(0, 1, 2), (1, 2, 0), (2, 0, 1)] {
            let n = (p[b] - p[3]).cross(&(p[c] - p[3]));
            let origin_side = -p[3].dot(&n);
            let opposite_side = (p[opposite] - p[3]).dot(&n);
            // A flat tetrahedron (opposite side 0) counts every face as a candidate.
            if origin_side * opposite_side > 0.0 {
                continue;
            }
            let f = triangle_feature(p, 3, b, c);
            let d = f.point(p).norm_squared();
            if best.as_ref().is_none_or(|(bd, _)| d < *bd) {
                best = Some((d, f));
            }
        }
        best.map_or_else(
            || Feature {
                index: [0, 1, 2, 3],
                weight: origin_weights(p),
                len: 4,
            },
            |(_, f)| f,
        )
    }
}

/// A vertex, edge or face of a simplex: up to three vertex indices and their barycentric
/// weights (four for the whole tetrahedron).
/// Barycentric coordinates of the origin in the tetrahedron `p` (ratios of signed volumes).
fn origin_weights(p: &[Vector3<f64>; 4]) -> [f64; 4] {
    let volume = |a: Vector3<f64>, b: Vector3<f64>, c: Vector3<f64>, d: Vector3<f64>| {
        (b - a).dot(&(c - a).cross(&(d - a)))
    };
    let total = volume(p[0], p[1], p[2], p[3]);
    let o = Vector3::zeros();
    [
        volume(o, p[1], p[2], p[3]) / total,
        volume(p[0], o, p[2], p[3]) / total,
        volume(p[0], p[1], o, p[3]) / total,
        volume(p[0], p[1], p[2], o) / total,
    ]
}

#[derive(Debug, Clone, Copy)]
struct Feature {
    index: [u8; 4],
    weight: [f64; 4],
    len: usize,
}

impl Feature {
    fn vertex(i: usize) -> Feature {
        Feature {
            index: [i as u8, 0, 0, 0],
            weight: [1.0, 0.0, 0.0, 0.0],
            len: 1,
        }
    }

    fn edge(i: usize, j: usize, t: f64) -> Feature {
        Feature {
            index: [i as u8, j as u8, 0, 0],
            weight: [1.0 - t, t, 0.0, 0.0],
            len: 2,
        }
    }

    fn point(&self, p: &[Vector3<f64>; 4]) -> Vector3<f64> {
        (0..self.len).fold(Vector3::zeros(), |v, k| {
            v + p[self.index[k] as usize] * self.weight[k]
        })
    }

    /// Orders the vertices by index (with their weights).
    fn sort(&mut self) {
        for i in 1..self.len {
            let mut k = i;
            while k > 0 && self.index[k - 1] > self.index[k] {
                self.index.swap(k - 1, k);
                self.weight.swap(k - 1, k);
                k -= 1;
            }
        }
    }
}

/// The feature of the segment `p[a] p[b]` closest to the origin.
fn segment_feature(p: &[Vector3<f64>; 4], a: usize, b: usize) -> Feature {
    let ab = p[b] - p[a];
    let num = -p[a].dot(&ab);
    let den = ab.norm_squared();
    if num <= 0.0 || den <= 0.0 {
        Feature::vertex(a)
    } else if num >= den {
        Feature::vertex(b)
    } else {
        Feature::edge(a, b, num / den)
    }
}

/// The feature of the triangle `p[a] p[b] p[c]` closest to the origin (Ericson 5.1.5; a
/// degenerate triangle gives its closest edge).
fn triangle_feature(p: &[Vector3<f64>; 4], a: usize, b: usize, c: usize) -> Feature {
    let (pa, pb, pc) = (p[a], p[b], p[c]);
    let (ab, ac) = (pb - pa, pc - pa);
    let (d1, d2) = (-ab.dot(&pa), -ac.dot(&pa));
    if d1 <= 0.0 && d2 <= 0.0 {
        return Feature::vertex(a);
    }
    let (d3, d4) = (-ab.dot(&pb), -ac.dot(&pb));
    if d3 >= 0.0 && d4 <= d3 {
        return Feature::vertex(b);
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return Feature::edge(a, b, d1 / (d1 - d3));
    }
    let (d5, d6) = (-ab.dot(&pc), -ac.dot(&pc));
    if d6 >= 0.0 && d5 <= d6 {
        return Feature::vertex(c);
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return Feature::edge(a, c, d2 / (d2 - d6));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && d4 - d3 >= 0.0 && d5 - d6 >= 0.0 {
        return Feature::edge(b, c, (d4 - d3) / ((d4 - d3) + (d5 - d6)));
    }
    let sum = va + vb + vc;
    if !sum.is_finite() || sum <= 0.0 {
        // Degenerate: the nearest of the three edges.
        return [
            segment_feature(p, a, b),
            segment_feature(p, a, c),
            segment_feature(p, b, c),
        ]
        .into_iter()
        .min_by(|x, y| {
            x.point(p)
                .norm_squared()
                .total_cmp(&y.point(p).norm_squared())
        })
        .expect("three edges");
    }
    let (v, w) = (vb / sum, vc / sum);
    Feature {
        index: [a as u8, b as u8, c as u8, 0],
        weight: [1.0 - v - w, v, w, 0.0],
        len: 3,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::Lcg;

    /// The distance from the origin to the simplex `p` by brute force: every face's
    /// affine projection whose barycentric weights are all non-negative (the whole
    /// tetrahedron excluded).
    fn closest_by_faces(p: &[Vector3<f64>]) -> f64 {
        let n = p.len();
        let mut best = f64::INFINITY;
        for mask in 1u32..(1 << n) {
            if mask == 0b1111 {
                continue;
            }
            let idx: Vec<usize> = (0..n).filter(|i| mask & (1 << i) != 0).collect();
            let o = p[idx[0]];
            let e: Vec<Vector3<f64>> = idx[1..].iter().map(|&i| p[i] - o).collect();
            let k = e.len();
            if k == 0 {
                best = best.min(o.norm());
                continue;
            }
            let g = nalgebra::DMatrix::from_fn(k, k, |r, c| e[r].dot(&e[c]));
            let b = nalgebra::DVector::from_fn(k, |r, _| -e[r].dot(&o));
            let Some(mu) = g.lu().solve(&b) else { continue };
            if mu.iter().any(|&m| m < 0.0) || mu.sum() > 1.0 {
                continue;
            }
            let v = (0..k).fold(o, |v, j| v + e[j] * mu[j]);
            best = best.min(v.norm());
        }
        best
    }

    /// [`Simplex::closest_to_origin`] finds the nearest point of random segments,
    /// triangles and tetrahedra (the latter among the faces through the newest vertex, or
    /// the origin when it is inside), within rounding of the brute-force face search, and
    /// the kept vertices' weights give that point back.
    #[test]
    fn simplex_closest_point_matches_face_search() {
        let mut s = Lcg(77);
        let mut f = move || 2.0 * s.f() - 1.0;
        let mut inside = 0;
        for case in 0..20_000 {
            let n = 2 + case % 3;
            let pts: Vec<Vector3<f64>> = (0..n)
                .map(|_| Vector3::new(f(), f(), f()) + Vector3::new(0.3, 0.0, 0.0))
                .collect();
            let mut simplex = Simplex::default();
            for (i, w) in pts.iter().enumerate() {
                let pair = (Point3::origin(), Point3::from(*w));
                assert!(simplex.push(*w, pair), "case {case}: vertex {i}");
            }
            let v = simplex.closest_to_origin();
            let expected = closest_by_faces(&pts);
            if n == 4 && closest_by_faces(&pts[..3]) <= expected + 1e-9 {
                // The face opposite the newest vertex (or an edge of it) holds the nearest
                // point: GJK never builds such a tetrahedron (the new vertex beats the old
                // triangle's nearest point).
                continue;
            }
            if n == 4 && simplex.len == 4 {
                // The origin inside: every face is farther than 0; check it is inside by
                // the faces' planes.
                assert_eq!(v, Vector3::zeros());
                inside += 1;
                continue;
            }
            assert!(
                (v.norm() - expected).abs() <= 1e-12,
                "case {case}: {} vs {expected}",
                v.norm()
            );
            let back = (0..simplex.len).fold(Vector3::zeros(), |acc, k| {
                acc + simplex.points[k] * simplex.weights[k]
            });
            assert!((back - v).norm() <= 1e-12, "case {case}: weights");
            let wsum: f64 = simplex.weights[..simplex.len].iter().sum();
            assert!(
                (wsum - 1.0).abs() <= 1e-12,
                "case {case}: weight sum {wsum}"
            );
        }
        assert!(inside > 100, "{inside} tetrahedra around the origin");
    }
}
