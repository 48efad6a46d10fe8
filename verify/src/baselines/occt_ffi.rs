//! The OpenCASCADE bridge (`cpp/include/occt_shim.h`), compiled only when `verify/build.rs`
//! found OCCT (`cfg(revdist_occt)`); the safe wrapper is [`super::occt`].

#[cxx::bridge(namespace = "revdist_shim")]
pub(crate) mod ffi {
    /// One profile piece: a clamped B-spline of `degree` in the (rho, z) plane.
    struct OcctCurve {
        degree: u32,
        /// `points.len() / 2 + degree + 1` non-decreasing knots.
        knots: Vec<f64>,
        /// rho, z of each control point.
        points: Vec<f64>,
        /// One positive weight per point, or empty for a polynomial piece.
        weights: Vec<f64>,
    }

    /// `BRepExtrema_DistShapeShape`'s answer; points in A's frame.
    struct OcctDistanceOut {
        distance: f64,
        /// `InnerSolution()`: a vertex of one solid was classified inside the other.
        inner: bool,
        solutions: u32,
        /// CPU time of the calling thread spent in `BRepExtrema_DistShapeShape`.
        cpu_seconds: f64,
        point_a: [f64; 3],
        point_b: [f64; 3],
    }

    unsafe extern "C++" {
        include!("occt_shim.h");

        type OcctSolid;

        fn occt_revolve(curves: &[OcctCurve], close_on_axis: bool) -> Result<UniquePtr<OcctSolid>>;
        fn occt_torus(major: f64, minor: f64, centre_z: f64) -> Result<UniquePtr<OcctSolid>>;
        fn occt_distance(
            a: &OcctSolid,
            b: &OcctSolid,
            pose_b: &[f64],
            deflection: f64,
            cached_classifiers: bool,
        ) -> Result<OcctDistanceOut>;
        fn occt_topology(s: &OcctSolid) -> Vec<u32>;
        fn occt_version() -> String;
        fn occt_thread_cpu_seconds() -> f64;
    }
}
