#include "mfree/linalg/rigid_body_modes.hpp"

#include <fmt/format.h>

#include <array>
#include <stdexcept>

namespace mfree {

template <int dim>
Eigen::MatrixXd rigid_body_modes(std::span<const Point<dim>> nodes, int block_size,
                                 const Point<dim>& origin) {
  const auto n = static_cast<Eigen::Index>(nodes.size());
  if (block_size == 1) {
    Eigen::MatrixXd r(n, 1 + dim);
    for (Eigen::Index i = 0; i < n; ++i) {
      r(i, 0) = 1.0;
      for (int c = 0; c < dim; ++c) r(i, 1 + c) = nodes[i][c] - origin[c];
    }
    return r;
  }
  if (block_size != dim)
    throw std::logic_error(fmt::format("rigid_body_modes: block size {} in {} dimensions", block_size, dim));
  constexpr int rotations = dim == 2 ? 1 : 3;
  Eigen::MatrixXd r = Eigen::MatrixXd::Zero(dim * n, dim + rotations);
  for (Eigen::Index i = 0; i < n; ++i) {
    const Point<dim> x = nodes[i] - origin;
    for (int c = 0; c < dim; ++c) r(dim * i + c, c) = 1.0;
    if constexpr (dim == 2) {
      r(2 * i, 2) = -x.y();
      r(2 * i + 1, 2) = x.x();
    } else {
      // omega x x for omega = e_x, e_y, e_z.
      r(3 * i + 1, 3) = -x.z(), r(3 * i + 2, 3) = x.y();
      r(3 * i, 4) = x.z(), r(3 * i + 2, 4) = -x.x();
      r(3 * i, 5) = -x.y(), r(3 * i + 1, 5) = x.x();
    }
  }
  return r;
}

template <int dim>
std::string_view rigid_body_mode_name(int j) {
  static constexpr std::array<std::string_view, 6> names3 = {"translation in x", "translation in y",
                                                             "translation in z", "rotation about x",
                                                             "rotation about y", "rotation about z"};
  static constexpr std::array<std::string_view, 3> names2 = {"translation in x", "translation in y",
                                                             "rotation"};
  if constexpr (dim == 2)
    return names2.at(j);
  else
    return names3.at(j);
}

template Eigen::MatrixXd rigid_body_modes(std::span<const Point<2>>, int, const Point<2>&);
template Eigen::MatrixXd rigid_body_modes(std::span<const Point<3>>, int, const Point<3>&);
template std::string_view rigid_body_mode_name<2>(int);
template std::string_view rigid_body_mode_name<3>(int);

}  // namespace mfree
