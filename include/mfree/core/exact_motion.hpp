#pragma once
// The interface of an exact motion, as the error measures of both solvers see it: fields of
// the reference position X and the time t. The concrete motions are problems (problems/).

#include <functional>

#include "mfree/core/types.hpp"

namespace mfree {

struct ExactMotion {
  std::function<Vec2(const Vec2&, double)> displacement;   ///< u(X, t)
  std::function<Vec2(const Vec2&, double)> velocity;       ///< v(X, t)
  std::function<Mat2(const Vec2&, double)> cauchy_stress;  ///< sigma(X, t)
  std::function<Vec2(const Vec2&, double)> body_force;  ///< b(X, t) per unit mass, rho0 u_tt = Div P + rho0 b
};

}  // namespace mfree
