#include "mfree/materials/linear_elastic.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

std::string_view to_string(PlaneModel model) { return model == PlaneModel::stress ? "plane_stress" : "plane_strain"; }

void LinearElastic::validate() const {
  if (!(youngs_modulus > 0.0) || !std::isfinite(youngs_modulus))
    throw InputError(fmt::format("linear elastic material: Young's modulus must be positive, got {}",
                                 youngs_modulus));
  if (!(poisson_ratio > -1.0 && poisson_ratio < 0.5))
    throw InputError(fmt::format("linear elastic material: Poisson's ratio must lie in (-1, 1/2), "
                                 "got {}",
                                 poisson_ratio));
}

}  // namespace mfree
