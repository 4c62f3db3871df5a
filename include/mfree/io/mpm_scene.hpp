#pragma once
// MPM scenes: the scene format of elasticity scenes with an [mpm] section in place of
// [domain], [nodes], [kernel] and [quadrature] (see verification/mpm-*/*.toml):
//
//   [mpm]         method (classic | ugimp | cpgimp | cpdi | qcpdi | cpdi2 | bspline |
//                 bspline_cubic | bspline_cpgimp | bspline_cpgimp_cubic | bspline_mls;
//                 mpm/particle_basis.hpp),
//                 update (usf | usl | szs | usavg | verlet), mapping (lumped |
//                 pseudo_inverse: particle data to nodal values, mpm/mass_matrix.hpp),
//                 box = [[x0, y0], [x1, y1]] (the grid box), cells (across its width; square
//                 cells, the height a whole number of them),
//                 particles_per_cell (1, 4, 9, 16, 25; default 4, for bodies stating none),
//                 walls = {left = "slip", right = "open", bottom = "fixed", top = "open"}
//                 (open | slip | fixed per side; a side not listed is open),
//                 gravity = [gx, gy] (body force per unit mass [m/s^2]; numbers or formulas
//                 in X, Y, t), damping (alpha [1/s] of the mass-proportional grid damping
//                 -alpha m_i v_i; default 0), mls_basis (linear | quadratic, default
//                 linear) and mls_support (kernel half width in cells, default 1.5) of
//                 bspline_mls (seed 000: linear, 3), deformation_terms (kmax of the dF
//                 series, default 2)
//   [constants]   names for the formulas (optional)
//   [[material]]  name, and the keys of an elasticity scene's [material]; density required.
//                 Every material must be used by a body. Laws with history too (the
//                 particles carry their state): model = "j2" with yield_stress,
//                 isotropic_modulus, kinematic_modulus, saturation_stress and saturation_rate
//                 (materials/j2_plasticity.hpp); model = "drucker_prager" with friction_angle,
//                 dilatancy_angle (degrees), cohesion, tension_cutoff
//                 (materials/drucker_prager.hpp); both with kinematics = "multiplicative"
//                 (default: F = F_e F_p, Kirchhoff stress, for flows of unbounded shear),
//                 "logarithmic" (additive in 1/2 ln C, moderate strains, kinematic
//                 hardening) or "small_strain" (src/materials/plastic_update.hpp).
//   [[body]]      name (distinct), material (a [[material]] name), shape:
//                   rectangle: box = [[x0, y0], [x1, y1]]
//                   circle:    centre = [x, y], radius
//                   polygon:   wkt = a WKT file, relative to the scene (geometry/domain.hpp)
//                 velocity = [vx, vy] (numbers or formulas in X, Y; default at rest),
//                 particles_per_cell (default [mpm]'s). Bodies lie in the grid box and do not
//                 overlap (mpm/body.hpp); each must get particles.
//   [exact]       solution = a built-in motion (problems/builtin_solutions.hpp; vibration:
//                 amplitude) (optional): initial velocity, body force and the errors come
//                 from it; needs one rectangle body filling the grid box, with no velocity of
//                 its own and no gravity (the motion says what else it needs)
//   [dynamics]    end_time, time_step, courant (default 0.5), allow_unstable_time_step,
//                 frames, error_times (fractions of end_time), energy_every (steps between
//                 energy records, 0: none; absent: about 500 records in a single run, so that
//                 its energy balance is checked, and none in a study)
//   [output]      folder, fields (displacement, velocity, stress, von_mises, plastic_strain, body, error,
//                 grid, domains: the particle domains, for the methods with domains), vtk,
//                 particles_csv (true: particles.csv of the end state, mpm_output.hpp),
//                 checkpoint_every (steps between checkpoints, io/checkpoint.hpp; 0: none; not in a study),
//                 probe = [X, Y] (a material point inside a body: u^h there every step,
//                 mpm/particle_probe.hpp; a study without [exact] compares it between grids)
//   [study]       for `mfree converge`: cells, methods, updates, mappings, particles_per_cell; without
//                 [exact], the probe's displacement at end_time per grid, its change, observed
//                 rate and extrapolated value
//
// Every key is type- and range-checked; unknown keys are errors (scene_reader.hpp).

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mfree/io/mpm_output.hpp"
#include "mfree/core/exact_motion.hpp"
#include "mfree/mpm/mpm_solver.hpp"

namespace mfree {

/// The scene's name of a method (mpm/particle_basis.hpp: mpm_method_names()).
std::string method_name(const MPMMethodChoice& m);
/// The method of a run's settings, as a scene names it.
MPMMethodChoice method_of(const MPMSettings& s);

struct MPMStudy {
  std::vector<int> cells;
  std::vector<MPMMethodChoice> methods;
  std::vector<UpdateScheme> updates;
  std::vector<GridMapping> mappings;
  std::vector<int> particles_per_side;
};

struct MPMScene {
  std::filesystem::path file;
  MPMProblem problem;
  MPMSettings settings;
  std::optional<ExactMotion<2>> exact;  ///< of [exact]
  int frames = 0;                   ///< VTK frames over the run (plus t = 0)
  std::vector<double> error_times;  ///< fractions of end_time (with [exact])
  int energy_every = -1;            ///< steps between energy records (0: none; -1: not given)
  std::filesystem::path folder;
  MPMFrameFields fields;
  bool vtk = true;
  bool particles_csv = false;  ///< particles.csv at the end
  int checkpoint_every = 0;    ///< steps between checkpoints (0: none)
  std::optional<Vec2> probe;   ///< reference position X of the probe
  std::optional<MPMStudy> study;
};

/// True when the scene file has an [mpm] section (then `mfree run` takes this path).
bool is_mpm_scene(const std::filesystem::path& file);

/// Parses and checks an MPM scene; `want_study` makes [study] required (mfree converge);
/// `overrides` as Scene::load.
MPMScene read_mpm_scene(const std::filesystem::path& file, bool want_study,
                        const std::vector<std::string>& overrides = {});

}  // namespace mfree
