#pragma once
// Meshfree quadrature weights from the RK functions of the quadrature cloud (seed 003):
//
//     w_K = integral over Omega of phi_K,
//
// phi_K built on the quadrature points x_K, the integral taken by the background lattice
// rule (trapezoid for linear RK, Simpson for quadratic; background_lattice.hpp). The
// rule sum_K w_K f(x_K) is then exact for linear functions (quadratic ones with quadratic
// RK) up to round-off, whatever the cloud.

#include <vector>

#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/quadrature/background_lattice.hpp"

namespace mfree {

/// w_K for every point of `quadrature_functions`; each lattice vertex is evaluated once.
std::vector<double> rk_quadrature_weights(const RKShapeFunctions& quadrature_functions,
                                          const BackgroundLattice& lattice);

/// Count and most negative value of the negative weights (quadratic RK makes some).
struct NegativeWeights {
  Index count = 0;
  double most_negative = 0.0;
};
NegativeWeights negative_weights(const std::vector<double>& weights);

}  // namespace mfree
