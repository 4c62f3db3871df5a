#include <catch2/catch.hpp>
#include <algorithm>
#include <random>

#include "mfree/search/cell_list.hpp"

using namespace mfree;

TEST_CASE("cell list finds exactly the points a brute-force search finds", "[search]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  std::vector<Vec2> points(5000);
  for (Vec2& p : points) p = Vec2(u(rng), 0.5 * u(rng));
  for (double cell : {0.05, 0.3, 2.0}) {
    const CellList cells(points, cell);
    std::vector<Index> found;
    for (int q = 0; q < 300; ++q) {
      const Vec2 x(u(rng) * 1.2, u(rng));  // some queries outside the cloud's box
      const double r = cell * (q % 3 == 0 ? 1.0 : 0.37);
      cells.within(x, r, found);
      std::vector<Index> expected;
      for (Index i = 0; i < static_cast<Index>(points.size()); ++i)
        if ((points[i] - x).squaredNorm() < r * r) expected.push_back(i);
      std::sort(found.begin(), found.end());
      REQUIRE(found == expected);
    }
  }
}
