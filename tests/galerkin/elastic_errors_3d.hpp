#pragma once
// The rates of the 3D convergence studies: the errors are the library's (galerkin/
// small_strain_errors.hpp); the observed rates between the last two of a sequence of spacings.
#include <cmath>
#include <vector>

#include "mfree/galerkin/small_strain_errors.hpp"

namespace mfree::testing {

using ElasticErrors = SmallStrainErrors;

/// The observed rates of the L2 and energy errors between the last two spacings.
inline ElasticErrors last_rates(const std::vector<double>& spacings, const std::vector<ElasticErrors>& e) {
  const std::size_t n = spacings.size() - 1;
  const double ratio = std::log(spacings[n - 1] / spacings[n]);
  return {std::log(e[n - 1].l2 / e[n].l2) / ratio, std::log(e[n - 1].energy / e[n].energy) / ratio};
}

}  // namespace mfree::testing
