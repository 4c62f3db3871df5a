#include "mfree/materials/j2_plasticity.hpp"

#include <fmt/format.h>

#include <cmath>

#include "j2_return.hpp"
#include "mfree/core/error.hpp"

namespace mfree {

double J2Plasticity::flow_stress(double alpha) const {
  double k, dk;
  plastic::J2Return{*this}.flow(alpha, k, dk);
  return k;
}

void J2Plasticity::validate() const {
  if (kinematics == Kinematics::multiplicative && kinematic_modulus != 0.0)
    throw InputError("J2 plasticity: kinematic hardening needs kinematics = \"logarithmic\" or \"small_strain\" (the "
                     "multiplicative state holds C_p^-1, not a plastic strain for the back stress)");
  if (!(yield_stress > 0.0) || !std::isfinite(yield_stress))
    throw InputError(fmt::format("J2 plasticity: the yield stress must be positive, got {}", yield_stress));
  if (!(isotropic_modulus >= 0.0) || !(kinematic_modulus >= 0.0) || !(saturation_rate >= 0.0))
    throw InputError(fmt::format("J2 plasticity: hardening moduli and the saturation rate must be >= 0, got {}, {}, {}",
                                 isotropic_modulus, kinematic_modulus, saturation_rate));
  if (saturation_stress != 0.0 && !(saturation_stress >= yield_stress))
    throw InputError(fmt::format("J2 plasticity: the saturation stress {} is below the yield stress {}",
                                 saturation_stress, yield_stress));
}

template double J2Plasticity::energy(const Tensor2<2>&, const MaterialState<2>&) const;
template MaterialUpdate<2> J2Plasticity::update(const Tensor2<2>&, const MaterialState<2>&, bool) const;

}  // namespace mfree
