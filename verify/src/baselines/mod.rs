//! C++ baselines through `cxx`: FCL 0.7 meshes ([`fcl`]), libccd 2.1 on convex point sets
//! ([`ccd`]), CGAL 5.5 exact references ([`cgal`]) and, when installed, OpenCASCADE 7.6 on the
//! true curved surfaces ([`occt`], bridge `occt_ffi.rs`).
//!
//! The C++ shims live in `cpp/` at the workspace root (headers in `cpp/include`, sources in
//! `cpp/src`) and are compiled by `verify/build.rs`; the core crate `revdist` stays free of
//! C++. This module holds the FCL/libccd bridge; the CGAL bridge is in `cgal_ffi.rs`, a
//! separate file so that its generated code (and the slow CGAL translation unit) is rebuilt
//! only when that bridge changes.
//!
//! Conventions shared by all wrappers:
//! * lengths are in the meshes' unit (whatever the caller uses; revdist's models are unitless);
//! * a pose is an [`Isometry3<f64>`] mapping a solid's local coordinates to the world frame;
//!   results (distances, nearest points, penetration directions) are in the world frame, as in
//!   `revdist::query::Distance` (A's frame when A's pose is the identity);
//! * every failure, including a C++ exception (bad input detected by the shim, a library error,
//!   a CGAL precondition), is an `Err(BaselineError)`; nothing aborts on bad input.

pub mod ccd;
pub mod cgal;
mod cgal_ffi;
pub mod fcl;
pub mod occt;
#[cfg(revdist_occt)]
mod occt_ffi;

use nalgebra::{Isometry3, Point3};

#[cxx::bridge(namespace = "revdist_shim")]
pub(crate) mod ffi {
    /// Bounding-volume type of an FCL mesh BVH.
    #[derive(Debug)]
    #[repr(u8)]
    enum BvKind {
        /// `fcl::OBBRSSd`: oriented box + rectangle swept sphere (FCL's default for distance).
        Obbrss = 0,
        /// `fcl::RSSd`: rectangle swept sphere (PQP's volume).
        Rss = 1,
    }

    /// FCL mesh-mesh distance; points in the world frame.
    struct FclDistanceOut {
        distance: f64,
        point_a: [f64; 3],
        point_b: [f64; 3],
    }

    /// FCL 0.7 continuous-collision solver for meshes (`fcl::CCDSolverType`).
    #[derive(Debug)]
    #[repr(u8)]
    enum CcdSolverKind {
        /// `CCDC_NAIVE`: discrete collision checks at evenly spaced times.
        Naive = 0,
        /// `CCDC_CONSERVATIVE_ADVANCEMENT`: conservative advancement over BVH distances.
        ConservativeAdvancement = 1,
    }

    /// FCL continuous collision (`supported == false`: FCL returned its failure value).
    struct FclToiOut {
        supported: bool,
        collide: bool,
        time_of_contact: f64,
    }

    /// libccd's `ccd_t` parameters (iteration cap and the three tolerances, length units).
    struct CcdParams {
        max_iterations: u64,
        epa_tolerance: f64,
        mpr_tolerance: f64,
        dist_tolerance: f64,
    }

    /// libccd penetration of B into A (`intersect == false`: separated, other fields zero).
    struct CcdPenetrationOut {
        intersect: bool,
        depth: f64,
        dir: [f64; 3],
        pos: [f64; 3],
    }

    /// libccd separation vector (minimal translation of B separating the hulls).
    struct CcdSeparationOut {
        intersect: bool,
        sep: [f64; 3],
    }

    /// FCL's libccd-based GJK distance (signed: negative penetration depth when overlapping).
    struct GjkDistanceOut {
        separated: bool,
        distance: f64,
        point_a: [f64; 3],
        point_b: [f64; 3],
    }

    unsafe extern "C++" {
        include!("fcl_shim.h");

        type FclMesh;

        fn fcl_mesh_new(
            vertices: &[f64],
            triangles: &[u32],
            bv: BvKind,
        ) -> Result<UniquePtr<FclMesh>>;
        fn fcl_mesh_num_bvs(mesh: &FclMesh) -> i64;
        fn fcl_mesh_bytes(mesh: &FclMesh) -> u64;
        fn fcl_mesh_distance(
            a: &FclMesh,
            pose_a: &[f64],
            b: &FclMesh,
            pose_b: &[f64],
        ) -> Result<FclDistanceOut>;
        #[allow(clippy::too_many_arguments)]
        fn fcl_mesh_continuous(
            a: &FclMesh,
            pose_a0: &[f64],
            pose_a1: &[f64],
            b: &FclMesh,
            pose_b0: &[f64],
            pose_b1: &[f64],
            solver: CcdSolverKind,
            max_iterations: u64,
            toc_err: f64,
        ) -> Result<FclToiOut>;
    }

