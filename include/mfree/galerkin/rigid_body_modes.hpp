#pragma once
// A check that a static problem is well posed: its essential conditions must remove every
// rigid-body motion. RK functions reproduce linear fields, so the coefficient vectors of
// linalg/rigid_body_modes.hpp (in 2D t_x: d_I = (1, 0), t_y: d_I = (0, 1),
// r: d_I = (-(y_I - c_y), x_I - c_x), c the nodes' centroid; in 3D three translations and
// three rotations) are exactly the rigid motions of u^h. The domain stiffness gives them zero energy (to
// round-off); only Nitsche's penalty terms of displacement and slip conditions can. With R the modes
// normalised, a well-posed problem has every eigenvalue of the m x m matrix sym(R^T K R) (m = 3, 6) well
// above round-off of K; a mode below 1e-9 max_i K_ii is free, and the solve would return an arbitrary
// multiple of it (a slip wall on one edge "solves" to u ~ 1e14).

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

template <int dim>
struct RigidBodyEnergy {
  static constexpr int count = dim == 2 ? 3 : 6;
  Eigen::Matrix<double, count, 1> eigenvalues;  ///< of sym(R^T K R), ascending, relative to max_i K_ii
  Eigen::Matrix<double, count, count> modes;    ///< columns: the eigenvectors in the modes' order
};

/// The energies of the rigid-body motions of the (dim N) x (dim N) stiffness k on `nodes`.
template <int dim>
RigidBodyEnergy<dim> rigid_body_energy(const SparseMatrix& k, const std::vector<Point<dim>>& nodes);

/// Throws InputError naming the free motion (e.g. "translation in x") when k leaves one free.
template <int dim>
void check_rigid_body_modes(const SparseMatrix& k, const std::vector<Point<dim>>& nodes);

}  // namespace mfree
