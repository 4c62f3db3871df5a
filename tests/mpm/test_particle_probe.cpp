// The probe of an MPM run: u^h(X) = sum_p phi_p(X) (x_p - X_p) with linear RK functions of
// the reference positions reproduces every linear displacement field, at points in the
// interior, at edges and corners; a probe where no particle is refuses with an InputError.
#include <catch2/catch.hpp>

#include "mfree/core/error.hpp"
#include "mfree/mpm/particle_probe.hpp"

using namespace mfree;

TEST_CASE("MPM probe: a linear displacement field is reproduced to round-off anywhere in the body", "[mpm]") {
  const Box block{Vec2(0.0, 0.0), Vec2(2.0, 1.0)};
  const double h = 0.25;
  const int per_side = 3;
  Particles P = fill_box(block, h, per_side, 1000.0, false);
  const Mat2 a = (Mat2() << 0.02, -0.013, 0.007, -0.031).finished();
  const Vec2 b(0.3, -0.1);
  for (Index p = 0; p < P.size(); ++p) P.position[p] = P.reference[p] + a * P.reference[p] + b;
  double worst = 0.0;
  for (const Vec2 X : {Vec2(1.0, 0.5), Vec2(0.37, 0.81), Vec2(0.0, 0.0), Vec2(2.0, 1.0), Vec2(2.0, 0.42)}) {
    const ParticleProbe probe(P, X, h / per_side);
    worst = std::max(worst, (probe.displacement(P) - (a * X + b)).norm());
  }
  CHECK(worst < 1e-13);
  CHECK_THROWS_AS(ParticleProbe(P, Vec2(5.0, 5.0), h / per_side), InputError);
}
