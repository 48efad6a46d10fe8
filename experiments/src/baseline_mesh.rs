//! FCL's side of an equal-accuracy comparison: a certified mesh of a profile (two-sided
//! Hausdorff error <= eps, `revdist::tessellate`) and FCL's OBBRSS and RSS hierarchies on it.

use nalgebra::Isometry3;
use revdist::profile::Profile;
use revdist::query::Distance;
use revdist::tessellate::{tessellate, CertifiedMesh, TessellateOptions, VertexPlacement};
use std::time::{Duration, Instant};
use verify::baselines::fcl::{Bv, FclMesh};
use verify::baselines::TriMesh;
use verify::crosscheck::criterion::{judge, Baseline, Certified, Verdict, SLACK_REL};

/// Capped layout: longest meridian edge as a fraction of the profile's bounding-box diagonal
/// (sliver fans on flat disks are slow for FCL; the cap helps there and costs triangles
/// elsewhere, so comparisons time both layouts and keep the faster).
pub const EDGE_CAP_REL: f64 = 1.0 / 64.0;

/// Names of the two mesh layouts, in the order [`Layout::both`] builds them.
pub const LAYOUT_NAMES: [&str; 2] = ["balanced", "capped"];

/// The certified mesh FCL gets (balanced vertices, meridian edges capped at `cap` when
/// given) and the time it took.
pub fn certified_mesh(
    p: &Profile,
    eps: f64,
    cap: Option<f64>,
) -> Result<(CertifiedMesh, Duration), Box<dyn std::error::Error>> {
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
    Ok((cm, t.elapsed()))
}

/// FCL's OBBRSS hierarchy on a certified mesh.
pub fn obbrss_of(cm: &CertifiedMesh) -> Result<FclMesh, Box<dyn std::error::Error>> {
    let tm = TriMesh::from_points(&cm.mesh.vertices, &cm.mesh.triangles);
    Ok(FclMesh::new(&tm, Bv::Obbrss)?)
}

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
        let (cm, mesh_time) = certified_mesh(p, eps, cap)?;
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

    /// The meridian-edge cap of the capped layout of `p` at `eps`, or `None` when the cap is
    /// not above `2 eps` (the tessellator's smallest allowed cap: the meridian segments of a
    /// coarse mesh are already shorter, and the capped layout is the balanced one).
    pub fn capped_edge(p: &Profile, eps: f64) -> Option<f64> {
        let cap = EDGE_CAP_REL * crate::shapes::diagonal(p);
        (cap > 2.0 * eps).then_some(cap)
    }

    /// Triangles in the mesh.
    pub fn triangles(&self) -> usize {
        self.cm.mesh.triangles.len()
    }
}

/// The cross-check of one revdist answer against one FCL mesh distance
/// (`verify::crosscheck::criterion`): revdist's certified interval must meet FCL's
/// `d ± (h_a + h_b)` widened by the rounding slack of the configuration (`size`: the sum of
/// both profiles' diagonals; B placed by `pose`). `true` when they agree.
pub fn agrees_with_fcl(
    d: &Distance,
    fcl_distance: f64,
    mesh_bounds: f64,
    pose: &Isometry3<f64>,
    size: f64,
) -> bool {
    let scale = 1.0 + pose.translation.vector.norm() + size;
    let base = Baseline {
        distance: fcl_distance,
        mesh_bounds,
        slack: SLACK_REL * scale,
    };
    let rev = Certified {
        lower: d.lower,
        upper: d.upper,
        overlap: d.overlap,
    };
    judge(rev, d.value, base, || false).verdict == Verdict::Passed
}
