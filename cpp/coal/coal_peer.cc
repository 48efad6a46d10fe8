// coal_peer: coal 3 (the maintained successor of FCL) as a peer of revdist's benchmarks, in a
// process of its own. coal must never share a process with Debian's FCL 0.7 (the two load
// different octomap versions and abort with a double free), so experiments' `peers` binary
// spawns this program instead of linking coal. Built by experiments/build.rs against the libcoal
// wheel that scripts/deps.sh installs under .peers/coal/cmeel.prefix.
//
// Protocol: whitespace-separated tokens on stdin, one reply line per command on stdout.
//   version                         -> "version <COAL_VERSION> <gjk_tolerance>"
//   mesh <id> <nv> <nt> x y z ... i j k ...
//                                   -> "shape <id> <build_ms> <bytes>"   (BVHModel<OBBRSS>)
//   sphere <id> <r> <zc>            -> "shape <id> 0 <bytes>"
//   capsule|cylinder|cone <id> <r> <lz> <zc>
//                                   -> "shape <id> 0 <bytes>"  (axis z, centred at z = zc)
//   query <id_a> <id_b> <n> then n poses "qw qx qy qz tx ty tz" of B (A at the identity)
//                                   -> n lines "d <distance> <ns>", then "end"
//   signed <id_a> <id_b> <n> then n poses, as query
//                                   -> n lines "d <signed distance> <ns> <nx> <ny> <nz>" (coal's
//                                      normal, world frame, from A to B: B moved by
//                                      -distance along it touches A), then "end"
//   quit
// Each query is timed on its own (steady_clock) in a loop over the n poses: the blocked mode of
// experiments' benchmarks. `query` distances are unsigned (enable_signed_distance = false), as
// FCL's; `signed` ones are coal's signed distance with its default request (the penetration
// depth of overlapping convex shapes by EPA, negated; GJK and EPA at their default tolerances
// and iteration limits), as the penetration experiment compares.
// A malformed command prints "error: ..." on stderr and exits with status 2.

#include <coal/BVH/BVH_model.h>
#include <coal/collision_object.h>
#include <coal/config.hh>
#include <coal/distance.h>
#include <coal/narrowphase/narrowphase_defaults.h>
#include <coal/shape/geometric_shapes.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace {

struct Shape {
  std::shared_ptr<coal::CollisionGeometry> geometry;
  // Offset of the primitive's centre along the solid's axis (0 for meshes).
  double zc = 0.0;
};

[[noreturn]] void fail(const std::string& what) {
  std::cerr << "error: coal_peer: " << what << std::endl;
  std::exit(2);
}

template <typename T>
T read(const char* what) {
  T v;
  if (!(std::cin >> v)) fail(std::string("expected ") + what);
  return v;
}

double positive(const char* what) {
  double v = read<double>(what);
  if (!(v > 0.0)) fail(std::string(what) + " must be positive");
  return v;
}

coal::Transform3s offset(double zc) {
  coal::Transform3s t;
  t.setIdentity();
  t.setTranslation(coal::Vec3s(0.0, 0.0, zc));
  return t;
}

}  // namespace

