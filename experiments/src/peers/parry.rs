//! parry3d (`parry3d-f64` 0.31, pure Rust) as a peer: `TriMesh` on the certified meshes and its
//! exact `Ball`, `Capsule`, `Cylinder` and `Cone`.
//!
//! Its TriMesh-TriMesh distance is one-sided: a best-first search over mesh 1's BVH bounded by
//! the AABB of all of mesh 2, then one BVH query into mesh 2 per leaf triangle of mesh 1 (not a
//! simultaneous descent of both trees as FCL, coal and revdist do). Wherever its mesh times are
//! quoted, this design is said with them.

use super::convex::Primitive;
use nalgebra::Isometry3;
use parry3d_f64::math::{Pose, Rotation, Vector};
use parry3d_f64::query;
use parry3d_f64::shape::{Ball, Capsule, Cone, Cylinder, Shape, TriMesh};
use revdist::tessellate::CertifiedMesh;
use std::time::{Duration, Instant};

type Res<T> = Result<T, Box<dyn std::error::Error>>;

/// A parry3d shape in revdist's frame of the solid: `local` places parry's shape (parry's
/// cylinders and cones stand on the y axis) on the solid's axis z.
pub struct ParryShape {
    shape: Box<dyn Shape>,
    local: Pose,
    /// Time to build it (the TriMesh's BVH) and the bytes of its arrays (vertices, indices,
    /// BVH; 0 for primitives beyond their few scalars).
    pub build: Duration,
    pub bytes: usize,
}

/// A nalgebra isometry as parry's pose.
pub fn pose(p: &Isometry3<f64>) -> Pose {
    let q = p.rotation.quaternion();
    let t = p.translation.vector;
    Pose::from_parts(
        Vector::new(t.x, t.y, t.z),
        Rotation::from_xyzw(q.i, q.j, q.k, q.w),
    )
}

impl ParryShape {
    /// parry's `TriMesh` (with its BVH) of a certified mesh.
    pub fn mesh(cm: &CertifiedMesh) -> Res<ParryShape> {
        let m = &cm.mesh;
        let start = Instant::now();
        let vertices: Vec<Vector> = m
            .vertices
            .iter()
            .map(|v| Vector::new(v.x, v.y, v.z))
            .collect();
        let indices = m.triangles.clone();
        let mesh = TriMesh::new(vertices, indices)
            .map_err(|e| format!("parry3d rejected the mesh: {e:?}"))?;
        let build = start.elapsed();
        let bytes = std::mem::size_of_val(mesh.vertices())
            + std::mem::size_of_val(mesh.indices())
            + mesh.bvh().total_memory_size();
        Ok(ParryShape {
            shape: Box::new(mesh),
            local: Pose::IDENTITY,
            build,
            bytes,
        })
    }

    /// parry's exact primitive of `p`.
    pub fn primitive(p: &Primitive) -> ParryShape {
        // parry's cylinder and cone stand on y (the cone's apex at +y); a quarter turn about x
        // takes y to z.
        let y_to_z = Rotation::from_rotation_x(std::f64::consts::FRAC_PI_2);
        let at = |zc: f64, rot: Rotation| Pose::from_parts(Vector::new(0.0, 0.0, zc), rot);
        let (shape, local): (Box<dyn Shape>, Pose) = match *p {
            Primitive::Sphere { r, zc } => (Box::new(Ball::new(r)), at(zc, Rotation::IDENTITY)),
            Primitive::Capsule { r, lz, zc } => (
                Box::new(Capsule::new_z(0.5 * lz, r)),
                at(zc, Rotation::IDENTITY),
            ),
            Primitive::Cylinder { r, lz, zc } => {
                (Box::new(Cylinder::new(0.5 * lz, r)), at(zc, y_to_z))
            }
            Primitive::Cone { r, lz, zc } => (Box::new(Cone::new(0.5 * lz, r)), at(zc, y_to_z)),
        };
        ParryShape {
            shape,
            local,
            build: Duration::ZERO,
            bytes: 0,
        }
    }

    /// parry's distance from `self` (at the identity) to `other` placed by `pose`.
    pub fn distance(&self, other: &ParryShape, pose_b: &Pose) -> Res<f64> {
        let pa = self.local;
        let pb = *pose_b * other.local;
        Ok(query::distance(&pa, &*self.shape, &pb, &*other.shape)
            .map_err(|_| "parry3d does not support this pair of shapes")?
            .distance)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The placement of parry's y-axis primitives on z: the cone's apex is up (+z), and the
    /// distances to a ball beside and above match the hand computation.
    #[test]
    fn primitives_stand_on_z() {
        let cone = ParryShape::primitive(&Primitive::Cone {
            r: 0.6,
            lz: 1.5,
            zc: 0.75,
        });
        let cyl = ParryShape::primitive(&Primitive::Cylinder {
            r: 0.5,
            lz: 1.5,
            zc: 0.75,
        });
        let ball = ParryShape::primitive(&Primitive::Sphere { r: 0.1, zc: 0.0 });
        let at = |x: f64, z: f64| pose(&Isometry3::translation(x, 0.0, z));
        // Ball above the apex (0, 0, 1.5): gap 0.4 - 0.1.
        assert!((cone.distance(&ball, &at(0.0, 1.9)).unwrap() - 0.3).abs() < 1e-9);
        // Ball under the base disk (z = 0) near the rim.
        assert!((cone.distance(&ball, &at(0.5, -0.3)).unwrap() - 0.2).abs() < 1e-9);
        // Beside the cylinder at mid-height: 1.0 - 0.5 - 0.1.
        assert!((cyl.distance(&ball, &at(1.0, 0.75)).unwrap() - 0.4).abs() < 1e-9);
        // Above the cylinder's top disk (z = 1.5).
        assert!((cyl.distance(&ball, &at(0.0, 1.8)).unwrap() - 0.2).abs() < 1e-9);
    }
}
