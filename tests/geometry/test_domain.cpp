#include <catch2/catch.hpp>
#include <cmath>
#include <string>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/polygon_integrals.hpp"

using mfree::Box;
using mfree::crack_offset;
using mfree::Domain;
using mfree::Index;
using mfree::Ring;
using mfree::split_on_cracks;
using mfree::Vec2;

namespace {

const double pi = std::acos(-1.0);

std::string mesh_path(const std::string& name) { return mfree::testing::source_dir() + "/meshes/" + name; }

Domain mesh(const std::string& name) { return Domain::from_file(mesh_path(name)); }

// Area of the 64-gon inscribed in the circle of radius 0.5: 64 triangles of area
// r^2 sin(2 pi / 64) / 2.
double hole_area() { return 0.5 * 64 * 0.25 * std::sin(2 * pi / 64); }

// The message of the InputError that f throws.
template <class F>
std::string input_error_message(F&& f) {
  return mfree::testing::message_of<mfree::InputError>(f);
}

// Box edges at uneven positions along [lo, hi]: t_i = (i / n)^1.4 plus a wobble, so that
// no two boxes are alike and some edges pass near (not only through) vertices.
std::vector<double> uneven_breaks(double lo, double hi, int n) {
  std::vector<double> t(n + 1);
  for (int i = 0; i <= n; ++i) {
    const double s = static_cast<double>(i) / n;
    t[i] = lo + (hi - lo) * (std::pow(s, 1.4) + 0.03 * std::sin(pi * s * 3.0));
  }
  t[0] = lo;
  t[n] = hi;
  return t;
}

struct Integrals {
  double area = 0.0;
  Vec2 moment = Vec2::Zero();
};

Integrals integrate(const std::vector<Ring>& rings) {
  Integrals sum;
  for (const Ring& r : rings) {
    sum.area += mfree::ring_area(r);
    sum.moment += mfree::ring_first_moment(r);
  }
  return sum;
}

}  // namespace

TEST_CASE("ring integrals match the exact values of a shifted triangle and square",
          "[geometry]") {
  // Triangle (1,1), (4,1), (1,3): area 3, centroid (2, 5/3).
  const Ring tri{Vec2(1, 1), Vec2(4, 1), Vec2(1, 3)};
  CHECK(mfree::ring_area(tri) == Approx(3.0).epsilon(1e-15));
  CHECK(mfree::ring_first_moment(tri).x() == Approx(6.0).epsilon(1e-15));
  CHECK(mfree::ring_first_moment(tri).y() == Approx(5.0).epsilon(1e-15));
  // Reversing the ring flips the signs.
  const Ring rev{Vec2(1, 3), Vec2(4, 1), Vec2(1, 1)};
  CHECK(mfree::ring_area(rev) == Approx(-3.0).epsilon(1e-15));
  CHECK(mfree::ring_first_moment(rev).x() == Approx(-6.0).epsilon(1e-15));
  // A tiny square far from the origin keeps its accuracy: its corners are exact doubles,
  // and the sums taken about a vertex are exact, while plain shoelace products of size
  // 1e6 would lose about 1e-2 of h^2.
  const double h = 1.0 / 8192;
  const Vec2 c(1e3, -2e3);
  const Ring sq{c, c + Vec2(h, 0), c + Vec2(h, h), c + Vec2(0, h)};
  CHECK(mfree::ring_area(sq) == Approx(h * h).epsilon(1e-15));
  CHECK(mfree::ring_first_moment(sq).x() == Approx((c.x() + h / 2) * h * h).epsilon(1e-15));
  CHECK(mfree::ring_first_moment(sq).y() == Approx((c.y() + h / 2) * h * h).epsilon(1e-15));
}

