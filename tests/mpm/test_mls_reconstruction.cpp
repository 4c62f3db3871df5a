// The MLS reconstruction at the Gauss points against the RK shape functions of kernels/
// evaluated point by point with the particles as nodes (the same functions, summed in
// another order), its reproduction of the basis's polynomials, and the mixed quadrature:
// Gauss points in the filled cells, the particles their own points elsewhere and in the
// cells where a Gauss point sees too few particles.

#include <algorithm>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>
#include <utility>

#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/mpm/mls_reconstruction.hpp"
#include "mfree/mpm/particles.hpp"

using namespace mfree;

namespace {

/// 3 x 3 particles per cell of the box [0, 1] x [0, 0.75] (8 x 6 cells), each moved at
/// random by up to `jitter` h, and the box's grid for quadratic B-splines.
std::vector<Vec2> jittered_particles(double h, double jitter, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> shift(-jitter * h, jitter * h);
  std::vector<Vec2> x;
  for (int j = 0; j < 18; ++j)
    for (int i = 0; i < 24; ++i) x.emplace_back(h / 3.0 * (i + 0.5) + shift(rng), h / 3.0 * (j + 0.5) + shift(rng));
  return x;
}

const Box box{Vec2(0.0, 0.0), Vec2(1.0, 0.75)};

/// F = I for n particles, and reference volumes whose domains (2 h / 3 wide, against the
/// particles' h / 3 spacing) cover the jittered lattice, so that every cell is filled.
std::vector<Mat2> undeformed(std::size_t n) { return std::vector<Mat2>(n, Mat2::Identity()); }
std::vector<double> covering_volumes(std::size_t n, double h) {
  return std::vector<double>(n, 4.0 * h * h / 9.0);
}

}  // namespace

TEST_CASE("MLS reconstruction equals the RK shape functions with the particles as nodes", "[mpm][mls]") {
  const Grid grid(box, 8, 2, 0);
  const ParticleBasis basis(MPMMethod::bspline_mls, grid);
  const double h = grid.spacing();
  for (const RKOrder order : {RKOrder::linear, RKOrder::quadratic})
    for (const double support : {1.5, 3.0}) {
      const std::vector<Vec2> x = jittered_particles(h, 0.15, 7);
      MLSReconstruction mls(grid, basis, order, support);
      mls.update(x, undeformed(x.size()), covering_volumes(x.size(), h));
      REQUIRE(mls.points() == 4 * 8 * 6);  // every cell filled: Gauss points only
      // A random field on the particles, and the polynomials the basis reproduces.
      std::mt19937 rng(11);
      std::uniform_real_distribution<double> value(-1.0, 1.0);
      std::vector<double> f(x.size());
      for (double& v : f) v = value(rng);
      const auto poly = [&](const Vec2& p) {
        const double linear = 0.3 - 1.2 * p.x() + 0.7 * p.y();
        return order == RKOrder::linear ? linear : linear + 0.9 * p.x() * p.x() - 0.4 * p.x() * p.y() + 1.1 * p.y() * p.y();
      };
      std::vector<Vec2> at_gauss;
      mls.reconstruct<Vec2>(at_gauss, [&](Index p) { return Vec2(f[p], poly(x[p])); });

      RKSettings s;
      s.order = order;
      s.window = Window::quadratic_spline;
      s.support = SupportShape::tensor;
      s.radius = support * h;
      const RKShapeFunctions<2> rk(x, s);
      ShapeValues<2> v;
      double random_difference = 0.0, poly_error = 0.0;
      for (Index g = 0; g < mls.gauss_count(); ++g) {
        rk.evaluate(mls.gauss_points()[g], v, false);
        double reference = 0.0;
        for (std::size_t k = 0; k < v.size(); ++k) reference += v.phi[k] * f[v.nodes[k]];
        random_difference = std::max(random_difference, std::abs(at_gauss[g].x() - reference));
        poly_error = std::max(poly_error, std::abs(at_gauss[g].y() - poly(mls.gauss_points()[g])));
      }
      INFO(to_string(order) << " basis, support " << support << " h");
      CHECK(random_difference <= 1e-12);
      CHECK(poly_error <= 1e-12);
      // The same again after the particles move (the rows are rebuilt in place).
      std::vector<Vec2> moved = x;
      for (Vec2& p : moved) p += Vec2(0.01 * std::sin(7.0 * p.y()), 0.01 * std::cos(5.0 * p.x()));
      mls.update(moved, undeformed(x.size()), covering_volumes(x.size(), h));
      mls.reconstruct<Vec2>(at_gauss, [&](Index p) { return Vec2(poly(moved[p]), 0.0); });
      double moved_error = 0.0;
      for (Index g = 0; g < mls.gauss_count(); ++g)
        moved_error = std::max(moved_error, std::abs(at_gauss[g].x() - poly(mls.gauss_points()[g])));
      CHECK(moved_error <= 1e-12);
    }
}

