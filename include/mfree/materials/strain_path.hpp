#pragma once
// One material point driven along a prescribed deformation gradient F(t), with no solver:
// the material-point test of plasticity texts (uniaxial strain through yield and back,
// tension then shear) and the check of a law's integration against closed forms
// (verification/material-point/).
//
// The path t -> F(t), t in [0, t_end], is cut into N equal increments, t_n = n t_end / N,
// and each increment is one update of the law (material.hpp), the update a solver's point
// makes once its step is accepted:
//
//   (P_n, sigma_zz,n, state_n) = update(m, F(t_n), state_{n-1}),   state_{-1} = virgin,
//
// with state_n committed at once (F is prescribed, not solved for: there is no iteration).
// For the plastic laws that is the return mapping of Simo & Hughes 1998, Box 3.2 (backward
// Euler of the flow rule): exact for any increment on a radial path with linear hardening,
// first order in the increment on any other path. Increment 0 is the update at F(0) from the
// virgin state: a path should start at F(0) = I (one that does not begins with a jump there).
//
// Units and conventions: F = dx/dX dimensionless, F(i, J) row i (current), column J
// (reference); plane strain (F_zz = 1). t is the path's own parameter (the laws are
// rate-independent: only the sequence of F matters). Stresses are in the unit of the law's
// moduli (Pa, or MPa when E is given in MPa); energies are per unit reference volume in that
// unit. P is the first Piola–Kirchhoff stress (force per reference area; the small-strain
// laws' P is sigma), sigma the Cauchy stress P F^T / J, sigma_zz the out-of-plane Cauchy stress.

#include <cstddef>
#include <functional>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/materials/material.hpp"

namespace mfree {

/// F(t): the deformation gradient at path time t (dimensionless, 2 x 2).
using DeformationPath = std::function<Mat2(double)>;

struct StrainPathSettings {
  double end_time = 1.0;  ///< t_end > 0
  int increments = 1;     ///< N >= 1 equal increments, t_n = n t_end / N
  int record_every = 1;   ///< k >= 1: increments 0, k, 2k, ... are recorded, and always N

  /// InputError for t_end not positive and finite, N < 1 or k < 1.
  void validate() const;
  /// How many increments run_strain_path records: floor(N / k) + 1, plus 1 when k does not
  /// divide N.
  [[nodiscard]] std::size_t recorded() const;
};

/// The point after one recorded increment.
struct PathRecord {
  int increment = 0;                    ///< n
  double time = 0.0;                    ///< t_n
  Mat2 deformation = Mat2::Identity();  ///< F(t_n)
  Mat2 first_piola = Mat2::Zero();      ///< P
  Mat2 cauchy = Mat2::Zero();           ///< sigma = cauchy_stress(m, P, F)
  double stress_zz = 0.0;               ///< sigma_zz
  MaterialState<2> state;               ///< after the update: E_p, alpha, plastic work
  double stored_energy = 0.0;           ///< energy(m, F, state): the elastic energy stored
};

/// Runs the path (above) and returns the recorded increments in order. Memory: the recorded
/// rows only (reserved before the first increment; no allocation per increment).
/// InputError for bad settings or when the rows would not fit the memory; NumericalError,
/// naming the increment and its time, when F or the stress is not finite or the law fails
/// (J <= 0, a return mapping that does not converge).
std::vector<PathRecord> run_strain_path(const Material& m, const DeformationPath& path, const StrainPathSettings& s);

}  // namespace mfree