TEST_CASE("mesh areas and first moments match the exact values", "[geometry]") {
  const Domain rect = mesh("rectangle.wkt");
  CHECK(rect.area() == Approx(2.0).epsilon(1e-15));
  CHECK(std::abs(rect.first_moment().x()) < 1e-15);
  CHECK(std::abs(rect.first_moment().y()) < 1e-15);

  const Domain l = mesh("l_shape.wkt");
  CHECK(l.area() == Approx(3.0).epsilon(1e-15));
  // [-1,1]^2 has zero moment; the removed unit square has moment (0.5, 0.5).
  CHECK(l.first_moment().x() == Approx(-0.5).epsilon(1e-15));
  CHECK(l.first_moment().y() == Approx(-0.5).epsilon(1e-15));

  const Domain plate = mesh("plate_with_hole.wkt");
  CHECK(plate.area() == Approx(16.0 - hole_area()).epsilon(1e-14));
  CHECK(std::abs(plate.first_moment().x()) < 1e-14);
  CHECK(std::abs(plate.first_moment().y()) < 1e-14);

  const Box box = plate.bounding_box();
  CHECK(box.lo == Vec2(-2, -2));
  CHECK(box.hi == Vec2(2, 2));
}

TEST_CASE("rings are normalised: outer CCW, holes CW, no closing vertex", "[geometry]") {
  const Domain l = mesh("l_shape.wkt");
  REQUIRE(l.rings().size() == 1);
  CHECK(l.rings()[0].size() == 6);
  CHECK(mfree::ring_area(l.rings()[0]) > 0.0);

  // The file lists the hole counter-clockwise; the domain turns it clockwise.
  const Domain plate = mesh("plate_with_hole.wkt");
  REQUIRE(plate.rings().size() == 2);
  CHECK(plate.rings()[0].size() == 4);
  CHECK(plate.rings()[1].size() == 64);
  CHECK(mfree::ring_area(plate.rings()[0]) == Approx(16.0));
  CHECK(mfree::ring_area(plate.rings()[1]) == Approx(-hole_area()).epsilon(1e-14));

  // A clockwise outer ring without closing vertex is accepted and reversed.
  const Domain cw = Domain::from_wkt("polygon ((0 0, 0 1, 2 1, 2 0))");
  CHECK(cw.rings()[0].size() == 4);
  CHECK(cw.area() == Approx(2.0).epsilon(1e-15));

  const Domain built = Domain::rectangle(Vec2(-1, -0.5), Vec2(1, 0.5));
  const Domain read = mesh("rectangle.wkt");
  CHECK(built.area() == read.area());
  CHECK(built.boundary().size() == read.boundary().size());

  Domain copy = plate;
  CHECK(copy.area() == plate.area());
  copy = l;
  CHECK(copy.area() == l.area());
  const Domain moved = std::move(copy);
  CHECK(moved.area() == l.area());
}

TEST_CASE("boundary segments satisfy the divergence theorem and point outward", "[geometry]") {
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt", "plate_with_hole.wkt"}) {
    INFO(name);
    const Domain d = mesh(name);
    Vec2 sum_nl = Vec2::Zero();
    double sum_xn = 0.0;
    double perimeter = 0.0;
    for (const mfree::BoundarySegment& s : d.boundary()) {
      CHECK(s.normal.norm() == Approx(1.0).epsilon(1e-15));
      CHECK(s.length == Approx((s.b - s.a).norm()).epsilon(1e-15));
      CHECK(std::abs(s.normal.dot(s.b - s.a)) < 1e-14 * s.length);
      const Vec2 mid = 0.5 * (s.a + s.b);
      const double eps = 1e-6 * s.length;
      CHECK_FALSE(d.contains(mid + eps * s.normal));
      CHECK(d.contains(mid - eps * s.normal));
      sum_nl += s.normal * s.length;
      sum_xn += mid.dot(s.normal) * s.length;
      perimeter += s.length;
    }
    // int_dOmega n ds = 0 and int_dOmega x . n ds = int_Omega div x dA = 2 |Omega|
    // (x . n is linear along a straight edge, so the midpoint rule is exact).
    CHECK(sum_nl.norm() < 1e-14 * perimeter);
    CHECK(sum_xn == Approx(2.0 * d.area()).epsilon(1e-14));
  }
  const Domain plate = mesh("plate_with_hole.wkt");
  int hole_segments = 0;
  for (const mfree::BoundarySegment& s : plate.boundary()) hole_segments += s.ring == 1;
  CHECK(hole_segments == 64);
}

