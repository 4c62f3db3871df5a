// mfree: meshfree Galerkin solid mechanics and the Material Point Method.
//
// Usage:
//   mfree run SCENE.toml [--set KEY=VALUE]...   one elasticity solve or MPM run
//   mfree converge SCENE.toml [--set ...]       refinement study of an elasticity or MPM scene
//   mfree integration SCENE.toml [--out DIR]   integration-accuracy study (seed 003)
//   mfree --help | mfree SUBCOMMAND --help
//
// Exit codes: 0 success, 1 bad input or a numerical failure (the message says what and
// where), 2 bad command line.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <fmt/format.h>
#include <iostream>

#include "mfree/apps/elasticity_app.hpp"
#include "mfree/apps/integration_study.hpp"
#include "mfree/apps/mpm_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"
#include "mfree/io/atomic_file.hpp"
#include "mfree/io/scene_reader.hpp"

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
  CLI::App app{"mfree: meshfree Galerkin solid mechanics and the Material Point Method"};
  app.set_version_flag("--version", "mfree 0.1.0");
  app.require_subcommand(1);

  std::filesystem::path scene, out = "results/integration";
  CLI::App* integration = app.add_subcommand(
      "integration", "Integration-accuracy study: meshfree quadrature weights against baselines");
  integration->add_option("scene", scene, "Study description (TOML)")->required();
  integration->add_option("--out", out, "Folder for integration.csv")->capture_default_str();

  std::vector<std::string> overrides;
  const std::string set_help = "Replace or add a scene key: section.key=value (TOML value; repeatable)";
  CLI::App* run = app.add_subcommand("run", "One solve or MPM run of a scene: summary, errors, VTK fields");
  run->add_option("scene", scene, "Scene file (TOML)")->required();
  run->add_option("--set", overrides, set_help);
  CLI::App* converge = app.add_subcommand("converge", "Refinement study of a scene: CSV, PNG plots, rates");
  converge->add_option("scene", scene, "Scene file (TOML) with a [study] section")->required();
  converge->add_option("--set", overrides, set_help);

  CLI11_PARSE(app, argc, argv);
  try {
    if (*integration) return run_integration(scene, out);
    // A scene with an [mpm] section is an MPM run; any other is an elasticity run.
    if ((*run || *converge) && mfree::is_mpm_scene(scene)) {
      const mfree::MPMScene mpm = mfree::read_mpm_scene(scene, static_cast<bool>(*converge), overrides);
      return *run ? mfree::run_mpm(mpm) : mfree::converge_mpm(mpm);
    }
    if (*run) return mfree::run_elasticity(scene, overrides);
    if (*converge) return mfree::converge_elasticity(scene, overrides);
  } catch (const mfree::Error& e) {
    std::cerr << "mfree: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
