// MPM scenes: the verification scene parses into the settings it states; bad input is
// refused naming the file, the key and what is wrong.

#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/mpm_scene.hpp"

using namespace mfree;

namespace {

std::string vibration_text() {
  std::ifstream in(std::string(MFREE_SOURCE_DIR) + "/verification/mpm-vibration/vibration.toml");
  return {std::istreambuf_iterator<char>(in), {}};
}

std::filesystem::path write_scene(const std::string& text) {
  static const testing::ScratchFolder folder("mpm_scene");  // one per test process
  const auto path = folder.path / "mpm.toml";
  std::ofstream(path) << text;
  return path;
}

/// The error message for a scene text, "" when it parses.
std::string scene_error(const std::string& text, bool study = false) {
  const std::string what = testing::message_of<InputError>([&] { (void)read_mpm_scene(write_scene(text), study); });
  return what == "<nothing thrown>" ? "" : what;
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return std::regex_replace(text, std::regex(from), to);
}

}  // namespace

TEST_CASE("MPM scenes: the vibration scene reads into its settings", "[io]") {
  const MPMScene s = read_mpm_scene(write_scene(vibration_text()), true);
  CHECK(is_mpm_scene(write_scene(vibration_text())));
  CHECK(s.settings.method == MPMMethod::bspline);
  CHECK(s.settings.degree == 2);
  CHECK(s.settings.update == UpdateScheme::usf);
  CHECK(s.settings.cells == 16);
  CHECK(s.settings.particles_per_side == 3);
  CHECK(s.settings.walls.size() == 4);
  CHECK(s.settings.time_step == 1e-5);
  CHECK(s.settings.courant == 0.5);
  REQUIRE(s.vibration);
  CHECK(s.vibration->amplitude == 0.05);
  CHECK(s.error_times == std::vector<double>{0.25, 0.5, 0.75, 1.0});
  CHECK((s.fields.displacement && s.fields.velocity && s.fields.stress && s.fields.error && s.fields.grid));
  CHECK_FALSE(s.fields.von_mises);
  REQUIRE(s.study);
  CHECK(s.study->cells == std::vector<int>{8, 16, 32, 64});
  CHECK(s.study->methods.size() == 6);
  CHECK(method_name(s.study->methods[4]) == "bspline_cubic");
  CHECK(s.study->particles_per_side == std::vector<int>{3, 2});
  // The initial velocity and body force are the vibration's.
  CHECK((s.problem.initial_velocity(Vec2(0.25, 0.3)) - s.vibration->velocity(Vec2(0.25, 0.3), 0.0)).norm() == 0.0);
  CHECK((s.problem.body_force(Vec2(0.2, 0.7), 0.004) - s.vibration->body_force(Vec2(0.2, 0.7), 0.004)).norm() == 0.0);
}

TEST_CASE("MPM scenes: bad input is refused naming the key", "[io]") {
  const std::string good = vibration_text();
  CHECK(scene_error(good).empty());
  CHECK_THAT(scene_error(replace(good, "method = \"bspline\"", "method = \"qcpdi\"")),
             Catch::Contains("mpm.method") && Catch::Contains("not one of") && Catch::Contains("mpm.toml:"));
  CHECK_THAT(scene_error(replace(good, "particles_per_cell = 9", "particles_per_cell = 6")),
             Catch::Contains("mpm.particles_per_cell") && Catch::Contains("square number"));
  CHECK_THAT(scene_error(replace(good, "cells = 16", "cells = 16\nmls_support = 2.0")),
             Catch::Contains("mpm.mls_support") && Catch::Contains("only bspline_mls"));
  CHECK_THAT(scene_error(replace(good, "cells = 16", "cells = 16\ngravity = [0.0, -9.81]")),
             Catch::Contains("mpm.gravity") && Catch::Contains("[exact] solution sets the body force"));
  CHECK_THAT(scene_error(replace(good, "density = 1000.0\n", "")), Catch::Contains("needs [material] density"));
  CHECK_THAT(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourrant = 0.4")),
             Catch::Contains("dynamics.courrant") && Catch::Contains("unknown key"));
  CHECK_THAT(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourant = 1.5")),
             Catch::Contains("dynamics.courant") && Catch::Contains("out of range"));
  CHECK(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourant = 1.5\nallow_unstable_time_step = true")).empty());
  CHECK_THAT(scene_error(replace(good, "rectangle = \\[\\[0.0, 0.0\\], \\[1.0, 1.0\\]\\]", "rectangle = [[0.0, 0.0], [1.0, 0.7]]")),
             Catch::Contains("exact.solution") && Catch::Contains("square domain"));
  CHECK_THAT(scene_error(replace(good, "model = \"neo_hookean\"", "model = \"plane_strain\"")),
             Catch::Contains("exact.solution") && Catch::Contains("neo_hookean"));
  CHECK_THAT(scene_error(replace(good, "\\[study\\]", "[study]\nupdates = [\"usx\"]"), true),
             Catch::Contains("study.updates") && Catch::Contains("not one of"));
}
