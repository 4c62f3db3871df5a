#include "mfree/galerkin/small_strain_errors.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"

namespace mfree {

Tensor2<3> linear_stress(const Lame& lame, const Tensor2<3>& g) {
  const Tensor2<3> eps = 0.5 * (g + g.transpose());
  return lame.lambda * eps.trace() * Tensor2<3>::Identity() + 2.0 * lame.mu * eps;
}

SmallStrainErrors small_strain_errors(const RKShapeFunctions<3>& trial, const Eigen::VectorXd& d,
                                      const QuadratureRule<3>& rule,
                                      const std::function<Lame(const Point<3>&)>& lame_at,
                                      const std::function<Point<3>(const Point<3>&)>& exact_u,
                                      const std::function<Tensor2<3>(const Point<3>&)>& exact_grad) {
  double l2 = 0.0, l2_norm = 0.0, energy = 0.0, energy_norm = 0.0;
  constexpr std::size_t block = 100000;
  for (std::size_t begin = 0; begin < rule.size(); begin += block) {
    const std::size_t end = std::min(rule.size(), begin + block);
    const std::vector<Point<3>> points(rule.points.begin() + static_cast<std::ptrdiff_t>(begin),
                                       rule.points.begin() + static_cast<std::ptrdiff_t>(end));
    const GalerkinQuadrature<3> at = sample_shape_functions(trial, points, true);
    // The exact fields may be formulas of a scene, evaluated point by point: the points are
    // shared among the threads (each sum in its own partial sums).
#pragma omp parallel for schedule(static) reduction(+ : l2, l2_norm, energy, energy_norm)
    for (Index k = 0; k < at.size(); ++k) {
      const double w = rule.weights[begin + static_cast<std::size_t>(k)];
      Tensor2<3> g = Tensor2<3>::Zero();
      for (Index j = at.row_begin(k); j < at.row_end(k); ++j)
        g += d.segment<3>(3 * at.nodes[j]) * at.grad[j].transpose();
      const Point<3>& x = points[static_cast<std::size_t>(k)];
      const Point<3> u = exact_u(x);
      const Tensor2<3> exact = exact_grad(x), e = g - exact;
      const Lame lame = lame_at(x);
      l2 += w * (displacement_at(at, k, d) - u).squaredNorm();
      l2_norm += w * u.squaredNorm();
      energy += w * (linear_stress(lame, e).array() * e.array()).sum();
      energy_norm += w * (linear_stress(lame, exact).array() * exact.array()).sum();
    }
  }
  return {std::sqrt(l2 / l2_norm), std::sqrt(energy / energy_norm)};
}

}  // namespace mfree
