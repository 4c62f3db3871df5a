#include "mfree/quadrature/rk_quadrature.hpp"

#include <algorithm>

#include "mfree/core/parallel.hpp"

namespace mfree {

std::vector<double> rk_quadrature_weights(const RKShapeFunctions& quadrature_functions,
                                          const BackgroundLattice& lattice) {
  const auto& points = lattice.points();
  const auto& c = lattice.weights();
  const std::size_t nq = quadrature_functions.nodes().size();
  // w_K = sum_v c_v phi_K(x_v): each thread scatters its share of vertices into its own
  // array; the arrays are summed in thread order (reproducible for a given thread count).
  std::vector<std::vector<double>> partial(thread_count());
  parallel_ranges(static_cast<Index>(points.size()), [&](int t, Index begin, Index end) {
    std::vector<double>& w = partial[t];
    w.assign(nq, 0.0);
    ShapeValues phi;
    for (Index v = begin; v < end; ++v) {
      quadrature_functions.evaluate(points[v], phi, /*with_gradient=*/false);
      for (std::size_t k = 0; k < phi.size(); ++k) w[phi.nodes[k]] += c[v] * phi.phi[k];
    }
  });
  std::vector<double> w = std::move(partial[0]);
  for (std::size_t t = 1; t < partial.size(); ++t)
    for (std::size_t k = 0; k < nq; ++k) w[k] += partial[t][k];
  return w;
}

NegativeWeights negative_weights(const std::vector<double>& weights) {
  NegativeWeights result;
  for (double w : weights)
    if (w < 0.0) {
      ++result.count;
      result.most_negative = std::min(result.most_negative, w);
    }
  return result;
}

}  // namespace mfree
