#pragma once
// VTK frames of an MPM run, for ParaView: particles_NNNN.vtu with one vertex per particle at
// its current position x_p and, when asked, grid_NNNN.vti with fields of the background grid
// on a uniform image. series.pvd lists the particle frames and grid.pvd the grid frames, each
// with the solver's time; both are rewritten after every frame, so a run stopped early
// leaves valid series of the frames written so far. Only the fields asked for are computed:
//
// At the particles
//   displacement        x_p - X_p
//   velocity            v_p
//   stress              Cauchy stress sigma_p (xx, yy, xy)
//   von_mises           of sigma_p with the particle's sigma_zz
//   plastic_strain      the equivalent plastic strain of the particle's state (plastic laws)
//   body                the index of the particle's body (0, 1, ... in the scene's order)
//   displacement_error  (x_p - X_p) - u(X_p, t)    } against the exact motion ("error";
//   stress_error        sigma_p - sigma(X_p, t)     } needs one)
//
// The particle domains ("domains"; methods with domains only, particle_basis.hpp), in
// domains_NNNN.vtu listed by domains.pvd: one quadrilateral cell per particle, its domain as
// the method sees it (uGIMP's translated square, cpGIMP's stretched rectangle, the CPDIs'
// parallelogram F_p r0, CPDI2's tracked corners), corners counter-clockwise and not shared
// between particles (4 points per particle), with the particle's body index at its corners.
//
// On the grid ("grid"), at the (cells + 1)^2 corners of the cells of the grid's extent
// (padding included), spacing h:
//   velocity  the grid velocity field v^h(x) = sum_i N_i(x) v_i, not the nodal coefficients
//             (which sit at Greville points, not at the corners; the two differ for B-splines)
//   mass      sum_i N_i(x) m_i / h^2: an indication of the mass density, not the density
//             itself. Away from the body's edges it is close to rho; it falls towards the
//             edges (the boundary functions of open knot vectors have smaller integrals) and
//             is zero where no particle reaches.
// The grid holds values only once the solver has stepped: a frame written before the first
// step has no grid file (its number is skipped in grid.pvd), so grid_NNNN and
// particles_NNNN with the same NNNN are always the same instant.

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "mfree/io/checkpoint.hpp"
#include "mfree/materials/material.hpp"
#include "mfree/core/exact_motion.hpp"
#include "mfree/mpm/mpm_solver.hpp"

namespace mfree {

/// The particles as a CSV table for scripts, one row per particle:
/// body (name), X, Y (reference position), x, y, vx, vy, sxx, syy, sxy (Cauchy stress).
/// NumericalError for a non-finite value (never written).
std::string particle_table(const Particles& particles, const std::vector<MPMBody>& bodies);

/// Which fields MPMFrames writes (see above).
struct MPMFrameFields {
  bool displacement = false;
  bool velocity = false;
  bool stress = false;
  bool von_mises = false;
  bool plastic_strain = false;  ///< the equivalent plastic strain alpha (plastic laws)
  bool body = false;   ///< the body index per particle
  bool error = false;  ///< displacement_error and stress_error
  bool grid = false;   ///< grid_NNNN.vti with velocity and mass
  bool domains = false;  ///< domains_NNNN.vtu with the particle domains
};

class MPMFrames {
 public:
  /// Frames into `folder`, created if missing (Error when it cannot be). exact: the motion
  /// errors are measured against; may be null, but then fields.error is an InputError.
  /// materials: the problem's (particles index them), for sigma_zz in von_mises.
  MPMFrames(std::filesystem::path folder, MPMFrameFields fields, const ExactMotion<2>* exact,
            std::vector<MPMMaterial> materials);

  /// Writes frame number frames() at solver.time() and rewrites the series. Errors as the
  /// writers of vtk_output.hpp (NumericalError for a non-finite value, naming the field).
  void write(const MPMSolver& solver);

  [[nodiscard]] int frames() const { return static_cast<int>(steps_.size()); }
  /// Checkpoints: the series written so far ("frames.time", "frames.grid"; the domain
  /// series has a file at every frame), and continuing them (the files themselves come back
  /// with the checkpoint's output folder). restore() takes at most `most` frames at times in
  /// [0, time], in order, and grid flags of 0 or 1 (InputError otherwise, io/checkpoint.hpp).
  void save(CheckpointState& state) const;
  void restore(const CheckpointState& state, double time, std::size_t most);
  [[nodiscard]] std::filesystem::path series() const { return folder_ / "series.pvd"; }
  [[nodiscard]] std::filesystem::path grid_series() const { return folder_ / "grid.pvd"; }
  [[nodiscard]] std::filesystem::path domain_series() const { return folder_ / "domains.pvd"; }

 private:
  void write_grid(const MPMSolver& solver, const std::string& name);
  void write_domains(const MPMSolver& solver, const std::string& name) const;

  std::filesystem::path folder_;
  MPMFrameFields fields_;
  const ExactMotion<2>* exact_;
  std::vector<MPMMaterial> materials_;
  std::vector<std::pair<double, std::string>> steps_, grid_steps_, domain_steps_;
};

}  // namespace mfree
