//! Mesh writers as pure functions: Wavefront OBJ (text, full `f64` precision) and binary STL
//! (`f32` coordinates, the format's only precision).
//!
//! Binary STL rounds every coordinate to `f32`, moving a vertex by at most
//! [`stl_rounding_error`]; a consumer that needs the certified bound must add it (the CLI
//! prints it). OBJ writes each `f64` in Rust's shortest round-trip form, so it is exact.

use std::fmt::Write as _;

use super::TriMesh;

/// OBJ text: a comment line per entry of `comments`, then `v x y z` lines and 1-based
/// `f a b c` lines (counter-clockwise seen from outside).
pub fn to_obj(mesh: &TriMesh, comments: &[String]) -> String {
    let mut s = String::with_capacity(40 * mesh.vertices.len() + 24 * mesh.triangles.len());
    for c in comments {
        for line in c.lines() {
            let _ = writeln!(s, "# {line}");
        }
    }
    for v in &mesh.vertices {
        let _ = writeln!(s, "v {} {} {}", v.x, v.y, v.z);
    }
    for t in &mesh.triangles {
        let _ = writeln!(s, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    s
}

/// Binary STL: an 80-byte header (`header`, truncated or zero-padded), the triangle count, and
/// per triangle its unit normal, three corners (`f32`, little endian) and a zero attribute.
pub fn to_stl_binary(mesh: &TriMesh, header: &str) -> Vec<u8> {
    let mut out = Vec::with_capacity(84 + 50 * mesh.triangles.len());
    let mut head = [0u8; 80];
    let bytes = header.as_bytes();
    let n = bytes.len().min(80);
    head[..n].copy_from_slice(&bytes[..n]);
    // A header starting with "solid" makes some readers take the file for ASCII STL.
    if head.starts_with(b"solid") {
        head[..5].copy_from_slice(b"SOLID");
    }
    out.extend_from_slice(&head);
    out.extend_from_slice(&(mesh.triangles.len() as u32).to_le_bytes());
    for t in 0..mesh.triangles.len() {
        let [a, b, c] = mesh.triangle(t);
        let normal = (b - a).cross(&(c - a));
        let len = normal.norm();
        let normal = if len > 0.0 { normal / len } else { normal };
        for v in [normal.x, normal.y, normal.z] {
            out.extend_from_slice(&(v as f32).to_le_bytes());
        }
        for p in [a, b, c] {
            for v in [p.x, p.y, p.z] {
                out.extend_from_slice(&(v as f32).to_le_bytes());
            }
        }
        out.extend_from_slice(&0u16.to_le_bytes());
    }
    out
}

/// Largest distance a vertex moves when its coordinates are rounded to `f32` (half an `f32`
/// ulp of the largest coordinate, in each of three coordinates). Because every mesh point is a
/// convex combination of its triangle's corners, the rounded mesh is within this distance of
/// the original (two-sided), so it adds to the Hausdorff bound.
pub fn stl_rounding_error(mesh: &TriMesh) -> f64 {
    let max = mesh
        .vertices
        .iter()
        .map(|v| v.coords.amax())
        .fold(0.0, f64::max);
    // f32 has a 24-bit significand: rounding to nearest moves x by <= |x| 2^-24.
    3f64.sqrt() * max * 2f64.powi(-24)
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point3;

    fn tri() -> TriMesh {
        TriMesh {
            vertices: vec![
                Point3::new(0.0, 0.0, 0.0),
                Point3::new(1.0, 0.0, 0.0),
                Point3::new(0.0, 0.1, 0.0),
            ],
            triangles: vec![[0, 1, 2]],
        }
    }

    #[test]
    fn obj_round_trips_f64_and_uses_one_based_faces() {
        let s = to_obj(&tri(), &["a\nb".to_string()]);
        assert!(s.starts_with("# a\n# b\nv 0 0 0\n"));
        assert!(s.contains("v 0 0.1 0\n"));
        assert!(s.ends_with("f 1 2 3\n"));
    }

    #[test]
    fn stl_layout() {
        let b = to_stl_binary(&tri(), "solid x");
        assert_eq!(b.len(), 84 + 50);
        assert_eq!(&b[..5], b"SOLID");
        assert_eq!(u32::from_le_bytes([b[80], b[81], b[82], b[83]]), 1);
        let nz = f32::from_le_bytes([b[92], b[93], b[94], b[95]]);
        assert_eq!(nz, 1.0);
        assert!(stl_rounding_error(&tri()) < 1.1e-7);
    }
}
