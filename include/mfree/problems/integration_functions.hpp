#pragma once
// The integrands of the integration-accuracy study (seed 003, SPEC section 2), each with its
// exact integral over the rectangle [x0, x0 + Lx] x [y0, y0 + Ly]. With (s, t) = (x - x0,
// y - y0) and (u, v) measured from the centre:
//
//   f1 = sin(pi s / Lx) sin(pi t / Ly)                 integral 4 Lx Ly / pi^2
//   f2 = [1 - (2 u / Lx)^2] [1 - (2 v / Ly)^2]         integral 4 Lx Ly / 9
//
// On the 2 x 1 rectangle f1 is seed 003's sin(pi x / 2) sin(pi y) in corner coordinates:
// written in centred coordinates it would be odd in x and y, integrate to zero, and
// symmetric clouds would integrate it exactly by symmetry alone, which measures nothing.

#include <functional>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"

namespace mfree {

struct Integrand {
  std::function<double(const Vec2&)> f;
  double integral = 0.0;  ///< exact, over the rectangle
};

using IntegrandOn = std::function<Integrand(const Box& rectangle)>;

/// f1, f2.
const NameTable<IntegrandOn>& integration_functions();

}  // namespace mfree
