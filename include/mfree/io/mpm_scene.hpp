#pragma once
// MPM scenes: the scene format of elasticity scenes with an [mpm] section in place of
// [nodes], [kernel] and [quadrature] (see verification/mpm-vibration/*.toml):
//
//   [domain]      rectangle = [[x0, y0], [x1, y1]]: the body fills it at t = 0; the grid
//                 covers it with square cells
//   [material]    as elasticity scenes; density is required
//   [exact]       solution = "vibration", amplitude (optional): initial velocity, body force
//                 and the errors come from it
//   [mpm]         method (classic | ugimp | cpdi | bspline | bspline_cubic | bspline_mls),
//                 update (usf | usl | szs | usavg), cells (across the width),
//                 particles_per_cell (1, 4, 9, 16, 25), mls_support (kernel half width in cells,
//                 bspline_mls), deformation_terms (kmax of the dF series, default 2),
//                 slip_walls (left, right, bottom, top), gravity = [gx, gy] and
//                 initial_velocity = [vx, vy] (without [exact])
//   [dynamics]    end_time, time_step, courant (default 0.5), allow_unstable_time_step,
//                 frames, error_times (fractions of end_time), energy_every (steps)
//   [output]      folder, fields (displacement, velocity, stress, von_mises, error, grid), vtk
//   [study]       for `mfree converge`: cells, methods, updates, particles_per_cell
//
// Every key is type- and range-checked; unknown keys are errors (scene_reader.hpp).

#include <filesystem>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "mfree/io/mpm_output.hpp"
#include "mfree/materials/vibration_solution.hpp"
#include "mfree/mpm/mpm_solver.hpp"

namespace mfree {

/// One method as a scene names it: the weights and, for B-splines, the degree.
struct MPMMethodChoice {
  MPMMethod method = MPMMethod::bspline;
  int degree = 2;
};
/// classic, ugimp, cpdi, bspline (quadratic), bspline_cubic, bspline_mls.
std::string method_name(const MPMMethodChoice& m);

struct MPMStudy {
  std::vector<int> cells;
  std::vector<MPMMethodChoice> methods;
  std::vector<UpdateScheme> updates;
  std::vector<int> particles_per_side;
};

struct MPMScene {
  std::filesystem::path file;
  MPMProblem problem;
  MPMSettings settings;
  std::optional<AxisAlignedVibration> vibration;
  int frames = 0;                   ///< VTK frames over the run (plus t = 0)
  std::vector<double> error_times;  ///< fractions of end_time (with [exact])
  int energy_every = 0;             ///< steps between energy records (0: none)
  std::filesystem::path folder;
  MPMFrameFields fields;
  bool vtk = true;
  std::optional<MPMStudy> study;
};

/// True when the scene file has an [mpm] section (then `mfree run` takes this path).
bool is_mpm_scene(const std::filesystem::path& file);

/// Parses and checks an MPM scene; `want_study` makes [study] required (mfree converge);
/// `overrides` as Scene::load.
MPMScene read_mpm_scene(const std::filesystem::path& file, bool want_study,
                        const std::vector<std::string>& overrides = {});

}  // namespace mfree
