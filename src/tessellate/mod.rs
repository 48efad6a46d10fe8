//! Certified tessellation of a solid of revolution: a closed triangle mesh whose two-sided
//! Hausdorff distance to the true surface is at most a requested `eps`, for use as
//! the baseline meshes of mesh-based distance libraries (FCL, libccd, CGAL in `verify/`).
//!
//! # Construction
//!
//! 1. **Profile -> arcs** ([`crate::biarc::BiarcTree`]): the leaves of a biarc tree built with a
//!    fraction of `eps`; leaf `L`'s arcs (as the query revolves them, near-straight arcs as
//!    chords) are within `eps_L` of its curve piece `C_L`, two-sided.
//! 2. **Arcs -> meridian polyline** ([`arc_chords`], [`meridian`]): every arc is replaced by
//!    segments `sigma` with a certified two-sided deviation `dev_sigma` from the arc piece they
//!    stand for (exact for circles: sagitta or offset-polygon formulas).
//! 3. **Polyline -> mesh** ([`revolve`]): every polyline vertex `(rho, z)` becomes a ring of
//!    `n_theta` vertices `(kappa rho cos theta_j, kappa rho sin theta_j, z)`,
//!    `theta_j = 2 pi j / n_theta`, or one vertex when `rho = 0` (a pole: a triangle fan);
//!    each segment between two rings becomes `n_theta` quads split into two triangles.
//!
//! # Theorem (the certified bound)
//!
//! Let `S` be the true surface (the profile curve `C` revolved) and `M` the mesh. Write
//! `tau = tan^2(pi / (2 n_theta))` and `kappa = 1 / cos^2(pi / (2 n_theta))` for
//! [`VertexPlacement::Balanced`], `tau = 1 - cos(pi / n_theta)` and `kappa = 1` for
//! [`VertexPlacement::OnSurface`]. Then
//!
//! ```text
//! d_H(M, S) <= max over segments sigma (of leaf L) of  eps_L + dev_sigma + tau * rho_max(sigma)
//! ```
//!
//! where `rho_max(sigma)` is the larger `rho` of the segment's end points. This is the
//! [`CertifiedMesh::bound`] (plus [`ROUNDING_SLACK_REL`] of the profile size for the rounding
//! of vertex coordinates); it is at most `tree_eps + meridian_error + revolution_error`.
//!
//! **Proof.** Write a point of 3-space in cylindrical coordinates: meridian point `(rho, z)`
//! and angle `phi`. Let `R_phi(p)` be the meridian point `p` placed at angle `phi`.
//!
//! (a) *Revolution preserves planar distances.* `|R_phi(p) - R_phi(q)| = |p - q|` for meridian
//! points `p, q`. Hence if a meridian point set `A` is within `h` of `B` (two-sided), then the
//! revolved sets are within `h` of each other: pair points at the same angle.
//!
//! (b) *The quads are planar and equal the "polygonal revolution" of the segment.* Let `g(u)`,
//! `u in [0, 1]`, run along the edge `j` of the regular `n_theta`-gon of circumradius `kappa`
//! in the plane `z = 0` (from angle `theta_j` to `theta_{j+1}`), and let `sigma(s) = (rho(s),
//! z(s))` run along a segment. The map `(s, u) -> rho(s) g(u) + z(s) e_z` is bilinear with
//! corners at the four mesh vertices of the quad; the quad's two ring edges are parallel to
//! `g(1) - g(0)` (both rings are scaled copies of the same polygon), so the four corners are
//! coplanar (an isosceles trapezoid, a triangle at a pole) and the bilinear map sweeps exactly
//! that convex quad, i.e. exactly the union of its two triangles. So, unlike for a general
//! bilinear patch, splitting a quad along a diagonal introduces **no** error, and
//! `M = { rho g + z e_z : (rho, z) in polyline, g on the polygon }`.
//!
//! (c) *Polygon vs circle.* The point `rho g + z e_z` with `g` on the polygon at angle `phi`
//! has `|g| in [kappa cos(pi/n), kappa]`, so it lies `rho | |g| - 1 | <= tau rho` from
//! `R_phi(rho, z)`, the point of the revolved polyline at the same angle; both maps between
//! `M` and the revolved polyline preserve `phi` and `(rho, z)`, so this holds in both
//! directions. (`kappa = 1 / cos^2(pi / 2n) = 2 / (1 + cos(pi / n))` balances the outward
//! deviation at the polygon's vertices, `kappa - 1`, against the inward one at its edge
//! midpoints, `1 - kappa cos(pi / n)`: both equal `tan^2(pi / 2n)`, about half of the
//! inscribed polygon's `1 - cos(pi / n)`.)
//!
//! (d) *Segment vs curve.* For every segment `sigma` of the arcs of leaf `L`, the segment and
//! its arc piece are within `dev_sigma` of each other, two-sided ([`arc_chords`]), vertex
//! moves (joins, poles) are added to `dev_sigma` ([`meridian`]), and the arcs of `L` are within
//! `eps_L` of `C_L`.
//!
//! Direction mesh -> surface: a point `X` of `M` lies on the quad of some segment `sigma` at
//! angle `phi` over the polyline point `q`; by (c) `|X - R_phi(q)| <= tau rho(q) <= tau
//! rho_max(sigma)`; by (d) there is an arc point `a` with `|q - a| <= dev_sigma` and a curve
//! point `c` with `|a - c| <= eps_L`; by (a) `|R_phi(q) - R_phi(c)| <= dev_sigma + eps_L`, and
//! `R_phi(c)` is on `S`. Direction surface -> mesh: a point `R_phi(c)` of `S` with `c` on `C_L`
//! has an arc point `a` of `L` within `eps_L`, which lies in the angular range of some segment
//! `sigma` of its arc with a point `q` within `dev_sigma`; `R_phi(q)` is within `tau
//! rho_max(sigma)` of the mesh point over `q` at angle `phi` (c). Summing with the triangle
//! inequality gives the bound in both directions. ∎
//!
//! The bound is a sum because the errors do add up in the worst place: at a mesh vertex on the
//! outer equator of a torus the meridian offset and the ring offset both point outwards (an
//! earlier construction that gave both directions a sagitta of eps each measured 1.6-2 eps).
//!
//! # Solid semantics
//!
//! A [`Profile`] is either closed (a loop in `rho > 0`: the mesh is a torus-like closed
//! surface) or open with both ends on the axis (the region is closed by the axis segment,
//! which revolves to a line, not a surface: the two ends become poles). Open profiles with an
//! end off the axis are rejected by [`Profile::new`], so no caps are ever needed; this matches
//! the query's containment (`crate::bvh::containment`). The mesh is oriented with outward
//! normals (positive signed volume) whichever way the profile runs, and is watertight: every
//! directed edge appears once and its reverse once ([`TriMesh::topology`]). One `n_theta` for
//! all rings keeps it free of T-junctions; creases need nothing special because consecutive
//! segments share their ring. A profile that touches the axis between its ends gives a pinch
//! vertex (still closed and consistently oriented, not a 2-manifold there).
//!
//! # Budget
//!
//! `eps` is split between the tree (`tree_eps`), the meridian chords and the revolution. The
//! split that gives the fewest triangles is searched ([`plan`]): a few tree fractions times a
//! few `n_theta`; each segment then takes the whole remaining budget of its place, so rings
//! near the axis (small `rho`, small revolution error) get longer segments.

