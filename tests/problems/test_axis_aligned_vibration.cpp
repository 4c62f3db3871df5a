#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/problems/axis_aligned_vibration.hpp"

using namespace mfree;

// The manufactured solution must satisfy rho0 u_tt = Div P + rho0 b with the body force of
// SPEC section 6: checked by central differences of P in X at scattered points and times.
TEST_CASE("axis-aligned vibration: the corrected body force balances the motion", "[problems]") {
  for (double amplitude : {0.05, 0.1}) {
    const AxisAlignedVibration v{amplitude};
    const NeoHookean m = v.material();
    CHECK(v.period() == Approx(0.02).epsilon(1e-14));
    const double h = 1e-5;
    for (double t : {0.0013, 0.0051, 0.0137})
      for (const Vec2 x : {Vec2(0.13, 0.71), Vec2(0.5, 0.25), Vec2(0.91, 0.05)}) {
        Vec2 div = Vec2::Zero();
        for (int j = 0; j < 2; ++j) {
          const Vec2 e = Vec2::Unit(j) * h;
          const Mat2 dp = (m.stress(v.deformation_gradient(x + e, t)) - m.stress(v.deformation_gradient(x - e, t))) / (2 * h);
          div += dp.col(j);
        }
        const Vec2 lhs = v.density * v.acceleration(x, t);
        const Vec2 rhs = div + v.density * v.body_force(x, t);
        INFO("A = " << amplitude << ", t = " << t << ", X = " << x.transpose());
        CHECK((lhs - rhs).norm() <= 1e-6 * lhs.norm());
        // F is the gradient of u (central differences).
        const Mat2 f = v.deformation_gradient(x, t);
        CHECK(std::abs(f(0, 0) - 1.0 - (v.displacement(x + Vec2(h, 0), t) - v.displacement(x - Vec2(h, 0), t)).x() / (2 * h)) <= 1e-8);
      }
    // b vanishes with sin(c pi t / L).
    CHECK(v.body_force(Vec2(0.3, 0.4), 0.01).norm() <= 1e-9);
  }
}
