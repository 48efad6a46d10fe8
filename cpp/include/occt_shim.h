// OpenCASCADE 7.6 shim: solids of revolution on the true curved surfaces, and their distance.
// * A profile (NURBS pieces in the (rho, z) half-plane, rational where they are exact arcs) is
//   placed in the XZ plane (x = rho), closed by the axis segment when it is open on the axis,
//   made into a planar face and revolved a full turn about Z (BRepPrimAPI_MakeRevol).
// * A torus can be made exactly with BRepPrimAPI_MakeTorus.
// * Every solid is checked once with BRepCheck_Analyzer and oriented outwards.
// * The distance is BRepExtrema_DistShapeShape(A, B.Located(pose_b), Extrema_ExtFlag_MIN).
//
// Bridged to Rust by verify/src/baselines/occt_ffi.rs (cxx), compiled in its own static library
// by verify/build.rs only when OCCT's headers and libraries are installed. This header includes
// no OCCT header, so the cxx bridge code compiles without OCCT's include path. Every OCCT
// exception (Standard_Failure, which does not derive from std::exception) is turned into a
// std::runtime_error, which cxx returns to Rust as Err.
#pragma once

#include <cstdint>
#include <memory>

#include "rust/cxx.h"

namespace revdist_shim {

// Shared types defined by the cxx-generated header (verify/src/baselines/occt_ffi.rs.h).
struct OcctCurve;
struct OcctDistanceOut;

// A validated OCCT solid. The TopoDS_Shape lives behind a pointer to an implementation
// defined in occt_shim.cc, so that this header needs no OCCT header. Not safe to share between
// threads while queried: each thread builds its own.
class OcctSolid {
 public:
  struct Impl;
  explicit OcctSolid(std::unique_ptr<Impl> impl);
  ~OcctSolid();
  OcctSolid(const OcctSolid&) = delete;
  OcctSolid& operator=(const OcctSolid&) = delete;
  std::unique_ptr<Impl> impl;
};

// The solid bounded by the revolution of `curves` (joined end to start in the (rho, z) plane),
// closed by the axis segment from the last end point to the first start point when
// `close_on_axis` is true.
std::unique_ptr<OcctSolid> occt_revolve(rust::Slice<const OcctCurve> curves, bool close_on_axis);

// The solid torus of major radius `major` and minor radius `minor` about Z, centred at
// (0, 0, centre_z).
std::unique_ptr<OcctSolid> occt_torus(double major, double minor, double centre_z);

// Minimum distance between `a` (at the identity) and `b` placed by `pose_b` (row-major 3x4
// [R | t], 12 doubles). `deflection` is BRepExtrema's precision (the tolerance within which two
// candidate distances count as equal; OCCT's default is Precision::Confusion() = 1e-7).
// With `cached_classifiers`, OCCT's inner-solution test (each vertex of one solid classified
// against the other, tolerance 1e-3) runs here with classifiers kept in the solids, and
// BRepExtrema gets the solids' shells; otherwise BRepExtrema gets the solids and classifies
// itself, building both classifiers on every call. The answers are the same.
OcctDistanceOut occt_distance(const OcctSolid& a, const OcctSolid& b,
                              rust::Slice<const double> pose_b, double deflection,
                              bool cached_classifiers);

// Counts of the solid's faces, edges and vertices (for reports and tests).
rust::Vec<std::uint32_t> occt_topology(const OcctSolid& s);

// CPU time of the calling thread in seconds (CLOCK_THREAD_CPUTIME_ID; NaN if unavailable).
double occt_thread_cpu_seconds();

// OCC_VERSION_COMPLETE of the headers compiled against.
rust::String occt_version();

}  // namespace revdist_shim
