//! The support function of the convex hull of a tree's approximating surface: the chain of
//! arcs and segments ([`crate::bvh::QueryTree::chain`]) revolved about the z axis.
//!
//! The revolved chain's hull is the revolved hull of the chain and its mirror image across
//! the axis, so its support in a direction `d` is the planar support of that symmetric set
//! in the direction `(|d_xy|, d_z)`, lifted back by the azimuth of `d_xy` (any azimuth when
//! `d_xy = 0`). The planar support of a union of pieces is the largest of theirs: an arc's
//! is its point whose outward normal is the direction when that lies in the arc's angle
//! range, else one of its end points; a segment's is an end point. So the candidates are
//! the hull vertices of all end points and the arcs whose range contains the direction.
//!
//! For speed the directions `(u, w)`, `u >= 0`, are cut into buckets of the monotone
//! parameter `w / (u + |w|)`; each bucket lists the hull vertices that are the support for
//! some direction of the bucket (a contiguous run of the hull, as the support walks
//! counter-clockwise with the direction) and the arcs whose angle range meets it. The answer
//! is the exact support of the chain's hull up to the rounding of the hull's orientation
//! tests (a point dropped from the hull is inside it up to [`HULL_ROUNDING_REL`] of the
//! extent) and of evaluating an arc's point (within the piece's representation error, which
//! the tree's eps counts).

use crate::bvh::ProfileArc;
use crate::num::cross2;
use nalgebra::{Point2, Point3, Vector2, Vector3};
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Distance (relative to the extent) by which the planar hull may miss an end point that
/// its floating-point orientation tests put inside: a few ulps of the coordinates.
pub const HULL_ROUNDING_REL: f64 = 1e-14;

/// Angular margin (radians) by which a bucket's direction range is widened when its
/// candidates are collected: rounding of the bucket index and of `atan2`.
const BUCKET_MARGIN: f64 = 1e-9;

/// A circular arc of the chain (or its mirror image), at most a quarter turn, running
/// counter-clockwise from `from` to `to` (unit directions from its centre).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SupportArc {
    pub center: Point2<f64>,
    pub radius: f64,
    pub from: Vector2<f64>,
    pub to: Vector2<f64>,
}

impl SupportArc {
    /// The arc's point with outward normal along `dir` (not necessarily unit), if `dir`
    /// lies in the arc's angle range.
    #[inline]
    fn support(&self, dir: Vector2<f64>, inv_norm: f64) -> Option<Point2<f64>> {
        let in_range = cross2(self.from, dir) >= 0.0 && cross2(dir, self.to) >= 0.0;
        in_range.then(|| self.center + dir * (self.radius * inv_norm))
    }
}

/// Candidate lists per direction bucket (module doc).
#[derive(Debug, Clone, PartialEq)]
pub struct SupportTable {
    /// `offsets[j]..offsets[j + 1]` index bucket `j`'s vertices and arcs.
    vertex_offsets: Vec<u32>,
    arc_offsets: Vec<u32>,
    vertices: Vec<Point2<f64>>,
    arcs: Vec<SupportArc>,
    /// Largest distance of a candidate point from the origin.
    pub extent: f64,
    /// Lowest and highest `z` of the hull's widest points (largest `rho`): the axis segment
    /// of a capsule's core, a cylinder's height, a ball's centre; GJK starts from it.
    pub core: [f64; 2],
}

