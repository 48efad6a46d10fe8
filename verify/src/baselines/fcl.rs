//! FCL 0.7 mesh baseline: `BVHModel<OBBRSS>` / `BVHModel<RSS>` built from a triangle mesh,
//! mesh-mesh distance with nearest points, BVH size and build time.
//!
//! FCL's mesh-mesh distance is exact for the meshes up to floating-point rounding (about 1e-16
//! relative, notes §2); its `rel_err`/`abs_err` are ignored for BVH pairs in 0.7, so there is
//! no accuracy knob to pass. Overlapping meshes give distance 0 (no signed distance for meshes).

use super::ffi::{self, BvKind, CcdSolverKind};
use super::{pose_rows, BaselineError, TriMesh};
use nalgebra::{Isometry3, Point3};
use std::time::{Duration, Instant};

const LIBRARY: &str = "FCL";

/// Bounding-volume type of the BVH.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Bv {
    /// Oriented bounding box + rectangle swept sphere (`fcl::OBBRSSd`, 256 B per node).
    Obbrss,
    /// Rectangle swept sphere (`fcl::RSSd`, PQP's volume, 136 B per node).
    Rss,
}

impl Bv {
    fn kind(self) -> BvKind {
        match self {
            Bv::Obbrss => BvKind::Obbrss,
            Bv::Rss => BvKind::Rss,
        }
    }
}

/// An FCL BVH over one triangle mesh (in the mesh's local frame; poses are given per query).
pub struct FclMesh {
    inner: cxx::UniquePtr<ffi::FclMesh>,
    bv: Bv,
    num_triangles: usize,
    build_time: Duration,
}

impl std::fmt::Debug for FclMesh {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("FclMesh")
            .field("bv", &self.bv)
            .field("num_triangles", &self.num_triangles)
            .field("num_bvs", &self.num_bvs())
            .field("bytes", &self.bytes())
            .field("build_time", &self.build_time)
            .finish()
    }
}

/// Result of [`FclMesh::distance`], in the world frame.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FclDistance {
    /// Minimum distance between the posed meshes (0 when they intersect).
    pub distance: f64,
    /// Nearest point on mesh A (world frame).
    pub point_a: Point3<f64>,
    /// Nearest point on mesh B (world frame).
    pub point_b: Point3<f64>,
}

impl FclMesh {
    /// Builds the BVH of `mesh` (FCL's default splitter and fitter). The wall-clock build time
    /// (copying into FCL's arrays + `endModel`) is measured here, see [`FclMesh::build_time`].
    pub fn new(mesh: &TriMesh, bv: Bv) -> Result<Self, BaselineError> {
        Self::from_slices(&mesh.vertices, &mesh.triangles, bv)
    }

    /// As [`FclMesh::new`], from flat xyz vertices and index triples.
    pub fn from_slices(vertices: &[f64], triangles: &[u32], bv: Bv) -> Result<Self, BaselineError> {
        let start = Instant::now();
        let inner = ffi::fcl_mesh_new(vertices, triangles, bv.kind())
            .map_err(BaselineError::cpp(LIBRARY))?;
        let build_time = start.elapsed();
        if inner.is_null() {
            return Err(BaselineError::Cpp {
                library: LIBRARY,
                message: "mesh construction returned null".into(),
            });
        }
        Ok(FclMesh {
            inner,
            bv,
            num_triangles: triangles.len() / 3,
            build_time,
        })
    }

    fn get(&self) -> &ffi::FclMesh {
        // Non-null by construction (checked in `from_slices`).
        self.inner.as_ref().expect("FclMesh is never null")
    }

    /// Bounding-volume type.
    pub fn bv(&self) -> Bv {
        self.bv
    }

    /// Number of triangles.
    pub fn num_triangles(&self) -> usize {
        self.num_triangles
    }

    /// Number of BVH nodes (`2 * triangles - 1`).
    pub fn num_bvs(&self) -> usize {
        usize::try_from(ffi::fcl_mesh_num_bvs(self.get())).unwrap_or(0)
    }

    /// Memory footprint in bytes: the `BVHModel` object plus its node, primitive-index,
    /// triangle and vertex arrays (FCL's `memUsage` returns 0 in 0.7, so it is computed from
    /// the array sizes; allocator overhead and the small splitter/fitter objects excluded).
    pub fn bytes(&self) -> usize {
        usize::try_from(ffi::fcl_mesh_bytes(self.get())).unwrap_or(usize::MAX)
    }

