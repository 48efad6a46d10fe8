// libccd 2.1 shim: the convex-case baseline on convex point sets (the convex hull of the points,
// reached through a support function), plus distance through FCL's libccd-based GJK
// (libccd 2.1 itself has no distance call).
//
// Bridged to Rust by the `ffi` module of verify/src/baselines/mod.rs (cxx). Point sets are flat
// xyz doubles (3 per point) in one common (world) frame; all outputs are in that frame.
// Bad input (empty set, length not a multiple of 3, non-finite coordinate, bad parameters) and
// libccd's allocation failure (return code -2) throw, arriving in Rust as Err(cxx::Exception).
#pragma once

#include <cstdint>

#include "rust/cxx.h"

namespace revdist_shim {

// Shared types defined by the cxx-generated header (verify/src/baselines/mod.rs.h).
struct CcdParams;
struct CcdPenetrationOut;
struct CcdSeparationOut;
struct GjkDistanceOut;

// ccdGJKIntersect / ccdMPRIntersect: true when the hulls intersect.
bool ccd_gjk_intersect(rust::Slice<const double> a, rust::Slice<const double> b,
                       const CcdParams& params);
bool ccd_mpr_intersect(rust::Slice<const double> a, rust::Slice<const double> b,
                       const CcdParams& params);

// ccdGJKSeparate: the minimal translation of `b` that separates the hulls (libccd's "obj2").
CcdSeparationOut ccd_gjk_separate(rust::Slice<const double> a, rust::Slice<const double> b,
                                  const CcdParams& params);

// ccdGJKPenetration (GJK + EPA) / ccdMPRPenetration: penetration of `b` into `a`: translating `b`
// by depth along dir brings the hulls into touching contact; pos is a contact position.
CcdPenetrationOut ccd_gjk_penetration(rust::Slice<const double> a, rust::Slice<const double> b,
                                      const CcdParams& params);
CcdPenetrationOut ccd_mpr_penetration(rust::Slice<const double> a, rust::Slice<const double> b,
                                      const CcdParams& params);

// fcl::detail::GJKDistance<double> (signed = false) or GJKSignedDistance<double> (signed = true).
GjkDistanceOut ccd_gjk_distance(rust::Slice<const double> a, rust::Slice<const double> b,
                                std::uint32_t max_iterations, double tolerance, bool is_signed);

}  // namespace revdist_shim