TEST_CASE("contains() on known points, boundary included", "[geometry]") {
  const Domain l = mesh("l_shape.wkt");
  CHECK(l.contains(Vec2(-0.5, 0.5)));
  CHECK(l.contains(Vec2(0.5, -0.5)));
  CHECK_FALSE(l.contains(Vec2(0.5, 0.5)));     // the cut-out quadrant
  CHECK_FALSE(l.contains(Vec2(1e-9, 1e-9)));   // just past the re-entrant corner
  CHECK(l.contains(Vec2(-1e-9, 1e-9)));
  CHECK(l.contains(Vec2(0, 0)));               // the re-entrant corner itself
  CHECK(l.contains(Vec2(0, 0.5)));             // on an edge
  CHECK(l.contains(Vec2(0.5, 0)));
  CHECK(l.contains(Vec2(-1, -1)));
  CHECK_FALSE(l.contains(Vec2(1.0 + 1e-12, -0.5)));
  CHECK_FALSE(l.contains(Vec2(5, 5)));

  const Domain plate = mesh("plate_with_hole.wkt");
  CHECK_FALSE(plate.contains(Vec2(0, 0)));
  CHECK_FALSE(plate.contains(Vec2(0.3, 0.3)));
  CHECK(plate.contains(Vec2(0.5, 0)));          // a vertex of the hole
  CHECK(plate.contains(plate.rings()[1][17]));  // another one
  CHECK(plate.contains(Vec2(0.36, 0.36)));      // outside the 64-gon (0.36 sqrt 2 > 0.5)
  CHECK(plate.contains(Vec2(2, 2)));
  CHECK(plate.contains(Vec2(-2, 0.3)));
  CHECK_FALSE(plate.contains(Vec2(2.01, 0)));
}

TEST_CASE("clip() pieces tile the domain exactly", "[geometry]") {
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt", "plate_with_hole.wkt"}) {
    INFO(name);
    const Domain d = mesh(name);
    const Box bb = d.bounding_box();
    // Overhang the bounding box a little so that outer boxes stick out of the domain.
    const std::vector<double> xs = uneven_breaks(bb.lo.x() - 0.1, bb.hi.x() + 0.07, 7);
    const std::vector<double> ys = uneven_breaks(bb.lo.y() - 0.05, bb.hi.y() + 0.13, 5);
    Integrals sum;
    for (std::size_t i = 0; i + 1 < xs.size(); ++i) {
      for (std::size_t j = 0; j + 1 < ys.size(); ++j) {
        const Box box{Vec2(xs[i], ys[j]), Vec2(xs[i + 1], ys[j + 1])};
        const Integrals piece = integrate(d.clip(box));
        CHECK(piece.area >= 0.0);
        CHECK(piece.area <= box.area() * (1 + 1e-14));
        sum.area += piece.area;
        sum.moment += piece.moment;
      }
    }
    CHECK(sum.area == Approx(d.area()).epsilon(1e-12));
    CHECK((sum.moment - d.first_moment()).norm() < 1e-12 * d.area());
  }
}

