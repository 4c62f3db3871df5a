// mfree: meshfree Galerkin solid mechanics and the Material Point Method.
//
// Usage:
//   mfree run SCENE.toml [--set KEY=VALUE]... [--restart DIR]
//                                               one elasticity solve, MPM run or material-point
//                                               path; --restart continues a run from its newest
//                                               checkpoint
//   mfree converge SCENE.toml [--set ...]       refinement study of an elasticity or MPM scene
//   mfree integration SCENE.toml [--out DIR]   integration-accuracy study (seed 003)
//   mfree --help | mfree SUBCOMMAND --help
//
// Exit codes (also in --help and README): 0 success, 1 bad input (a scene, a mesh, a file
// that cannot be read or written, not enough memory), 2 bad command line, 3 a numerical
// failure (a singular matrix, an inverted material, Newton not converging). The message on
// standard error says what and where. Every exception ends here with one of them: none
// reaches std::terminate.

#include <fmt/format.h>

#include <CLI/CLI.hpp>
#include <csignal>
#include <filesystem>
#include <iostream>
#include <new>

#include "mfree/apps/elasticity_app.hpp"
#include "mfree/apps/integration_study.hpp"
#include "mfree/apps/mpm_app.hpp"
#include "mfree/apps/path_app.hpp"
#include "mfree/apps/report.hpp"
#include "mfree/apps/solid_scene_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/interrupt.hpp"
#include "mfree/io/scene_reader.hpp"
#include "mfree/io/solid_scene.hpp"

namespace {

int run_integration(const std::filesystem::path& scene_path, const std::filesystem::path& out) {
  const mfree::Scene scene = mfree::Scene::load(scene_path);
  const mfree::IntegrationStudySettings settings = mfree::read_integration_study(scene.root());
  std::cout << fmt::format("mfree integration: {} ({} levels, {} thread(s))\n", scene_path.string(),
                           settings.levels.size(), mfree::thread_count());
  const auto rows = mfree::run_integration_study(settings, std::cout);
  const std::filesystem::path csv = out / "integration.csv";
  mfree::write_file_atomically(csv, mfree::integration_csv(rows));
  std::cout << '\n' << mfree::integration_report(rows) << '\n';
  std::cout << fmt::format("wrote {}\n", csv.string());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  mfree::remove_staging_folders_on_signals();
  // A write past a file-size limit fails with an error naming the file (EFBIG) instead of
  // ending the program by SIGXFSZ with its staging folder left behind.
  std::signal(SIGXFSZ, SIG_IGN);
  CLI::App app{"mfree: meshfree Galerkin solid mechanics and the Material Point Method"};
  app.footer(
      "Exit codes: 0 success, 1 bad input (scene, mesh, files, memory), 2 bad command line, "
      "3 numerical failure.");
  app.set_version_flag("--version", "mfree 0.1.0");
  app.require_subcommand(1);

  std::filesystem::path scene, out = "results/integration";
  CLI::App* integration = app.add_subcommand(
      "integration", "Integration-accuracy study: meshfree quadrature weights against baselines");
  integration->add_option("scene", scene, "Study description (TOML)")->required();
  integration->add_option("--out", out, "Folder for integration.csv")->capture_default_str();

  std::vector<std::string> overrides;
  const std::string set_help = "Replace or add a scene key: section.key=value (TOML value; repeatable)";
  CLI::App* run =
      app.add_subcommand("run", "One solve, MPM run or material-point path of a scene: summary, errors, VTK fields");
  run->add_option("scene", scene, "Scene file (TOML)")->required();
  run->add_option("--set", overrides, set_help);
  std::filesystem::path restart;
  run->add_option("--restart", restart,
                  "Continue a dynamics or MPM run from the newest checkpoint in this folder (the OUTPUT.checkpoints "
                  "folder a run with [output] checkpoint_every wrote), with the same scene and --set overrides");
  CLI::App* converge = app.add_subcommand("converge", "Refinement study of a scene: CSV, PNG plots, rates");
  converge->add_option("scene", scene, "Scene file (TOML) with a [study] section")->required();
  converge->add_option("--set", overrides, set_help);

  // A first word that is no subcommand is named (CLI11 alone would say one is missing).
  if (argc > 1 && argv[1][0] != '-') {
    try {
      (void)app.get_subcommand(argv[1]);
    } catch (const CLI::OptionNotFound&) {
      std::cerr << fmt::format("mfree: unknown subcommand '{}' (run, converge, integration; see mfree --help)\n",
                               argv[1]);
      return 2;
    }
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    (void)app.exit(e);
    return 2;
  }
  try {
    if (*integration) return run_integration(scene, out);
    // A scene with a [path] section drives one material point along a given F(t).
    if ((*run || *converge) && mfree::is_path_scene(scene)) {
      if (*converge)
        throw mfree::InputError(fmt::format("{}: a material-point path has no refinement study; run it with mfree run "
                                            "(and its increments with --set path.increments=N)",
                                            scene.string()));
      return mfree::run_path_scene(scene, overrides, restart);
    }
    // A scene whose [domain] is a box or a solid part is a solid (3D) run.
    if ((*run || *converge) && mfree::is_solid_scene(scene))
      return mfree::run_solid_scene(scene, overrides, static_cast<bool>(*converge), restart);
    // A scene with an [mpm] section is an MPM run; any other is an elasticity run.
    if ((*run || *converge) && mfree::is_mpm_scene(scene)) {
      mfree::MPMScene mpm = mfree::read_mpm_scene(scene, static_cast<bool>(*converge), overrides);
      if (*converge) return mfree::in_staged_folder(mpm.folder, [&] { return mfree::converge_mpm(mpm); });
      const mfree::Checkpoints checkpoints(mpm.folder, mpm.checkpoint_every, mfree::scene_fingerprint(scene, overrides),
                                           restart);
      return mfree::in_staged_folder(mpm.folder, checkpoints, [&] { return mfree::run_mpm(mpm, &checkpoints); });
    }
    if (*run) return mfree::run_elasticity(scene, overrides, restart);
    if (*converge) return mfree::converge_elasticity(scene, overrides);
  } catch (const mfree::NumericalError& e) {
    std::cerr << "mfree: error: " << e.what() << '\n';
    return 3;
  } catch (const mfree::Error& e) {
    std::cerr << "mfree: error: " << e.what() << '\n';
    return 1;
  } catch (const std::bad_alloc&) {
    std::cerr << "mfree: error: out of memory: the problem does not fit this machine (fewer nodes, particles "
                 "or cells, or a coarser spacing)\n";
    return 1;
  } catch (const std::filesystem::filesystem_error& e) {
    // A path the file system refuses (a loop of symbolic links, no permission, a name too
    // long): what() names the operation and the path.
    std::cerr << "mfree: error: " << e.what() << '\n';
    return 1;
  } catch (const std::exception& e) {
    // Input that reached the standard library unchecked: a bad input all the same, and a
    // check missing in mfree.
    std::cerr << "mfree: error: " << e.what() << " (an error mfree did not expect here: please report it with the "
              << "scene and command line)\n";
    return 1;
  } catch (...) {
    std::cerr << "mfree: error: an exception of unknown type (please report it with the scene and command line)\n";
    return 1;
  }
  return 0;
}
