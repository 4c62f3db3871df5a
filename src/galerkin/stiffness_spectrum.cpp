#include "mfree/galerkin/stiffness_spectrum.hpp"

#include <Eigen/Eigenvalues>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

StiffnessSpectrum stiffness_spectrum(const ElasticityProblem& problem, const Domain& domain,
                                     const Discretisation<2>& disc, int count, double zero_tolerance) {
  const Index dofs = 2 * disc.node_count();
  if (dofs > spectrum_max_dofs)
    throw InputError(fmt::format("stiffness eigenvalues: {} DOFs, the dense eigenvalue solve takes at most {}; "
                                 "use a coarser node spacing",
                                 dofs, spectrum_max_dofs));
  ElasticityProblem free = problem;
  free.conditions.clear();
  free.body_force = {};
  const ElasticitySystem sys =
      assemble_elasticity(free, domain, disc.node_count(), disc.quadrature, disc.test(), disc.boundary, disc.at_boundary);
  const Eigen::MatrixXd k = Eigen::MatrixXd(sys.stiffness);
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(0.5 * (k + k.transpose()), Eigen::EigenvaluesOnly);
  if (eig.info() != Eigen::Success) throw NumericalError("stiffness eigenvalues: the dense eigenvalue solve failed");
  const Eigen::VectorXd& lambda = eig.eigenvalues();  // ascending
  StiffnessSpectrum out;
  out.largest = lambda[dofs - 1];
  for (Index i = 0; i < dofs; ++i) {
    if (i < count) out.smallest.push_back(lambda[i] / out.largest);
    if (lambda[i] < zero_tolerance * out.largest) ++out.zero_modes;
  }
  return out;
}

}  // namespace mfree
