#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/boundary_selection.hpp"

using namespace mfree;
using mfree::testing::message_of;

TEST_CASE("boundary selection: parts, rings, edges and clipping boxes select the expected lengths", "[geometry]") {
  const Domain r = Domain::rectangle(Vec2(0.0, 0.0), Vec2(2.0, 1.0));
  CHECK(selection_length(r, select_part(r, "left")) == 1.0);
  CHECK(selection_length(r, select_part(r, "bottom")) == 2.0);
  CHECK(selection_length(r, select_ring(r, 0)) == 6.0);
  CHECK(selection_length(r, select_edges(r, 0, {0, 2})) == 4.0);
  // A box over half of the bottom edge selects half of it: the segment is clipped.
  const BoundarySelection<2> half = select_box(r, Box{Vec2(-1.0, -1.0), Vec2(1.0, 0.5)});
  CHECK(selection_length(r, half) == Approx(1.5).epsilon(1e-15));  // bottom x in [0, 1] and left y in [0, 0.5]
  CHECK(selection_length(r, select_box(r, Box{Vec2(0.5, -0.1), Vec2(1.25, 0.1)})) == Approx(0.75).epsilon(1e-15));
  // A box that misses the boundary by 1e-3 selects nothing (scenes refuse that).
  CHECK(select_box(r, Box{Vec2(-0.5, 0.2), Vec2(-0.001, 0.8)}).empty());
  CHECK(select_box(r, Box{Vec2(0.5, 0.2), Vec2(1.5, 0.8)}).empty());  // inside the domain, off the boundary
  CHECK(overlap_length(r, half, select_part(r, "bottom")) == Approx(1.0).epsilon(1e-15));
  CHECK(overlap_length(r, select_part(r, "left"), select_part(r, "right")) == 0.0);

  CHECK_THAT(message_of<InputError>([&] { (void)select_part(r, "inner"); }),
             Catch::Contains("no boundary part 'inner'") && Catch::Contains("bottom, right, top, left"));
  CHECK_THAT(message_of<InputError>([&] { (void)select_ring(r, 1); }), Catch::Contains("no ring 1"));
  CHECK_THAT(message_of<InputError>([&] { (void)select_edges(r, 0, {4}); }), Catch::Contains("no edge 4"));
}

TEST_CASE("boundary selection: edges are numbered as written, whatever the ring's orientation", "[geometry]") {
  // Clockwise outer ring (mfree reverses it) with edges of lengths 3, 1, 3, 1 from vertex 0;
  // a counter-clockwise hole (reversed too) with edges of lengths 1, 0.5, 1, 0.5.
  const Domain d = Domain::from_wkt(
      "POLYGON((0 0, 0 1, 3 1, 3 0, 0 0), (1 0.25, 2 0.25, 2 0.75, 1 0.75, 1 0.25))");
  CHECK(selection_length(d, select_edges(d, 0, {0})) == 1.0);   // (0 0) -> (0 1)
  CHECK(selection_length(d, select_edges(d, 0, {1})) == 3.0);   // (0 1) -> (3 1)
  CHECK(selection_length(d, select_edges(d, 1, {1})) == 0.5);   // (2 0.25) -> (2 0.75)
  CHECK(selection_length(d, select_ring(d, 1)) == 3.0);
  const BoundarySelection<2> e0 = select_edges(d, 0, {0});
  REQUIRE(e0.size() == 1);
  const BoundarySegment& s = d.boundary()[e0[0].segment];
  CHECK(((s.a - Vec2(0, 0)).norm() + (s.b - Vec2(0, 1)).norm() == 0.0 ||
         (s.a - Vec2(0, 1)).norm() + (s.b - Vec2(0, 0)).norm() == 0.0));
  CHECK(s.normal.x() == -1.0);  // outward, whatever the orientation written
}

TEST_CASE("domains from rings carry their named parts through reorientation", "[geometry]") {
  // Clockwise square: edge 0 (0 0)-(0 1) is "wall", edge 2 (1 1)-(1 0) is "load".
  const Domain d = Domain::from_rings({{Vec2(0, 0), Vec2(0, 1), Vec2(1, 1), Vec2(1, 0)}}, {{0, -1, 1, -1}},
                                      {"wall", "load"}, "test");
  const BoundarySelection<2> wall = select_part(d, "wall"), load = select_part(d, "load");
  REQUIRE(wall.size() == 1);
  REQUIRE(load.size() == 1);
  CHECK(d.boundary()[wall[0].segment].normal.x() == -1.0);
  CHECK(d.boundary()[load[0].segment].normal.x() == 1.0);
  CHECK_THAT(message_of<InputError>([] {
               (void)Domain::from_rings({{Vec2(0, 0), Vec2(1, 0), Vec2(0, 1)}}, {{0, 0}}, {"a"}, "test");
             }),
             Catch::Contains("3 edges but 2 edge parts"));
}

TEST_CASE("boundary selection: a box drawn round an edge clips the edges it crosses at the corners",
          "[geometry]") {
  const Domain r = Domain::rectangle(Vec2(0.0, 0.0), Vec2(2.0, 1.0));
  // Round the bottom with a margin: 0.01 of each side at (0, 0) and (2, 0), turning 90 degrees.
  const std::vector<CornerSliver> round =
      corner_slivers(r, select_box(r, Box{Vec2(-0.1, -0.1), Vec2(2.1, 0.01)}));
  REQUIRE(round.size() == 2);
  for (const CornerSliver& s : round) {
    CHECK(s.length == Approx(0.01).epsilon(1e-12));
    CHECK(s.turn == Approx(90.0).epsilon(1e-12));
    CHECK(s.corner.y() == 0.0);
  }
  CHECK(round[0].corner.x() != round[1].corner.x());
  // Flush with the bottom: the sides are touched at a point only.
  CHECK(corner_slivers(r, select_box(r, Box{Vec2(-0.1, -0.1), Vec2(2.1, 0.0)})).empty());
  // Round a corner on purpose: both edges long.
  CHECK(corner_slivers(r, select_box(r, Box{Vec2(1.0, -0.1), Vec2(2.1, 0.6)})).empty());
  // A finely faceted arc turns by 0.35 degrees per piece: no corner, whatever the box cuts.
  Ring arc{Vec2(0.0, 0.0)};
  for (int k = 0; k <= 256; ++k) {
    const double a = 0.5 * std::numbers::pi * k / 256;
    arc.push_back(Vec2(std::cos(a), std::sin(a)));
  }
  const Domain quarter = Domain::from_rings({arc}, {std::vector<int>(arc.size(), -1)}, {}, "quarter disk");
  CHECK(corner_slivers(quarter, select_box(quarter, Box{Vec2(0.3, 0.3), Vec2(1.1, 1.1)})).empty());
}
