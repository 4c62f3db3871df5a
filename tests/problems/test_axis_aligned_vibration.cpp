#include <catch2/catch.hpp>
#include <cmath>

#include "mfree/problems/axis_aligned_vibration.hpp"

using namespace mfree;

namespace {

/// rho0 u_tt = Div P + rho0 b at scattered points and times, Div P and F = I + grad u by
/// central differences in X.
template <int dim>
void check_balance(const AxisAlignedVibration& v, const std::vector<Point<dim>>& points) {
  const NeoHookean m = v.material();
  const double h = 1e-5;
  for (double t : {0.0013, 0.0051, 0.0137})
    for (const Point<dim>& x : points) {
      Point<dim> div = Point<dim>::Zero();
      Tensor2<dim> grad_u;
      for (int j = 0; j < dim; ++j) {
        const Point<dim> plus = x + Point<dim>::Unit(j) * h, minus = x - Point<dim>::Unit(j) * h;
        const Tensor2<dim> dp =
            (m.stress(v.deformation_gradient(plus, t)) - m.stress(v.deformation_gradient(minus, t))) /
            (2 * h);
        div += dp.col(j);
        grad_u.col(j) = (v.displacement(plus, t) - v.displacement(minus, t)) / (2 * h);
      }
      const Point<dim> lhs = v.density * v.acceleration(x, t);
      const Point<dim> rhs = div + v.density * v.body_force(x, t);
      INFO("dim = " << dim << ", A = " << v.amplitude << ", t = " << t << ", X = " << x.transpose());
      CHECK((lhs - rhs).norm() <= 1e-6 * lhs.norm());
      CHECK((v.deformation_gradient(x, t) - Tensor2<dim>::Identity() - grad_u).norm() <= 1e-8);
    }
}

}  // namespace

// The manufactured solution must satisfy rho0 u_tt = Div P + rho0 b with the body force of
// SPEC section 6 (on the cube with J = F_xx F_yy F_zz): checked by central differences of P
// in X at scattered points and times.
TEST_CASE("axis-aligned vibration: the corrected body force balances the motion, square and cube",
          "[problems]") {
  for (double amplitude : {0.05, 0.1}) {
    const AxisAlignedVibration v{amplitude};
    CHECK(v.period() == Approx(0.02).epsilon(1e-14));
    check_balance<2>(v, {Vec2(0.13, 0.71), Vec2(0.5, 0.25), Vec2(0.91, 0.05)});
    check_balance<3>(v, {Point<3>(0.13, 0.71, 0.42), Point<3>(0.5, 0.25, 0.8), Point<3>(0.91, 0.05, 0.17)});
    // b vanishes with sin(c pi t / L).
    CHECK(v.body_force(Vec2(0.3, 0.4), 0.01).norm() <= 1e-9);
    CHECK(v.body_force(Point<3>(0.3, 0.4, 0.7), 0.01).norm() <= 1e-9);
    // The cube's motion restricted to z = 0: the square's in x and y.
    const Point<3> x3(0.3, 0.6, 0.0);
    CHECK((v.displacement(x3, 0.004).head<2>() - v.displacement(Vec2(0.3, 0.6), 0.004)).norm() == 0.0);
  }
}
