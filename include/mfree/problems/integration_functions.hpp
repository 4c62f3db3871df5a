#pragma once
// The integrands of the integration-accuracy study (seed 003, SPEC section 2), each with its
// exact integral over the box [lo, hi] = [lo, lo + L] (a rectangle in the plane, a box in space). With s_i
// = x_i - lo_i and u_i measured from the centre:
//
//   f1 = prod_i sin(pi s_i / L_i)               integral prod_i 2 L_i / pi  (4 Lx Ly / pi^2)
//   f2 = prod_i [1 - (2 u_i / L_i)^2]           integral prod_i 2 L_i / 3   (4 Lx Ly / 9)
//
// On the 2 x 1 rectangle f1 is seed 003's sin(pi x / 2) sin(pi y) in corner coordinates:
// written in centred coordinates it would be odd in x and y, integrate to zero, and
// symmetric clouds would integrate it exactly by symmetry alone, which measures nothing. On a
// solid that is not a box, the same functions of its bounding box are integrated, against the
// integral over its tetrahedra (apps/integration_study.hpp).

#include <functional>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"

namespace mfree {

template <int dim>
struct IntegrandOf {
  std::function<double(const Point<dim>&)> f;
  double integral = 0.0;  ///< exact, over the box
};
using Integrand = IntegrandOf<2>;

/// A named integrand over the box [lo, hi].
template <int dim>
using IntegrandOn = std::function<IntegrandOf<dim>(const Point<dim>& lo, const Point<dim>& hi)>;

/// f1, f2 (dim = 2 or 3).
template <int dim>
const NameTable<IntegrandOn<dim>>& integration_functions();

}  // namespace mfree
