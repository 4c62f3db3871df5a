// The MLS reconstruction at the Gauss points against the RK shape functions of kernels/
// evaluated point by point with the particles as nodes (the same functions, summed in
// another order), its reproduction of the basis's polynomials, and the error of a Gauss point
// that sees too few particles.

#include <catch2/catch.hpp>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/mpm/mls_reconstruction.hpp"

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

}  // namespace

TEST_CASE("MLS reconstruction equals the RK shape functions with the particles as nodes", "[mpm][mls]") {
  const Grid grid(box, 8, 2, 0);
  const ParticleBasis basis(MPMMethod::bspline_mls, grid);
  const double h = grid.spacing();
  for (const RKOrder order : {RKOrder::linear, RKOrder::quadratic})
    for (const double support : {1.5, 3.0}) {
      const std::vector<Vec2> x = jittered_particles(h, 0.15, 7);
      MLSReconstruction mls(grid, basis, order, support);
      mls.update(x);
      REQUIRE(mls.points() == 4 * 8 * 6);  // every cell holds particles
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
      const RKShapeFunctions rk(x, s);
      ShapeValues v;
      double random_difference = 0.0, poly_error = 0.0;
      for (Index g = 0; g < mls.points(); ++g) {
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
      mls.update(moved);
      mls.reconstruct<Vec2>(at_gauss, [&](Index p) { return Vec2(poly(moved[p]), 0.0); });
      double moved_error = 0.0;
      for (Index g = 0; g < mls.points(); ++g)
        moved_error = std::max(moved_error, std::abs(at_gauss[g].x() - poly(mls.gauss_points()[g])));
      CHECK(moved_error <= 1e-12);
    }
}

TEST_CASE("MLS reconstruction names the Gauss point that sees too few particles", "[mpm][mls]") {
  const Grid grid(box, 8, 2, 0);
  const ParticleBasis basis(MPMMethod::bspline_mls, grid);
  // Two particles in the bottom-left cell only: no Gauss point sees three.
  MLSReconstruction mls(grid, basis, RKOrder::linear, 1.5);
  const std::vector<Vec2> x{Vec2(0.02, 0.02), Vec2(0.05, 0.06)};
  CHECK_THROWS_WITH(mls.update(x), Catch::Contains("RK moment matrix at point") && Catch::Contains("2 neighbour(s)") &&
                                       Catch::Contains("at least 3") && Catch::Contains("mls_support"));
}