    unsafe extern "C++" {
        include!("ccd_shim.h");

        fn ccd_gjk_intersect(a: &[f64], b: &[f64], params: &CcdParams) -> Result<bool>;
        fn ccd_mpr_intersect(a: &[f64], b: &[f64], params: &CcdParams) -> Result<bool>;
        fn ccd_gjk_separate(a: &[f64], b: &[f64], params: &CcdParams) -> Result<CcdSeparationOut>;
        fn ccd_gjk_penetration(
            a: &[f64],
            b: &[f64],
            params: &CcdParams,
        ) -> Result<CcdPenetrationOut>;
        fn ccd_mpr_penetration(
            a: &[f64],
            b: &[f64],
            params: &CcdParams,
        ) -> Result<CcdPenetrationOut>;
        fn ccd_gjk_distance(
            a: &[f64],
            b: &[f64],
            max_iterations: u32,
            tolerance: f64,
            is_signed: bool,
        ) -> Result<GjkDistanceOut>;
    }
}

// SAFETY: an `FclMesh` owns its BVHModel exclusively (no thread affinity, no shared mutable
// state), so moving it to another thread is sound. It is not declared `Sync`: concurrent
// queries on one FCL model have not been audited.
unsafe impl Send for ffi::FclMesh {}

/// Error of a baseline call.
#[derive(Debug, thiserror::Error)]
pub enum BaselineError {
    /// Input rejected on the Rust side before reaching C++.
    #[error("invalid input: {0}")]
    Input(String),
    /// A C++ exception: input rejected by the shim, or a failure inside the library.
    #[error("{library}: {message}")]
    Cpp {
        library: &'static str,
        message: String,
    },
    /// An optional library was not found when `verify` was built.
    #[error("{hint}")]
    Missing {
        library: &'static str,
        hint: &'static str,
    },
}

impl BaselineError {
    pub(crate) fn cpp(library: &'static str) -> impl FnOnce(cxx::Exception) -> Self {
        move |e| BaselineError::Cpp {
            library,
            message: e.what().to_owned(),
        }
    }
}

/// A triangle mesh in the flat layout the shims use: `vertices` holds x, y, z of each vertex
/// (local frame, length units), `triangles` three vertex indices per triangle. The fields are
/// public and unchecked; the shims validate them (length a multiple of 3, indices in range,
/// finite coordinates) and return `Err` otherwise.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh {
    pub vertices: Vec<f64>,
    pub triangles: Vec<u32>,
}

impl TriMesh {
    /// From points and index triples (the layout of `revdist::tessellate`'s output).
    pub fn from_points(vertices: &[Point3<f64>], triangles: &[[u32; 3]]) -> Self {
        TriMesh {
            vertices: vertices.iter().flat_map(|p| [p.x, p.y, p.z]).collect(),
            triangles: triangles.as_flattened().to_vec(),
        }
    }

    /// Number of vertices (complete xyz triples).
    pub fn num_vertices(&self) -> usize {
        self.vertices.len() / 3
    }

    /// Number of triangles (complete index triples).
    pub fn num_triangles(&self) -> usize {
        self.triangles.len() / 3
    }

    /// The mesh with every vertex mapped by `pose` (rounded to double).
    pub fn transformed(&self, pose: &Isometry3<f64>) -> TriMesh {
        let vertices = self
            .vertices
            .chunks(3)
            .flat_map(|c| {
                let p = pose * Point3::new(c[0], c[1], c[2]);
                [p.x, p.y, p.z]
            })
            .collect();
        TriMesh {
            vertices,
            triangles: self.triangles.clone(),
        }
    }
}

/// A pose as the shims take it: the row-major 3x4 matrix `[R | t]` (local -> world).
pub(crate) fn pose_rows(pose: &Isometry3<f64>) -> [f64; 12] {
    let m = pose.to_homogeneous();
    let mut out = [0.0; 12];
    for r in 0..3 {
        for c in 0..4 {
            out[4 * r + c] = m[(r, c)];
        }
    }
    out
}

/// Flattens points to x, y, z triples.
pub(crate) fn flatten(points: &[Point3<f64>]) -> Vec<f64> {
    points.iter().flat_map(|p| [p.x, p.y, p.z]).collect()
}