TEST_CASE("clip() with boxes in the hole, over the hole, at the corner and over all",
          "[geometry]") {
  const Domain plate = mesh("plate_with_hole.wkt");
  CHECK(plate.clip(Box{Vec2(-0.3, -0.3), Vec2(0.3, 0.3)}).empty());
  CHECK(plate.clip(Box{Vec2(3, 3), Vec2(4, 4)}).empty());

  const std::vector<Ring> all = plate.clip(Box{Vec2(-10, -10), Vec2(10, 10)});
  CHECK(integrate(all).area == Approx(plate.area()).epsilon(1e-15));

  // A box holding the whole hole but not the plate: one CCW outer ring and one CW hole.
  const std::vector<Ring> ring = plate.clip(Box{Vec2(-1, -1), Vec2(1, 1)});
  REQUIRE(ring.size() == 2);
  int ccw = 0, cw = 0;
  for (const Ring& r : ring) (mfree::ring_area(r) > 0 ? ccw : cw) += 1;
  CHECK(ccw == 1);
  CHECK(cw == 1);
  CHECK(integrate(ring).area == Approx(4.0 - hole_area()).epsilon(1e-14));

  // Straddling the hole: the half plane y >= 0 of the plate.
  const Integrals upper = integrate(plate.clip(Box{Vec2(-3, 0), Vec2(3, 3)}));
  CHECK(upper.area == Approx(plate.area() / 2).epsilon(1e-14));
  CHECK(std::abs(upper.moment.x()) < 1e-14);
  // int y dA: the half square [-2,2]x[0,2] gives 8; the upper half of the 64-gon is the fan
  // of triangles (0, v_k, v_k+1), k < 32, each of area r^2 sin(2 pi/64) / 2 and centroid
  // height (y_k + y_k+1) / 3.
  double fan = 0.0;
  for (int k = 0; k < 32; ++k) {
    const double yk = 0.5 * std::sin(2 * pi * k / 64);
    const double yk1 = 0.5 * std::sin(2 * pi * (k + 1) / 64);
    fan += 0.5 * 0.25 * std::sin(2 * pi / 64) * (yk + yk1) / 3.0;
  }
  CHECK(upper.moment.y() == Approx(8.0 - fan).epsilon(1e-14));

  // A box the boundary does not reach comes back whole.
  const Box inner{Vec2(1, 1), Vec2(1.5, 1.75)};
  const std::vector<Ring> whole = plate.clip(inner);
  REQUIRE(whole.size() == 1);
  CHECK(mfree::ring_area(whole[0]) == Approx(inner.area()).epsilon(1e-15));

  // The L's re-entrant corner: [-0.5, 0.5]^2 keeps three of its four quarters.
  const Domain l = mesh("l_shape.wkt");
  const Integrals corner = integrate(l.clip(Box{Vec2(-0.5, -0.5), Vec2(0.5, 0.5)}));
  CHECK(corner.area == Approx(0.75).epsilon(1e-15));
  // Moment: the full square's is 0, minus the quarter [0,0.5]^2 with moment (1/16, 1/16).
  CHECK(corner.moment.x() == Approx(-1.0 / 16).epsilon(1e-14));
  CHECK(corner.moment.y() == Approx(-1.0 / 16).epsilon(1e-14));
  // A box wholly in the cut-out quadrant but touching the corner has no area inside.
  CHECK(integrate(l.clip(Box{Vec2(0, 0), Vec2(1, 1)})).area == Approx(0.0).margin(1e-15));
}

