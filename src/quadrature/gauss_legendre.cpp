#include <Eigen/Eigenvalues>
#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

namespace mfree {

GaussLegendre1D gauss_legendre(int n) {
  if (n < 1 || n > 64) throw InputError(fmt::format("Gauss–Legendre: need 1..64 points, got {}", n));
  // Golub–Welsch: the nodes on [-1, 1] are the eigenvalues of the Jacobi matrix of the
  // Legendre recurrence, off-diagonal k / sqrt(4k^2 - 1); weights are 2 v_0^2.
  Eigen::MatrixXd jacobi = Eigen::MatrixXd::Zero(n, n);
  for (int k = 1; k < n; ++k) {
    const double beta = k / std::sqrt(4.0 * k * k - 1.0);
    jacobi(k, k - 1) = jacobi(k - 1, k) = beta;
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(jacobi);
  GaussLegendre1D rule;
  for (int k = 0; k < n; ++k) {
    const double v0 = eig.eigenvectors()(0, k);
    rule.points.push_back(0.5 * (eig.eigenvalues()(k) + 1.0));  // map to [0, 1]
    rule.weights.push_back(v0 * v0);                            // 2 v0^2 / 2
  }
  return rule;
}

}  // namespace mfree
