// libccd 2.1 shim (see include/ccd_shim.h for the conventions).
#include "ccd_shim.h"

#include <limits>
#include <stdexcept>
#include <string>

#include <ccd/ccd.h>
// FCL's libccd extension (GJKDistance / GJKSignedDistance), exported from libfcl.so.
#include <fcl/narrowphase/detail/convexity_based_algorithm/gjk_libccd.h>

#include "common.h"
#include "verify/src/baselines/mod.rs.h"

namespace revdist_shim {
namespace {

// A convex point set seen through its support function (libccd's "object").
struct PointSet {
  const double* xyz;
  std::size_t n;
};

PointSet point_set(rust::Slice<const double> xyz, const char* what) {
  const std::size_t n = detail::check_points(xyz, what);
  return PointSet{xyz.data(), n};
}

// Support point: the vertex maximising dir . p (first one on ties), i.e. the support of the hull.
void support(const void* obj, const ccd_vec3_t* dir, ccd_vec3_t* out) {
  const auto* s = static_cast<const PointSet*>(obj);
  std::size_t best = 0;
  double best_dot = -std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < s->n; ++i) {
    const double* p = s->xyz + 3 * i;
    const double dot = p[0] * dir->v[0] + p[1] * dir->v[1] + p[2] * dir->v[2];
    if (dot > best_dot) {
      best_dot = dot;
      best = i;
    }
  }
  ccdVec3Set(out, s->xyz[3 * best], s->xyz[3 * best + 1], s->xyz[3 * best + 2]);
}

// Interior point needed by MPR: the centroid of the points (inside the hull).
void center(const void* obj, ccd_vec3_t* out) {
  const auto* s = static_cast<const PointSet*>(obj);
  double c[3] = {0.0, 0.0, 0.0};
  for (std::size_t i = 0; i < s->n; ++i) {
    for (int k = 0; k < 3; ++k) c[k] += s->xyz[3 * i + k];
  }
  const double inv = 1.0 / static_cast<double>(s->n);
  ccdVec3Set(out, c[0] * inv, c[1] * inv, c[2] * inv);
}

ccd_t make_ccd(const CcdParams& p) {
  if (p.max_iterations == 0) throw std::invalid_argument("libccd: max_iterations must be > 0");
  for (double tol : {p.epa_tolerance, p.mpr_tolerance, p.dist_tolerance}) {
    if (!(tol > 0.0) || !std::isfinite(tol)) {
      throw std::invalid_argument("libccd: tolerances must be finite and > 0");
    }
  }
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = support;
  ccd.support2 = support;
  ccd.center1 = center;
  ccd.center2 = center;
  // CCD_INIT sets max_iterations to (unsigned long)-1, i.e. no cap: a degenerate input could
  // loop for ever, so the caller's cap is always used.
  ccd.max_iterations = static_cast<unsigned long>(p.max_iterations);
  ccd.epa_tolerance = p.epa_tolerance;
  ccd.mpr_tolerance = p.mpr_tolerance;
  ccd.dist_tolerance = p.dist_tolerance;
  return ccd;
}

// libccd's return codes: 0 = intersecting (outputs filled), -1 = separated, -2 = out of memory.
bool intersecting(int code, const char* call) {
  if (code == 0) return true;
  if (code == -1) return false;
  throw std::runtime_error(std::string("libccd ") + call + " failed with code " +
                           std::to_string(code));
}

void copy(const ccd_vec3_t& v, std::array<double, 3>& out) {
  for (int k = 0; k < 3; ++k) out[k] = v.v[k];
}

template <typename F>
CcdPenetrationOut penetration(rust::Slice<const double> a, rust::Slice<const double> b,
                              const CcdParams& params, F call, const char* name) {
  const PointSet pa = point_set(a, "libccd set A");
  const PointSet pb = point_set(b, "libccd set B");
  const ccd_t ccd = make_ccd(params);
  ccd_real_t depth = 0.0;
  ccd_vec3_t dir, pos;
  ccdVec3Set(&dir, 0.0, 0.0, 0.0);
  ccdVec3Set(&pos, 0.0, 0.0, 0.0);
  CcdPenetrationOut out{};
  out.intersect = intersecting(call(&pa, &pb, &ccd, &depth, &dir, &pos), name);
  out.depth = out.intersect ? depth : 0.0;
  copy(dir, out.dir);
  copy(pos, out.pos);
  return out;
}

}  // namespace

