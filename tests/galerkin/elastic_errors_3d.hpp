#pragma once
// The relative L2 and energy errors of a 3D small-strain solution u^h = sum phi_I d_I against
// an exact field (u, grad u), over a rule independent of the discretisation; the convergence
// rates between the last two of a sequence of spacings. Shared by the 3D convergence studies.
#include <algorithm>
#include <cmath>
#include <vector>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"
#include "mfree/materials/finite_strain.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree::testing {

struct ElasticErrors {
  double l2 = 0.0, energy = 0.0;
};

/// sigma = lambda tr(eps) I + 2 mu eps of the 3D linear law for a displacement gradient g.
inline Tensor2<3> linear_stress(const Lame& lame, const Tensor2<3>& g) {
  const Tensor2<3> eps = 0.5 * (g + g.transpose());
  return lame.lambda * eps.trace() * Tensor2<3>::Identity() + 2.0 * lame.mu * eps;
}

/// |u^h - u|_L2 / |u|_L2 and the energy norm of the gradient error over its own, on `rule`;
/// the functions are sampled in blocks of points (all at once would take gigabytes on fine
/// rules).
template <class Displacement, class Gradient>
ElasticErrors elastic_errors(const RKShapeFunctions<3>& trial, const Eigen::VectorXd& d,
                             const QuadratureRule<3>& rule, const Lame& lame, Displacement&& exact_u,
                             Gradient&& exact_grad) {
  double l2 = 0.0, l2_norm = 0.0, energy = 0.0, energy_norm = 0.0;
  constexpr std::size_t block = 100000;
  for (std::size_t begin = 0; begin < rule.size(); begin += block) {
    const std::size_t end = std::min(rule.size(), begin + block);
    const std::vector<Point<3>> points(rule.points.begin() + begin, rule.points.begin() + end);
    const GalerkinQuadrature<3> at = sample_shape_functions(trial, points, true);
    for (Index k = 0; k < at.size(); ++k) {
      const double w = rule.weights[begin + k];
      Tensor2<3> g = Tensor2<3>::Zero();
      for (Index j = at.row_begin(k); j < at.row_end(k); ++j)
        g += d.segment<3>(3 * at.nodes[j]) * at.grad[j].transpose();
      const Point<3> u = exact_u(points[k]);
      const Tensor2<3> exact = exact_grad(points[k]), e = g - exact;
      l2 += w * (displacement_at(at, k, d) - u).squaredNorm();
      l2_norm += w * u.squaredNorm();
      energy += w * (linear_stress(lame, e).array() * e.array()).sum();
      energy_norm += w * (linear_stress(lame, exact).array() * exact.array()).sum();
    }
  }
  return {std::sqrt(l2 / l2_norm), std::sqrt(energy / energy_norm)};
}

/// The observed rates of the L2 and energy errors between the last two spacings.
inline ElasticErrors last_rates(const std::vector<double>& spacings, const std::vector<ElasticErrors>& e) {
  const std::size_t n = spacings.size() - 1;
  const double ratio = std::log(spacings[n - 1] / spacings[n]);
  return {std::log(e[n - 1].l2 / e[n].l2) / ratio, std::log(e[n - 1].energy / e[n].energy) / ratio};
}

}  // namespace mfree::testing