    /// Wall-clock time of the BVH build (measured around the FFI call).
    pub fn build_time(&self) -> Duration {
        self.build_time
    }

    /// Distance between `self` placed by `pose_a` and `other` placed by `pose_b`, with the
    /// nearest points in the world frame. Both meshes must have the same [`Bv`] (FCL has no
    /// mixed-type BVH distance); FCL's failure value `DBL_MAX` is reported as `Err`.
    pub fn distance(
        &self,
        other: &FclMesh,
        pose_a: &Isometry3<f64>,
        pose_b: &Isometry3<f64>,
    ) -> Result<FclDistance, BaselineError> {
        if self.bv != other.bv {
            return Err(BaselineError::Input(format!(
                "FCL distance needs equal BV types, got {:?} and {:?}",
                self.bv, other.bv
            )));
        }
        let out = ffi::fcl_mesh_distance(
            self.get(),
            &pose_rows(pose_a),
            other.get(),
            &pose_rows(pose_b),
        )
        .map_err(BaselineError::cpp(LIBRARY))?;
        Ok(FclDistance {
            distance: out.distance,
            point_a: Point3::from(out.point_a),
            point_b: Point3::from(out.point_b),
        })
    }
}

/// FCL 0.7's continuous-collision solvers for meshes (`fcl::continuousCollide`); its ray
/// shooting is for primitive shapes only and its polynomial solver for translations only,
/// and the latter overwrites the models' vertices (a `const_cast` in FCL 0.7), so neither is
/// offered.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum CcdSolver {
    /// `CCDC_NAIVE`: discrete collision checks at `min(max_iterations, ceil(1 / toc_err))`
    /// evenly spaced times; the first colliding sample is the time of contact.
    Naive,
    /// `CCDC_CONSERVATIVE_ADVANCEMENT`: advancement over BVH distances and FCL's motion
    /// bounds; stops when a step falls below `toc_err`.
    ConservativeAdvancement,
}

impl CcdSolver {
    fn kind(self) -> CcdSolverKind {
        match self {
            CcdSolver::Naive => CcdSolverKind::Naive,
            CcdSolver::ConservativeAdvancement => CcdSolverKind::ConservativeAdvancement,
        }
    }

    pub fn name(self) -> &'static str {
        match self {
            CcdSolver::Naive => "naive",
            CcdSolver::ConservativeAdvancement => "conservative-advancement",
        }
    }
}

/// FCL's continuous-collision answer.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FclToi {
    /// FCL returned a time (not its failure value -1).
    pub supported: bool,
    /// FCL reports a contact on `[0, 1]`.
    pub collide: bool,
    /// FCL's time of contact (1 when no contact).
    pub time_of_contact: f64,
}

impl FclMesh {
    /// Continuous collision of `self` moving from `a0` to `a1` and `other` moving from `b0`
    /// to `b1` (FCL's interpolated motion, `CCDM_LINEAR`), by `solver` with FCL's
    /// `num_max_iterations` and `toc_err`.
    #[allow(clippy::too_many_arguments)]
    pub fn continuous_collide(
        &self,
        other: &FclMesh,
        a: [&Isometry3<f64>; 2],
        b: [&Isometry3<f64>; 2],
        solver: CcdSolver,
        max_iterations: u64,
        toc_err: f64,
    ) -> Result<FclToi, BaselineError> {
        if self.bv != other.bv {
            return Err(BaselineError::Input(format!(
                "FCL continuous collision needs equal BV types, got {:?} and {:?}",
                self.bv, other.bv
            )));
        }
        let out = ffi::fcl_mesh_continuous(
            self.get(),
            &pose_rows(a[0]),
            &pose_rows(a[1]),
            other.get(),
            &pose_rows(b[0]),
            &pose_rows(b[1]),
            solver.kind(),
            max_iterations,
            toc_err,
        )
        .map_err(BaselineError::cpp(LIBRARY))?;
        Ok(FclToi {
            supported: out.supported,
            collide: out.collide,
            time_of_contact: out.time_of_contact,
        })
    }
}
