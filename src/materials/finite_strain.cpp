#include "mfree/materials/finite_strain.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

double checked_jacobian(const Mat2& f, const char* model) {
  const double j = f.determinant();
  if (!(j > 0.0))
    throw NumericalError(fmt::format(
        "{} material: J = det F = {:.4g} <= 0 (F = [[{:.4g}, {:.4g}], [{:.4g}, {:.4g}]]): the material "
        "is inverted",
        model, j, f(0, 0), f(0, 1), f(1, 0), f(1, 1)));
  return j;
}

}  // namespace mfree
