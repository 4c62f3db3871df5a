#include "mfree/quadrature/rk_quadrature.hpp"

#include <algorithm>

namespace mfree {

std::vector<double> rk_quadrature_weights(const RKShapeFunctions<2>& quadrature_functions,
                                          const BackgroundLattice& lattice) {
  std::vector<double> w(quadrature_functions.nodes().size(), 0.0);
  for_lattice_terms(
      quadrature_functions, lattice, [](Index, Index) {},
      [&](Index k, Index, Index, double c) { w[k] += c; });
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