impl SupportTable {
    /// The table of a chain of profile pieces.
    pub fn of_chain(chain: &[ProfileArc]) -> Option<SupportTable> {
        let mut points = Vec::new();
        let mut arcs = Vec::new();
        for piece in chain {
            match *piece {
                ProfileArc::Segment { start, end } => points.extend([start, end]),
                ProfileArc::Arc { center, radius, .. } => {
                    let (from, sweep) = piece.ascending_angles().expect("an arc");
                    let n = ((sweep / FRAC_PI_2).ceil() as usize).max(1);
                    let dir = |phi: f64| Vector2::new(phi.cos(), phi.sin());
                    points.extend([piece.start(), piece.end()]);
                    for i in 0..n {
                        let (a, b) = (
                            from + sweep * i as f64 / n as f64,
                            from + sweep * (i + 1) as f64 / n as f64,
                        );
                        let arc = SupportArc {
                            center,
                            radius,
                            from: dir(a),
                            to: dir(b),
                        };
                        points.extend([center + arc.from * radius, center + arc.to * radius]);
                        arcs.push(arc);
                    }
                }
            }
        }
        // The mirror image across the axis (reverses the arcs' orientation).
        let mirror = |p: Point2<f64>| Point2::new(-p.x, p.y);
        let mirror_dir = |v: Vector2<f64>| Vector2::new(-v.x, v.y);
        let n = points.len();
        for i in 0..n {
            points.push(mirror(points[i]));
        }
        let m = arcs.len();
        for i in 0..m {
            let a = arcs[i];
            arcs.push(SupportArc {
                center: mirror(a.center),
                radius: a.radius,
                from: mirror_dir(a.to),
                to: mirror_dir(a.from),
            });
        }
        if !points.iter().all(|p| p.x.is_finite() && p.y.is_finite()) {
            return None;
        }
        let hull = convex_hull(points);
        if hull.len() < 2 {
            return None;
        }
        let extent = hull.iter().map(|p| p.coords.norm()).fold(0.0, f64::max);
        let widest = hull.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
        let core = hull
            .iter()
            .filter(|p| p.x >= widest - 1e-9 * extent)
            .fold([f64::INFINITY, f64::NEG_INFINITY], |r, p| {
                [r[0].min(p.y), r[1].max(p.y)]
            });
        let buckets = (4 * (hull.len() + arcs.len()))
            .next_power_of_two()
            .clamp(16, 4096);
        let mut table = SupportTable {
            vertex_offsets: vec![0],
            arc_offsets: vec![0],
            vertices: Vec::new(),
            arcs: Vec::new(),
            extent,
            core,
        };
        for j in 0..buckets {
            let t0 = 2.0 * j as f64 / buckets as f64 - 1.0;
            let t1 = 2.0 * (j + 1) as f64 / buckets as f64 - 1.0;
            let (lo, hi) = (angle_of(t0) - BUCKET_MARGIN, angle_of(t1) + BUCKET_MARGIN);
            // Hull vertices: the run from the support at `lo` to the support at `hi`, and one
            // more on each side for ties.
            let h = hull.len();
            let at = |phi: f64| argmax(&hull, Vector2::new(phi.cos(), phi.sin()));
            let (i0, i1) = (at(lo), at(hi));
            let run = (i1 + h - i0) % h;
            for k in 0..(run + 3).min(h) {
                table.vertices.push(hull[(i0 + h - 1 + k) % h]);
            }
            let (mid, half) = (0.5 * (lo + hi), 0.5 * (hi - lo));
            for a in &arcs {
                let (a0, a1) = (a.from.y.atan2(a.from.x), a.to.y.atan2(a.to.x));
                let sweep = (a1 - a0).rem_euclid(TAU);
                let arc_mid = a0 + 0.5 * sweep;
                let gap = (arc_mid - mid + PI).rem_euclid(TAU) - PI;
                if gap.abs() <= half + 0.5 * sweep + BUCKET_MARGIN {
                    table.arcs.push(*a);
                }
            }
            table.vertex_offsets.push(table.vertices.len() as u32);
            table.arc_offsets.push(table.arcs.len() as u32);
        }
        Some(table)
    }

    /// Number of direction buckets.
    fn buckets(&self) -> usize {
        self.vertex_offsets.len() - 1
    }

