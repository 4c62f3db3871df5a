#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <filesystem>
#include <memory>

#include "../test_support.hpp"
#include "checkpoint_restarts.hpp"
#include "mfree/apps/solid_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/stage_timer.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_scene.hpp"

using namespace mfree;
using mfree::testing::ScratchFolder;
namespace fs = std::filesystem;

namespace {

constexpr std::uint64_t fingerprint = 12;

/// A dynamic run of tests/apps/checkpoint_NAME.toml (9 nodes, 18 DOFs, 10 steps) with
/// checkpoints every 3 steps; its newest checkpoint is of step 9.
struct Restarts : mfree::testing::CheckpointRestarts {
  explicit Restarts(const std::string& name)
      : Restarts(name,
                 std::make_shared<ElasticityScene>(read_elasticity_scene(
                     fs::path(mfree::testing::source_dir()) / "tests/apps" / ("checkpoint_" + name + ".toml"),
                     false))) {}
  Restarts(const std::string& name, const std::shared_ptr<ElasticityScene>& scene)
      : CheckpointRestarts("solid_restore_" + name, fingerprint,
                           [scene](const fs::path& folder, const Checkpoints* c) {
                             scene->output.folder = folder;
                             (void)simulate(*scene, scene->dynamics->settings, false, c);
                           }),
        scene(*scene) {}
  const ElasticityScene& scene;  ///< kept alive by the run
};

/// What a refusal of array `name` of the checkpoint of step 9 starts with.
std::string refused(const std::string& name) {
  return fmt::format("broken.checkpoints/step_0000000009/state.bin: array '{}': ", name);
}

}  // namespace

TEST_CASE("dynamics restarts: the checkpoints as written restore, and run to the end", "[apps][checkpoint]") {
  for (const char* name : {"dynamics", "dynamics_j2"}) {
    const Restarts r(name);
    REQUIRE(r.step == 9);
    REQUIRE(r.get("d").size() == 18);
    CHECK(r.restore(r.state, r.step) == "restored");
  }
}

TEST_CASE("dynamics restarts: vectors and records whose sizes do not fit the run are refused",
          "[apps][checkpoint]") {
  const Restarts r("dynamics_j2");
  std::vector<double> v_half = r.get("v_half");
  v_half.pop_back();
  CHECK_THAT(r.restore("v_half", v_half),
             Catch::Contains(refused("v_half") + "it holds 17 values, and this run needs 18 (its DOFs)"));
  std::vector<double> tangent = r.get("tangent");
  REQUIRE(tangent.size() > 18);
  tangent.resize(18);
  CHECK_THAT(r.restore("tangent", tangent), Catch::Contains(refused("tangent") + "it holds 18 values") &&
                                                Catch::Contains("(the nonzeros of its tangent, or none)"));
  // One material state (7 numbers) too few at the quadrature points.
  std::vector<double> history = r.get("history.domain");
  const std::size_t points = history.size() / 7;
  history.resize(history.size() - 7);
  CHECK_THAT(r.restore("history.domain", history),
             Catch::Contains(refused("history.domain") +
                             fmt::format("it holds {} points, and this run has {}", points - 1, points)));
  // Energy records at every step 0 to 9, of 5 numbers each: one too few.
  std::vector<double> energy = r.get("energy");
  REQUIRE(energy.size() == 10 * 5);
  energy.resize(9 * 5);
  CHECK_THAT(r.restore("energy", energy),
             Catch::Contains(refused("energy") + "it holds 9 records, and the run wrote 10 by step 9"));

  // The probe of the central-difference scene: a record at t = 0 and after every step.
  const Restarts c("dynamics");
  std::vector<double> probe = c.get("probe");
  REQUIRE(probe.size() == 3 * 10);
  probe.resize(3 * 9);
  CHECK_THAT(c.restore("probe", probe),
             Catch::Contains(refused("probe") + "it holds 27 values, and this run needs 30"));
}

TEST_CASE("dynamics restarts: a negative plastic strain and an inverted displacement are refused",
          "[apps][checkpoint]") {
  const Restarts r("dynamics_j2");
  std::vector<double> history = r.get("history.domain");
  history[7 * 2 + 5] = -1.0;  // alpha of point 2
  CHECK_THAT(r.restore("history.domain", history),
             Catch::Contains(refused("history.domain") +
                             "value 19 is -1, not an equivalent plastic strain (0 or more)"));
  // d_I = (-2 X_I, 0): the linear RK functions reproduce u = (-2 x, 0), F = diag(-1, 1).
  StageTimer timer;
  const Discretisation<2> disc = discretise(r.scene.domain, r.scene.settings, timer);
  std::vector<double> d(2 * disc.nodes.size(), 0.0);
  for (std::size_t n = 0; n < disc.nodes.size(); ++n) d[2 * n] = -2.0 * disc.nodes[n].x();
  CHECK_THAT(r.restore("d", d), Catch::Contains(refused("d") + "det F = -1") &&
                                    Catch::Contains("at quadrature point 0") &&
                                    Catch::Contains("not positive"));
}

TEST_CASE("dynamics restarts: a step past the end of the run, or another than the checkpoint's, is refused",
          "[apps][checkpoint]") {
  const Restarts r("dynamics");
  // A checkpoint claiming step 10^15 (its folder named so) would run on past end_time.
  CHECK_THAT(r.restore(r.state, 1000000000000000),
             Catch::Contains(
                 "broken.checkpoints/step_1000000000000000/state.bin: step 1000000000000000 is past the most "
                 "steps a run may take (1e+09)"));
  // Step 12 of 10, the same in the file and its folder's name.
  CHECK_THAT(
      r.restore(r.with("step", {12.0}), 12),
      Catch::Contains(
          "step_0000000012/state.bin: array 'step': value 0 is 12, not one of this run's steps (0 to 9)"));
  CHECK_THAT(r.restore("step", {4.0}),
             Catch::Contains(refused("step") + "value 0 is 4, not the checkpoint's step 9"));
  // Records after the checkpoint's time (step 9 of dt = 1e-5 s).
  std::vector<double> errors = r.get("errors");
  REQUIRE(errors.size() == 4);  // at half the end time
  errors[0] = 2e-4;
  CHECK_THAT(
      r.restore("errors", errors),
      Catch::Contains(refused("errors") + "value 0 is 0.0002, after the run's time 9e-05 s at step 9"));
  CHECK_THAT(r.restore("next_frame", {1.0}),
             Catch::Contains(refused("next_frame") +
                             "value 0 is 1, not a time within a frame interval past end_time"));
}
