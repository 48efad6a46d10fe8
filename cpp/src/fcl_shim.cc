// FCL 0.7 shim (see include/fcl_shim.h for the conventions).
#include "fcl_shim.h"

#include <cfloat>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include <fcl/fcl.h>

#include "common.h"
#include "verify/src/baselines/mod.rs.h"

namespace revdist_shim {

struct FclMesh::Impl {
  BvKind bv;
  // Exactly one of the two models is set, according to `bv`.
  std::shared_ptr<fcl::BVHModel<fcl::OBBRSSd>> obbrss;
  std::shared_ptr<fcl::BVHModel<fcl::RSSd>> rss;
};

FclMesh::FclMesh(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
FclMesh::~FclMesh() = default;

namespace {

// FCL's DistanceRequest::distance_tolerance (only used by its GJK solver for primitive shapes;
// mesh-mesh distance is exact for the meshes). rel_err/abs_err are 0: FCL 0.7 ignores them for
// BVH-BVH distance anyway (the traversal node copies them before they are assigned).
constexpr double kGjkDistanceTolerance = 1e-6;

template <typename BV>
std::shared_ptr<fcl::BVHModel<BV>> build_model(rust::Slice<const double> vertices,
                                               rust::Slice<const std::uint32_t> triangles) {
  std::vector<fcl::Vector3d> points(vertices.size() / 3);
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = fcl::Vector3d(vertices[3 * i], vertices[3 * i + 1], vertices[3 * i + 2]);
  }
  std::vector<fcl::Triangle> tris(triangles.size() / 3);
  for (std::size_t i = 0; i < tris.size(); ++i) {
    tris[i] = fcl::Triangle(triangles[3 * i], triangles[3 * i + 1], triangles[3 * i + 2]);
  }
  auto model = std::make_shared<fcl::BVHModel<BV>>();
  const auto check = [](int code, const char* step) {
    if (code != fcl::BVH_OK) {
      throw std::runtime_error(std::string("FCL BVHModel::") + step + " failed with code " +
                               std::to_string(code));
    }
  };
  check(model->beginModel(static_cast<int>(tris.size()), static_cast<int>(points.size())),
        "beginModel");
  check(model->addSubModel(points, tris), "addSubModel");
  check(model->endModel(), "endModel");
  return model;
}

// Bytes held by a built BVHModel: the object itself, the BV nodes (BVNode<BV>, not BV as FCL's
// own memUsage counts), the primitive-index array (allocated with one entry per node), the
// triangles (three size_t each) and the vertices. The splitter/fitter objects (< 1 kB) and
// allocator overhead are not counted.
template <typename BV>
std::uint64_t model_bytes(const fcl::BVHModel<BV>& m) {
  const auto nodes = static_cast<std::uint64_t>(m.getNumBVs());
  return sizeof(fcl::BVHModel<BV>) + nodes * sizeof(fcl::BVNode<BV>) +
         nodes * sizeof(unsigned int) +
         static_cast<std::uint64_t>(m.num_tris) * sizeof(fcl::Triangle) +
         static_cast<std::uint64_t>(m.num_vertices) * sizeof(fcl::Vector3d);
}

fcl::Transform3d to_transform(rust::Slice<const double> pose) {
  fcl::Transform3d tf = fcl::Transform3d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) tf.linear()(r, c) = pose[4 * r + c];
    tf.translation()(r) = pose[4 * r + 3];
  }
  return tf;
}

const fcl::CollisionGeometryd* geometry(const FclMesh::Impl& m) {
  if (m.bv == BvKind::Obbrss) return m.obbrss.get();
  return m.rss.get();
}

}  // namespace

std::unique_ptr<FclMesh> fcl_mesh_new(rust::Slice<const double> vertices,
                                      rust::Slice<const std::uint32_t> triangles, BvKind bv) {
  detail::check_mesh(vertices, triangles, "FCL mesh");
  auto impl = std::make_unique<FclMesh::Impl>();
  impl->bv = bv;
  switch (bv) {
    case BvKind::Obbrss:
      impl->obbrss = build_model<fcl::OBBRSSd>(vertices, triangles);
      break;
    case BvKind::Rss:
      impl->rss = build_model<fcl::RSSd>(vertices, triangles);
      break;
    default:
      throw std::invalid_argument("FCL mesh: unknown BV kind");
  }
  return std::make_unique<FclMesh>(std::move(impl));
}

std::int64_t fcl_mesh_num_bvs(const FclMesh& mesh) {
  const auto& m = mesh.impl();
  return m.bv == BvKind::Obbrss ? m.obbrss->getNumBVs() : m.rss->getNumBVs();
}

