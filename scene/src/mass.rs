//! Mass properties of a solid of revolution of uniform density: volume, centre of mass and
//! inertia tensor, from the closed certified tessellation ([`revdist::tessellate`]) by the
//! divergence theorem.
//!
//! # Method
//!
//! The tessellation is a closed, outward-oriented triangle mesh `M` within a certified
//! Hausdorff distance `h` of the true surface. Fix the origin `o = 0`; every triangle
//! `(a, b, c)` spans a signed tetrahedron `(0, a, b, c)` of volume `V_t = a . (b x c) / 6`, and
//! the signed tetrahedra of a closed oriented mesh add up to the enclosed solid (the
//! divergence theorem applied to `x`, `x x^T`, ... over the mesh polyhedron). For one
//! tetrahedron with a vertex at the origin, exactly:
//!
//! ```text
//! integral of 1      = V_t
//! integral of x      = V_t (a + b + c) / 4
//! integral of x x^T  = V_t / 20 (a a^T + b b^T + c c^T + s s^T),   s = a + b + c
//! ```
//!
//! (the second moments of a simplex: `V / ((n+1)(n+2))` times the sum over vertex pairs,
//! `n = 3`, with the origin vertex contributing nothing). Summing gives the volume `V`, the
//! first moment and the covariance `C = integral of x x^T`; the inertia about the origin is
//! `trace(C) Id - C`, moved to the centre of mass `c` by `C_c = C - V c c^T` (times the
//! density).
//!
//! # Why the mesh and not the profile
//!
//! Pappus-style integration along the profile (`V = 2 pi integral rho dA` over the meridian
//! region) would be exact up to quadrature, but needs derivatives of every NURBS piece and
//! care at pieces on the axis; the certified mesh is already there (the renderer uses it),
//! works for every shape the scene format knows, and its error is bounded: the mesh solid
//! and the true solid differ only within distance `h` of the surface, a shell of volume at
//! most `area * 2 h` (plus curvature terms of order `h^2`), so the relative error of the
//! volume is about `2 h area / V`. At the `MASS_EPS` used here (`1e-5` of the body's size) that
//! is below `1e-4` relative for every built-in model and the thin tori of the ring mesh;
//! the dynamics needs a few digits, not more. The tests compare against closed forms (solid
//! torus, ball).
//!
//! # Symmetry
//!
//! A solid of revolution about the local z axis has its centre of mass on the axis and an
//! inertia tensor `diag(I_xy, I_xy, I_z)` in its local frame. The mesh is `n_theta`-fold
//! symmetric (`n_theta >= 3`), which already gives this up to rounding; [`MassProperties`]
//! stores the symmetrised values (the average of `I_xx` and `I_yy`, off-diagonal terms and the
//! centre's x, y dropped), so that the rotational kinetic energy of a freely spinning body is
//! conserved exactly by the integrator ([`crate::dynamics`]).

use nalgebra::{Matrix3, Point3, Vector3};
use revdist::profile::Profile;
use revdist::tessellate::{tessellate, TessellateOptions, TriMesh};

/// Tessellation bound for mass properties, relative to the profile's size.
pub const MASS_EPS_REL: f64 = 1e-5;

/// Mass properties of a uniform solid of revolution in its local frame (axis = local z).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassProperties {
    /// Volume (length units cubed).
    pub volume: f64,
    /// Mass (`density * volume`).
    pub mass: f64,
    /// Height of the centre of mass on the local z axis.
    pub com_z: f64,
    /// Moment of inertia about any axis through the centre of mass perpendicular to z.
    pub inertia_xy: f64,
    /// Moment of inertia about the z axis.
    pub inertia_z: f64,
}

impl MassProperties {
    /// The centre of mass in the local frame.
    pub fn com(&self) -> Point3<f64> {
        Point3::new(0.0, 0.0, self.com_z)
    }

    /// The inertia tensor about the centre of mass, local frame.
    pub fn inertia(&self) -> Matrix3<f64> {
        Matrix3::from_diagonal(&Vector3::new(
            self.inertia_xy,
            self.inertia_xy,
            self.inertia_z,
        ))
    }
}

/// Volume, first moment and second-moment (covariance) matrix of a closed oriented mesh,
/// about the origin (unit density).
pub fn mesh_moments(mesh: &TriMesh) -> (f64, Vector3<f64>, Matrix3<f64>) {
    let mut volume = 0.0;
    let mut first = Vector3::zeros();
    let mut cov = Matrix3::zeros();
    for t in &mesh.triangles {
        let [a, b, c] = t.map(|i| mesh.vertices[i as usize].coords);
        let v = a.dot(&b.cross(&c)) / 6.0;
        let s = a + b + c;
        volume += v;
        first += s * (v / 4.0);
        cov += (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose())
            * (v / 20.0);
    }
    (volume, first, cov)
}

/// Full (unsymmetrised) mass properties of a mesh: volume, centre of mass and the inertia
/// tensor about it, unit density.
pub fn mesh_mass_properties(mesh: &TriMesh) -> (f64, Point3<f64>, Matrix3<f64>) {
    let (volume, first, cov) = mesh_moments(mesh);
    let c = first / volume;
    let cov_c = cov - c * c.transpose() * volume;
    let inertia = Matrix3::identity() * cov_c.trace() - cov_c;
    (volume, Point3::from(c), inertia)
}

/// Mass properties of a profile's solid: `density` per unit volume, or a total `mass`
/// when given (then the density is `mass / volume`).
pub fn mass_properties(
    profile: &Profile,
    density: Option<f64>,
    mass: Option<f64>,
) -> Result<MassProperties, String> {
    let bb = profile.bounding_box();
    let size = (bb.max - bb.min).norm().max(bb.max.x.abs());
    let mesh = tessellate(profile, MASS_EPS_REL * size, TessellateOptions::default())
        .map_err(|e| format!("tessellation for mass properties: {e}"))?;
    let (volume, com, inertia) = mesh_mass_properties(&mesh.mesh);
    if !(volume.is_finite() && volume > 0.0) {
        return Err(format!("solid has no volume ({volume})"));
    }
    let density = match (mass, density) {
        (Some(m), _) => m / volume,
        (None, Some(d)) => d,
        (None, None) => 1.0,
    };
    Ok(MassProperties {
        volume,
        mass: density * volume,
        com_z: com.z,
        inertia_xy: density * 0.5 * (inertia[(0, 0)] + inertia[(1, 1)]),
        inertia_z: density * inertia[(2, 2)],
    })
}
