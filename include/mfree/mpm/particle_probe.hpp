#pragma once
// The displacement of an MPM run at one material point X (a probe), as a field rather than
// one particle's value: with the linear reproducing-kernel functions phi_p of the particles'
// reference positions (kernels/, cubic B-spline window, support radius 2 x the particle
// spacing),
//
//   u^h(X, t) = sum_p phi_p(X) (x_p(t) - X_p),
//
// which reproduces any linear displacement field exactly and does not jump from level to
// level as the particle nearest to X would in a refinement study. The functions are
// evaluated once (reference positions do not move). Units: those of the positions [m].

#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/mpm/particles.hpp"

namespace mfree {

class ParticleProbe {
 public:
  /// spacing: the particles' spacing (cell size / particles per side; the largest over the
  /// bodies). InputError when X lies where the particles cannot represent a linear field
  /// (outside the bodies, or too few particles around it), naming X.
  ParticleProbe(const Particles& particles, const Vec2& X, double spacing);

  [[nodiscard]] const Vec2& point() const { return point_; }
  /// u^h(X) of the particles' current positions.
  [[nodiscard]] Vec2 displacement(const Particles& particles) const;

 private:
  Vec2 point_;
  std::vector<Index> particles_;
  std::vector<double> phi_;
};

}  // namespace mfree
