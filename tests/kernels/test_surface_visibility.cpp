// Supports that respect a solid: the visibility test against obstacle triangles, the
// obstacles a solid's surface makes, the gaps plain supports would bridge, and RK functions
// that do not reach across a gap. Solids: the two blocks of
// verification/slotted-block/two_blocks.geo (a gap 0.03 wide between y = 0.5 and y = 0.53),
// meshes/notched_block.step (a re-entrant edge and a hole), a box.
#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/geometry/gmsh_solid.hpp"
#include "mfree/geometry/support_obstacles.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/kernels/surface_visibility.hpp"

using namespace mfree;

namespace {

const Solid& two_blocks() {
  static const Solid s =
      read_gmsh_solid(testing::source_dir() + "/verification/slotted-block/two_blocks.geo");
  return s;
}

/// One obstacle: the unit square in the plane z = 0, normal +z.
SurfaceObstacles square() {
  SurfaceObstacles o;
  o.triangles = {{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(1, 1, 0)},
                 {Vec3(0, 0, 0), Vec3(1, 1, 0), Vec3(0, 1, 0)}};
  o.normals = {Vec3::UnitZ(), Vec3::UnitZ()};
  return o;
}

bool sees(const SurfaceVisibility& v, const Vec3& p, const Vec3& x) {
  VisibilityScratch s;
  return !v.prepare(x, s) || v.visible(p, 0.0, x, s);
}

}  // namespace

TEST_CASE("surface visibility: a segment crossing a triangle is blocked, touching or along it is not",
          "[kernels][support]") {
  const SurfaceVisibility v(square(), 1.0);
  CHECK_FALSE(sees(v, Vec3(0.3, 0.6, -0.2), Vec3(0.4, 0.5, 0.3)));  // through the face
  CHECK_FALSE(sees(v, Vec3(0.5, 0.5, -0.2), Vec3(0.5, 0.5, 0.2)));  // through the shared edge
  CHECK_FALSE(sees(v, Vec3(1.0, 1.0, -0.2), Vec3(1.0, 1.0, 0.2)));  // through a vertex
  CHECK(sees(v, Vec3(0.5, 0.5, -0.3), Vec3(0.5, 0.5, 0.0)));        // ends on it from the inside
  CHECK_FALSE(sees(v, Vec3(0.5, 0.5, 0.3), Vec3(0.5, 0.5, 0.0)));   // from the outside
  CHECK_FALSE(sees(v, Vec3(0.5, 0.5, 0.0), Vec3(0.4, 0.4, 0.2)));   // starts on it, runs outside
  CHECK(sees(v, Vec3(0.2, 0.5, 0.0), Vec3(0.7, 0.3, 0.0)));         // in its plane
  CHECK(sees(v, Vec3(1.2, 0.5, -0.2), Vec3(1.2, 0.5, 0.2)));        // beside it
  CHECK(sees(v, Vec3(0.5, 0.5, 0.1), Vec3(0.6, 0.4, 0.4)));         // on one side
  // A segment shorter than the clearances of its ends is visible without a test.
  VisibilityScratch s;
  REQUIRE(v.prepare(Vec3(0.5, 0.5, 0.4), s));
  CHECK(s.clearance == Approx(0.4).epsilon(1e-14));
  CHECK(v.clearance(Vec3(2.0, 0.5, 0.0)) == Approx(1.0));  // capped at the reach
}

