//! The shapes of the cross-check: a built-in model at one eps as a revdist solid (biarc tree
//! of bound eps) and as a certified mesh (two-sided Hausdorff bound <= eps).

use crate::baselines::TriMesh;
use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::solid::Solid;
use revdist::tessellate::{tessellate, TessellateOptions};
use std::sync::Arc;

/// The five models of the paper (Son et al. 2020, section 5).
pub const PAPER_MODELS: [&str; 5] = ["pawn", "cup", "bottle", "table", "lightmill"];

/// Frames of the deforming model M_t checked against each paper model.
pub const MORPH_FRAMES: [&str; 3] = ["morph@0.1", "morph@0.5", "morph@0.9"];

/// The convex built-in models (libccd and CGAL `Polytope_distance_d` need convex hulls).
pub const CONVEX_MODELS: [&str; 4] = ["sphere", "capsule", "cone", "cylinder"];

/// One model prepared at one eps.
pub struct Prepared {
    pub name: String,
    pub eps: f64,
    /// The solid at the identity pose (tree bound `eps`).
    pub solid: Solid,
    /// The certified mesh in the solid's frame, in the layout the shims take.
    pub mesh: Arc<TriMesh>,
    /// Its vertices (for convex hulls).
    pub vertices: Arc<Vec<nalgebra::Point3<f64>>>,
    /// The mesh's certified two-sided Hausdorff bound (`<= eps`).
    pub bound: f64,
    /// Axis point at mid-height (`z`) and the radius of a ball about it holding the solid.
    pub centre_z: f64,
    pub radius: f64,
}

/// Builds the solid and the certified mesh of model `name` (a built-in name) at `eps`.
pub fn prepare(name: &str, eps: f64) -> Result<Prepared, String> {
    let profile = revdist::models::model(name).map_err(|e| format!("model '{name}': {e}"))?;
    prepare_profile(name, profile, eps)
}

/// As [`prepare`], from a profile.
pub fn prepare_profile(name: &str, profile: Profile, eps: f64) -> Result<Prepared, String> {
    let cm = tessellate(&profile, eps, TessellateOptions::default())
        .map_err(|e| format!("tessellating '{name}' at eps {eps:e}: {e}"))?;
    let b = profile.bounding_box();
    let centre_z = 0.5 * (b.min.y + b.max.y);
    let half_h = 0.5 * (b.max.y - b.min.y);
    let radius = b.max.x.hypot(half_h);
    let solid = Solid::from_profile(Arc::new(profile), eps)
        .map_err(|e| format!("tree of '{name}' at eps {eps:e}: {e}"))?;
    Ok(Prepared {
        name: name.to_owned(),
        eps,
        solid,
        mesh: Arc::new(TriMesh::from_points(&cm.mesh.vertices, &cm.mesh.triangles)),
        vertices: Arc::new(cm.mesh.vertices),
        bound: cm.bound,
        centre_z,
        radius,
    })
}

/// The configuration scale of a pose (for the rounding slack).
pub fn scale(a: &Prepared, b: &Prepared, pose: &Isometry3<f64>) -> f64 {
    1.0 + pose.translation.vector.norm() + a.radius + b.radius + a.centre_z.abs() + b.centre_z.abs()
}