    /// The planar support point of the chain and its mirror image in direction `(u, w)`,
    /// `u >= 0`, not both zero.
    #[inline]
    pub fn support_2d(&self, u: f64, w: f64) -> Point2<f64> {
        let k = self.buckets();
        let t = w / (u + w.abs());
        let j = (((t + 1.0) * 0.5 * k as f64) as usize).min(k - 1);
        let dir = Vector2::new(u, w);
        let (v0, v1) = (
            self.vertex_offsets[j] as usize,
            self.vertex_offsets[j + 1] as usize,
        );
        let mut best = self.vertices[v0];
        let mut best_value = dir.dot(&best.coords);
        for p in &self.vertices[v0 + 1..v1] {
            let value = dir.dot(&p.coords);
            if value > best_value {
                best = *p;
                best_value = value;
            }
        }
        let (a0, a1) = (
            self.arc_offsets[j] as usize,
            self.arc_offsets[j + 1] as usize,
        );
        if a0 < a1 {
            let inv_norm = 1.0 / (u * u + w * w).sqrt();
            for arc in &self.arcs[a0..a1] {
                if let Some(p) = arc.support(dir, inv_norm) {
                    let value = dir.dot(&p.coords);
                    if value > best_value {
                        best = p;
                        best_value = value;
                    }
                }
            }
        }
        best
    }

    /// The support point of the revolved hull in direction `d` (the solid's own frame, axis
    /// z): the planar support lifted by the azimuth of `d`.
    #[inline]
    pub fn support(&self, d: &Vector3<f64>) -> Point3<f64> {
        let u = (d.x * d.x + d.y * d.y).sqrt();
        if u > 0.0 {
            let p = self.support_2d(u, d.z);
            let k = p.x / u;
            Point3::new(k * d.x, k * d.y, p.y)
        } else {
            let p = self.support_2d(0.0, d.z);
            Point3::new(p.x, 0.0, p.y)
        }
    }
}

/// The direction angle (in `[-pi/2, pi/2]`) of the bucket parameter `t = w / (u + |w|)`.
fn angle_of(t: f64) -> f64 {
    if t >= 0.0 {
        t.atan2(1.0 - t)
    } else {
        t.atan2(1.0 + t)
    }
}

fn argmax(points: &[Point2<f64>], dir: Vector2<f64>) -> usize {
    let mut best = 0;
    for (i, p) in points.iter().enumerate() {
        if dir.dot(&p.coords) > dir.dot(&points[best].coords) {
            best = i;
        }
    }
    best
}

/// Counter-clockwise convex hull (Andrew's monotone chain); collinear points dropped.
fn convex_hull(mut points: Vec<Point2<f64>>) -> Vec<Point2<f64>> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let turn = |o: Point2<f64>, a: Point2<f64>, b: Point2<f64>| cross2(a - o, b - o);
    let mut hull: Vec<Point2<f64>> = Vec::with_capacity(points.len() + 1);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Point2<f64>>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && turn(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force support of the chain and its mirror (dense samples of the arcs).
    fn brute(chain: &[ProfileArc], dir: Vector2<f64>) -> f64 {
        let mut best = f64::NEG_INFINITY;
        for piece in chain {
            for i in 0..=20000 {
                let p = piece.point_at(i as f64 / 20000.0);
                best = best.max(dir.dot(&p.coords)).max(dir.x * -p.x + dir.y * p.y);
            }
        }
        best
    }

    #[test]
    fn support_matches_dense_sampling() {
        let chain = [
            ProfileArc::Arc {
                center: Point2::new(0.0, 0.4),
                radius: 0.4,
                phi_start: -FRAC_PI_2,
                sweep: FRAC_PI_2,
            },
            ProfileArc::Segment {
                start: Point2::new(0.4, 0.4),
                end: Point2::new(0.4, 1.2),
            },
            ProfileArc::Arc {
                center: Point2::new(0.0, 1.2),
                radius: 0.4,
                phi_start: 0.0,
                sweep: FRAC_PI_2,
            },
        ];
        let table = SupportTable::of_chain(&chain).unwrap();
        for k in 0..=400 {
            let phi = -FRAC_PI_2 + PI * k as f64 / 400.0;
            let dir = Vector2::new(phi.cos().max(0.0), phi.sin());
            let p = table.support_2d(dir.x, dir.y);
            let exact = brute(&chain, dir);
            let got = dir.dot(&p.coords);
            assert!(
                got <= exact + 1e-12 && got >= exact - 1e-8,
                "phi {phi}: {got} vs {exact}"
            );
        }
    }
}
