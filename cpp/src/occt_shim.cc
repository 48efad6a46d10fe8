// OpenCASCADE 7.6 shim (see include/occt_shim.h).
#include "occt_shim.h"

#include <cmath>
#include <ctime>
#include <stdexcept>
#include <string>
#include <vector>

#include <BRep_Builder.hxx>
#include <BRep_Tool.hxx>
#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepCheck_Analyzer.hxx>
#include <BRepClass3d_SolidClassifier.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <BRepLib.hxx>
#include <BRepPrimAPI_MakeRevol.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <Geom_BSplineCurve.hxx>
#include <Precision.hxx>
#include <Standard_Failure.hxx>
#include <Standard_Version.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColgp_Array1OfPnt.hxx>
#include <TopExp.hxx>
#include <TopExp_Explorer.hxx>
#include <TopLoc_Location.hxx>
#include <TopTools_IndexedMapOfShape.hxx>
#include <TopoDS.hxx>
#include <TopoDS_Compound.hxx>
#include <TopoDS_Shape.hxx>
#include <TopoDS_Solid.hxx>
#include <gp_Ax1.hxx>
#include <gp_Ax2.hxx>
#include <gp_Trsf.hxx>

#include "common.h"
#include "verify/src/baselines/occt_ffi.rs.h"

namespace revdist_shim {

// OCCT's own inner-solution test (BRepExtrema_DistShapeShape::Perform, 7.6) classifies each
// vertex of one solid against the other with this tolerance.
constexpr double kInnerTolerance = 0.001;

struct OcctSolid::Impl {
  TopoDS_Shape shape;
  // The solid's vertices (its local frame).
  std::vector<gp_Pnt> vertices;
  // The solid's point classifier, built on first use and kept: OCCT's Perform builds one per
  // query for each solid (ray-face intersection polyhedra of every face), which dominates the
  // time of a query on these models. Mutable: an Impl is only used by one thread.
  mutable std::unique_ptr<BRepClass3d_SolidClassifier> classifier;

