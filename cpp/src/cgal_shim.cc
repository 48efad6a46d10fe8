// CGAL 5.5 shim (see include/cgal_shim.h). Compiled with -frounding-math, as CGAL's own CMake
// configuration does for GCC (the interval filters of Epick/Epeck switch rounding modes).
#include "cgal_shim.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include <CGAL/Exact_predicates_exact_constructions_kernel.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/Gmpzf.h>
#include <CGAL/Polytope_distance_d.h>
#include <CGAL/Polytope_distance_d_traits_3.h>
#include <CGAL/squared_distance_3.h>
#include <gmp.h>

#include "common.h"
#include "verify/src/baselines/cgal_ffi.rs.h"

namespace revdist_shim {
namespace {

using Epick = CGAL::Exact_predicates_inexact_constructions_kernel;
using Epeck = CGAL::Exact_predicates_exact_constructions_kernel;

// Candidate selection of the mesh reference. The Epick pass evaluates squared distances in
// double precision without certification; its error is a small multiple of eps * scale^2
// (scale = largest coordinate magnitude of the posed vertices), about 1e-14 * scale^2 in the
// worst case seen. A pair is kept for the exact pass when its float squared distance (and its
// bounding-box lower bound) is at most best * (1 + kRelSlack) + kAbsSlack * scale^2, which
// leaves a margin of about 100x over that error.
constexpr double kRelSlack = 1e-9;
constexpr double kAbsSlack = 1e-12;

// Owned copy of a GMP rational, converted to the hexadecimal strings shared with Rust.
class Mpq {
 public:
  Mpq() { mpq_init(q_); }
  ~Mpq() { mpq_clear(q_); }
  Mpq(const Mpq&) = delete;
  Mpq& operator=(const Mpq&) = delete;
  mpq_ptr get() { return q_; }
  mpq_srcptr get() const { return q_; }

  ExactRational to_shared() const {
    ExactRational out;
    out.num = rust::String(hex(mpq_numref(q_)));
    out.den = rust::String(hex(mpq_denref(q_)));
    return out;
  }

