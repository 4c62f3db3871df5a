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

namespace {

/// The Lamé constants of the 3D law; InputError for the plane-stress model.
Lame solid_constants(const LinearElastic& law) {
  if (law.model == PlaneModel::stress)
    throw InputError(
        "linear elastic material: the plane-stress law has no 3D form (a solid takes the 3D law, "
        "whose plane reduction is plane strain)");
  return lame_constants(law.youngs_modulus, law.poisson_ratio);
}

Tensor2<3> small_strain(const Tensor2<3>& f) { return 0.5 * (f + f.transpose()) - Tensor2<3>::Identity(); }

}  // namespace

double LinearElastic::energy(const Tensor2<3>& f) const {
  const Lame l = solid_constants(*this);
  const Tensor2<3> e = small_strain(f);
  return 0.5 * l.lambda * e.trace() * e.trace() + l.mu * e.cwiseProduct(e).sum();
}

Tensor2<3> LinearElastic::stress(const Tensor2<3>& f) const {
  const Lame l = solid_constants(*this);
  const Tensor2<3> e = small_strain(f);
  return l.lambda * e.trace() * Tensor2<3>::Identity() + 2.0 * l.mu * e;
}

Tangent<3> LinearElastic::tangent(const Tensor2<3>&) const {
  const Lame l = solid_constants(*this);
  Tangent<3> a;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k)
        for (int m = 0; m < 3; ++m)
          a(tensor_index<3>(i, j), tensor_index<3>(k, m)) =
              l.lambda * (i == j) * (k == m) + l.mu * ((i == k) * (j == m) + (i == m) * (j == k));
  return a;
}

}  // namespace mfree
