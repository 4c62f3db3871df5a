#include "mfree/mpm/particle_probe.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/kernels/rk_shape_functions.hpp"

namespace mfree {

ParticleProbe::ParticleProbe(const Particles& particles, const Vec2& X, double spacing) : point_(X) {
  RKSettings s;
  s.radius = 2.0 * spacing;
  const RKShapeFunctions<2> rk(particles.reference, s);
  ShapeValues<2> v;
  try {
    rk.evaluate(X, v, false);
  } catch (const NumericalError& e) {
    throw InputError(fmt::format("probe ({:.6g}, {:.6g}): the particles around it cannot represent the displacement "
                                 "there (is it inside a body?): {}",
                                 X.x(), X.y(), e.what()));
  }
  particles_ = v.nodes;
  phi_ = v.phi;
}

Vec2 ParticleProbe::displacement(const Particles& P) const {
  Vec2 u = Vec2::Zero();
  for (std::size_t k = 0; k < particles_.size(); ++k) u += phi_[k] * (P.position[particles_[k]] - P.reference[particles_[k]]);
  return u;
}

}  // namespace mfree
