// Support paths on the L of meshes/l_shape.wkt (the square [-1, 1]^2 without the quadrant
// x > 0, y > 0; its re-entrant corner at the origin, faces y = 0 and x = 0 for 0 <= s <= 1).
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <limits>
#include <numbers>
#include <string>

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
  // A point a thousandth above the face is outside: no path in the domain reaches it (the
  // corner (0, 0) is reached from the domain's side of its edges only).
  const Vec2 across(0.075, 1e-3);
  CHECK(path_distance(SupportRule::visibility, node, across) == std::numeric_limits<double>::infinity());
  CHECK(path_distance(SupportRule::geodesic, node, across) == std::numeric_limits<double>::infinity());
  // Inside, beyond the corner's other face x = 0, the path bends at the corner.
  const Vec2 beyond(-1e-3, 0.075);
  CHECK(path_distance(SupportRule::geodesic, node, beyond) == Approx(node.norm() + beyond.norm()).epsilon(1e-14));
  CHECK(path_distance(SupportRule::plain, node, across) == Approx((across - node).norm()).epsilon(1e-14));
}

namespace {

/// The unit square with a crack from (0.2, 0.5) to its tip (0.5, 0.5), and a slot 0.04 wide
/// and 0.7 deep from the top at x = 0.8.
const Domain& cracked_square() {
  static const Domain d = Domain::from_wkt(
      "GEOMETRYCOLLECTION(POLYGON((0 0, 1 0, 1 1, 0.82 1, 0.82 0.3, 0.78 0.3, 0.78 1, 0 1, 0 0)),"
      " LINESTRING(0.2 0.5, 0.5 0.5))");
  return d;
}

double distance_in(const Domain& domain, SupportRule rule, double reach, const Vec2& xi, const Vec2& x,
                   Vec2& g) {
  const SupportPaths paths(support_obstacles(domain, reach), rule, reach);
  PathScratch s;
  if (!paths.prepare(x, s)) {
    g = (x - xi).normalized();
    return (x - xi).norm();
  }
  return paths.distance(xi, x, s, g);
}

}  // namespace

TEST_CASE("support paths: around a crack tip the geodesic distance is continuous, visibility jumps to a cut",
          "[kernels][crack]") {
  // A node below the crack, points moving along y = 0.6 from behind the tip to ahead of it:
  // the straight line to the node crosses the crack until x passes the shadow line.
  const Vec2 node(0.4, 0.45);
  double largest_step = 0.0, previous = -1.0;
  bool visibility_cut = false, visibility_seen = false;
  for (int k = 0; k <= 400; ++k) {
    const Vec2 x(0.3 + 0.4 * k / 400.0, 0.6);
    Vec2 g;
    const double d = distance_in(cracked_square(), SupportRule::geodesic, 0.5, node, x, g);
    REQUIRE(std::isfinite(d));
    CHECK(d >= (x - node).norm() - 1e-15);
    if (previous >= 0.0) largest_step = std::max(largest_step, std::abs(d - previous));
    previous = d;
    const double v = distance_in(cracked_square(), SupportRule::visibility, 0.5, node, x, g);
    visibility_cut |= std::isinf(v);
    visibility_seen |= std::isfinite(v);
  }
  // Steps of 0.001 along the line move a continuous distance by at most 0.001.
  CHECK(largest_step <= 1.0001e-3);
  CHECK(visibility_cut);
  CHECK(visibility_seen);
  // Behind the tip the path bends at it: |node - tip| + |tip - x|.
  Vec2 g;
  const Vec2 tip(0.5, 0.5), behind(0.35, 0.55);
  CHECK(distance_in(cracked_square(), SupportRule::geodesic, 0.5, node, behind, g) ==
        Approx((tip - node).norm() + (behind - tip).norm()).epsilon(1e-14));
}

TEST_CASE("support paths: the gradient of the geodesic distance is its finite difference, also past a bend",
          "[kernels][crack]") {
  const Vec2 node(0.4, 0.45);
  for (const Vec2& x : {Vec2(0.35, 0.55), Vec2(0.6, 0.62), Vec2(0.3, 0.7)}) {
    Vec2 g;
    distance_in(cracked_square(), SupportRule::geodesic, 0.5, node, x, g);
    const double e = 1e-7;
    Vec2 fd;
    for (int c = 0; c < 2; ++c) {
      Vec2 p = x, m = x, gp, gm;
      p[c] += e;
      m[c] -= e;
      fd[c] = (distance_in(cracked_square(), SupportRule::geodesic, 0.5, node, p, gp) -
               distance_in(cracked_square(), SupportRule::geodesic, 0.5, node, m, gm)) /
              (2 * e);
    }
    CAPTURE(x.transpose(), g.transpose(), fd.transpose());
    CHECK((g - fd).norm() <= 1e-7);
  }
}

