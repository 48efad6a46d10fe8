//! An indexed triangle mesh and the checks a closed solid mesh must pass.

use nalgebra::Point3;

/// An indexed triangle mesh; triangles are counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct TriMesh {
    /// Vertex positions.
    pub vertices: Vec<Point3<f64>>,
    /// Vertex indices of each triangle.
    pub triangles: Vec<[u32; 3]>,
}

/// Edge statistics of a mesh: a closed, consistently oriented mesh has every directed edge
/// once and its reverse once, i.e. all three counts zero.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct MeshTopology {
    /// Directed edges whose reverse is missing (holes).
    pub open_edges: usize,
    /// Directed edges used by more than one triangle (flipped neighbours or more than two
    /// triangles at an edge).
    pub repeated_edges: usize,
    /// Triangles with a repeated vertex index.
    pub degenerate_triangles: usize,
}

impl MeshTopology {
    /// Closed and consistently oriented, without degenerate triangles.
    pub fn is_watertight(&self) -> bool {
        self.open_edges == 0 && self.repeated_edges == 0 && self.degenerate_triangles == 0
    }
}

impl TriMesh {
    /// Number of triangles.
    pub fn triangle_count(&self) -> usize {
        self.triangles.len()
    }

    /// The corners of triangle `t`.
    pub fn triangle(&self, t: usize) -> [Point3<f64>; 3] {
        self.triangles[t].map(|i| self.vertices[i as usize])
    }

    /// Edge statistics (see [`MeshTopology`]). Sorts the directed edges (8 bytes each), so it
    /// stays cheap on meshes of millions of triangles.
    pub fn topology(&self) -> MeshTopology {
        let mut top = MeshTopology::default();
        let mut directed: Vec<(u32, u32)> = Vec::with_capacity(3 * self.triangles.len());
        for t in &self.triangles {
            if t[0] == t[1] || t[1] == t[2] || t[2] == t[0] {
                top.degenerate_triangles += 1;
            }
            directed.extend([(t[0], t[1]), (t[1], t[2]), (t[2], t[0])]);
        }
        directed.sort_unstable();
        for (i, &(a, b)) in directed.iter().enumerate() {
            if i > 0 && directed[i - 1] == (a, b) {
                top.repeated_edges += 1;
            }
            if directed.binary_search(&(b, a)).is_err() {
                top.open_edges += 1;
            }
        }
        top
    }

    /// Signed volume (divergence theorem): positive for a closed mesh with outward normals.
    pub fn signed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|i| self.vertices[i as usize].coords);
                a.dot(&b.cross(&c))
            })
            .sum::<f64>()
            / 6.0
    }

    /// Smallest triangle area (0 for an empty mesh).
    pub fn min_triangle_area(&self) -> f64 {
        (0..self.triangles.len())
            .map(|t| {
                let [a, b, c] = self.triangle(t);
                0.5 * (b - a).cross(&(c - a)).norm()
            })
            .reduce(f64::min)
            .unwrap_or(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tetrahedron_is_watertight_with_positive_volume() {
        let mut m = TriMesh {
            vertices: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 1.0, 0.0),
                Point3::new(0.0, 0.0, 1.0),
            ],
            triangles: vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [0, 3, 2]],
        };
        assert!(m.topology().is_watertight());
        assert!((m.signed_volume() - 1.0 / 6.0).abs() < 1e-15);
        m.triangles[0] = [0, 1, 2];
        let top = m.topology();
        assert!(top.repeated_edges > 0 && top.open_edges > 0);
        m.triangles.pop();
        assert!(m.topology().open_edges > 0);
    }
}
