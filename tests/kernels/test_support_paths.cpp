// Support paths on the L of meshes/l_shape.wkt (the square [-1, 1]^2 without the quadrant
// x > 0, y > 0; its re-entrant corner at the origin, faces y = 0 and x = 0 for 0 <= s <= 1).
#include <catch2/catch.hpp>
#include <cmath>
#include <limits>

#include "mfree/geometry/support_obstacles.hpp"
#include "mfree/kernels/support_paths.hpp"

using namespace mfree;

namespace {

const Domain& l_shape() {
  static const Domain d = Domain::from_wkt("POLYGON((-1 -1, 1 -1, 1 0, 0 0, 0 1, -1 1, -1 -1))");
  return d;
}

/// d(xi, x) under `rule` with supports of radius 0.3.
double path_distance(SupportRule rule, const Vec2& xi, const Vec2& x) {
  const SupportPaths paths(support_obstacles(l_shape(), 0.3), rule, 0.3);
  PathScratch s;
  Vec2 g;
  return paths.prepare(x, s) ? paths.distance(xi, x, s, g) : (x - xi).norm();
}

}  // namespace

TEST_CASE("support paths: a point on a corner face with round-off in its coordinates is seen from the domain",
          "[kernels]") {
  // The projected scheme's points on the L at node spacing 0.1 put one at (0.075, 2^-54):
  // on the face y = 0 to round-off. Every rule sees it from the node below it (the exact
  // crossing test cut it off from all: 0 neighbours, a singular moment matrix).
  const Vec2 on_face(0.075, std::ldexp(1.0, -54)), node(0.1, -0.1);
  for (SupportRule rule : {SupportRule::plain, SupportRule::visibility, SupportRule::geodesic}) {
    CAPTURE(to_string(rule));
    CHECK(path_distance(rule, node, on_face) == Approx((on_face - node).norm()).epsilon(1e-14));
    CHECK(path_distance(rule, on_face, node) == Approx((on_face - node).norm()).epsilon(1e-14));
  }
  // A point a thousandth above the face is across it: visibility cuts it off, geodesic goes
  // round the corner (0, 0): |(0.1, -0.1)| + |(0.075, 0.001)|.
  const Vec2 across(0.075, 1e-3);
  CHECK(path_distance(SupportRule::visibility, node, across) == std::numeric_limits<double>::infinity());
  CHECK(path_distance(SupportRule::geodesic, node, across) ==
        Approx(node.norm() + across.norm()).epsilon(1e-14));
  CHECK(path_distance(SupportRule::plain, node, across) == Approx((across - node).norm()).epsilon(1e-14));
}
