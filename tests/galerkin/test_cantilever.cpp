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