int main() {
  std::ios::sync_with_stdio(false);
  std::map<std::string, Shape> shapes;
  coal::DistanceRequest request(false, false);  // no nearest points needed, unsigned
  request.enable_signed_distance = false;
  coal::DistanceRequest signed_request;  // coal's defaults: signed, EPA in collision
  signed_request.enable_signed_distance = true;
  std::string cmd;
  while (std::cin >> cmd) {
    if (cmd == "quit") break;
    if (cmd == "version") {
      std::printf("version %s %.17g\n", COAL_VERSION, request.gjk_tolerance);
    } else if (cmd == "mesh") {
      auto id = read<std::string>("mesh id");
      auto nv = read<long>("vertex count");
      auto nt = read<long>("triangle count");
      if (nv < 3 || nt < 1) fail("mesh " + id + " needs 3 vertices and 1 triangle");
      std::vector<coal::Vec3s> vs(nv);
      for (auto& v : vs)
        for (int k = 0; k < 3; ++k) v[k] = read<double>("vertex coordinate");
      std::vector<coal::Triangle> ts(nt);
      for (auto& t : ts) {
        long i[3];
        for (auto& x : i) {
          x = read<long>("vertex index");
          if (x < 0 || x >= nv) fail("mesh " + id + ": vertex index out of range");
        }
        t.set(i[0], i[1], i[2]);
      }
      auto start = std::chrono::steady_clock::now();
      auto m = std::make_shared<coal::BVHModel<coal::OBBRSS>>();
      m->beginModel(static_cast<unsigned>(nt), static_cast<unsigned>(nv));
      m->addSubModel(vs, ts);
      m->endModel();
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
      int bytes = m->memUsage(false);
      shapes[id] = Shape{m, 0.0};
      std::printf("shape %s %.6f %d\n", id.c_str(), ms, bytes);
    } else if (cmd == "sphere" || cmd == "capsule" || cmd == "cylinder" || cmd == "cone") {
      auto id = read<std::string>("shape id");
      double r = positive("radius");
      std::shared_ptr<coal::CollisionGeometry> g;
      std::size_t bytes = 0;
      if (cmd == "sphere") {
        g = std::make_shared<coal::Sphere>(r);
        bytes = sizeof(coal::Sphere);
      } else {
        double lz = positive("length");
        if (cmd == "capsule") {
          g = std::make_shared<coal::Capsule>(r, lz);
          bytes = sizeof(coal::Capsule);
        } else if (cmd == "cylinder") {
          g = std::make_shared<coal::Cylinder>(r, lz);
          bytes = sizeof(coal::Cylinder);
        } else {
          g = std::make_shared<coal::Cone>(r, lz);
          bytes = sizeof(coal::Cone);
        }
      }
      double zc = read<double>("centre z");
      g->computeLocalAABB();
      shapes[id] = Shape{g, zc};
      std::printf("shape %s 0 %zu\n", id.c_str(), bytes);
    } else if (cmd == "query" || cmd == "signed") {
      const coal::DistanceRequest& req = cmd == "query" ? request : signed_request;
      auto ia = read<std::string>("shape id");
      auto ib = read<std::string>("shape id");
      auto n = read<long>("pose count");
      auto a = shapes.find(ia), b = shapes.find(ib);
      if (a == shapes.end()) fail("unknown shape " + ia);
      if (b == shapes.end()) fail("unknown shape " + ib);
      if (n < 0) fail("negative pose count");
      std::vector<coal::Transform3s> poses(n);
      for (auto& p : poses) {
        double q[4], t[3];
        for (auto& x : q) x = read<double>("quaternion component");
        for (auto& x : t) x = read<double>("translation component");
        coal::Quatf quat(q[0], q[1], q[2], q[3]);
        if (!(std::abs(quat.norm() - 1.0) < 1e-9)) fail("pose quaternion is not a unit quaternion");
        p = coal::Transform3s(quat, coal::Vec3s(t[0], t[1], t[2])) * offset(b->second.zc);
      }
      const coal::Transform3s ta = offset(a->second.zc);
      coal::ComputeDistance functor(a->second.geometry.get(), b->second.geometry.get());
      std::vector<double> d(n), ns(n);
      std::vector<coal::Vec3s> normal(n);
      for (long k = 0; k < n; ++k) {
        coal::DistanceResult result;
        auto start = std::chrono::steady_clock::now();
        functor(ta, poses[k], req, result);
        auto stop = std::chrono::steady_clock::now();
        d[k] = result.min_distance;
        normal[k] = result.normal;
        ns[k] = std::chrono::duration<double, std::nano>(stop - start).count();
      }
      for (long k = 0; k < n; ++k) {
        if (cmd == "query") {
          std::printf("d %.17g %.1f\n", d[k], ns[k]);
        } else {
          std::printf("d %.17g %.1f %.17g %.17g %.17g\n", d[k], ns[k], normal[k][0], normal[k][1],
                      normal[k][2]);
        }
      }
      std::printf("end\n");
    } else {
      fail("unknown command '" + cmd + "'");
    }
    std::fflush(stdout);
  }
  return 0;
}
