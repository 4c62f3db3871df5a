#pragma once
// A check that a static problem is well posed: its essential conditions must remove every
// rigid-body motion. RK functions reproduce linear fields, so the coefficient vectors
//   t_x: d_I = (1, 0),  t_y: d_I = (0, 1),  r: d_I = (-(y_I - c_y), x_I - c_x)
// (c the nodes' centroid) are exactly the motions u^h = e_x, e_y and the infinitesimal
// rotation about c. The domain stiffness gives them zero energy (to round-off); only Nitsche's
// penalty terms of displacement and slip conditions can. With R = [t_x t_y r] normalised, a
// well-posed problem has every eigenvalue of the 3 x 3 matrix sym(R^T K R) well above
// round-off of K; a mode below 1e-9 max_i K_ii is free, and the solve would return an
// arbitrary multiple of it (a slip wall on one edge "solves" to u ~ 1e14).

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/linalg/linear_solver.hpp"

namespace mfree {

struct RigidBodyEnergy {
  Eigen::Vector3d eigenvalues;  ///< of sym(R^T K R), ascending, relative to max_i K_ii
  Eigen::Matrix3d modes;        ///< columns: the eigenvectors in (t_x, t_y, r)
};

/// The energies of the rigid-body motions of the 2N x 2N stiffness k on `nodes`.
RigidBodyEnergy rigid_body_energy(const SparseMatrix& k, const std::vector<Vec2>& nodes);

/// Throws InputError naming the free motion (e.g. "translation in x") when k leaves one free.
void check_rigid_body_modes(const SparseMatrix& k, const std::vector<Vec2>& nodes);

}  // namespace mfree
