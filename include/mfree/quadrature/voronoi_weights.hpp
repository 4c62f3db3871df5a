#pragma once
// Voronoi-cell quadrature weights: the baseline nodal rule of meshfree Galerkin methods,
//   w_K = |V_K ∩ Omega|,  V_K = { x : |x - x_K| <= |x - x_J| for every J },
// so that sum_K w_K = |Omega| and the rule integrates constants exactly.

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/domain.hpp"

namespace mfree {

/// The area of each point's Voronoi cell clipped to the domain. Points need not lie in the
/// domain (a point outside gets the part of its cell that reaches in), but they must be
/// finite and pairwise distinct; otherwise InputError names the offending index.
[[nodiscard]] std::vector<double> voronoi_weights(const std::vector<Vec2>& points,
                                                  const Domain& domain);

}  // namespace mfree
