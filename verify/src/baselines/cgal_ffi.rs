//! The CGAL bridge, kept apart from the FCL/libccd one (`mod.rs`) so that `build.rs` can cache
//! the CGAL static library (a 15 s, 0.9 GB translation unit) keyed on this bridge's generated
//! code: edits elsewhere in `baselines/` do not recompile it.

#[cxx::bridge(namespace = "revdist_shim")]
pub(crate) mod ffi {
    /// An exact rational num / den (den > 0, lowest terms) as hexadecimal integer strings
    /// (num may carry a leading '-'); parsed with rug on the Rust side.
    struct ExactRational {
        num: String,
        den: String,
    }

    /// Exact mesh-mesh squared distance with its minimising triangle pair.
    struct CgalMeshOut {
        sqd: ExactRational,
        triangle_a: u32,
        triangle_b: u32,
        /// Pairs evaluated exactly (within the float pass's slack of its minimum).
        candidates: u64,
        /// The float (Epick) minimum squared distance.
        float_sqd: f64,
    }

    /// Exact squared distance between convex hulls, with approximate realizing points.
    struct CgalPolytopeOut {
        sqd: ExactRational,
        point_p: [f64; 3],
        point_q: [f64; 3],
    }

    unsafe extern "C++" {
        include!("cgal_shim.h");

        fn cgal_triangle_sqd(a: &[f64], b: &[f64]) -> Result<ExactRational>;
        #[allow(clippy::too_many_arguments)]
        fn cgal_mesh_sqd(
            vertices_a: &[f64],
            triangles_a: &[u32],
            pose_a: &[f64],
            vertices_b: &[f64],
            triangles_b: &[u32],
            pose_b: &[f64],
            max_pairs: u64,
            max_candidates: u64,
        ) -> Result<CgalMeshOut>;
        fn cgal_polytope_sqd(p: &[f64], q: &[f64]) -> Result<CgalPolytopeOut>;
    }
}
