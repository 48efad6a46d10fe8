// Input checks shared by the shims: every slice coming from Rust is validated before a library
// sees it, because FCL and libccd do not check indices or lengths (out-of-range triangle indices
// would be read out of bounds, an empty point set makes libccd's support function undefined).
#pragma once

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>

#include "rust/cxx.h"

namespace revdist_shim {
namespace detail {

// Entries of a pose: the row-major 3x4 matrix [R | t].
constexpr std::size_t kPoseEntries = 12;

// Largest accepted deviation of R^T R from the identity (entrywise). nalgebra's Isometry3 gives
// rotations orthonormal to a few ulps; anything far off is a caller error, and FCL's Isometry
// transforms assume orthonormality (they invert by transposition).
constexpr double kOrthonormalityTolerance = 1e-9;

inline void check_finite(rust::Slice<const double> xs, const char* what) {
  for (std::size_t i = 0; i < xs.size(); ++i) {
    if (!std::isfinite(xs[i])) {
      throw std::invalid_argument(std::string(what) + ": entry " + std::to_string(i) +
                                  " is not finite");
    }
  }
}

// Flat xyz array: a multiple of 3, non-empty, finite. Returns the number of points.
inline std::size_t check_points(rust::Slice<const double> xyz, const char* what) {
  if (xyz.size() % 3 != 0) {
    throw std::invalid_argument(std::string(what) + ": length " + std::to_string(xyz.size()) +
                                " is not a multiple of 3");
  }
  if (xyz.empty()) {
    throw std::invalid_argument(std::string(what) + ": no points");
  }
  check_finite(xyz, what);
  return xyz.size() / 3;
}

// Triangle mesh: points as above, indices a non-empty multiple of 3, each < number of vertices.
inline void check_mesh(rust::Slice<const double> vertices,
                       rust::Slice<const std::uint32_t> triangles, const char* what) {
  const std::size_t nv = check_points(vertices, what);
  if (triangles.size() % 3 != 0) {
    throw std::invalid_argument(std::string(what) + ": triangle index array length " +
                                std::to_string(triangles.size()) + " is not a multiple of 3");
  }
  if (triangles.empty()) {
    throw std::invalid_argument(std::string(what) + ": no triangles");
  }
  for (std::size_t i = 0; i < triangles.size(); ++i) {
    if (triangles[i] >= nv) {
      throw std::invalid_argument(std::string(what) + ": triangle " + std::to_string(i / 3) +
                                  " has vertex index " + std::to_string(triangles[i]) +
                                  " out of range (" + std::to_string(nv) + " vertices)");
    }
  }
}

// Pose: 12 finite entries; with `rigid`, R must be orthonormal within kOrthonormalityTolerance.
inline void check_pose(rust::Slice<const double> pose, const char* what, bool rigid) {
  if (pose.size() != kPoseEntries) {
    throw std::invalid_argument(std::string(what) + ": pose must have 12 entries (row-major "
                                "3x4 [R | t]), got " + std::to_string(pose.size()));
  }
  check_finite(pose, what);
  if (!rigid) return;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) {
      double dot = 0.0;  // (R^T R)_ij = column i . column j
      for (int k = 0; k < 3; ++k) dot += pose[4 * k + i] * pose[4 * k + j];
      if (std::fabs(dot - (i == j ? 1.0 : 0.0)) > kOrthonormalityTolerance) {
        throw std::invalid_argument(std::string(what) + ": rotation part is not orthonormal");
      }
    }
  }
}

}  // namespace detail
}  // namespace revdist_shim