 private:
  static std::string hex(mpz_srcptr z) {
    std::string s(mpz_sizeinbase(z, 16) + 2, '\0');  // sign + digits + NUL
    mpz_get_str(s.data(), 16, z);
    s.resize(std::char_traits<char>::length(s.c_str()));
    return s;
  }
  mpq_t q_;
};

// The GMP rational behind an exact number type: Epeck's exact field type is
// boost::multiprecision::number<gmp_rational> in this build (CGAL::Gmpq in others).
template <typename Q>
mpq_srcptr mpq_of(const Q& q) {
  if constexpr (std::is_same_v<Q, CGAL::Gmpq>) {
    return q.mpq();
  } else {
    return q.backend().data();
  }
}

template <typename FT>
ExactRational exact_to_shared(const FT& x) {
  Mpq q;
  mpq_set(q.get(), mpq_of(CGAL::exact(x)));
  return q.to_shared();
}

// Gmpzf value man * 2^exp as an exact rational.
void gmpzf_to_mpq(const CGAL::Gmpzf& x, mpq_ptr out) {
  mpz_t num, den;
  mpz_init_set(num, x.man());
  mpz_init_set_ui(den, 1);
  const long e = x.exp();
  if (e >= 0) {
    mpz_mul_2exp(num, num, static_cast<mp_bitcnt_t>(e));
  } else {
    mpz_mul_2exp(den, den, static_cast<mp_bitcnt_t>(-e));
  }
  mpq_set_num(out, num);
  mpq_set_den(out, den);
  mpq_canonicalize(out);
  mpz_clear(num);
  mpz_clear(den);
}

template <typename K>
typename K::Triangle_3 triangle_from(rust::Slice<const double> t) {
  using P = typename K::Point_3;
  return typename K::Triangle_3(P(t[0], t[1], t[2]), P(t[3], t[4], t[5]), P(t[6], t[7], t[8]));
}

// Mesh posed in double precision (Epick pass) with per-triangle bounding boxes.
struct FloatMesh {
  std::vector<Epick::Point_3> points;
  std::vector<Epick::Triangle_3> triangles;
  std::vector<CGAL::Bbox_3> boxes;
  double max_abs = 0.0;
};

FloatMesh pose_float(rust::Slice<const double> v, rust::Slice<const std::uint32_t> t,
                     rust::Slice<const double> pose) {
  FloatMesh m;
  const std::size_t nv = v.size() / 3;
  m.points.reserve(nv);
  for (std::size_t i = 0; i < nv; ++i) {
    double w[3];
    for (int r = 0; r < 3; ++r) {
      w[r] = pose[4 * r] * v[3 * i] + pose[4 * r + 1] * v[3 * i + 1] +
             pose[4 * r + 2] * v[3 * i + 2] + pose[4 * r + 3];
      m.max_abs = std::max(m.max_abs, std::fabs(w[r]));
    }
    m.points.emplace_back(w[0], w[1], w[2]);
  }
  const std::size_t nt = t.size() / 3;
  m.triangles.reserve(nt);
  m.boxes.reserve(nt);
  for (std::size_t i = 0; i < nt; ++i) {
    const auto& a = m.points[t[3 * i]];
    const auto& b = m.points[t[3 * i + 1]];
    const auto& c = m.points[t[3 * i + 2]];
    m.triangles.emplace_back(a, b, c);
    m.boxes.push_back(a.bbox() + b.bbox() + c.bbox());
  }
  return m;
}

// Lower bound of the squared distance between two boxes (rounding is covered by kAbsSlack).
double box_sqd(const CGAL::Bbox_3& a, const CGAL::Bbox_3& b) {
  double s = 0.0;
  for (int k = 0; k < 3; ++k) {
    const double gap = std::max({0.0, a.min(k) - b.max(k), b.min(k) - a.max(k)});
    s += gap * gap;
  }
  return s;
}

// Vertex i of a mesh placed by `pose`, computed exactly (the pose entries and coordinates are
// doubles, hence exact rationals; R need not be exactly orthonormal).
Epeck::Point_3 pose_exact(rust::Slice<const double> v, std::size_t i,
                          rust::Slice<const double> pose) {
  Epeck::FT w[3];
  for (int r = 0; r < 3; ++r) {
    w[r] = Epeck::FT(pose[4 * r]) * v[3 * i] + Epeck::FT(pose[4 * r + 1]) * v[3 * i + 1] +
           Epeck::FT(pose[4 * r + 2]) * v[3 * i + 2] + Epeck::FT(pose[4 * r + 3]);
  }
  return Epeck::Point_3(w[0], w[1], w[2]);
}

Epeck::Triangle_3 triangle_exact(rust::Slice<const double> v, rust::Slice<const std::uint32_t> t,
                                 std::size_t i, rust::Slice<const double> pose) {
  return Epeck::Triangle_3(pose_exact(v, t[3 * i], pose), pose_exact(v, t[3 * i + 1], pose),
                           pose_exact(v, t[3 * i + 2], pose));
}

std::vector<Epick::Point_3> points_from(rust::Slice<const double> xyz, const char* what) {
  const std::size_t n = detail::check_points(xyz, what);
  std::vector<Epick::Point_3> out;
  out.reserve(n);
  for (std::size_t i = 0; i < n; ++i) out.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
  return out;
}

}  // namespace

ExactRational cgal_triangle_sqd(rust::Slice<const double> a, rust::Slice<const double> b) {
  if (a.size() != 9 || b.size() != 9) {
    throw std::invalid_argument("CGAL triangle distance: each triangle needs 9 coordinates");
  }
  detail::check_finite(a, "CGAL triangle A");
  detail::check_finite(b, "CGAL triangle B");
  const auto ta = triangle_from<Epeck>(a);
  const auto tb = triangle_from<Epeck>(b);
  return exact_to_shared(CGAL::squared_distance(ta, tb));
}

CgalMeshOut cgal_mesh_sqd(rust::Slice<const double> vertices_a,
                          rust::Slice<const std::uint32_t> triangles_a,
                          rust::Slice<const double> pose_a, rust::Slice<const double> vertices_b,
                          rust::Slice<const std::uint32_t> triangles_b,
                          rust::Slice<const double> pose_b, std::uint64_t max_pairs,
                          std::uint64_t max_candidates) {
  detail::check_mesh(vertices_a, triangles_a, "CGAL mesh A");
  detail::check_mesh(vertices_b, triangles_b, "CGAL mesh B");
  detail::check_pose(pose_a, "CGAL pose A", false);
  detail::check_pose(pose_b, "CGAL pose B", false);
  const std::size_t na = triangles_a.size() / 3, nb = triangles_b.size() / 3;
  const auto pairs = static_cast<std::uint64_t>(na) * static_cast<std::uint64_t>(nb);
  if (pairs > max_pairs) {
    throw std::invalid_argument("CGAL mesh distance: " + std::to_string(pairs) +
                                " triangle pairs exceed the limit " + std::to_string(max_pairs));
  }
  const FloatMesh fa = pose_float(vertices_a, triangles_a, pose_a);
  const FloatMesh fb = pose_float(vertices_b, triangles_b, pose_b);
  const double scale = std::max({1.0, fa.max_abs, fb.max_abs});
  const double abs_slack = kAbsSlack * scale * scale;
  const auto slack = [&](double s) { return s * (1.0 + kRelSlack) + abs_slack; };

  // Pass 1 (Epick): the float minimum, skipping pairs whose boxes are already too far, and
  // keeping every evaluated pair that is within the slack of the minimum so far (the minimum
  // only decreases, so a pair rejected at any time can never be within the final slack).
  double best = std::numeric_limits<double>::infinity();
  struct Near {
    std::size_t i, j;
    double sqd;
  };
  std::vector<Near> near;
  for (std::size_t i = 0; i < na; ++i) {
    for (std::size_t j = 0; j < nb; ++j) {
      if (box_sqd(fa.boxes[i], fb.boxes[j]) > slack(best)) continue;
      const double s = CGAL::to_double(CGAL::squared_distance(fa.triangles[i], fb.triangles[j]));
      if (s > slack(best)) continue;
      best = std::min(best, s);
      near.push_back({i, j, s});
    }
  }
  // Pass 2: candidates within the slack of the final float minimum.
  const double threshold = slack(best);
  std::vector<std::pair<std::size_t, std::size_t>> candidates;
  for (const Near& n : near) {
    if (n.sqd <= threshold) {
      candidates.emplace_back(n.i, n.j);
      if (candidates.size() > max_candidates) {
        throw std::runtime_error("CGAL mesh distance: more than " +
                                 std::to_string(max_candidates) +
                                 " near-tied candidate pairs; raise the limit");
      }
    }
  }
  if (candidates.empty()) {
    throw std::runtime_error("CGAL mesh distance: no candidate pair (non-finite float pass)");
  }
  // Pass 3 (Epeck): exact squared distances of the candidates, poses applied exactly.
  bool have = false;
  Epeck::FT exact_best;
  std::pair<std::size_t, std::size_t> arg{0, 0};
  for (const auto& [i, j] : candidates) {
    const Epeck::FT s =
        CGAL::squared_distance(triangle_exact(vertices_a, triangles_a, i, pose_a),
                               triangle_exact(vertices_b, triangles_b, j, pose_b));
    if (!have || s < exact_best) {
      exact_best = s;
      arg = {i, j};
      have = true;
    }
  }
  CgalMeshOut out;
  out.sqd = exact_to_shared(exact_best);
  out.triangle_a = static_cast<std::uint32_t>(arg.first);
  out.triangle_b = static_cast<std::uint32_t>(arg.second);
  out.candidates = candidates.size();
  out.float_sqd = best;
  return out;
}

CgalPolytopeOut cgal_polytope_sqd(rust::Slice<const double> p, rust::Slice<const double> q) {
  using Traits = CGAL::Polytope_distance_d_traits_3<Epick, CGAL::Gmpzf, double>;
  using Polytope = CGAL::Polytope_distance_d<Traits>;
  const auto pp = points_from(p, "CGAL polytope P");
  const auto qq = points_from(q, "CGAL polytope Q");
  const Polytope pd(pp.begin(), pp.end(), qq.begin(), qq.end());
  // The squared distance is num / den with Gmpzf num and den; dividing as exact rationals
  // (rather than to_double(num) / to_double(den)) leaves a single rounding, done in Rust.
  Mpq num, den, ratio;
  gmpzf_to_mpq(pd.squared_distance_numerator(), num.get());
  gmpzf_to_mpq(pd.squared_distance_denominator(), den.get());
  if (mpq_sgn(den.get()) == 0) throw std::runtime_error("CGAL polytope distance: zero denominator");
  mpq_div(ratio.get(), num.get(), den.get());
  CgalPolytopeOut out;
  out.sqd = ratio.to_shared();
  // Realizing points: homogeneous coordinates (x, y, z, w) in Gmpzf, rounded to double
  // (approximate witnesses; the distance itself is exact).
  const auto homogeneous = [](auto first, std::array<double, 3>& xyz) {
    double c[4];
    for (int k = 0; k < 4; ++k, ++first) c[k] = CGAL::to_double(*first);
    for (int k = 0; k < 3; ++k) xyz[k] = c[k] / c[3];
  };
  homogeneous(pd.realizing_point_p_coordinates_begin(), out.point_p);
  homogeneous(pd.realizing_point_q_coordinates_begin(), out.point_q);
  return out;
}

}  // namespace revdist_shim
