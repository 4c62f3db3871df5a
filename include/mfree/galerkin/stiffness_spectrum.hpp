#pragma once
// Zero-energy modes of a discretisation: the smallest eigenvalues of the free stiffness.
//
// Without boundary conditions the stiffness K (2N x 2N) of a stable 2D discretisation has
// exactly three zero eigenvalues, the rigid-body modes (two translations, one rotation).
// Every further (near-)zero eigenvalue is a spurious zero-energy mode: a displacement the
// quadrature cannot see, which under-integrated schemes (nodal integration, too few
// quadrature points per node) admit.
//
// Dense eigenvalues: for small clouds only (at most max_dofs).

#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"

namespace mfree {

struct StiffnessSpectrum {
  std::vector<double> smallest;  ///< smallest eigenvalues / the largest, ascending
  double largest = 0.0;          ///< largest eigenvalue [N/m per unit thickness]
  int zero_modes = 0;            ///< eigenvalues below zero_tolerance * largest (rigid + spurious)
};

inline constexpr Index spectrum_max_dofs = 6000;

/// The `count` smallest eigenvalues of the stiffness of `problem`'s material on `disc`,
/// with every boundary condition and body force dropped. A non-symmetric stiffness (VCI)
/// is symmetrised: (K + K^T) / 2 holds the energy u^T K u.
StiffnessSpectrum stiffness_spectrum(const ElasticityProblem& problem, const Domain& domain,
                                     const Discretisation<2>& disc, int count, double zero_tolerance = 1e-8);

}  // namespace mfree