TEST_CASE("support paths: across a slot the path bends twice, and plain supports that reach across are found",
          "[kernels][crack]") {
  // From one wall of the slot to the other: down, round its bottom corners (0.78, 0.3) and
  // (0.82, 0.3), and up.
  const Vec2 left(0.76, 0.4), right(0.84, 0.4);
  Vec2 g;
  const double expected = (Vec2(0.78, 0.3) - left).norm() + 0.04 + (right - Vec2(0.82, 0.3)).norm();
  CHECK(distance_in(cracked_square(), SupportRule::geodesic, 0.5, left, right, g) ==
        Approx(expected).epsilon(1e-14));
  CHECK(std::isinf(distance_in(cracked_square(), SupportRule::visibility, 0.5, left, right, g)));

  const SupportObstacles slot = support_obstacles(cracked_square(), 0.2);
  // Supports of 0.1 on either side of the slot reach across it; supports of 0.1 away from it
  // (and the crack's neighbourhood is not asked about) do not.
  const auto b = find_bridge({Vec2(0.76, 0.5)}, {Vec2(0.84, 0.5)}, slot, 0.1);
  REQUIRE(b);
  CHECK(b->straight == Approx(0.08));
  CHECK(b->in_domain > 0.4);
  CHECK(!find_bridge({Vec2(0.76, 0.5)}, {Vec2(0.7, 0.5)}, slot, 0.1));
  // Around the L's re-entrant corner a path is at most sqrt(2) the straight one: no bridge.
  const SupportObstacles corner = support_obstacles(l_shape(), 0.3);
  CHECK(!find_bridge({Vec2(0.05, -0.01)}, {Vec2(-0.01, 0.05)}, corner, 0.3));
}

TEST_CASE("support paths: a path from a crack tip runs along the face to the crack's kink and bends there",
          "[kernels][crack]") {
  // An edge crack from the mouth (1.2, 0) kinked at (1.3, 0.25) to its tip (1.2, 0.45): from
  // above the tip to just right of the lower segment below the kink, the shortest path goes round
  // the tip, along the upper segment's right face to the kink, and round it. Its leg from the
  // tip lies on the segment's line: the tip is on neither side of it.
  const Domain d = Domain::from_wkt(
      "GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1, 0 1, 0 0)), LINESTRING(1.2 0, 1.3 0.25, 1.2 0.45))");
  const Vec2 node(1.17600645, 0.493429895), x(1.296875, 0.234375), tip(1.2, 0.45), kink(1.3, 0.25);
  REQUIRE(orientation(Vec2(1.2, 0), kink, x) < 0.0);  // right of the lower segment
  Vec2 g;
  for (SupportRule rule : {SupportRule::geodesic}) {
    const double dist = distance_in(d, rule, 0.35, node, x, g);
    // The corner is 1e-3 of the shorter segment off the kink on its reflex face.
    CHECK(dist == Approx((tip - node).norm() + (kink - tip).norm() + (x - kink).norm()).epsilon(1e-3));
  }
  // A point of the left face beside the upper segment is still not reached through the kink.
  const Vec2 left_face = kink + 0.5 * (tip - kink) + 1e-7 * Vec2(-0.2, -0.1).normalized();
  CHECK(distance_in(d, SupportRule::geodesic, 0.35, x, left_face, g) > (x - kink).norm() + (left_face - kink).norm());
}

TEST_CASE("support paths: a path from a slot's corner does not cut across the slot to its far wall",
          "[kernels]") {
  // The slot of cracked_square(): walls x = 0.78 and 0.82 down to y = 0.3. From a node right of
  // the slot to a point on the left wall the path passes under the slot and bends at its left
  // corner (before: straight from the right corner across the slot, 0.1168).
  const Vec2 node(0.86, 0.28), wall(0.78, 0.36), left(0.78, 0.3);
  Vec2 g;
  CHECK(distance_in(cracked_square(), SupportRule::geodesic, 0.3, node, wall, g) ==
        Approx((left - node).norm() + (wall - left).norm()).epsilon(1e-12));
  CHECK(std::isinf(distance_in(cracked_square(), SupportRule::visibility, 0.3, node, wall, g)));
}

TEST_CASE("support paths: from one face of a re-entrant corner to the other the path bends at the corner",
          "[kernels]") {
  // (0, 0.1) on the face x = 0 and (0.15, 0) on the face y = 0 of the L: the straight segment
  // runs outside and touches the boundary at its ends only (the projected scheme's lattice
  // joined such a node to quadrature points it does not reach).
  const Vec2 upper(0.0, 0.1), lower(0.15, 0.0);
  CHECK(std::isinf(path_distance(SupportRule::visibility, upper, lower)));
  CHECK(path_distance(SupportRule::geodesic, upper, lower) == Approx(0.25).epsilon(1e-14));
  CHECK(path_distance(SupportRule::geodesic, lower, upper) == Approx(0.25).epsilon(1e-14));
  // Along a face the segment stays on it.
  CHECK(path_distance(SupportRule::visibility, lower, Vec2(0.05, 0.0)) == Approx(0.1).epsilon(1e-14));
}

