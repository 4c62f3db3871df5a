#include "mfree/galerkin/rigid_body_modes.hpp"

#include <Eigen/Eigenvalues>
#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {
constexpr double free_below = 1e-9;
}

RigidBodyEnergy rigid_body_energy(const SparseMatrix& k, const std::vector<Vec2>& nodes) {
  const Eigen::Index n = static_cast<Eigen::Index>(nodes.size());
  Vec2 c = Vec2::Zero();
  for (const Vec2& x : nodes) c += x;
  c /= static_cast<double>(n);
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(2 * n, 3);
  for (Eigen::Index i = 0; i < n; ++i) {
    r(2 * i, 0) = 1.0;
    r(2 * i + 1, 1) = 1.0;
    r(2 * i, 2) = -(nodes[i].y() - c.y());
    r(2 * i + 1, 2) = nodes[i].x() - c.x();
  }
  for (int j = 0; j < 3; ++j) r.col(j).normalize();
  const Eigen::MatrixXd kr = k * r;
  Eigen::Matrix3d g = r.transpose() * kr;
  g = 0.5 * (g + g.transpose()).eval();
  double scale = 0.0;
  for (Eigen::Index i = 0; i < k.rows(); ++i) scale = std::max(scale, std::abs(k.coeff(i, i)));
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(g);
  return {eig.eigenvalues() / scale, eig.eigenvectors()};
}

void check_rigid_body_modes(const SparseMatrix& k, const std::vector<Vec2>& nodes) {
  const RigidBodyEnergy e = rigid_body_energy(k, nodes);
  // A negative energy is no free mode but an indefinite system (a Nitsche penalty too
  // small): the factorisation refuses that with its own message.
  int free = -1;
  for (int j = 0; j < 3 && free < 0; ++j)
    if (std::abs(e.eigenvalues[j]) < free_below) free = j;
  if (free < 0) return;
  const Eigen::Vector3d v = e.modes.col(free);
  const char* names[] = {"translation in x", "translation in y", "rotation"};
  std::string mode;
  for (int j = 0; j < 3; ++j)
    if (std::abs(v[j]) > 0.1) mode += fmt::format("{}{:.2f} {}", mode.empty() ? "" : " + ", v[j], names[j]);
  throw InputError(fmt::format(
      "the problem is not well posed: its essential conditions leave a rigid-body motion free ({}; energy {:.2e} of "
      "the stiffness scale): add displacement or slip conditions that stop it (for example a slip wall on a second, "
      "non-parallel edge, or a displacement condition)",
      mode, e.eigenvalues[free]));
}

}  // namespace mfree
