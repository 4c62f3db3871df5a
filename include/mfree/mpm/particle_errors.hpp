#pragma once
// Errors of an MPM run against an exact motion: root-mean-square values over the
// particles (seed 000 eq. 43), each particle's exact value taken at its reference position
// X_p and the current time,
//
//   e_u = ( sum_p |(x_p - X_p) - u(X_p, t)|^2 / N_p )^1/2
//   e_v = ( sum_p |v_p - v(X_p, t)|^2 / N_p )^1/2        v_p the particle's own (FLIP) velocity
//   e_vg: the same with sum_i S_ip v_i, the grid velocity at the particle
//   e_s = ( sum_p |sigma_p - sigma(X_p, t)|_F^2 / N_p )^1/2   (Frobenius norm)
//
// The particles are the method's own sample of the body; seed 000 and the CPDI study measure
// there, so the figures compare with theirs.

#include "mfree/core/exact_motion.hpp"
#include "mfree/mpm/mpm_solver.hpp"

namespace mfree {

struct ParticleErrors {
  double time = 0.0;
  double displacement = 0.0;   ///< m
  double velocity = 0.0;       ///< m/s, particle (FLIP) velocity
  double grid_velocity = 0.0;  ///< m/s, grid velocity interpolated to the particles
  double stress = 0.0;         ///< Pa
};

ParticleErrors particle_errors(const MPMSolver& solver, const ExactMotion<2>& exact);

}  // namespace mfree
