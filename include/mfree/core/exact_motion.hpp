#pragma once
// The interface of an exact motion, as the error measures of both solvers see it: fields of
// the reference position X and the time t, in dim = 2 (plane) or 3 dimensions. The concrete
// motions are problems (problems/).

#include <functional>

#include "mfree/core/types.hpp"

namespace mfree {

template <int dim>
struct ExactMotion {
  std::function<Point<dim>(const Point<dim>&, double)> displacement;     ///< u(X, t)
  std::function<Point<dim>(const Point<dim>&, double)> velocity;         ///< v(X, t)
  std::function<Tensor2<dim>(const Point<dim>&, double)> cauchy_stress;  ///< sigma(X, t)
  /// b(X, t) per unit mass, rho0 u_tt = Div P + rho0 b
  std::function<Point<dim>(const Point<dim>&, double)> body_force;
};

}  // namespace mfree