TEST_CASE("bad WKT and bad rings are InputErrors naming the source", "[geometry]") {
  using Catch::Contains;
  auto wkt_error = [](const std::string& text) {
    return input_error_message([&] { (void)Domain::from_wkt(text, "shape.wkt"); });
  };
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, 1 1)"), Contains("shape.wkt") && Contains("')'"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, 1))"), Contains("shape.wkt") && Contains("number"));
  CHECK_THAT(wkt_error("LINESTRING(0 0, 1 1)"), Contains("shape.wkt") && Contains("POLYGON"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, 1 1, 0 0)) POINT(1 1)"),
             Contains("shape.wkt") && Contains("after"));
  CHECK_THAT(wkt_error("POLYGON Z ((0 0 0, 1 0 0, 1 1 0, 0 0 0))"), Contains("shape.wkt"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, 1 1 1, 0 0))"), Contains("shape.wkt"));
  CHECK_THAT(wkt_error("POLYGON EMPTY"), Contains("shape.wkt") && Contains("EMPTY"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, nan 1, 0 0))"), Contains("shape.wkt"));
  CHECK_THAT(wkt_error(""), Contains("shape.wkt"));
  // The position of the error: line 2, column 10 (the 'x').
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0,\n  1 1, 0 x))"), Contains("shape.wkt:2:10"));

  CHECK_THAT(wkt_error("POLYGON((0 0, 1 1, 0 0))"),
             Contains("shape.wkt") && Contains("at least 3"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 0, 2 0, 0 0))"),
             Contains("shape.wkt") && Contains("zero area"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 1 1, 1 0, 0 1, 0 0))"),
             Contains("shape.wkt") && Contains("not simple"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 4 0, 4 4, 0 4), (5 5, 6 5, 6 6, 5 6))"),
             Contains("shape.wkt") && Contains("outside"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 4 0, 4 4, 0 4), (3 1, 5 1, 5 2, 3 2))"),
             Contains("shape.wkt") && Contains("hole 1"));
  CHECK_THAT(wkt_error("POLYGON((0 0, 4 0, 4 4, 0 4), (1 1, 3 1, 3 3, 1 3), (1.5 1.5, 2 1.5, 2 2))"),
             Contains("shape.wkt") && Contains("hole 2"));

  const std::string missing = mesh_path("no_such_mesh.wkt");
  CHECK_THAT(input_error_message([&] { (void)Domain::from_file(missing); }), Contains(missing));
  const std::string directory = mfree::testing::source_dir() + "/meshes";
  CHECK_THAT(input_error_message([&] { (void)Domain::from_file(directory); }),
             Contains(directory));
  CHECK_THAT(input_error_message([] { (void)Domain::rectangle(Vec2(0, 0), Vec2(1, 0)); }),
             Contains("lo < hi"));
}

TEST_CASE("cracks: line strings beside the polygon, tips and mouths, two faces each, points on them split",
          "[geometry][crack]") {
  const Domain d = Domain::from_wkt(
      "GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1, 0 1, 0 0)), LINESTRING(0.5 0.5, 1 0.5, 1.2 0.7),"
      " MULTILINESTRING((2 0.3, 1.7 0.3)))",
      "cracked");
  REQUIRE(d.cracks().size() == 2);
  CHECK(d.cracks()[0].name == "crack1");
  CHECK(d.cracks()[0].tip[0]);
  CHECK(d.cracks()[0].tip[1]);
  CHECK(!d.cracks()[1].tip[0]);  // on the edge x = 2: a mouth
  CHECK(d.cracks()[1].tip[1]);
  CHECK(d.area() == Approx(2.0).epsilon(1e-15));
  // 4 ring edges, then two faces per crack segment (3 segments) with opposite normals.
  const auto& b = d.boundary();
  REQUIRE(b.size() == 4 + 6);
  double length = 0.0;
  Vec2 normal_sum = Vec2::Zero();
  for (std::size_t s = 4; s < b.size(); ++s) {
    CHECK(b[s].ring == -1);
    CHECK(d.part_names()[b[s].part] == d.cracks()[b[s].crack].name);
    length += b[s].length;
    normal_sum += b[s].length * b[s].normal;
  }
  CHECK(length == Approx(2.0 * (0.5 + std::sqrt(0.08) + 0.3)).epsilon(1e-14));
  CHECK(normal_sum.norm() <= 1e-15);
  CHECK(b[4].normal.isApprox(Vec2(0, -1)));  // face a -> b of the first segment: material above
  // A lattice point on a crack becomes two, one on each side; a point at a tip stays one.
  std::vector<Index> origin;
  const std::vector<Vec2> split =
      split_on_cracks(d, {Vec2(0.75, 0.5), Vec2(0.5, 0.5), Vec2(0.3, 0.3), Vec2(1.8, 0.3)}, 0.1, &origin);
  REQUIRE(split.size() == 6);
  CHECK(origin == std::vector<Index>{0, 0, 1, 2, 3, 3});
  CHECK(split[0].y() - 0.5 == Approx(crack_offset * 0.1).epsilon(1e-6));
  CHECK(split[1].y() - 0.5 == Approx(-crack_offset * 0.1).epsilon(1e-6));
  CHECK(split[2] == Vec2(0.5, 0.5));
  // Names of cracks may not repeat a part name.
  CHECK_THROWS_WITH(
      Domain::rectangle(Vec2(0, 0), Vec2(1, 1)).with_cracks({{Vec2(0.2, 0.5), Vec2(0.6, 0.5)}}, {"top"}, "t"),
      Catch::Contains("crack name 'top' is already a part name"));
}

