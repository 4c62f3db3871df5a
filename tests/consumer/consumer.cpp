// A program of another project against an installed mfree: linear RK on a lattice of the unit
// square reproduces x exactly, and a material update (a struct of Eigen 2 x 2 matrices passed
// across the library's boundary, whose layout depends on the instruction set both are compiled
// for) gives the Neo-Hookean stress of a uniaxial stretch. Prints the errors and exits non-zero
// above round-off.
#include <cmath>
#include <cstdio>

#include "mfree/clouds/point_cloud.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/materials/material.hpp"

int main() {
  using namespace mfree;
  const Domain square = Domain::rectangle(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  CloudSettings c;
  c.spacing = 0.1;
  const std::vector<Vec2> nodes = make_cloud(square, c);
  RKSettings s;
  s.radius = 2.0 * c.spacing;
  const RKShapeFunctions<2> rk(nodes, s);
  double worst = 0.0;
  ShapeValues<2> v;
  for (const Vec2 x : {Vec2(0.05, 0.5), Vec2(0.33, 0.71), Vec2(0.99, 0.01)}) {
    rk.evaluate(x, v, false);
    Vec2 sum = Vec2::Zero();
    for (std::size_t k = 0; k < v.size(); ++k) sum += v.phi[k] * nodes[v.nodes[k]];
    worst = std::max(worst, (sum - x).norm());
  }
  // P_xx = mu (a - 1 / a) + lambda ln(a) / a for F = diag(a, 1).
  const double e = 1000.0, nu = 0.3, a = 1.2;
  const double lambda = e * nu / ((1 + nu) * (1 - 2 * nu)), mu = e / (2 * (1 + nu));
  Mat2 f = Mat2::Identity();
  f(0, 0) = a;
  const MaterialUpdate<2> u = update(make_material("neo_hookean", e, nu), f, MaterialState<2>{}, true);
  const double stress = std::abs(u.stress(0, 0) - (mu * (a - 1 / a) + lambda * std::log(a) / a)) / e;
  std::printf("mfree consumer: %zu nodes, largest error of linear reproduction %.3e, of a material update %.3e\n",
              nodes.size(), worst, stress);
  return worst < 1e-12 && stress < 1e-12 ? 0 : 1;
}
