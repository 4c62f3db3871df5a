#include <catch2/catch.hpp>
#include <algorithm>
#include <random>

#include "mfree/search/cell_list.hpp"

using namespace mfree;

namespace {

/// Queries of radius r and 0.37 r about random points (some outside the cloud's box): the
/// cell list finds exactly the points a brute-force search finds.
template <int dim>
void check_against_brute_force(const std::vector<Eigen::Matrix<double, dim, 1>>& points, double cell,
                               std::mt19937_64& rng) {
  using Point = Eigen::Matrix<double, dim, 1>;
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  const CellList<dim> cells(points, cell);
  std::vector<Index> found;
  for (int q = 0; q < 300; ++q) {
    Point x;
    for (int c = 0; c < dim; ++c) x[c] = u(rng) * (c == 0 ? 1.2 : 1.0);
    const double r = cell * (q % 3 == 0 ? 1.0 : 0.37);
    cells.within(x, r, found);
    std::vector<Index> expected;
    for (Index i = 0; i < static_cast<Index>(points.size()); ++i)
      if ((points[i] - x).squaredNorm() < r * r) expected.push_back(i);
    std::sort(found.begin(), found.end());
    REQUIRE(found == expected);
  }
}

}  // namespace

TEST_CASE("cell list finds exactly the points a brute-force search finds", "[search]") {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  std::vector<Vec2> points(5000);
  for (Vec2& p : points) p = Vec2(u(rng), 0.5 * u(rng));
  for (double cell : {0.05, 0.3, 2.0}) check_against_brute_force<2>(points, cell, rng);
}

TEST_CASE("cell list in three dimensions finds exactly the points a brute-force search finds", "[search]") {
  std::mt19937_64 rng(6);
  std::uniform_real_distribution<double> u(-3.0, 5.0);
  std::vector<Eigen::Vector3d> points(20000);
  for (Eigen::Vector3d& p : points) p = Eigen::Vector3d(u(rng), 0.5 * u(rng), 0.25 * u(rng));
  for (double cell : {0.05, 0.3, 2.0}) check_against_brute_force<3>(points, cell, rng);
  // Points on a line with a tiny cell: the grid is capped (about 4 cells a point), and the
  // search still exact.
  std::vector<Eigen::Vector3d> line(1000);
  for (std::size_t i = 0; i < line.size(); ++i)
    line[i] = Eigen::Vector3d(0.001 * static_cast<double>(i), 1.0, 2.0);
  const CellList<3> capped(line, 1e-9);
  CHECK(capped.cell_size() > 1e-4);
  std::vector<Index> found;
  capped.within(Eigen::Vector3d(0.5, 1.0, 2.0), 0.0025, found);
  std::sort(found.begin(), found.end());
  CHECK(found == std::vector<Index>{498, 499, 500, 501, 502});
}