TEST_CASE("regions: the union of polygons that share edges, interfaces along the shared pieces",
          "[geometry][regions]") {
  // Two squares side by side; the right one has a vertex half-way up the shared edge, so the
  // shared edge comes in two pieces that join into one interface.
  const Domain d = Domain::from_wkt("MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1)), ((1 0, 2 0, 2 1, 1 1, 1 0.5)))",
                                    "two.wkt", {{"left", "right"}, true});
  REQUIRE(d.regions().size() == 2);
  CHECK(d.regions()[1].name == "right");
  CHECK(d.area() == Approx(2.0).epsilon(1e-15));
  CHECK(d.rings().size() == 1);
  REQUIRE(d.cracks().size() == 1);
  const mfree::Crack& c = d.cracks()[0];
  CHECK(c.name == "left/right");
  CHECK(c.interface());
  CHECK(c.left == 0);
  CHECK(c.right == 1);
  CHECK(!c.tip[0]);
  CHECK(!c.tip[1]);
  REQUIRE(c.points.size() == 3);
  CHECK(c.points.front() == Vec2(1, 0));  // along the left square's edge, which runs upwards
  CHECK(c.points.back() == Vec2(1, 1));
  CHECK(d.region_at(Vec2(0.5, 0.5)) == 0);
  CHECK(d.region_at(Vec2(1.5, 0.5)) == 1);
  CHECK(d.region_at(Vec2(3, 0.5)) == -1);
  // Without interfaces the regions stay, the shared edge is inside the domain.
  const Domain smooth = Domain::from_wkt("MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1)), ((1 0, 2 0, 2 1, 1 1)))",
                                         "two.wkt", {{}, false});
  CHECK(smooth.cracks().empty());
  CHECK(smooth.regions()[0].name == "region1");
  CHECK(smooth.boundary().size() >= 4);

  // Parts pass from the region edges to the union's edges along them, also to a piece of one:
  // the top of the lower rectangle is split at (1, 1), where the upper square starts.
  const Domain parted = Domain::from_regions({{{Vec2(0, 0), Vec2(2, 0), Vec2(2, 1), Vec2(0, 1)}},
                                              {{Vec2(1, 1), Vec2(2, 1), Vec2(2, 2), Vec2(1, 2)}}},
                                             {{}, false}, "parted", {{{0, 1, 2, -1}}, {{-1, 1, 2, -1}}},
                                             {"bottom", "right", "top"});
  std::vector<double> part_lengths(4, 0.0);  // bottom, right, top, none
  for (const mfree::BoundarySegment& s : parted.boundary())
    if (s.ring == 0) part_lengths[s.part < 0 ? 3 : s.part] += s.length;
  CHECK(part_lengths == std::vector<double>{2.0, 2.0, 2.0, 2.0});
  for (const mfree::BoundarySegment& s : parted.boundary())
    if (s.ring == 0 && s.a.y() == 1 && s.b.y() == 1)
      CHECK((s.part >= 0 && parted.part_names()[s.part] == "top"));

  // An inclusion: the interface closes on itself, the matrix on its left.
  const Domain inclusion =
      Domain::from_wkt("MULTIPOLYGON(((0 0, 3 0, 3 3, 0 3), (1 1, 1 2, 2 2, 2 1)), ((1 1, 2 1, 2 2, 1 2)))");
  REQUIRE(inclusion.cracks().size() == 1);
  const mfree::Crack& loop = inclusion.cracks()[0];
  CHECK(loop.closed());
  CHECK(loop.points.size() == 5);
  CHECK((!loop.tip[0] && !loop.tip[1]));
  CHECK((loop.left == 0 && loop.right == 1));
  CHECK(mfree::ring_area(mfree::Ring(loop.points.begin(), loop.points.end() - 1)) <
        0.0);  // clockwise: the matrix outside

  // Refusals: apart, overlapping, a crack that closes on itself, a crack across the interface.
  const auto refusal = [](const std::string& text) {
    return input_error_message([&] { (void)Domain::from_wkt(text, "regions.wkt"); });
  };
  using Catch::Matchers::Contains;
  CHECK_THAT(refusal("MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1)), ((2 0, 3 0, 3 1, 2 1)))"),
             Contains("2 separate pieces"));
  CHECK_THAT(refusal("MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1)), ((0.5 0, 2 0, 2 1, 0.5 1)))"),
             Contains("overlap"));
  CHECK_THAT(
      refusal("GEOMETRYCOLLECTION(POLYGON((0 0, 3 0, 3 3, 0 3)), LINESTRING(1 1, 2 1, 2 2, 1 2, 1 1))"),
      Contains("crack 'crack1' closes on itself at (1, 1): it would cut its inside loose"));
  CHECK_THAT(refusal("GEOMETRYCOLLECTION(MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1)), ((1 0, 2 0, 2 1, 1 1))),"
                     " LINESTRING(0.5 0.5, 1.5 0.5))"),
             Contains("meets the interface 'region1/region2'"));
}

