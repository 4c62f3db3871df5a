#include <catch2/catch.hpp>

#include "../test_support.hpp"

#include <limits>
#include <numeric>
#include <random>
#include <string>
#include <vector>

#include "mfree/core/error.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/quadrature/voronoi_weights.hpp"

using mfree::Domain;
using mfree::Vec2;

namespace {

Domain mesh(const std::string& name) {
  return Domain::from_file(mfree::testing::source_dir() + "/meshes/" + name);
}

// n points drawn uniformly from the domain by rejection from its bounding box.
std::vector<Vec2> random_points(const Domain& d, int n, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  const mfree::Box box = d.bounding_box();
  std::uniform_real_distribution<double> ux(box.lo.x(), box.hi.x());
  std::uniform_real_distribution<double> uy(box.lo.y(), box.hi.y());
  std::vector<Vec2> points;
  while (static_cast<int>(points.size()) < n) {
    const Vec2 x(ux(rng), uy(rng));
    if (d.contains(x)) points.push_back(x);
  }
  return points;
}

std::string input_error_message(const std::vector<Vec2>& points, const Domain& d) {
  return mfree::testing::message_of<mfree::InputError>([&] { (void)mfree::voronoi_weights(points, d); });
}

}  // namespace

TEST_CASE("cell-centred lattice in the rectangle: every weight is h^2", "[quadrature]") {
  const Domain rect = mesh("rectangle.wkt");
  const double h = 0.1;
  std::vector<Vec2> points;
  for (int j = 0; j < 10; ++j)
    for (int i = 0; i < 20; ++i) points.emplace_back(-1 + (i + 0.5) * h, -0.5 + (j + 0.5) * h);
  const std::vector<double> w = mfree::voronoi_weights(points, rect);
  REQUIRE(w.size() == points.size());
  for (std::size_t k = 0; k < w.size(); ++k) {
    INFO("point " << k);
    CHECK(w[k] == Approx(h * h).epsilon(1e-12));
  }
}

TEST_CASE("two and one sites split the domain as expected", "[quadrature]") {
  const Domain rect = mesh("rectangle.wkt");
  const std::vector<double> w2 = mfree::voronoi_weights({Vec2(-0.5, 0.1), Vec2(0.5, 0.1)}, rect);
  CHECK(w2[0] == Approx(1.0).epsilon(1e-14));
  CHECK(w2[1] == Approx(1.0).epsilon(1e-14));

  const Domain l = mesh("l_shape.wkt");
  const std::vector<double> w1 = mfree::voronoi_weights({Vec2(-0.3, -0.2)}, l);
  CHECK(w1[0] == Approx(3.0).epsilon(1e-14));
  CHECK(mfree::voronoi_weights({}, l).empty());
}

TEST_CASE("weights of random points sum to the domain area", "[quadrature]") {
  for (const std::string name : {"l_shape.wkt", "plate_with_hole.wkt"}) {
    INFO(name);
    const Domain d = mesh(name);
    const std::vector<Vec2> points = random_points(d, 3000, 20240531);
    const std::vector<double> w = mfree::voronoi_weights(points, d);
    REQUIRE(w.size() == points.size());
    for (double wk : w) {
      CHECK(wk > 0.0);
      CHECK(wk < d.area());
    }
    CHECK(std::accumulate(w.begin(), w.end(), 0.0) == Approx(d.area()).epsilon(1e-10));
  }
}

TEST_CASE("sites outside the domain get only what of their cell reaches in",
          "[quadrature]") {
  const Domain plate = mesh("plate_with_hole.wkt");
  std::vector<Vec2> points = random_points(plate, 500, 7);
  // One site deep inside the hole whose cell stays inside it, some near the hole's edge,
  // some outside the plate.
  points.emplace_back(0.0, 0.0);
  points.emplace_back(0.45, 0.0);
  points.emplace_back(-0.1, 0.47);
  points.emplace_back(2.5, 0.0);
  points.emplace_back(-3.0, -3.0);
  const std::vector<double> w = mfree::voronoi_weights(points, plate);
  CHECK(std::accumulate(w.begin(), w.end(), 0.0) == Approx(plate.area()).epsilon(1e-10));
  for (double wk : w) CHECK(wk >= 0.0);
  CHECK(w[w.size() - 1] == Approx(0.0).margin(1e-3));  // far corner: a sliver at most
}

TEST_CASE("duplicate and non-finite points are InputErrors naming the index",
          "[quadrature]") {
  const Domain l = mesh("l_shape.wkt");
  std::vector<Vec2> points = random_points(l, 20, 3);
  points[11] = points[4];
  CHECK_THAT(input_error_message(points, l), Catch::Contains("points 4 and 11"));

  std::vector<Vec2> bad = random_points(l, 5, 4);
  bad[2].y() = std::numeric_limits<double>::quiet_NaN();
  CHECK_THAT(input_error_message(bad, l), Catch::Contains("point 2"));
}
