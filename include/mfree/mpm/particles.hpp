#pragma once
// Material points, stored field by field (one array per quantity, index p): the loops of a
// time step each touch a few fields of every particle.
//
// Units: mass [kg per unit thickness], volume [m^2 per unit thickness], positions [m],
// velocity [m/s], F dimensionless, Cauchy stress [Pa] (tension positive). Each particle
// belongs to one body and is made of one material (indices into the problem's lists).

#include <array>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/materials/material_state.hpp"

namespace mfree {

/// The four corners of a particle domain [m], counter-clockwise, c_0 the corner that starts
/// at (-l_x, -l_y) from the particle.
using DomainCorners = std::array<Vec2, 4>;

struct Particles {
  std::vector<double> mass;
  std::vector<double> volume0;     ///< reference volume V_p0
  std::vector<double> volume;      ///< current volume J V_p0
  std::vector<Vec2> reference;     ///< X_p, where the particle started
  std::vector<Vec2> position;      ///< x_p
  std::vector<Vec2> velocity;      ///< v_p, updated from grid accelerations (FLIP)
  std::vector<Mat2> deformation;   ///< F_p
  std::vector<Mat2> stress;        ///< Cauchy stress sigma_p
  std::vector<double> stress_zz;   ///< its out-of-plane component sigma_zz (plane strain)
  /// The material's history (plastic laws; materials/material_state.hpp), updated where the
  /// stress is: the solver fills it with virgin states when it is empty.
  std::vector<MaterialState<2>> state;
  /// Reference half sizes (l_x, l_y) of the particle domain: only for the methods whose
  /// weights need the domain (uses_domains() in particle_basis.hpp; empty otherwise).
  std::vector<Vec2> half_size;
  /// CPDI2 only (empty otherwise): the domain's corners, particles of their own moved with
  /// the grid velocity (mpm_solver.hpp); the solver seeds them from half_size and F when
  /// empty.
  std::vector<DomainCorners> corners;
  std::vector<int> body;      ///< index of the particle's body
  std::vector<int> material;  ///< index of the particle's material

  [[nodiscard]] Index size() const { return static_cast<Index>(mass.size()); }
};

/// "particle p (started at (X, Y))": a particle as messages name it, by its index and its
/// reference position X_p (finite whatever became of its current state).
std::string particle_name(const Particles& P, Index p);

/// per_side^2 particles in every cell of size h of the box, at the centres of a regular
/// per_side x per_side subdivision of the cell; mass density * volume, F = I, zero velocity
/// and stress, virgin material states, body 0 of material 0. with_domains fills half_size = (h / (2 per_side),
/// h / (2 per_side)). (Tests place blocks off the grid with it; scenes seed bodies,
/// mpm/body.hpp.)
/// Throws InputError for per_side outside [1, 5] or a box that is not a whole number of cells.
Particles fill_box(const Box& box, double h, int per_side, double density, bool with_domains);

}  // namespace mfree
