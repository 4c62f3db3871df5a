#include "mfree/mpm/particle_errors.hpp"

#include <cmath>

namespace mfree {

ParticleErrors particle_errors(const MPMSolver& solver, const ExactMotion<2>& exact) {
  const Particles& P = solver.particles();
  const double t = solver.time();
  const std::vector<Vec2> grid_v = solver.interpolated_grid_velocity();
  ParticleErrors e;
  e.time = t;
  for (Index p = 0; p < P.size(); ++p) {
    const Vec2& X = P.reference[p];
    const Vec2 v = exact.velocity(X, t);
    e.displacement += (P.position[p] - X - exact.displacement(X, t)).squaredNorm();
    e.velocity += (P.velocity[p] - v).squaredNorm();
    e.grid_velocity += (grid_v[p] - v).squaredNorm();
    e.stress += (P.stress[p] - exact.cauchy_stress(X, t)).squaredNorm();
  }
  const double n = P.size();
  e.displacement = std::sqrt(e.displacement / n);
  e.velocity = std::sqrt(e.velocity / n);
  e.grid_velocity = std::sqrt(e.grid_velocity / n);
  e.stress = std::sqrt(e.stress / n);
  return e;
}

}  // namespace mfree
