//! The bounding-box hierarchy over a profile's polyline: distance to the polyline, the
//! segments near a point, and point-in-polygon by crossing parity (module documentation of
//! [`super`]).

use crate::oracle::profile_eval::{seg_distance_sq, ProfileGeom, Sample, P2};

/// Segments per leaf of the hierarchy.
const LEAF_SEGMENTS: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Node {
    min: P2,
    max: P2,
    /// Children, or `u32::MAX` for a leaf.
    left: u32,
    right: u32,
    /// Segment range `[start, end)` (segment `i` joins samples `i` and `i + 1`).
    start: u32,
    end: u32,
}

/// Hierarchy over a profile's polyline, with the profile itself for refinement.
#[derive(Debug, Clone)]
pub struct PlanarIndex {
    /// The profile (pieces, polyline, sag).
    pub geom: ProfileGeom,
    nodes: Vec<Node>,
}

#[inline]
fn box_distance_sq(q: P2, min: P2, max: P2) -> f64 {
    let dx = (min[0] - q[0]).max(0.0).max(q[0] - max[0]);
    let dz = (min[1] - q[1]).max(0.0).max(q[1] - max[1]);
    dx * dx + dz * dz
}

impl PlanarIndex {
    /// Builds the hierarchy over `geom`'s polyline.
    pub fn new(geom: ProfileGeom) -> PlanarIndex {
        let nseg = geom.samples.len().saturating_sub(1);
        let mut idx = PlanarIndex {
            geom,
            nodes: Vec::with_capacity(2 * nseg / LEAF_SEGMENTS + 2),
        };
        if nseg > 0 {
            idx.build(0, nseg);
        }
        idx
    }

    fn build(&mut self, start: usize, end: usize) -> u32 {
        let s = &self.geom.samples;
        let mut min = [f64::INFINITY; 2];
        let mut max = [f64::NEG_INFINITY; 2];
        for smp in &s[start..=end] {
            for c in 0..2 {
                min[c] = min[c].min(smp.p[c]);
                max[c] = max[c].max(smp.p[c]);
            }
        }
        let id = self.nodes.len() as u32;
        self.nodes.push(Node {
            min,
            max,
            left: u32::MAX,
            right: u32::MAX,
            start: start as u32,
            end: end as u32,
        });
        if end - start > LEAF_SEGMENTS {
            let mid = (start + end) / 2;
            let l = self.build(start, mid);
            let r = self.build(mid, end);
            self.nodes[id as usize].left = l;
            self.nodes[id as usize].right = r;
        }
        id
    }

    pub(super) fn samples(&self) -> &[Sample] {
        &self.geom.samples
    }

    /// Squared distance to the polyline and the nearest segment.
    pub fn poly_nearest(&self, q: P2) -> (f64, usize) {
        self.poly_nearest_below(q, f64::INFINITY)
            .expect("an unbounded search finds a segment")
    }

    /// Like [`Self::poly_nearest`], searching only below the squared distance `limit_sq`
    /// (`None` when no segment is that close).
    pub fn poly_nearest_below(&self, q: P2, limit_sq: f64) -> Option<(f64, usize)> {
        let s = self.samples();
        let mut best = (limit_sq, usize::MAX);
        if self.nodes.is_empty() {
            return None;
        }
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if box_distance_sq(q, n.min, n.max) >= best.0 {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    let (d2, _) = seg_distance_sq(q, s[i].p, s[i + 1].p);
                    if d2 < best.0 {
                        best = (d2, i);
                    }
                }
            } else {
                let l = &self.nodes[n.left as usize];
                let r = &self.nodes[n.right as usize];
                let dl = box_distance_sq(q, l.min, l.max);
                let dr = box_distance_sq(q, r.min, r.max);
                // Push the farther first so the nearer is visited first.
                let (first, second) = if dl <= dr {
                    (n.right, n.left)
                } else {
                    (n.left, n.right)
                };
                stack[top] = first;
                stack[top + 1] = second;
                top += 2;
            }
        }
        (best.1 != usize::MAX).then_some(best)
    }

    /// Distance from `q` to the polyline.
    pub fn poly_distance(&self, q: P2) -> f64 {
        self.poly_nearest(q).0.sqrt()
    }

    /// Distance from `q` to the polyline, given an upper bound `hint` of it (e.g. a nearby
    /// point's distance plus the distance to that point): the search prunes against the
    /// hint, and falls back to a full search if the hint was wrong.
    pub fn poly_distance_hint(&self, q: P2, hint: f64) -> f64 {
        let h = hint * (1.0 + 1e-9) + 1e-300;
        match self.poly_nearest_below(q, h * h) {
            Some((d2, _)) => d2.sqrt(),
            None => self.poly_distance(q),
        }
    }

    /// Segments whose distance to `q` is at most `r`.
    pub(super) fn segments_within(&self, q: P2, r: f64, out: &mut Vec<usize>) {
        out.clear();
        if self.nodes.is_empty() {
            return;
        }
        let s = self.samples();
        let r2 = r * r;
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if box_distance_sq(q, n.min, n.max) > r2 {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    if seg_distance_sq(q, s[i].p, s[i + 1].p).0 <= r2 {
                        out.push(i);
                    }
                }
            } else {
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
    }

    /// Whether `q` is inside the polygon (crossing parity of the ray towards `+rho`).
    pub fn inside_poly(&self, q: P2) -> bool {
        let s = self.samples();
        if s.len() < 2 {
            return false;
        }
        let mut inside = false;
        let crosses = |a: P2, b: P2| -> bool {
            if (a[1] <= q[1]) != (b[1] <= q[1]) {
                let x = a[0] + (q[1] - a[1]) * (b[0] - a[0]) / (b[1] - a[1]);
                x > q[0]
            } else {
                false
            }
        };
        let mut stack: [u32; 64] = [0; 64];
        let mut top = 1usize;
        while top > 0 {
            top -= 1;
            let n = &self.nodes[stack[top] as usize];
            if n.max[0] <= q[0] || n.min[1] > q[1] || n.max[1] < q[1] {
                continue;
            }
            if n.left == u32::MAX {
                for i in n.start as usize..n.end as usize {
                    if crosses(s[i].p, s[i + 1].p) {
                        inside = !inside;
                    }
                }
            } else {
                stack[top] = n.left;
                stack[top + 1] = n.right;
                top += 2;
            }
        }
        // Closing edge: the axis segment (never crosses) or the loop's own closure.
        if crosses(s[s.len() - 1].p, s[0].p) {
            inside = !inside;
        }
        inside
    }
}
