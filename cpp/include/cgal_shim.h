// CGAL 5.5 shim: exact references.
// * Exact squared distance between two triangles (Epeck).
// * Exact squared distance between two posed triangle meshes: an Epick brute-force pass (with
//   bounding-box rejection) selects the candidate pairs within a rounding slack of the float
//   minimum, then Epeck evaluates those pairs exactly, with the poses applied exactly.
// * Exact squared distance between the convex hulls of two point sets (Polytope_distance_d with
//   Epick points and Gmpzf exact arithmetic).
//
// Bridged to Rust by verify/src/baselines/cgal_ffi.rs (cxx), compiled in its own static library
// (it is the 15 s translation unit; see verify/build.rs). Exact values leave C++ as rationals in
// hexadecimal strings, so the Rust side (rug) rounds them once. Errors, including CGAL's own
// precondition failures (CGAL::Failure_exception), are exceptions -> Err(cxx::Exception).
#pragma once

#include <cstdint>

#include "rust/cxx.h"

namespace revdist_shim {

// Shared types defined by the cxx-generated header (verify/src/baselines/cgal_ffi.rs.h).
struct ExactRational;
struct CgalMeshOut;
struct CgalPolytopeOut;

// Exact squared distance between triangles a and b (9 doubles each: three xyz vertices).
ExactRational cgal_triangle_sqd(rust::Slice<const double> a, rust::Slice<const double> b);

// Exact squared distance between mesh A placed by pose_a and mesh B placed by pose_b (layout as
// in fcl_shim.h). Throws when na * nb exceeds max_pairs or the float pass leaves more than
// max_candidates near-tied pairs.
CgalMeshOut cgal_mesh_sqd(rust::Slice<const double> vertices_a,
                          rust::Slice<const std::uint32_t> triangles_a,
                          rust::Slice<const double> pose_a, rust::Slice<const double> vertices_b,
                          rust::Slice<const std::uint32_t> triangles_b,
                          rust::Slice<const double> pose_b, std::uint64_t max_pairs,
                          std::uint64_t max_candidates);

// Exact squared distance between the convex hulls of point sets p and q (flat xyz).
CgalPolytopeOut cgal_polytope_sqd(rust::Slice<const double> p, rust::Slice<const double> q);

}  // namespace revdist_shim