TEST_CASE(
    "surface obstacles: the walls of a gap and the faces of a re-entrant edge and a hole, no convex face",
    "[kernels][support]") {
  CHECK(support_obstacles(Solid::box(Vec3::Zero(), Vec3::Ones()), 0.5).empty());
  const SurfaceObstacles o = support_obstacles(two_blocks(), 0.2);
  REQUIRE_FALSE(o.empty());
  double area = 0.0;
  for (std::size_t k = 0; k < o.triangles.size(); ++k) {
    const auto& t = o.triangles[k];
    // Every obstacle is a wall of the gap, its normal pointing across it.
    for (const Vec3& v : t) CHECK((std::abs(v.y() - 0.5) < 1e-12 || std::abs(v.y() - 0.53) < 1e-12));
    CHECK(std::abs(o.normals[k].y()) == Approx(1.0));
    area += 0.5 * (t[1] - t[0]).cross(t[2] - t[0]).norm();
  }
  CHECK(area == Approx(2 * 1.0 * 0.5).epsilon(1e-12));  // both walls, whole
  // Farther apart than the reach, the walls do not see each other: no obstacles.
  CHECK(support_obstacles(two_blocks(), 0.02).empty());
  const Solid notched = read_gmsh_solid(testing::source_dir() + "/meshes/notched_block.step");
  const SurfaceObstacles n = support_obstacles(notched, 0.2);
  bool notch = false, hole = false;
  for (const auto& t : n.triangles) {
    const Vec3 c = (t[0] + t[1] + t[2]) / 3.0;
    notch = notch || (std::abs(c.x() - 0.6) < 1e-9 && c.y() > 0.45) ||
            (std::abs(c.y() - 0.45) < 1e-9 && c.x() > 0.6);
    hole = hole || std::abs(std::hypot(c.x() - 0.3, c.y() - 0.4) - 0.15) < 0.01;
    CHECK(c.x() > 1e-9);  // never the face x = 0
  }
  CHECK(notch);
  CHECK(hole);
}

TEST_CASE(
    "surface gaps: the gap between the two blocks and a fork's slot are found with their widths, a notch and "
    "a hole are not gaps",
    "[kernels][support]") {
  const auto g = find_gap(support_obstacles(two_blocks(), 0.2), 0.2);
  REQUIRE(g);
  CHECK(g->width == Approx(0.03).epsilon(1e-10));
  CHECK(std::abs(g->from.y() - g->to.y()) == Approx(0.03).epsilon(1e-10));
  CHECK_FALSE(find_gap(support_obstacles(two_blocks(), 0.025), 0.025));  // supports narrower than the gap
  const Solid fork = read_gmsh_solid(testing::source_dir() + "/verification/slotted-block/fork.geo");
  const auto slot = find_gap(support_obstacles(fork, 0.2), 0.2);
  REQUIRE(slot);
  CHECK(slot->width == Approx(0.04).epsilon(1e-10));
  // The notch's faces meet at 90 degrees; round the hole (diameter 0.3, narrower than these
  // supports) the path is pi / 2 times as long as across it.
  const Solid notched = read_gmsh_solid(testing::source_dir() + "/meshes/notched_block.step");
  CHECK_FALSE(find_gap(support_obstacles(notched, 0.4), 0.4));
}

TEST_CASE(
    "visibility supports in a solid: no node reaches across the gap, linear fields reproduced on each side",
    "[kernels][support]") {
  const Solid& solid = two_blocks();
  const double h = 0.1;
  const std::vector<Vec3> nodes = make_cloud(solid, CloudSettings{CloudKind::lattice, h});
  RKSettings settings;
  settings.radius = 2.0 * h;
  settings.rule = SupportRule::visibility;
  settings.surface_obstacles =
      std::make_shared<const SurfaceObstacles>(support_obstacles(solid, settings.radius));
  const RKShapeFunctions<3> rk(nodes, settings);
  RKSettings plain = settings;
  plain.rule = SupportRule::plain;
  const RKShapeFunctions<3> bridging(nodes, plain);
  ShapeValues<3> v, p;
  int across_plain = 0;
  for (const Vec3& x :
       {Vec3(0.37, 0.49, 0.21), Vec3(0.5, 0.46, 0.25), Vec3(0.81, 0.54, 0.33), Vec3(0.15, 0.56, 0.12)}) {
    rk.evaluate(x, v);
    bridging.evaluate(x, p);
    const bool in_a = x.y() < 0.515;
    double sum = 0.0;
    Vec3 first = Vec3::Zero();
    Eigen::Matrix3d gradient = Eigen::Matrix3d::Zero();
    for (std::size_t k = 0; k < v.size(); ++k) {
      CHECK((nodes[v.nodes[k]].y() < 0.515) == in_a);
      sum += v.phi[k];
      first += v.phi[k] * nodes[v.nodes[k]];
      gradient += nodes[v.nodes[k]] * v.grad[k].transpose();
    }
    CHECK(std::abs(sum - 1.0) < 1e-11);
    CHECK((first - x).norm() < 1e-11);
    CHECK((gradient - Eigen::Matrix3d::Identity()).norm() < 1e-8);
    for (Index i : p.nodes) across_plain += (nodes[i].y() < 0.515) != in_a ? 1 : 0;
  }
  CHECK(across_plain > 0);  // plain supports do reach across
}
