#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <memory>

#include "../test_support.hpp"
#include "checkpoint_restarts.hpp"
#include "mfree/apps/mpm_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/mpm_scene.hpp"

using namespace mfree;
using mfree::testing::ScratchFolder;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t fingerprint = 11;

/// A run of tests/apps/checkpoint_mpm_cpdi2_j2.toml (8 particles of two bodies and two
/// materials, 8 steps) with checkpoints every 3 steps; its newest checkpoint is of step 6.
struct Restarts : mfree::testing::CheckpointRestarts {
  Restarts()
      : Restarts(std::make_shared<MPMScene>(read_mpm_scene(
            fs::path(mfree::testing::source_dir()) / "tests/apps/checkpoint_mpm_cpdi2_j2.toml", false))) {}
  explicit Restarts(const std::shared_ptr<MPMScene>& scene)
      : CheckpointRestarts("mpm_restore", fingerprint,
                           [scene](const fs::path& folder, const Checkpoints* c) {
                             scene->folder = folder;
                             (void)simulate_mpm(*scene, scene->settings, false, c);
                           }),
        scene(*scene) {}
  const MPMScene& scene;  ///< kept alive by the run
};

/// What a refusal of array `name` of the checkpoint of step 6 starts with.
std::string refused(const std::string& name) {
  return fmt::format("broken.checkpoints/step_0000000006/state.bin: array '{}': ", name);
}

}  // namespace

TEST_CASE("MPM restarts: the checkpoint as written restores, and runs to the end", "[apps][checkpoint]") {
  const Restarts r;
  REQUIRE(r.step == 6);
  REQUIRE(r.get("particles.mass").size() == 8);
  CHECK(r.restore(r.state, r.step) == "restored");
}

TEST_CASE("MPM restarts: a body or material index out of the scene's lists is refused",
          "[apps][checkpoint]") {
  const Restarts r;
  std::vector<double> material = r.get("particles.material");
  material[3] = 2.0;
  CHECK_THAT(r.restore("particles.material", material),
             Catch::Contains(refused("particles.material") +
                             "value 3 is 2, not one of this scene's 2 materials (0 to 1)"));
  material[3] = 0.5;
  CHECK_THAT(r.restore("particles.material", material),
             Catch::Contains(refused("particles.material") + "value 3 is 0.5"));
  std::vector<double> body = r.get("particles.body");
  body[0] = -1.0;
  CHECK_THAT(r.restore("particles.body", body),
             Catch::Contains(refused("particles.body") +
                             "value 0 is -1, not one of this scene's 2 bodies (0 to 1)"));
}

TEST_CASE("MPM restarts: arrays whose sizes do not fit the scene's particles and bodies are refused",
          "[apps][checkpoint]") {
  const Restarts r;
  std::vector<double> mass = r.get("particles.mass");
  mass.pop_back();
  CHECK_THAT(r.restore("particles.mass", mass),
             Catch::Contains(refused("particles.mass") + "it holds 7 values, and this run needs 8"));
  std::vector<double> velocity = r.get("particles.velocity");
  velocity.push_back(0.0);
  CHECK_THAT(r.restore("particles.velocity", velocity),
             Catch::Contains(refused("particles.velocity") + "it holds 17 values, and this run needs 16"));
  CHECK_THAT(r.restore("particles.corners", {}),
             Catch::Contains(refused("particles.corners") + "it holds 0 values, and this run needs 64"));
  CHECK_THAT(r.restore("external_work", {0.0}),
             Catch::Contains(refused("external_work") + "it holds 1 values, and this run needs 2"));
  // Energy records every 3 steps: at steps 0, 3 and 6, of 1 + 6 (2 bodies + 1) numbers each.
  std::vector<double> energy = r.get("energy");
  REQUIRE(energy.size() == 3 * 19);
  energy.resize(2 * 19);
  CHECK_THAT(r.restore("energy", energy),
             Catch::Contains(refused("energy") + "it holds 38 values, and this run needs 57"));
}

TEST_CASE("MPM restarts: masses, volumes and det F that are not positive are refused", "[apps][checkpoint]") {
  const Restarts r;
  std::vector<double> mass = r.get("particles.mass");
  mass[2] = 0.0;
  CHECK_THAT(r.restore("particles.mass", mass),
             Catch::Contains(refused("particles.mass") + "value 2 is 0, not positive"));
  std::vector<double> volume = r.get("particles.volume");
  volume[5] = -1e-6;
  CHECK_THAT(r.restore("particles.volume", volume),
             Catch::Contains(refused("particles.volume") + "value 5 is -1e-06, not positive"));
  std::vector<double> deformation = r.get("particles.deformation");
  // Particle 1's F (4 coefficients from index 4) = diag(1, -1).
  deformation[4] = 1.0;
  deformation[5] = 0.0;
  deformation[6] = 0.0;
  deformation[7] = -1.0;
  CHECK_THAT(r.restore("particles.deformation", deformation),
             Catch::Contains(refused("particles.deformation") + "particle 1 has det F = -1, not positive"));
  std::vector<double> alpha = r.get("particles.alpha");
  alpha[0] = -0.25;
  CHECK_THAT(r.restore("particles.alpha", alpha),
             Catch::Contains(refused("particles.alpha") +
                             "value 0 is -0.25, not an equivalent plastic strain (0 or more)"));
}

TEST_CASE("MPM restarts: a step or a time past the end of the run, or not the step's time, is refused",
          "[apps][checkpoint]") {
  const Restarts r;
  // A checkpoint claiming step 10^15 (its folder named so) would run on past end_time.
  CHECK_THAT(
      r.restore(r.state, 1000000000000000),
      Catch::Contains(
          "broken.checkpoints/step_1000000000000000/state.bin: step 1000000000000000 is not one of this "
          "run's steps (0 to 7)"));
  CHECK_THAT(r.restore(r.state, 8), Catch::Contains("step 8 is not one of this run's steps (0 to 7)"));
  const double end = r.scene.settings.end_time, time = r.state.scalar("time");
  CHECK_THAT(r.restore("time", {2 * end}),
             Catch::Contains(
                 refused("time") +
                 fmt::format("value 0 is {}, not a time of this run (0 to end_time {} s)", 2 * end, end)));
  CHECK_THAT(r.restore("time", {time / 3}),
             Catch::Contains(refused("time")) && Catch::Contains("not the time of step 6"));
  // Records past the checkpoint's time.
  std::vector<double> energy = r.get("energy");
  energy[19] = 2 * time;  // the time of the second record
  CHECK_THAT(r.restore("energy", energy), Catch::Contains(refused("energy") + "value 19 is"));
}