TEST_CASE(
    "MLS reconstruction returns a cell to particle quadrature where a Gauss point sees too few particles",
    "[mpm][mls]") {
  // The jittered lattice with a hole of 4 x 4 cells (x in [2 h, 6 h], y in [h, 5 h]) and
  // domains 4 h wide, which cover the hole: every cell is interior, but the Gauss points
  // within 1.5 h of the hole's centre see no particle, and those near its edges few (a
  // line, a conic). The cells returned are exactly those with a point where the RK
  // functions with the particles as nodes, evaluated alone, fail.
  const Grid grid(box, 8, 2, 0);
  const ParticleBasis basis(MPMMethod::bspline_mls, grid);
  const double h = grid.spacing();
  std::vector<Vec2> x;
  for (const Vec2& p : jittered_particles(h, 0.15, 5))
    if (!(p.x() > 2 * h && p.x() < 6 * h && p.y() > h && p.y() < 5 * h)) x.push_back(p);
  const std::vector<double> volumes(x.size(), 16.0 * h * h);
  for (const RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
    INFO(to_string(order) << " basis");
    MLSReconstruction mls(grid, basis, order, 1.5);
    mls.update(x, undeformed(x.size()), volumes);
    RKSettings s;
    s.order = order;
    s.window = Window::quadratic_spline;
    s.support = SupportShape::tensor;
    s.radius = 1.5 * h;
    const RKShapeFunctions<2> rk(x, s);
    ShapeValues<2> v;
    const double offset = 0.5 / std::sqrt(3.0);
    std::vector<unsigned char> expected(8 * 6, 0);  // the cells returned to particle quadrature
    for (int c = 0; c < 8 * 6; ++c)
      for (const double sy : {-offset, offset})
        for (const double sx : {-offset, offset}) try {
            rk.evaluate(h * Vec2(c % 8 + 0.5 + sx, c / 8 + 0.5 + sy), v, false);
          } catch (const NumericalError&) {
            expected[c] = 1;
          }
    const auto demoted = static_cast<Index>(std::count(expected.begin(), expected.end(), 1));
    REQUIRE(demoted >= 4);  // the hole's centre
    REQUIRE(demoted < 16);  // and not the whole hole
    CHECK(mls.demoted_cells() == demoted);
    REQUIRE(mls.gauss_count() == 4 * (8 * 6 - demoted));
    const auto cell_of = [&](const Vec2& p) {
      return static_cast<int>(std::floor(p.x() / h)) + 8 * static_cast<int>(std::floor(p.y() / h));
    };
    for (const Vec2& g : mls.gauss_points()) CHECK(!expected[cell_of(g)]);
    std::vector<Index> own;  // the particles of the returned cells, in order
    for (std::size_t p = 0; p < x.size(); ++p)
      if (expected[cell_of(x[p])]) own.push_back(static_cast<Index>(p));
    CHECK(mls.own_particles() == own);
    // The other Gauss points reconstruct as before, from every particle of the interior
    // cells (those of the returned cells too): the RK functions' values, x reproduced.
    std::vector<Vec2> at;
    mls.reconstruct<Vec2>(at, [&](Index p) { return x[p]; });
    double difference = 0.0, error = 0.0;
    for (Index g = 0; g < mls.gauss_count(); ++g) {
      rk.evaluate(mls.gauss_points()[g], v, false);
      Vec2 reference = Vec2::Zero();
      for (std::size_t k = 0; k < v.size(); ++k) reference += v.phi[k] * x[v.nodes[k]];
      difference = std::max(difference, (at[g] - reference).norm());
      error = std::max(error, (at[g] - mls.gauss_points()[g]).norm());
    }
    // Points next to the hole see their particles on one side: moment matrices near the
    // conditioning limit (rcond_min) lose digits.
    INFO("difference " << difference << ", error " << error << ", cells returned " << demoted);
    CHECK(difference <= 1e-10);
    CHECK(error <= 1e-10);
  }
}