TEST_CASE("regions: an interface may end where the boundary runs straight on past it (a lap joint)",
          "[geometry][regions]") {
  const Domain d = Domain::from_wkt(
      "MULTIPOLYGON(((0 0, 1.2 0, 1.2 0.5, 0 0.5)), ((0.8 0.5, 2 0.5, 2 1, 0.8 1)))", "lap.wkt");
  REQUIRE(d.cracks().size() == 1);
  CHECK(d.cracks()[0].points.size() == 2);
  CHECK(!d.cracks()[0].tip[0]);
  CHECK(!d.cracks()[0].tip[1]);
  CHECK(d.area() == Approx(1.2).epsilon(1e-15));
  // A crack along the boundary beyond its mouth is still refused.
  CHECK_THAT(input_error_message([] {
               (void)Domain::from_wkt(
                   "GEOMETRYCOLLECTION(POLYGON((0 0, 2 0, 2 1, 0 1)), LINESTRING(0 0, 1 0))", "edge");
             }),
             Catch::Matchers::Contains("meets the boundary"));
}

TEST_CASE("crack faces: a node at a sharp corner of an inclusion gets one copy in each region",
          "[geometry][regions]") {
  // The apex (0.5, 0.75) of a triangular inclusion turns by 127 degrees: a copy moved along one
  // edge's normal left the 53-degree wedge of the inclusion, and both copies were the matrix's.
  const Domain d = Domain::from_wkt(
      "MULTIPOLYGON(((0 0, 1 0, 1 1, 0 1), (0.25 0.25, 0.5 0.75, 0.75 0.25)), ((0.25 0.25, 0.75 0.25, 0.5 "
      "0.75)))");
  REQUIRE(d.cracks().size() == 1);
  for (const Vec2& corner : {Vec2(0.5, 0.75), Vec2(0.25, 0.25), Vec2(0.75, 0.25)}) {
    CAPTURE(corner.x(), corner.y());
    const std::vector<Vec2> copies = mfree::split_on_cracks(d, {corner}, 0.125);
    REQUIRE(copies.size() == 2);
    CHECK(d.region_at(copies[0]) + d.region_at(copies[1]) == 1);  // one in each (regions 0 and 1)
    CHECK((copies[0] - corner).norm() <= 2e-8);
  }
}
