#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <initializer_list>
#include <set>
#include <string>
#include <vector>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/domain_triangulation.hpp"

using mfree::Domain;
using mfree::Index;
using mfree::Triangulation;
using mfree::Vec2;

namespace {

Domain mesh(const std::string& name) {
  return Domain::from_file(mfree::testing::source_dir() + "/meshes/" + name);
}

/// Points built one by one: GCC 12 at -O2 with -march=native on AVX-512 processors copies
/// the elements of a std::vector<Vec2> initializer list wrongly.
std::vector<Vec2> points_of(std::initializer_list<std::array<double, 2>> xy) {
  std::vector<Vec2> points;
  for (const auto& p : xy) points.emplace_back(p[0], p[1]);
  return points;
}

double signed_area(const Vec2& a, const Vec2& b, const Vec2& c) {
  return 0.5 * ((b - a).x() * (c - a).y() - (b - a).y() * (c - a).x());
}

/// Distance from x to the nearest boundary segment.
double distance_to_boundary(const Domain& domain, const Vec2& x) {
  double nearest = INFINITY;
  for (const mfree::BoundarySegment& s : domain.boundary()) {
    const Vec2 d = s.b - s.a;
    const double t = std::clamp((x - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
    nearest = std::min(nearest, (s.a + t * d - x).norm());
  }
  return nearest;
}

/// A lattice of spacing h with its points on cracks split into face copies.
std::vector<Vec2> split_lattice(const Domain& domain, double h) {
  mfree::CloudSettings settings;
  settings.kind = mfree::CloudKind::lattice;
  settings.spacing = h;
  return mfree::split_on_cracks(domain, mfree::make_cloud(domain, settings), h);
}

/// Checks a triangulation of `domain` through `points` and returns how many of the given
/// points are vertices of some triangle.
std::size_t check_triangulation(const Domain& domain, const std::vector<Vec2>& points,
                                const Triangulation& tri) {
  REQUIRE(tri.input_points == static_cast<Index>(points.size()));
  REQUIRE(tri.points.size() >= points.size());
  // Given points keep their place; those a round-off outside move just into the domain.
  const double tolerance = 1e-9 * domain.bounding_box().size().norm();
  std::size_t moved_too_far = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    if (domain.contains(points[i])) {
      REQUIRE(tri.points[i] == points[i]);
    } else if (!domain.contains(tri.points[i]) || (tri.points[i] - points[i]).norm() > tolerance) {
      ++moved_too_far;
    }
  }
  CHECK(moved_too_far == 0);

  double area = 0.0;
  std::size_t non_ccw = 0, outside = 0, bad_index = 0;
  std::set<Index> used;
  for (const auto& t : tri.triangles) {
    bool in_range = true;
    for (const Index v : t) {
      in_range = in_range && v >= 0 && v < static_cast<Index>(tri.points.size());
      used.insert(v);
    }
    if (!in_range) {
      ++bad_index;
      continue;
    }
    const Vec2& a = tri.points[static_cast<std::size_t>(t[0])];
    const Vec2& b = tri.points[static_cast<std::size_t>(t[1])];
    const Vec2& c = tri.points[static_cast<std::size_t>(t[2])];
    const double s = signed_area(a, b, c);
    if (!(s > 0.0)) ++non_ccw;
    // A sliver along the boundary may have its rounded centroid an ulp outside.
    const Vec2 centroid = (a + b + c) / 3.0;
    if (!domain.contains(centroid) && distance_to_boundary(domain, centroid) > 1e-14) ++outside;
    area += s;
  }
  CHECK(bad_index == 0);
  CHECK(non_ccw == 0);
  CHECK(outside == 0);
  CHECK(area == Approx(domain.area()).epsilon(1e-12));
  // Every boundary vertex is a vertex of the triangulation.
  for (const auto& ring : domain.rings()) {
    for (const Vec2& x : ring) {
      bool found = false;
      for (const Index v : used) found = found || tri.points[static_cast<std::size_t>(v)] == x;
      CHECK(found);
    }
  }
  std::size_t given_used = 0;
  for (const Index v : used) given_used += v < tri.input_points ? 1 : 0;
  return given_used;
}

}  // namespace

TEST_CASE("domain triangulation: covers the three meshes exactly, counter-clockwise",
          "[geometry]") {
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt", "plate_with_hole.wkt"}) {
    const Domain domain = mesh(name);
    for (const auto kind : {mfree::CloudKind::random, mfree::CloudKind::lattice}) {
      for (const double h : {0.1, 0.037}) {
        INFO(name << ", " << mfree::to_string(kind) << " cloud, h = " << h);
        mfree::CloudSettings settings;
        settings.kind = kind;
        settings.spacing = h;
        settings.seed = 11;
        const std::vector<Vec2> points = mfree::make_cloud(domain, settings);
        const Triangulation tri = mfree::triangulate_domain(domain, points);
        // Every given point is a vertex of the plot (clouds have no repeated points).
        CHECK(check_triangulation(domain, points, tri) == points.size());
      }
    }
  }
}