TEST_CASE("support paths: a crack from a notch's root cuts the root's wedge; no path passes through the root",
          "[kernels][crack]") {
  // The notch's root (0.4, 0.6) is a reflex vertex and the crack's mouth: a path bending there
  // went from one face to the other (0.1086 between (0.45, 0.63) and (0.45, 0.595)).
  const Domain d = Domain::from_wkt(
      "GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1.2, 0 1.2, 0 0.64, 0.4 0.6, 0 0.56, 0 0)),"
      " LINESTRING(0.4 0.6, 0.9 0.62))");
  const Vec2 above(0.45, 0.63), below(0.45, 0.595);
  Vec2 g;
  CHECK(std::isinf(distance_in(d, SupportRule::geodesic, 0.3, above, below, g)));
  // Without the crack the root is a corner: round it from the notch's upper face to below.
  const Domain notch = Domain::from_wkt("POLYGON((0 0, 2 0, 2 1.2, 0 1.2, 0 0.64, 0.4 0.6, 0 0.56, 0 0))");
  const Vec2 over_notch(0.2, 0.635), root(0.4, 0.6), under(0.45, 0.5);
  CHECK(distance_in(notch, SupportRule::geodesic, 0.4, over_notch, under, g) ==
        Approx((root - over_notch).norm() + (under - root).norm()).epsilon(1e-12));
}

TEST_CASE(
    "support paths: round a hole faceted into 1024 edges the path wraps along the arc, as round a circle",
    "[kernels]") {
  // A square with a hole of radius R = 1 (a 1024-gon on the circle). From x at r = 1.2 on one
  // side to x_I on the other, the shortest path runs along the tangents and the arc between
  // them: 2 sqrt(r^2 - R^2) + R (pi - 2 acos(R / r)); the polygon's chords shorten the arc by
  // about 1.6e-6 of it. Its bends are hundreds of reflex vertices, of which a path from a point
  // may start only at the two its line is tangent to.
  std::string wkt = "POLYGON((-2 -2, 2 -2, 2 2, -2 2, -2 -2), (";
  constexpr int facets = 1024;
  for (int k = 0; k <= facets; ++k) {
    const double t = 2.0 * std::numbers::pi * (k % facets) / facets;
    wkt += fmt::format("{}{:.17g} {:.17g}", k == 0 ? "" : ", ", std::cos(t), std::sin(t));
  }
  wkt += "))";
  const Domain d = Domain::from_wkt(wkt);
  const double r = 1.2, tangent = std::sqrt(r * r - 1.0),
               expected = 2.0 * tangent + std::numbers::pi - 2.0 * std::acos(1.0 / r);
  const Vec2 x(-r, 0.0), xi(r * std::cos(0.3), r * std::sin(0.3));
  Vec2 g;
  const double around = 2.0 * tangent + (std::numbers::pi - 0.3) - 2.0 * std::acos(1.0 / r);
  CHECK(distance_in(d, SupportRule::geodesic, 3.5, xi, x, g) == Approx(around).epsilon(1e-5));
  CHECK(distance_in(d, SupportRule::geodesic, 3.5, Vec2(r, 0.0), x, g) == Approx(expected).epsilon(1e-5));
  // The last leg is the tangent from x: it ends on the circle, at right angles to the radius.
  const Vec2 touch = x - tangent * g;
  CHECK(touch.norm() == Approx(1.0).epsilon(1e-5));
  CHECK(std::abs(touch.dot(g)) <= 1e-3);
  CHECK(std::isinf(distance_in(d, SupportRule::visibility, 3.5, xi, x, g)));
}

TEST_CASE(
    "support paths: a segment through two corners of a square hole is blocked; the path goes round the hole",
    "[kernels]") {
  // The diagonal from (0.3, 0.3) to (0.7, 0.7) passes through the hole's corners (0.4, 0.4) and
  // (0.6, 0.6), reflex vertices where the edges end unmoved: it touched every edge at an end
  // and was seen.
  const Domain d =
      Domain::from_wkt("POLYGON((0 0, 1 0, 1 1, 0 1, 0 0), (0.4 0.4, 0.4 0.6, 0.6 0.6, 0.6 0.4, 0.4 0.4))");
  const Vec2 below(0.3, 0.3), above(0.7, 0.7);
  Vec2 g;
  CHECK(std::isinf(distance_in(d, SupportRule::visibility, 0.8, below, above, g)));
  const double round = 2.0 * std::sqrt(0.1);  // by the corner (0.6, 0.4) or (0.4, 0.6)
  CHECK(distance_in(d, SupportRule::geodesic, 0.8, below, above, g) == Approx(round).epsilon(1e-12));
  CHECK(distance_in(d, SupportRule::geodesic, 0.8, above, below, g) == Approx(round).epsilon(1e-12));
  // From a corner along an edge of the hole is in the domain.
  CHECK(distance_in(d, SupportRule::visibility, 0.8, Vec2(0.4, 0.4), Vec2(0.4, 0.6), g) ==
        Approx(0.2).epsilon(1e-12));
}