pub mod arc_chords;
pub mod export;
pub mod meridian;
pub mod mesh;
pub mod plan;
pub mod revolve;

pub use mesh::{MeshTopology, TriMesh};

use crate::biarc::TreeError;
use crate::profile::Profile;

/// Slack added to the certified bound for the rounding of vertex coordinates, relative to the
/// profile size (bounding-box diagonal). A mesh vertex is a few floating-point operations
/// (arc evaluation, an offset, a product with a cosine) on values at most the profile size,
/// each off by at most ~1.1e-16 relative; 1e-13 covers several hundred such roundings, and is
/// still 1e-8 of any `eps` above 1e-5 of the size.
pub const ROUNDING_SLACK_REL: f64 = 1e-13;

/// Where the mesh vertices sit relative to the surface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum VertexPlacement {
    /// Vertices off the surface by half the chord error, so that chords deviate both ways by
    /// about half the sagitta: 0.5-0.7 times the triangles of [`VertexPlacement::OnSurface`] for
    /// the same bound.
    #[default]
    Balanced,
    /// Every mesh vertex on the biarc approximation of the surface (inscribed chords and
    /// polygons; the mesh lies inside the arcs' surface where the profile is convex).
    OnSurface,
}

/// Options of [`tessellate`]. `Default` searches the budget split.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TessellateOptions {
    /// Vertex placement (see [`VertexPlacement`]).
    pub placement: VertexPlacement,
    /// Longest meridian segment (in profile units); `None` for no cap. Capping avoids long
    /// sliver triangles on flat disks (fans) at the price of more triangles. Must exceed
    /// `2 eps`.
    pub max_meridian_edge: Option<f64>,
    /// Fraction of `eps` given to the biarc tree, in (0, 1); `None` searches it.
    pub tree_fraction: Option<f64>,
    /// Number of vertices per ring (>= 3); `None` searches it.
    pub n_theta: Option<usize>,
}

