#include "mfree/quadrature/rk_quadrature.hpp"

#include <algorithm>

namespace mfree {

template <int dim>
std::vector<double> rk_quadrature_weights(const RKShapeFunctions<dim>& quadrature_functions,
                                          const BackgroundLattice<dim>& lattice) {
  std::vector<double> w(quadrature_functions.nodes().size(), 0.0);
  for_lattice_terms(
      quadrature_functions, lattice, [](Index, Index) {},
      [&](Index k, Index, Index, double c) { w[k] += c; });
  return w;
}

template std::vector<double> rk_quadrature_weights(const RKShapeFunctions<2>&, const BackgroundLattice<2>&);
template std::vector<double> rk_quadrature_weights(const RKShapeFunctions<3>&, const BackgroundLattice<3>&);

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
