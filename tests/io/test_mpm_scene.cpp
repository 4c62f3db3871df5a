// MPM scenes: the verification scene parses into the settings it states; bad input is
// refused naming the file, the key and what is wrong.

#include <catch2/catch.hpp>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numbers>
#include <regex>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/mpm_scene.hpp"

using namespace mfree;

namespace {

std::string vibration_text() {
  std::ifstream in(mfree::testing::source_dir() + "/verification/mpm-vibration/vibration.toml");
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
  CHECK(s.settings.walls == Walls{Wall::slip, Wall::slip, Wall::slip, Wall::slip});
  REQUIRE(s.problem.bodies.size() == 1);
  CHECK(s.problem.bodies.front().name == "square");
  CHECK(s.problem.materials.front().density == 1000.0);
  CHECK(s.settings.time_step == 1e-5);
  CHECK(s.settings.courant == 0.5);
  REQUIRE(s.exact);
  // The vibration of amplitude 0.05 on the unit square: its speed amplitude A pi c / L at t = 0.
  CHECK(s.exact->velocity(Vec2(0.25, 0.75), 0.0).x() == Approx(0.05 * std::numbers::pi * 100.0).epsilon(1e-14));
  CHECK(s.error_times == std::vector<double>{0.25, 0.5, 0.75, 1.0});
  CHECK((s.fields.displacement && s.fields.velocity && s.fields.stress && s.fields.error && s.fields.grid));
  CHECK_FALSE(s.fields.von_mises);
  REQUIRE(s.study);
  CHECK(s.study->cells == std::vector<int>{8, 16, 32, 64});
  CHECK(s.study->methods.size() == 11);
  CHECK(method_name(s.study->methods[7]) == "bspline_cubic");
  CHECK(method_name(s.study->methods[9]) == "bspline_cpgimp_cubic");
  CHECK(s.study->methods[9] == MPMMethodChoice{MPMMethod::bspline_cpgimp, 3});
  CHECK(s.study->particles_per_side == std::vector<int>{3, 2});
  // The initial velocity and body force are the vibration's.
  CHECK((s.problem.bodies.front().initial_velocity(Vec2(0.25, 0.3)) - s.exact->velocity(Vec2(0.25, 0.3), 0.0)).norm() ==
        0.0);
  CHECK((s.problem.body_force(Vec2(0.2, 0.7), 0.004) - s.exact->body_force(Vec2(0.2, 0.7), 0.004)).norm() == 0.0);
}

TEST_CASE("MPM scenes: bodies, materials, walls, gravity and damping read as the cases state them", "[io]") {
  const std::string cases = mfree::testing::source_dir() + "/verification/";
  const MPMScene disks = read_mpm_scene(cases + "mpm-disks/disks.toml", false);
  REQUIRE(disks.problem.bodies.size() == 2);
  const MPMBody& upper = disks.problem.bodies[1];
  CHECK(upper.name == "upper");
  CHECK(upper.shape == Shape::circle);
  CHECK(upper.contains(Vec2(0.8, 0.61)));
  CHECK_FALSE(upper.contains(Vec2(0.8, 0.59)));
  CHECK(upper.bounds.lo.isApprox(Vec2(0.6, 0.6)));
  CHECK(upper.initial_velocity(Vec2(0.7, 0.9)) == Vec2(-0.1, -0.1));
  CHECK(disks.problem.materials.size() == 1);
  CHECK(std::holds_alternative<LinearElastic>(disks.problem.materials.front().law));
  CHECK(disks.settings.walls == Walls{Wall::open, Wall::open, Wall::open, Wall::open});
  CHECK_FALSE(disks.problem.body_force);

  const MPMScene bar = read_mpm_scene(cases + "mpm-bar/bar.toml", false);
  CHECK(bar.settings.walls == Walls{Wall::fixed, Wall::open, Wall::slip, Wall::slip});
  // v = v0 sin(pi X / (2 L)) from the formula and [constants].
  CHECK(bar.problem.bodies.front().initial_velocity(Vec2(12.5, 1.0)).x() == Approx(0.1 * std::sin(M_PI / 4)).epsilon(1e-14));
  CHECK(bar.problem.box.hi == Vec2(31.25, 3.125));

  const MPMScene column = read_mpm_scene(cases + "mpm-column/column.toml", false);
  CHECK(column.settings.damping == 100.0);
  CHECK(column.problem.body_force(Vec2(0.1, 0.5), 0.3) == Vec2(0.0, -10.0));
  CHECK(column.particles_csv);

  // The WKT polygon of tests/apps/mpm_polygon.toml, and its gravity formula in t.
  const MPMScene polygon =
      read_mpm_scene(mfree::testing::source_dir() + "/tests/apps/mpm_polygon.toml", false);
  const MPMBody& ell = polygon.problem.bodies.front();
  CHECK(ell.shape == Shape::polygon);
  CHECK(ell.contains(Vec2(-0.5, 0.5)));
  CHECK_FALSE(ell.contains(Vec2(0.5, 0.5)));  // the L's missing quadrant
  CHECK(polygon.problem.body_force(Vec2(0.0, 0.0), 0.005).y() == Approx(-5.0).epsilon(1e-14));
}

TEST_CASE("MPM scenes: bad input is refused naming the key", "[io]") {
  const std::string good = vibration_text();
  CHECK(scene_error(good).empty());
  CHECK_THAT(scene_error(replace(good, "method = \"bspline\"", "method = \"gimp2\"")),
             Catch::Contains("mpm.method") && Catch::Contains("not one of") && Catch::Contains("mpm.toml:"));
  CHECK_THAT(scene_error(replace(good, "particles_per_cell = 9", "particles_per_cell = 6")),
             Catch::Contains("mpm.particles_per_cell") && Catch::Contains("square number"));
  CHECK_THAT(scene_error(replace(good, "cells = 16", "cells = 16\nmls_support = 2.0")),
             Catch::Contains("mpm.mls_support") && Catch::Contains("only bspline_mls"));
  CHECK_THAT(scene_error(replace(good, "cells = 16", "cells = 16\ngravity = [0.0, -9.81]")),
             Catch::Contains("mpm.gravity") && Catch::Contains("[exact] solution sets the body force"));
  CHECK_THAT(scene_error(replace(good, "density = 1000.0\n", "")),
             Catch::Contains("material[0].model") && Catch::Contains("needs a density"));
  CHECK_THAT(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourrant = 0.4")),
             Catch::Contains("dynamics.courrant") && Catch::Contains("unknown key"));
  CHECK_THAT(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourant = 1.5")),
             Catch::Contains("dynamics.courant") && Catch::Contains("out of range"));
  CHECK(scene_error(replace(good, "time_step = 1.0e-5", "time_step = 1.0e-5\ncourant = 1.5\nallow_unstable_time_step = true")).empty());
  CHECK_THAT(scene_error(replace(good, "\\[1.0, 1.0\\]\\]", "[1.0, 0.75]]")),
             Catch::Contains("exact.solution") && Catch::Contains("vibration solution needs the square domain"));
  CHECK_THAT(scene_error(replace(good, "box = \\[\\[0.0, 0.0\\], \\[1.0, 1.0\\]\\]\nmaterial", "box = [[0.0, 0.0], [1.0, 0.5]]\nmaterial")),
             Catch::Contains("exact.solution") && Catch::Contains("the rectangle filling the grid box"));
  CHECK_THAT(scene_error(replace(good, "model = \"neo_hookean\"", "model = \"plane_strain\"")),
             Catch::Contains("exact.solution") && Catch::Contains("neo_hookean"));
  CHECK_THAT(scene_error(replace(good, "material = \"rubber\"", "material = \"steel\"")),
             Catch::Contains("body[0].material") && Catch::Contains("no [[material]] is named 'steel'") &&
                 Catch::Contains("'rubber'"));
  CHECK_THAT(scene_error(replace(good, "\\[\\[body\\]\\]", "[[material]]\nname = \"steel\"\nmodel = \"plane_strain\"\n"
                                 "youngs_modulus = 2e11\npoisson_ratio = 0.3\ndensity = 7800.0\n\n[[body]]")),
             Catch::Contains("material[1].name") && Catch::Contains("'steel' is used by no [[body]]"));
  CHECK_THAT(scene_error(replace(good, "material = \"rubber\"", "material = \"rubber\"\nvelocity = [1.0, 0.0]")),
             Catch::Contains("body[0].velocity") && Catch::Contains("[exact] solution sets the initial velocity"));
  CHECK_THAT(scene_error(replace(good, "left = \"slip\"", "left = \"sticky\"")),
             Catch::Contains("mpm.walls.left") && Catch::Contains("not one of"));
  CHECK_THAT(scene_error(replace(good, "left = \"slip\"", "front = \"slip\"")),
             Catch::Contains("mpm.walls.front") && Catch::Contains("unknown key"));
  CHECK_THAT(scene_error(replace(good, "shape = \"rectangle\"", "shape = \"ellipse\"")),
             Catch::Contains("body[0].shape") && Catch::Contains("not one of"));
  CHECK_THAT(scene_error(replace(good, "shape = \"rectangle\"", "shape = \"circle\"")),
             Catch::Contains("body[0].centre"));
  CHECK_THAT(scene_error(replace(good, "shape = \"rectangle\"", "shape = \"polygon\"\nwkt = \"none.wkt\"")),
             Catch::Contains("body[0].wkt") && Catch::Contains("none.wkt"));
  CHECK_THAT(scene_error(replace(replace(good, "\\[exact\\]\nsolution = \"vibration\"\namplitude = 0.05\n", ""),
                                 "material = \"rubber\"", "material = \"rubber\"\nvelocity = [\"t\", \"0\"]")),
             Catch::Contains("body[0].velocity") && Catch::Contains("not t"));
  CHECK_THAT(scene_error(replace(good, "name = \"square\"", "name = \"square\"\nparticles_per_cell = 4"), true),
             Catch::Contains("study.particles_per_cell") && Catch::Contains("body 'square' sets its own"));
  // The single [material] table of elasticity scenes is not an MPM scene's.
  CHECK_THAT(scene_error(replace(good, "\\[\\[material\\]\\]\nname = \"rubber\"", "[material]")),
             Catch::Contains("material") && Catch::Contains("array of tables"));
  CHECK_THAT(scene_error(replace(good, "\\[study\\]", "[study]\nupdates = [\"usx\"]"), true),
             Catch::Contains("study.updates") && Catch::Contains("not one of"));
}