TEST_CASE("domain triangulation: the L-shape's notch and the plate's hole stay empty",
          "[geometry]") {
  // Without points inside, the triangles are those of the boundary polygon alone.
  const Domain l_shape = mesh("l_shape.wkt");
  const Triangulation bare = mfree::triangulate_domain(l_shape, {});
  CHECK(bare.input_points == 0);
  CHECK(bare.points.size() == 6);   // the six corners, appended in ring order
  CHECK(bare.triangles.size() == 4);  // a hexagon: 6 - 2 triangles
  check_triangulation(l_shape, {}, bare);

  // Points on the boundary, at a corner and in the middle of edges, are used as they are.
  const std::vector<Vec2> on_boundary = points_of({{-1, -1}, {0, 0.5}, {0.5, 0}, {-0.5, -0.5}});
  const Triangulation tri = mfree::triangulate_domain(l_shape, on_boundary);
  CHECK(tri.points.size() == 4 + 5);  // (-1, -1) is given, the other five corners appended
  CHECK(check_triangulation(l_shape, on_boundary, tri) == 4);

  const Domain plate = mesh("plate_with_hole.wkt");
  const std::vector<Vec2> corner = points_of({{1.5, 1.5}});
  const Triangulation ring_only = mfree::triangulate_domain(plate, corner);
  CHECK(ring_only.points.size() == 1 + 4 + 64);
  check_triangulation(plate, corner, ring_only);
}

TEST_CASE("domain triangulation: points a round-off outside the boundary move into it",
          "[geometry]") {
  const Domain l_shape = mesh("l_shape.wkt");
  // 1e-15 right of the re-entrant edge x = 0 (0 < y < 1), 1e-15 below the edge y = -1,
  // 1e-15 beyond the corner (1, 0) diagonally, and one inside.
  const std::vector<Vec2> points =
      points_of({{1e-15, 0.5}, {0.3, -1 - 1e-15}, {1 + 1e-15, 1e-15}, {-0.5, 0.5}});
  for (std::size_t i = 0; i < 3; ++i) REQUIRE_FALSE(l_shape.contains(points[i]));
  const Triangulation tri = mfree::triangulate_domain(l_shape, points);
  CHECK(tri.points[0] == Vec2(0, 0.5));
  CHECK(tri.points[1].y() == -1.0);
  CHECK(tri.points[1].x() == Approx(0.3).epsilon(1e-15));
  CHECK(tri.points[2] == Vec2(1, 0));
  CHECK(tri.points[3] == points[3]);
  // (1, 0) is now given, so only the five other corners are appended.
  CHECK(tri.points.size() == 4 + 5);
  CHECK(check_triangulation(l_shape, points, tri) == 4);

  // On a slanted edge the nearest boundary point rounds off the line; it is stepped inside.
  const Domain triangle = Domain::from_wkt("POLYGON((0 0, 1 0, 0.3 0.7, 0 0))");
  // Points of the slanted edge (not exactly representable), pushed out along its normal.
  const Vec2 normal = Vec2(0.7, 0.7).normalized();
  std::vector<Vec2> near;
  near.push_back(Vec2(0.65, 0.35) + 1e-14 * normal);
  near.push_back(Vec2(0.825, 0.175) + 3e-13 * normal);
  near.emplace_back(0.3, 0.1);
  REQUIRE_FALSE(triangle.contains(near[0]));
  REQUIRE_FALSE(triangle.contains(near[1]));
  const Triangulation slanted = mfree::triangulate_domain(triangle, near);
  CHECK(check_triangulation(triangle, near, slanted) == 3);
}

