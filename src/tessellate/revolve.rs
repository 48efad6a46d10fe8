//! Revolving the meridian polyline into a triangle mesh: rings of `n_theta` vertices (one
//! vertex on the axis), two triangles per quad, a fan at a pole, outward orientation.
//!
//! The ring error per unit `rho` (`tau`) and the ring scale (`kappa`) follow part (c) of the
//! proof in the module doc of [`super`].

use std::f64::consts::PI;

use nalgebra::Point3;

use super::meridian::Meridian;
use super::{TessellateError, TriMesh, VertexPlacement};

/// Fewest vertices per ring: a triangle is the smallest polygon.
pub const MIN_N_THETA: usize = 3;

/// Revolution error per unit `rho` of an `n`-gon ring: `tan^2(pi / 2n)` for a balanced ring,
/// `1 - cos(pi / n) = 2 sin^2(pi / 2n)` for an inscribed one.
pub fn revolution_factor(n: usize, placement: VertexPlacement) -> f64 {
    let half = PI / (2.0 * n as f64);
    match placement {
        VertexPlacement::Balanced => half.tan().powi(2),
        VertexPlacement::OnSurface => 2.0 * half.sin().powi(2),
    }
}

/// Circumradius of the ring polygon per unit `rho`: `1 / cos^2(pi / 2n)` (balanced) or 1.
pub fn ring_scale(n: usize, placement: VertexPlacement) -> f64 {
    match placement {
        VertexPlacement::Balanced => 1.0 / (PI / (2.0 * n as f64)).cos().powi(2),
        VertexPlacement::OnSurface => 1.0,
    }
}

/// Fewest vertices per ring whose [`revolution_factor`] is at most `tau` (> 0).
pub fn n_theta_for(tau: f64, placement: VertexPlacement) -> usize {
    let half = match placement {
        VertexPlacement::Balanced => tau.sqrt().atan(),
        VertexPlacement::OnSurface => (0.5 * tau).min(1.0).sqrt().asin(),
    };
    let mut n = (PI / (2.0 * half)).ceil().max(MIN_N_THETA as f64) as usize;
    // The closed form can be one short after rounding; the factor is decreasing in n.
    while revolution_factor(n, placement) > tau {
        n += 1;
    }
    n
}

/// Number of triangles [`revolve`] makes: `2 n` per segment between rings, `n` per segment
/// with one pole, none along the axis.
pub fn triangle_count(meridian: &Meridian, n: usize) -> usize {
    let p = &meridian.points;
    (0..meridian.segments())
        .map(|i| {
            let poles = usize::from(p[i].x == 0.0) + usize::from(p[(i + 1) % p.len()].x == 0.0);
            n * (2 - poles.min(2))
        })
        .sum()
}

/// The mesh of `meridian` revolved with `n` vertices per ring (see the module doc).
///
/// Orientation: the profile region lies to the left of a counter-clockwise polyline (positive
/// shoelace area, the axis closing an open one); for it, the triangles `(a_j, a_j+1, b_j+1)`
/// and `(a_j, b_j+1, b_j)` of the segment from ring `a` to ring `b` face outwards (at the outer
/// wall, rising in z, their normal is `+rho`). A clockwise profile gets every triangle reversed.
pub fn revolve(
    meridian: &Meridian,
    n: usize,
    placement: VertexPlacement,
) -> Result<TriMesh, TessellateError> {
    let pts = &meridian.points;
    let kappa = ring_scale(n, placement);
    let trig: Vec<(f64, f64)> = (0..n)
        .map(|j| {
            let (s, c) = (2.0 * PI * j as f64 / n as f64).sin_cos();
            (c, s)
        })
        .collect();
    let total: usize = pts.iter().map(|p| if p.x == 0.0 { 1 } else { n }).sum();
    if total > u32::MAX as usize {
        return Err(TessellateError::TooManyVertices(total));
    }
    let mut vertices = Vec::with_capacity(total);
    let mut first = Vec::with_capacity(pts.len());
    for p in pts {
        first.push(vertices.len() as u32);
        if p.x == 0.0 {
            vertices.push(Point3::new(0.0, 0.0, p.y));
        } else {
            let r = kappa * p.x;
            vertices.extend(trig.iter().map(|&(c, s)| Point3::new(r * c, r * s, p.y)));
        }
    }
    let area2: f64 = (0..pts.len())
        .map(|i| {
            let (a, b) = (pts[i], pts[(i + 1) % pts.len()]);
            a.x * b.y - b.x * a.y
        })
        .sum();
    let flip = area2 < 0.0;
    let mut triangles = Vec::with_capacity(triangle_count(meridian, n));
    let mut push = |t: [u32; 3]| triangles.push(if flip { [t[0], t[2], t[1]] } else { t });
    let nn = n as u32;
    for i in 0..meridian.segments() {
        let k = (i + 1) % pts.len();
        let (pa, pb) = (pts[i].x == 0.0, pts[k].x == 0.0);
        let (a, b) = (first[i], first[k]);
        for j in 0..nn {
            let j1 = (j + 1) % nn;
            match (pa, pb) {
                (false, false) => {
                    push([a + j, a + j1, b + j1]);
                    push([a + j, b + j1, b + j]);
                }
                (true, false) => push([a, b + j1, b + j]),
                (false, true) => push([a + j, a + j1, b]),
                (true, true) => {}
            }
        }
    }
    Ok(TriMesh {
        vertices,
        triangles,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn n_theta_is_the_smallest_meeting_tau() {
        for placement in [VertexPlacement::Balanced, VertexPlacement::OnSurface] {
            for &tau in &[1e-1, 1e-3, 2.7e-4, 1e-7] {
                let n = n_theta_for(tau, placement);
                assert!(revolution_factor(n, placement) <= tau);
                assert!(n == MIN_N_THETA || revolution_factor(n - 1, placement) > tau);
            }
        }
        // kappa - 1 = 1 - kappa cos(pi / n) = tau for the balanced ring.
        let n = 17;
        let (k, t) = (
            ring_scale(n, VertexPlacement::Balanced),
            revolution_factor(n, VertexPlacement::Balanced),
        );
        assert!((k - 1.0 - t).abs() < 1e-15);
        assert!((1.0 - k * (PI / n as f64).cos() - t).abs() < 1e-15);
    }
}