  BRepClass3d_SolidClassifier& classify() const {
    if (!classifier) classifier = std::make_unique<BRepClass3d_SolidClassifier>(shape);
    return *classifier;
  }
};

OcctSolid::OcctSolid(std::unique_ptr<Impl> i) : impl(std::move(i)) {}
OcctSolid::~OcctSolid() = default;

namespace {

// Runs f, turning OCCT's exceptions (Standard_Failure is not a std::exception) into
// std::runtime_error with the context `what`, so that cxx hands them to Rust as Err.
template <typename F>
auto guarded(const char* what, F&& f) -> decltype(f()) {
  try {
    return f();
  } catch (const Standard_Failure& e) {
    throw std::runtime_error(std::string(what) + ": OCCT " + e.DynamicType()->Name() + ": " +
                             (e.GetMessageString() ? e.GetMessageString() : ""));
  } catch (const std::exception&) {
    throw;
  } catch (...) {
    throw std::runtime_error(std::string(what) + ": unknown C++ exception from OCCT");
  }
}

// Highest B-spline degree OCCT's Geom_BSplineCurve accepts.
constexpr std::uint32_t kMaxDegree = 25;

// One profile piece as a 3D B-spline curve in the XZ plane (x = rho, y = 0).
Handle(Geom_BSplineCurve) make_curve(const OcctCurve& c, std::size_t index) {
  const std::string name = "piece " + std::to_string(index);
  if (c.degree == 0 || c.degree > kMaxDegree) {
    throw std::invalid_argument(name + ": degree " + std::to_string(c.degree) +
                                " outside OCCT's range 1.." + std::to_string(kMaxDegree));
  }
  const std::size_t n = c.points.size() / 2;
  if (c.points.size() % 2 != 0 || n < c.degree + 1) {
    throw std::invalid_argument(name + ": needs at least degree + 1 (rho, z) points");
  }
  if (c.knots.size() != n + c.degree + 1) {
    throw std::invalid_argument(name + ": knot count must be points + degree + 1");
  }
  if (!c.weights.empty() && c.weights.size() != n) {
    throw std::invalid_argument(name + ": weight count must equal the point count");
  }
  detail::check_finite(rust::Slice<const double>(c.points.data(), c.points.size()), name.c_str());
  detail::check_finite(rust::Slice<const double>(c.knots.data(), c.knots.size()), name.c_str());
  // Distinct knots with multiplicities (OCCT's representation).
  std::vector<double> knots;
  std::vector<int> mults;
  for (double k : c.knots) {
    if (!knots.empty() && k < knots.back()) {
      throw std::invalid_argument(name + ": knots decrease");
    }
    if (!knots.empty() && k == knots.back()) {
      ++mults.back();
    } else {
      knots.push_back(k);
      mults.push_back(1);
    }
  }
  TColgp_Array1OfPnt poles(1, static_cast<int>(n));
  for (std::size_t i = 0; i < n; ++i) {
    poles.SetValue(static_cast<int>(i + 1), gp_Pnt(c.points[2 * i], 0.0, c.points[2 * i + 1]));
  }
  TColStd_Array1OfReal kn(1, static_cast<int>(knots.size()));
  TColStd_Array1OfInteger mu(1, static_cast<int>(knots.size()));
  for (std::size_t i = 0; i < knots.size(); ++i) {
    kn.SetValue(static_cast<int>(i + 1), knots[i]);
    mu.SetValue(static_cast<int>(i + 1), mults[i]);
  }
  if (c.weights.empty()) {
    return new Geom_BSplineCurve(poles, kn, mu, static_cast<int>(c.degree));
  }
  TColStd_Array1OfReal w(1, static_cast<int>(n));
  for (std::size_t i = 0; i < n; ++i) {
    if (!(std::isfinite(c.weights[i]) && c.weights[i] > 0.0)) {
      throw std::invalid_argument(name + ": weights must be finite and positive");
    }
    w.SetValue(static_cast<int>(i + 1), c.weights[i]);
  }
  return new Geom_BSplineCurve(poles, w, kn, mu, static_cast<int>(c.degree));
}

// Checks the shape with BRepCheck_Analyzer, extracts its single solid and orients it so that a
// point at infinity is outside. Throws with `what` otherwise.
TopoDS_Shape validated_solid(const TopoDS_Shape& shape, const char* what) {
  TopTools_IndexedMapOfShape solids;
  TopExp::MapShapes(shape, TopAbs_SOLID, solids);
  if (solids.Extent() != 1) {
    throw std::runtime_error(std::string(what) + ": expected one solid, OCCT made " +
                             std::to_string(solids.Extent()));
  }
  TopoDS_Solid solid = TopoDS::Solid(solids(1));
  BRepLib::OrientClosedSolid(solid);
  BRepCheck_Analyzer check(solid);
  if (!check.IsValid()) {
    throw std::runtime_error(std::string(what) +
                             ": BRepCheck_Analyzer rejects the solid (invalid B-rep)");
  }
  BRepClass3d_SolidClassifier outside(solid);
  outside.PerformInfinitePoint(Precision::Confusion());
  if (outside.State() != TopAbs_OUT) {
    throw std::runtime_error(std::string(what) + ": the solid is not closed and oriented (a "
                             "point at infinity is not outside)");
  }
  return solid;
}

// CPU time of the calling thread (POSIX CLOCK_THREAD_CPUTIME_ID), in seconds: unlike wall-clock
// time it does not grow when other processes share the cores.
double thread_cpu_seconds() {
  timespec ts{};
  if (clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts) != 0) return std::nan("");
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

std::unique_ptr<OcctSolid> wrap(TopoDS_Shape shape) {
  auto impl = std::make_unique<OcctSolid::Impl>();
  TopTools_IndexedMapOfShape vertices;
  TopExp::MapShapes(shape, TopAbs_VERTEX, vertices);
  for (int i = 1; i <= vertices.Extent(); ++i) {
    impl->vertices.push_back(BRep_Tool::Pnt(TopoDS::Vertex(vertices(i))));
  }
  impl->shape = std::move(shape);
  return std::make_unique<OcctSolid>(std::move(impl));
}

// The shells of a solid as one compound: BRepExtrema treats it like the solid's boundary but
// skips the solid classification (done by the caller with cached classifiers).
TopoDS_Shape boundary(const TopoDS_Shape& solid) {
  TopoDS_Compound c;
  BRep_Builder builder;
  builder.MakeCompound(c);
  for (TopExp_Explorer e(solid, TopAbs_SHELL); e.More(); e.Next()) builder.Add(c, e.Current());
  return c;
}

// OCCT's inner-solution test with the solids' cached classifiers, in OCCT's order: the
// vertices of B (placed by trsf) in A, then the vertices of A in B. Returns the first vertex
// found inside, in A's frame.
bool inner_vertex(const OcctSolid::Impl& a, const OcctSolid::Impl& b, const gp_Trsf& trsf,
                  gp_Pnt& found) {
  BRepClass3d_SolidClassifier& ca = a.classify();
  for (const gp_Pnt& v : b.vertices) {
    const gp_Pnt p = v.Transformed(trsf);
    ca.Perform(p, kInnerTolerance);
    if (ca.State() == TopAbs_IN) {
      found = p;
      return true;
    }
  }
  BRepClass3d_SolidClassifier& cb = b.classify();
  const gp_Trsf inverse = trsf.Inverted();
  for (const gp_Pnt& v : a.vertices) {
    cb.Perform(v.Transformed(inverse), kInnerTolerance);
    if (cb.State() == TopAbs_IN) {
      found = v;
      return true;
    }
  }
  return false;
}

}  // namespace

std::unique_ptr<OcctSolid> occt_revolve(rust::Slice<const OcctCurve> curves, bool close_on_axis) {
  return guarded("revolving a profile", [&] {
    if (curves.empty()) throw std::invalid_argument("a profile needs at least one piece");
    BRepBuilderAPI_MakeWire wire;
    for (std::size_t i = 0; i < curves.size(); ++i) {
      BRepBuilderAPI_MakeEdge edge(make_curve(curves[i], i));
      if (!edge.IsDone()) {
        throw std::runtime_error("piece " + std::to_string(i) + ": BRepBuilderAPI_MakeEdge failed");
      }
      wire.Add(edge.Edge());
      if (!wire.IsDone()) {
        throw std::runtime_error("piece " + std::to_string(i) +
                                 " does not join the previous piece (BRepBuilderAPI_MakeWire)");
      }
    }
    if (close_on_axis) {
      const OcctCurve& first = curves[0];
      const OcctCurve& last = curves[curves.size() - 1];
      const std::size_t m = last.points.size();
      const gp_Pnt top(0.0, 0.0, last.points[m - 1]);
      const gp_Pnt bottom(0.0, 0.0, first.points[1]);
      BRepBuilderAPI_MakeEdge axis(top, bottom);
      if (!axis.IsDone()) {
        throw std::runtime_error("the axis segment closing the profile is degenerate");
      }
      wire.Add(axis.Edge());
      if (!wire.IsDone()) {
        throw std::runtime_error("the axis segment does not join the profile's ends");
      }
    }
    if (!wire.Wire().Closed()) {
      throw std::runtime_error("the profile's wire is not closed");
    }
    BRepBuilderAPI_MakeFace face(wire.Wire(), /*OnlyPlane=*/Standard_True);
    if (!face.IsDone()) {
      throw std::runtime_error("the profile does not bound a planar face (BRepBuilderAPI_MakeFace)");
    }
    BRepPrimAPI_MakeRevol revol(face.Face(), gp_Ax1(gp_Pnt(0, 0, 0), gp_Dir(0, 0, 1)),
                                2.0 * M_PI, /*Copy=*/Standard_False);
    revol.Build();
    if (!revol.IsDone()) throw std::runtime_error("BRepPrimAPI_MakeRevol failed");
    return wrap(validated_solid(revol.Shape(), "revolved profile"));
  });
}

std::unique_ptr<OcctSolid> occt_torus(double major, double minor, double centre_z) {
  return guarded("making a torus", [&] {
    if (!(std::isfinite(major) && std::isfinite(minor) && std::isfinite(centre_z) &&
          minor > 0.0 && major > minor)) {
      throw std::invalid_argument("a solid torus needs finite radii with major > minor > 0");
    }
    BRepPrimAPI_MakeTorus torus(gp_Ax2(gp_Pnt(0, 0, centre_z), gp_Dir(0, 0, 1)), major, minor);
    torus.Build();
    if (!torus.IsDone()) throw std::runtime_error("BRepPrimAPI_MakeTorus failed");
    return wrap(validated_solid(torus.Shape(), "torus"));
  });
}

OcctDistanceOut occt_distance(const OcctSolid& a, const OcctSolid& b,
                              rust::Slice<const double> pose_b, double deflection,
                              bool cached_classifiers) {
  detail::check_pose(pose_b, "occt_distance pose_b", /*rigid=*/true);
  if (!(std::isfinite(deflection) && deflection > 0.0)) {
    throw std::invalid_argument("occt_distance: deflection must be finite and positive");
  }
  return guarded("BRepExtrema_DistShapeShape", [&] {
    gp_Trsf trsf;
    trsf.SetValues(pose_b[0], pose_b[1], pose_b[2], pose_b[3], pose_b[4], pose_b[5], pose_b[6],
                   pose_b[7], pose_b[8], pose_b[9], pose_b[10], pose_b[11]);
    OcctDistanceOut out{};
    const double cpu0 = thread_cpu_seconds();
    if (cached_classifiers) {
      gp_Pnt p;
      if (inner_vertex(*a.impl, *b.impl, trsf, p)) {
        out.cpu_seconds = thread_cpu_seconds() - cpu0;
        out.distance = 0.0;
        out.inner = true;
        out.solutions = 1;
        out.point_a = {p.X(), p.Y(), p.Z()};
        out.point_b = out.point_a;
        return out;
      }
    }
    const TopoDS_Shape sa = cached_classifiers ? boundary(a.impl->shape) : a.impl->shape;
    const TopoDS_Shape sb = cached_classifiers ? boundary(b.impl->shape) : b.impl->shape;
    const TopoDS_Shape placed = sb.Located(TopLoc_Location(trsf));
    BRepExtrema_DistShapeShape dist(sa, placed, deflection, Extrema_ExtFlag_MIN);
    const double cpu1 = thread_cpu_seconds();
    if (!dist.IsDone() || dist.NbSolution() < 1) {
      throw std::runtime_error("no solution (IsDone() is false)");
    }
    out.distance = dist.Value();
    out.inner = dist.InnerSolution();
    out.solutions = static_cast<std::uint32_t>(dist.NbSolution());
    out.cpu_seconds = cpu1 - cpu0;
    const gp_Pnt pa = dist.PointOnShape1(1);
    const gp_Pnt pb = dist.PointOnShape2(1);
    out.point_a = {pa.X(), pa.Y(), pa.Z()};
    out.point_b = {pb.X(), pb.Y(), pb.Z()};
    return out;
  });
}

rust::Vec<std::uint32_t> occt_topology(const OcctSolid& s) {
  rust::Vec<std::uint32_t> out;
  for (TopAbs_ShapeEnum kind : {TopAbs_FACE, TopAbs_EDGE, TopAbs_VERTEX}) {
    TopTools_IndexedMapOfShape map;
    TopExp::MapShapes(s.impl->shape, kind, map);
    out.push_back(static_cast<std::uint32_t>(map.Extent()));
  }
  return out;
}

double occt_thread_cpu_seconds() { return thread_cpu_seconds(); }

rust::String occt_version() { return rust::String(OCC_VERSION_COMPLETE); }

}  // namespace revdist_shim