TEST_CASE("MLS quadrature: Gauss points in the cells a deformed block fills, its particles elsewhere",
          "[mpm][mls]") {
  // A block of 3 x 3 particles per reference cell (spacing l), sheared, stretched and turned
  // by F about its centre: the particle domains, widened by a quarter, cover the deformed
  // block grown by l / 8 in its reference coordinates, so a cell is filled exactly when its
  // corners, edge midpoints and centre map into that grown block, and interior when its
  // neighbours are filled too.
  const Grid grid(box, 16, 2, 0);
  const double h = grid.spacing();
  const ParticleBasis basis(MPMMethod::bspline_mls, grid);
  const Box block{Vec2(0.2, 0.15), Vec2(0.7, 0.5)};
  const double l = 0.05 / 3.0;
  Particles P = fill_box(block, 0.05, 3, 1000.0, false);
  const double turn = 0.3;
  const Mat2 R = (Mat2() << std::cos(turn), -std::sin(turn), std::sin(turn), std::cos(turn)).finished();
  const Mat2 F = R * (Mat2() << 1.1, 0.2, 0.0, 0.9).finished();
  const Vec2 centre = 0.5 * (block.lo + block.hi);
  for (Index p = 0; p < P.size(); ++p) {
    P.deformation[p] = F;
    P.position[p] = centre + F * (P.reference[p] - centre);
  }
  MLSReconstruction mls(grid, basis, RKOrder::linear, 1.5);
  mls.update(P.position, P.deformation, P.volume0);

  const auto in_grown_block = [&](const Vec2& x) {
    const Vec2 X = centre + F.inverse() * (x - centre);
    return (X.array() >= block.lo.array() - l / 8).all() && (X.array() <= block.hi.array() + l / 8).all();
  };
  std::vector<unsigned char> filled(static_cast<std::size_t>(16 * 12), 0), expected(filled.size(), 0);
  for (int j = 0; j < 12; ++j)
    for (int i = 0; i < 16; ++i) {
      bool all = true;
      for (int dj = 0; dj <= 2; ++dj)
        for (int di = 0; di <= 2; ++di) all = all && in_grown_block(h * Vec2(i + 0.5 * di, j + 0.5 * dj));
      filled[i + 16 * j] = all;
    }
  int interior = 0;
  for (int j = 1; j < 11; ++j)  // the block stays a cell away from the grid's edges
    for (int i = 1; i < 15; ++i) {
      bool all = true;
      for (int dj = -1; dj <= 1; ++dj)
        for (int di = -1; di <= 1; ++di) all = all && filled[i + di + 16 * (j + dj)];
      expected[i + 16 * j] = all;
      interior += all;
    }
  REQUIRE(interior >= 4);  // the block has interior cells, and leaves many cells in part
  REQUIRE(mls.gauss_count() == 4 * interior);
  for (Index g = 0; g < mls.gauss_count(); g += 4) {  // the four points of one cell
    const Vec2 c = 0.25 * (mls.gauss_points()[g] + mls.gauss_points()[g + 1] + mls.gauss_points()[g + 2] +
                           mls.gauss_points()[g + 3]);
    CHECK(expected[static_cast<int>(std::floor(c.x() / h)) + 16 * static_cast<int>(std::floor(c.y() / h))]);
  }
  // The particles of the other cells are their own quadrature points, in order, after the
  // Gauss points, with their values.
  std::size_t own = 0;
  for (Index p = 0; p < P.size(); ++p) {
    const int i = static_cast<int>(std::floor(P.position[p].x() / h)),
              j = static_cast<int>(std::floor(P.position[p].y() / h));
    if (expected[i + 16 * j]) continue;
    REQUIRE(own < mls.own_particles().size());
    CHECK(mls.own_particles()[own++] == p);
  }
  CHECK(own == mls.own_particles().size());
  CHECK(own > 0);
  std::vector<Vec2> at;
  mls.reconstruct<Vec2>(at, [&](Index p) { return P.position[p]; });
  REQUIRE(static_cast<Index>(at.size()) == mls.points());
  double error = 0.0;  // x itself: reproduced at the Gauss points, the particle's own elsewhere
  for (Index g = 0; g < mls.gauss_count(); ++g)
    error = std::max(error, (at[g] - mls.gauss_points()[g]).norm());
  for (std::size_t k = 0; k < own; ++k)
    error = std::max(error, (at[mls.gauss_count() + k] - P.position[mls.own_particles()[k]]).norm());
  CHECK(error <= 1e-13);
  // The grid weights of a particle of its own are the B-spline weights at the particle.
  WeightTable at_particles;
  basis.resize(at_particles, P.size());
  for (Index p = 0; p < P.size(); ++p)
    basis.evaluate(P.position[p], Mat2::Identity(), Vec2::Zero(), at_particles, p);
  double weight_difference = 0.0;
  for (std::size_t k = 0; k < own; ++k) {
    const Index q = mls.gauss_count() + static_cast<Index>(k), p = mls.own_particles()[k];
    std::vector<std::pair<Index, double>> a, b;
    mls.grid_weights().for_each(q, [&](Index i, double S, const Vec2&) { a.emplace_back(i, S); });
    at_particles.for_each(p, [&](Index i, double S, const Vec2&) { b.emplace_back(i, S); });
    REQUIRE(a.size() == b.size());
    for (std::size_t e = 0; e < a.size(); ++e) {
      CHECK(a[e].first == b[e].first);
      weight_difference = std::max(weight_difference, std::abs(a[e].second - b[e].second));
    }
  }
  CHECK(weight_difference == 0.0);
}