TEST_CASE("domain triangulation: points outside the domain are input errors naming them",
          "[geometry]") {
  const Domain plate = mesh("plate_with_hole.wkt");
  const auto message = [&](std::initializer_list<std::array<double, 2>> xy) {
    return mfree::testing::message_of<mfree::InputError>([&] { mfree::triangulate_domain(plate, points_of(xy)); });
  };
  CHECK_THAT(message({{1, 1}, {0, 0}}),
             Catch::Contains("point 1 at (0, 0) lies outside the domain"));
  CHECK_THAT(message({{1, 1}, {1, 1.5}, {3, 0}}), Catch::Contains("point 2"));
  CHECK_THAT(message({{1, 1}, {NAN, 0}}), Catch::Contains("point 1 is not finite"));
}

TEST_CASE("domain triangulation: a crack from a notch's root, its nodes split, is covered exactly",
          "[geometry][crack]") {
  // The crack's vertices were inserted with a hint face taken before the boundary constraints,
  // which may have removed it (a crash at h = 0.0125, found running this notched plate).
  const Domain domain = Domain::from_wkt(
      "GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1.2, 0 1.2, 0 0.64, 0.4 0.6, 0 0.56, 0 0)),"
      " LINESTRING(0.4 0.6, 0.9 0.62))");
  for (const double h : {0.025, 0.0125}) {
    INFO("h = " << h);
    const std::vector<Vec2> points = split_lattice(domain, h);
    const Triangulation tri = mfree::triangulate_domain(domain, points);
    CHECK(check_triangulation(domain, points, tri) == points.size());
  }
}

TEST_CASE(
    "domain triangulation: round an inclusion each region's triangles hold copies of the interface's "
    "vertices",
    "[geometry][regions]") {
  // The interface's vertices lie on both regions: sampled there, the functions of both faces
  // meet (a ring of von Mises 0.83 where the exact field has 0.30 round a stiff inclusion).
  // Each face's triangles take a copy moved into their region.
  const Domain domain = Domain::from_wkt(
      "MULTIPOLYGON(((0 0, 2 0, 2 1.25, 0 1.25), (0.45 0.3, 0.32 0.62, 0.6 0.92, 1.35 0.95, 1.6 0.6, 1.3 "
      "0.32)),"
      " ((0.45 0.3, 1.3 0.32, 1.6 0.6, 1.35 0.95, 0.6 0.92, 0.32 0.62)))");
  const double h = 0.125;
  const std::vector<Vec2> points = split_lattice(domain, h);
  const Triangulation tri = mfree::triangulate_domain(domain, points);
  CHECK(check_triangulation(domain, points, tri) == points.size());
  CHECK(tri.points.size() == points.size() + 2 * 6);  // each interface vertex twice (the corners are nodes)
  REQUIRE(tri.samples.size() == tri.points.size());
  std::size_t mixed = 0, moved = 0;
  for (const auto& t : tri.triangles) {
    const Vec2 centroid = (tri.points[t[0]] + tri.points[t[1]] + tri.points[t[2]]) / 3.0;
    for (const Index v : t) mixed += domain.region_at(tri.samples[v]) != domain.region_at(centroid);
  }
  for (std::size_t i = 0; i < tri.points.size(); ++i) moved += tri.samples[i] != tri.points[i];
  CHECK(mixed == 0);
  CHECK(moved == 12);
}