/// A triangle mesh with its certified Hausdorff bound and how the budget was spent.
#[derive(Debug, Clone, PartialEq)]
pub struct CertifiedMesh {
    /// The mesh, outward oriented, in the solid's local frame (axis = z).
    pub mesh: TriMesh,
    /// Certified bound on the two-sided Hausdorff distance between mesh and true surface
    /// (<= the requested eps).
    pub bound: f64,
    /// The requested eps.
    pub eps: f64,
    /// Leaf bound the biarc tree was built with (the largest leaf bound is at most this).
    pub tree_eps: f64,
    /// Largest leaf bound actually reached.
    pub leaf_error: f64,
    /// Largest deviation of a meridian segment from its arc (chord error plus vertex moves).
    pub meridian_error: f64,
    /// Largest revolution error `tau * rho` over the polyline vertices.
    pub revolution_error: f64,
    /// Rounding slack included in `bound` ([`ROUNDING_SLACK_REL`] times the profile size).
    pub rounding_slack: f64,
    /// Vertices per ring.
    pub n_theta: usize,
    /// Vertices of the meridian polyline (poles included).
    pub meridian_vertices: usize,
    /// The vertex placement used.
    pub placement: VertexPlacement,
}

/// Why a profile could not be tessellated.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum TessellateError {
    /// `eps` is not a positive finite number.
    #[error("eps must be positive and finite, got {0}")]
    InvalidEps(f64),
    /// An option is out of range.
    #[error("invalid tessellation option: {0}")]
    InvalidOption(String),
    /// Building the biarc tree failed (e.g. eps below what rounding can certify).
    #[error("biarc tree: {0}")]
    Tree(#[from] TreeError),
    /// No split of the budget meets `eps` (e.g. a fixed `n_theta` whose revolution error alone
    /// exceeds it).
    #[error("no budget split meets eps = {eps:e}: {detail}")]
    BudgetTooSmall {
        /// The requested bound.
        eps: f64,
        /// What failed.
        detail: String,
    },
    /// More vertices than `u32` indices can address.
    #[error("mesh too large: {0} vertices exceed u32 indices")]
    TooManyVertices(usize),
}

/// Tessellates `profile` into a closed, outward-oriented triangle mesh whose two-sided
/// Hausdorff distance to the surface of revolution is at most `eps` (see the module doc for
/// the construction and the proof of [`CertifiedMesh::bound`]).
pub fn tessellate(
    profile: &Profile,
    eps: f64,
    options: TessellateOptions,
) -> Result<CertifiedMesh, TessellateError> {
    if !(eps > 0.0 && eps.is_finite()) {
        return Err(TessellateError::InvalidEps(eps));
    }
    let chosen = plan::plan(profile, eps, &options)?;
    let mesh = revolve::revolve(&chosen.meridian, chosen.n_theta, options.placement)?;
    let m = &chosen.meridian;
    Ok(CertifiedMesh {
        mesh,
        bound: m.bound + chosen.rounding_slack,
        eps,
        tree_eps: chosen.tree_eps,
        leaf_error: m.leaf_error,
        meridian_error: m.deviation,
        revolution_error: m.revolution_error,
        rounding_slack: chosen.rounding_slack,
        n_theta: chosen.n_theta,
        meridian_vertices: m.points.len(),
        placement: options.placement,
    })
}