std::uint64_t fcl_mesh_bytes(const FclMesh& mesh) {
  const auto& m = mesh.impl();
  return m.bv == BvKind::Obbrss ? model_bytes(*m.obbrss) : model_bytes(*m.rss);
}

FclDistanceOut fcl_mesh_distance(const FclMesh& a, rust::Slice<const double> pose_a,
                                 const FclMesh& b, rust::Slice<const double> pose_b) {
  if (a.impl().bv != b.impl().bv) {
    // FCL dispatches BVH-BVH distance on the pair of node types; mixed pairs are unsupported.
    throw std::invalid_argument("FCL distance: both meshes must use the same BV type");
  }
  detail::check_pose(pose_a, "FCL pose A", true);
  detail::check_pose(pose_b, "FCL pose B", true);
  fcl::DistanceRequestd request(/*enable_nearest_points=*/true,
                                /*enable_signed_distance=*/false, /*rel_err=*/0.0,
                                /*abs_err=*/0.0, kGjkDistanceTolerance, fcl::GST_LIBCCD);
  fcl::DistanceResultd result;
  const double d = fcl::distance(geometry(a.impl()), to_transform(pose_a), geometry(b.impl()),
                                 to_transform(pose_b), request, result);
  if (!std::isfinite(d) || d < 0.0 || d >= DBL_MAX) {
    // FCL signals unsupported node-type pairs by printing a warning and returning DBL_MAX.
    throw std::runtime_error("FCL distance failed (returned " + std::to_string(d) + ")");
  }
  FclDistanceOut out;
  out.distance = d;
  for (int k = 0; k < 3; ++k) {
    out.point_a[k] = result.nearest_points[0](k);
    out.point_b[k] = result.nearest_points[1](k);
  }
  return out;
}

FclToiOut fcl_mesh_continuous(const FclMesh& a, rust::Slice<const double> pose_a0,
                              rust::Slice<const double> pose_a1, const FclMesh& b,
                              rust::Slice<const double> pose_b0,
                              rust::Slice<const double> pose_b1, CcdSolverKind solver,
                              std::uint64_t max_iterations, double toc_err) {
  if (a.impl().bv != b.impl().bv) {
    throw std::invalid_argument("FCL continuous collision: both meshes must use the same BV type");
  }
  detail::check_pose(pose_a0, "FCL start pose A", true);
  detail::check_pose(pose_a1, "FCL end pose A", true);
  detail::check_pose(pose_b0, "FCL start pose B", true);
  detail::check_pose(pose_b1, "FCL end pose B", true);
  if (!(toc_err > 0.0) || !std::isfinite(toc_err) || max_iterations < 2) {
    throw std::invalid_argument("FCL continuous collision: need toc_err > 0 and >= 2 iterations");
  }
  fcl::ContinuousCollisionRequestd request(
      static_cast<std::size_t>(max_iterations), toc_err, fcl::CCDM_LINEAR, fcl::GST_LIBCCD,
      solver == CcdSolverKind::Naive ? fcl::CCDC_NAIVE : fcl::CCDC_CONSERVATIVE_ADVANCEMENT);
  fcl::ContinuousCollisionResultd result;
  // The motions are built here rather than by the Transform3 overload of continuousCollide:
  // that overload's InterpMotion(tf1, tf2) constructor leaves the reference point (the point
  // moving on a straight line) uninitialised in FCL 0.7, and the (tf1, tf2, O) constructor
  // does not compute the velocities; this one sets O = the frame origin and computes them.
  const auto motion = [](rust::Slice<const double> p0, rust::Slice<const double> p1) {
    const fcl::Transform3d t0 = to_transform(p0);
    const fcl::Transform3d t1 = to_transform(p1);
    return fcl::InterpMotion<double>(t0.linear(), t0.translation(), t1.linear(), t1.translation(),
                                     fcl::Vector3d::Zero());
  };
  const fcl::InterpMotion<double> motion_a = motion(pose_a0, pose_a1);
  const fcl::InterpMotion<double> motion_b = motion(pose_b0, pose_b1);
  const double toc = fcl::continuousCollide(geometry(a.impl()), &motion_a, geometry(b.impl()),
                                            &motion_b, request, result);
  FclToiOut out;
  out.supported = std::isfinite(toc) && toc >= 0.0;
  out.collide = result.is_collide;
  out.time_of_contact = result.time_of_contact;
  return out;
}

}  // namespace revdist_shim