bool ccd_gjk_intersect(rust::Slice<const double> a, rust::Slice<const double> b,
                       const CcdParams& params) {
  const PointSet pa = point_set(a, "libccd set A");
  const PointSet pb = point_set(b, "libccd set B");
  const ccd_t ccd = make_ccd(params);
  return ccdGJKIntersect(&pa, &pb, &ccd) != 0;
}

bool ccd_mpr_intersect(rust::Slice<const double> a, rust::Slice<const double> b,
                       const CcdParams& params) {
  const PointSet pa = point_set(a, "libccd set A");
  const PointSet pb = point_set(b, "libccd set B");
  const ccd_t ccd = make_ccd(params);
  return ccdMPRIntersect(&pa, &pb, &ccd) != 0;
}

CcdSeparationOut ccd_gjk_separate(rust::Slice<const double> a, rust::Slice<const double> b,
                                  const CcdParams& params) {
  const PointSet pa = point_set(a, "libccd set A");
  const PointSet pb = point_set(b, "libccd set B");
  const ccd_t ccd = make_ccd(params);
  ccd_vec3_t sep;
  ccdVec3Set(&sep, 0.0, 0.0, 0.0);
  CcdSeparationOut out{};
  out.intersect = intersecting(ccdGJKSeparate(&pa, &pb, &ccd, &sep), "ccdGJKSeparate");
  copy(sep, out.sep);
  return out;
}

CcdPenetrationOut ccd_gjk_penetration(rust::Slice<const double> a, rust::Slice<const double> b,
                                      const CcdParams& params) {
  return penetration(a, b, params, ccdGJKPenetration, "ccdGJKPenetration");
}

CcdPenetrationOut ccd_mpr_penetration(rust::Slice<const double> a, rust::Slice<const double> b,
                                      const CcdParams& params) {
  return penetration(a, b, params, ccdMPRPenetration, "ccdMPRPenetration");
}

GjkDistanceOut ccd_gjk_distance(rust::Slice<const double> a, rust::Slice<const double> b,
                                std::uint32_t max_iterations, double tolerance, bool is_signed) {
  PointSet pa = point_set(a, "GJK set A");
  PointSet pb = point_set(b, "GJK set B");
  if (max_iterations == 0) throw std::invalid_argument("GJK: max_iterations must be > 0");
  if (!(tolerance > 0.0) || !std::isfinite(tolerance)) {
    throw std::invalid_argument("GJK: tolerance must be finite and > 0");
  }
  double d = 0.0;
  fcl::Vector3d p1 = fcl::Vector3d::Zero(), p2 = fcl::Vector3d::Zero();
  // The object pointers are passed back to `support` only (never written through).
  const bool separated =
      is_signed ? fcl::detail::GJKSignedDistance<double>(&pa, support, &pb, support,
                                                         max_iterations, tolerance, &d, &p1, &p2)
                : fcl::detail::GJKDistance<double>(&pa, support, &pb, support, max_iterations,
                                                   tolerance, &d, &p1, &p2);
  if (!std::isfinite(d)) throw std::runtime_error("GJK distance returned a non-finite value");
  GjkDistanceOut out{};
  out.separated = separated;
  out.distance = d;
  for (int k = 0; k < 3; ++k) {
    out.point_a[k] = p1(k);
    out.point_b[k] = p2(k);
  }
  return out;
}

}  // namespace revdist_shim
