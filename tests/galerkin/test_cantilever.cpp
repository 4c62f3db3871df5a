#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/io/elasticity_scene.hpp"

using namespace mfree;

// The Timoshenko cantilever of verification/cantilever, read from its scene.
TEST_CASE("cantilever: optimal rates for linear RK and the tip deflection within 1%", "[galerkin][study]") {
  ElasticityScene scene =
      read_elasticity_scene(mfree::testing::source_dir() + "/verification/cantilever/cantilever.toml", false);
  const ExactElasticity exact = *scene.exact();
  std::vector<double> h, l2, energy;
  double tip = 0.0;
  for (double spacing : {0.75, 0.375}) {
    ElasticitySettings s = scene.settings;
    s.nodes.spacing = spacing;
    const ElasticityResult r = solve_elasticity(scene.domain, s, &exact);
    h.push_back(spacing);
    l2.push_back(r.errors->l2_displacement);
    energy.push_back(r.errors->energy);
    tip = r.displacement({Vec2(48.0, 0.0)})[0].y();
    CHECK(r.consistency_after <= 1e-12);
  }
  const double l2_rate = std::log(l2[0] / l2[1]) / std::log(h[0] / h[1]);
  const double energy_rate = std::log(energy[0] / energy[1]) / std::log(h[0] / h[1]);
  CAPTURE(l2, energy, tip);
  CHECK(l2_rate >= 1.8);
  CHECK(energy_rate >= 0.9);
  // Tip deflection P L (8 L^2 + (4 + 5 nu) D^2) / (2 E D^3) = 0.0089000 (SPEC section 4).
  CHECK(std::abs(tip - 0.0089) <= 0.01 * 0.0089);
}

// The default scheme with quadratic RK: Gauss cells (4 x 4 by default) and quadratic VCI on the
// monomials up to degree 2. With the monomials 1, x, y only, or 3 x 3 points, the L2 error at
// h = 0.75 is 3e-6 to 1.4e-4 and its rate from h = 1.5 falls to 1.5-2.7 (README).
TEST_CASE("cantilever: quadratic RK on Gauss cells with VCI, L2 rate >= 2.7 on lattice and perturbed clouds",
          "[galerkin][study]") {
  ElasticityScene scene =
      read_elasticity_scene(mfree::testing::source_dir() + "/verification/cantilever/cantilever.toml", false);
  const ExactElasticity exact = *scene.exact();
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed}) {
    std::vector<double> l2, energy;
    for (double spacing : {1.5, 0.75}) {
      ElasticitySettings s = scene.settings;
      s.nodes.kind = kind;
      s.nodes.spacing = spacing;
      s.order = RKOrder::quadratic;
      s.support_factor = 3.0;
      s.scheme = QuadratureScheme::gauss_cells;
      const ElasticityResult r = solve_elasticity(scene.domain, s, &exact);
      CHECK(r.consistency == Consistency::vci);
      CHECK(r.consistency_after <= 1e-10);
      l2.push_back(r.errors->l2_displacement);
      energy.push_back(r.errors->energy);
    }
    const double l2_rate = std::log2(l2[0] / l2[1]), energy_rate = std::log2(energy[0] / energy[1]);
    CAPTURE(to_string(kind), l2, energy);
    CHECK(l2[1] <= 1.5e-6);
    CHECK(l2_rate >= 2.7);
    CHECK(energy_rate >= 1.9);
  }
}
