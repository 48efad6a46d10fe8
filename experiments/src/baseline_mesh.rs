//! FCL's side of an equal-accuracy comparison: a certified mesh of a profile (two-sided
//! Hausdorff error <= eps, `revdist::tessellate`) and FCL's OBBRSS and RSS hierarchies on it.

use revdist::profile::Profile;
use revdist::tessellate::{tessellate, CertifiedMesh, TessellateOptions, VertexPlacement};
use std::time::{Duration, Instant};
use verify::baselines::fcl::{Bv, FclMesh};
use verify::baselines::TriMesh;

/// Capped layout: longest meridian edge as a fraction of the profile's bounding-box diagonal
/// (sliver fans on flat disks are slow for FCL; the cap helps there and costs triangles
/// elsewhere, so comparisons time both layouts and keep the faster).
pub const EDGE_CAP_REL: f64 = 1.0 / 64.0;

/// Names of the two mesh layouts, in the order [`Layout::both`] builds them.
pub const LAYOUT_NAMES: [&str; 2] = ["balanced", "capped"];

/// One mesh layout of one shape, with both FCL hierarchies and their build times.
pub struct Layout {
    pub cm: CertifiedMesh,
    pub mesh_time: Duration,
    /// FCL `BVHModel<OBBRSS>` (its build time: [`FclMesh::build_time`]).
    pub obbrss: FclMesh,
    /// FCL `BVHModel<RSS>`.
    pub rss: FclMesh,
}

impl Layout {
    /// Tessellate `p` within `eps` (meridian edges capped at `cap` when given) and build
    /// both hierarchies.
    pub fn build(
        p: &Profile,
        eps: f64,
        cap: Option<f64>,
    ) -> Result<Layout, Box<dyn std::error::Error>> {
        let t = Instant::now();
        let cm = tessellate(
            p,
            eps,
            TessellateOptions {
                placement: VertexPlacement::Balanced,
                max_meridian_edge: cap,
                ..TessellateOptions::default()
            },
        )?;
        let mesh_time = t.elapsed();
        let tm = TriMesh::from_points(&cm.mesh.vertices, &cm.mesh.triangles);
        let obbrss = FclMesh::new(&tm, Bv::Obbrss)?;
        let rss = FclMesh::new(&tm, Bv::Rss)?;
        Ok(Layout {
            cm,
            mesh_time,
            obbrss,
            rss,
        })
    }

    /// Both layouts of `p` at `eps`, in the order of [`LAYOUT_NAMES`].
    pub fn both(p: &Profile, eps: f64) -> Result<[Layout; 2], Box<dyn std::error::Error>> {
        let cap = EDGE_CAP_REL * crate::shapes::diagonal(p);
        Ok([
            Layout::build(p, eps, None)?,
            Layout::build(p, eps, Some(cap))?,
        ])
    }

    /// Triangles in the mesh.
    pub fn triangles(&self) -> usize {
        self.cm.mesh.triangles.len()
    }
}
