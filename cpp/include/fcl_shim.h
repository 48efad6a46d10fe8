// FCL 0.7 shim: triangle-mesh BVHs (OBBRSS, RSS) and mesh-mesh distance with nearest points.
//
// Bridged to Rust by the `ffi` module of verify/src/baselines/mod.rs (cxx). The FCL headers stay
// out of this header (pimpl), so the cxx-generated bridge TU compiles without them; `FclMesh`
// must nevertheless be a complete type here because cxx static_asserts it for UniquePtr.
//
// Conventions (shared with the Rust wrappers):
// * vertices: flat xyz doubles (3 per vertex); triangles: flat u32 vertex indices (3 per triangle).
// * poses: 12 doubles, the row-major 3x4 matrix [R | t] mapping local to world coordinates.
// * distances in the meshes' length unit; nearest points in the world frame.
// Every error (bad input, FCL build failure, unsupported query) is a C++ exception, which cxx
// turns into Err(cxx::Exception) on the Rust side.
#pragma once

#include <cstdint>
#include <memory>

#include "rust/cxx.h"

namespace revdist_shim {

// Shared types defined by the cxx-generated header (verify/src/baselines/mod.rs.h).
struct FclDistanceOut;
struct FclToiOut;
enum class BvKind : std::uint8_t;
enum class CcdSolverKind : std::uint8_t;

// An FCL BVHModel (OBBRSS or RSS) built from one triangle mesh.
class FclMesh {
 public:
  struct Impl;  // complete only in fcl_shim.cc, where <fcl/fcl.h> is included
  explicit FclMesh(std::unique_ptr<Impl> impl);
  ~FclMesh();
  FclMesh(const FclMesh&) = delete;
  FclMesh& operator=(const FclMesh&) = delete;
  const Impl& impl() const { return *impl_; }

 private:
  std::unique_ptr<Impl> impl_;
};

// Builds the BVH (beginModel/addSubModel/endModel). Throws std::invalid_argument on bad input
// (lengths not multiples of 3, empty mesh, index out of range, non-finite coordinate) and
// std::runtime_error when FCL reports a build error.
std::unique_ptr<FclMesh> fcl_mesh_new(rust::Slice<const double> vertices,
                                      rust::Slice<const std::uint32_t> triangles, BvKind bv);

// Number of BV nodes (2 * triangles - 1 for FCL's binary tree).
std::int64_t fcl_mesh_num_bvs(const FclMesh& mesh);

// Heap + object footprint in bytes, from the node, vertex, triangle and primitive-index arrays
// (FCL 0.7's memUsage() returns BVH_OK = 0 instead of a byte count).
std::uint64_t fcl_mesh_bytes(const FclMesh& mesh);

// Distance between two posed meshes of the same BV type, with nearest points (world frame).
// Throws when the BV types differ, a pose is not a finite rigid motion, or FCL returns a
// failed result (negative, NaN or DBL_MAX, which FCL uses for unsupported BV pairs).
FclDistanceOut fcl_mesh_distance(const FclMesh& a, rust::Slice<const double> pose_a,
                                 const FclMesh& b, rust::Slice<const double> pose_b);

// Continuous collision (fcl::continuousCollide) of two meshes of the same BV type, each moving
// from its start to its end pose with FCL's interpolated motion (fcl::InterpMotion with the
// frame origin as reference point: constant linear velocity of the origin, rotation about a
// constant axis along the shortest arc), by `solver` with
// num_max_iterations = `max_iterations` and toc_err = `toc_err`. `supported` is false when FCL
// returns its failure value -1 (unsupported pair); `collide` and `time_of_contact` are FCL's.
FclToiOut fcl_mesh_continuous(const FclMesh& a, rust::Slice<const double> pose_a0,
                              rust::Slice<const double> pose_a1, const FclMesh& b,
                              rust::Slice<const double> pose_b0,
                              rust::Slice<const double> pose_b1, CcdSolverKind solver,
                              std::uint64_t max_iterations, double toc_err);

}  // namespace revdist_shim
