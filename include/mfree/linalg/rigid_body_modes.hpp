#pragma once
// The rigid-body modes of a cloud of nodes: the motions an elastic body's stiffness gives
// zero energy, as coefficient vectors of its unknowns (node I's unknown c at row
// block_size I + c).
//
//   block_size == dim  the dim translations e_x, e_y (, e_z), then the infinitesimal rotations
//                      about `origin`: in 2D one, (-(y - o_y), x - o_x); in 3D three, about
//                      x: (0, -(z - o_z), y - o_y), about y: (z - o_z, 0, -(x - o_x)), about z:
//                      (-(y - o_y), x - o_x, 0): 3 modes in 2D, 6 in 3D.
//   block_size == 1    the linear functions 1, x - o_x, y - o_y (, z - o_z) of a scalar field.
//
// Algebraic multigrid takes them as its near-null space (linalg/krylov_solver.cpp, origin 0),
// the well-posedness check of a static problem measures their energies
// (galerkin/rigid_body_modes.hpp, origin the centroid).

#include <Eigen/Core>
#include <span>
#include <string_view>

#include "mfree/core/types.hpp"

namespace mfree {

/// The modes above as the columns of an (N block_size) x m matrix (m = 3 or 6 for
/// block_size == dim, 1 + dim for block_size == 1).
template <int dim>
Eigen::MatrixXd rigid_body_modes(std::span<const Point<dim>> nodes, int block_size, const Point<dim>& origin);

/// The name of column j of rigid_body_modes(nodes, dim, origin): "translation in x", ...,
/// "rotation" (2D), "rotation about x" ... (3D).
template <int dim>
std::string_view rigid_body_mode_name(int j);

}  // namespace mfree
