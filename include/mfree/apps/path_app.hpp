#pragma once
// `mfree run SCENE` for material-point path scenes (io/path_scene.hpp): one material point
// along a prescribed F(t) (materials/strain_path.hpp).
//
//   build/mfree run verification/material-point/uniaxial.toml
//
// prints the law, the path and a table of the point every tenth of the path (t, F_yy, F_xy,
// sigma_xx, sigma_yy, sigma_xy, sigma_zz, alpha), and writes to the scene's output folder
//
//   path.csv      every recorded increment: time, F_xx, F_xy, F_yx, F_yy, sigma_xx, sigma_yy,
//                 sigma_xy, sigma_zz (Cauchy), alpha, Ep_xx, Ep_yy, Ep_xy, Ep_zz (plastic
//                 strain, plastic_strain() of materials/material.hpp: E_p, or 1/2 ln C_p with
//                 multiplicative kinematics), dissipation (plastic work per unit reference volume), stored_energy
//   summary.json  the run's summary (io/run_summary.hpp; kind "material_point_path")
//
// A failure on the way (J <= 0, a stress that is not finite) is a NumericalError naming the
// increment and its time; the output folder then keeps what it held (io/staged_folder.hpp).

#include <filesystem>
#include <string>
#include <vector>

#include "mfree/io/path_scene.hpp"

namespace mfree {

/// Reads the scene (`overrides` as Scene::load) and runs it in its staged output folder;
/// --restart is refused (a path has no checkpoints).
int run_path_scene(const std::filesystem::path& scene, const std::vector<std::string>& overrides = {},
                   const std::filesystem::path& restart = {});

/// The run of a scene that was read, writing into scene.folder.
int run_path(const PathScene& scene);

}  // namespace mfree
