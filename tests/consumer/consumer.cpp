// Reproducing-kernel shape functions of an installed mfree: linear RK on a lattice of the
// unit square reproduces x exactly; prints the largest error of sum phi_I x_I at a few points
// and exits non-zero above round-off.
#include <cmath>
#include <cstdio>

#include "mfree/clouds/point_cloud.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

int main() {
  using namespace mfree;
  const Domain square = Domain::rectangle(Vec2(0.0, 0.0), Vec2(1.0, 1.0));
  CloudSettings c;
  c.spacing = 0.1;
  const std::vector<Vec2> nodes = make_cloud(square, c);
  RKSettings s;
  s.radius = 2.0 * c.spacing;
  const RKShapeFunctions rk(nodes, s);
  double worst = 0.0;
  ShapeValues v;
  for (const Vec2 x : {Vec2(0.05, 0.5), Vec2(0.33, 0.71), Vec2(0.99, 0.01)}) {
    rk.evaluate(x, v, false);
    Vec2 sum = Vec2::Zero();
    for (std::size_t k = 0; k < v.size(); ++k) sum += v.phi[k] * nodes[v.nodes[k]];
    worst = std::max(worst, (sum - x).norm());
  }
  std::printf("mfree consumer: %zu nodes, largest error of linear reproduction %.3e\n", nodes.size(), worst);
  return worst < 1e-12 ? 0 : 1;
}
