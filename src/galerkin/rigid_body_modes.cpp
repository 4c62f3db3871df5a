#include "mfree/galerkin/rigid_body_modes.hpp"

#include <fmt/format.h>

#include <Eigen/Eigenvalues>
#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/linalg/rigid_body_modes.hpp"

namespace mfree {

namespace {
constexpr double free_below = 1e-9;
}

template <int dim>
RigidBodyEnergy<dim> rigid_body_energy(const SparseMatrix& k, const std::vector<Point<dim>>& nodes) {
  constexpr int m = RigidBodyEnergy<dim>::count;
  Point<dim> c = Point<dim>::Zero();
  for (const Point<dim>& x : nodes) c += x;
  c /= static_cast<double>(nodes.size());
  Eigen::MatrixXd r = rigid_body_modes<dim>(nodes, dim, c);
  for (int j = 0; j < m; ++j) r.col(j).normalize();
  const Eigen::MatrixXd kr = k * r;
  Eigen::Matrix<double, m, m> g = r.transpose() * kr;
  g = 0.5 * (g + g.transpose()).eval();
  double scale = 0.0;
  for (Eigen::Index i = 0; i < k.rows(); ++i) scale = std::max(scale, std::abs(k.coeff(i, i)));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, m, m>> eig(g);
  return {eig.eigenvalues() / scale, eig.eigenvectors()};
}

template <int dim>
void check_rigid_body_modes(const SparseMatrix& k, const std::vector<Point<dim>>& nodes) {
  constexpr int m = RigidBodyEnergy<dim>::count;
  const RigidBodyEnergy<dim> e = rigid_body_energy(k, nodes);
  // A negative energy is no free mode but an indefinite system (a Nitsche penalty too
  // small): the factorisation refuses that with its own message.
  int free = -1;
  for (int j = 0; j < m && free < 0; ++j)
    if (std::abs(e.eigenvalues[j]) < free_below) free = j;
  if (free < 0) return;
  const Eigen::Matrix<double, m, 1> v = e.modes.col(free);
  std::string mode;
  for (int j = 0; j < m; ++j)
    if (std::abs(v[j]) > 0.1)
      mode += fmt::format("{}{:.2f} {}", mode.empty() ? "" : " + ", v[j], rigid_body_mode_name<dim>(j));
  throw InputError(fmt::format(
      "the problem is not well posed: its essential conditions leave a rigid-body motion free ({}; energy {:.2e} of "
      "the stiffness scale): add displacement or slip conditions that stop it (for example a slip wall on a second, "
      "non-parallel edge, or a displacement condition)",
      mode, e.eigenvalues[free]));
}

template RigidBodyEnergy<2> rigid_body_energy(const SparseMatrix&, const std::vector<Point<2>>&);
template RigidBodyEnergy<3> rigid_body_energy(const SparseMatrix&, const std::vector<Point<3>>&);
template void check_rigid_body_modes(const SparseMatrix&, const std::vector<Point<2>>&);
template void check_rigid_body_modes(const SparseMatrix&, const std::vector<Point<3>>&);

}  // namespace mfree
