// Solid scenes: a box or a gmsh part, formulas in x, y, z, conditions by part and by box,
// errors against [exact], reactions, the fields written as tetrahedra and surface triangles,
// dynamics; and the
// refusals of what a solid does not take or a scene gets wrong.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <regex>

#include "../test_support.hpp"
#include "mfree/apps/solid_scene_app.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/solid_scene.hpp"
#include "mfree/io/vtk_output.hpp"

using namespace mfree;

namespace {

/// A box [0, 1] x [0, 0.6] x [0, 0.8] holding the linear field u = G x + c of the gradient G
/// below: clamped to it on x_min (by a box round the face), slip on y_min (where its shear
/// stresses vanish), its tractions (sigma n, E = 1, nu = 0.3) on the other four faces. `order` the RK order,
/// `extra` added to the end.
std::string box_scene(const std::string& folder, const std::string& order = "linear",
                      const std::string& extra = "") {
  std::string sides;
  for (const char* face : {"x_max", "y_max", "z_min", "z_max"})
    sides += fmt::format(
        "\n[[boundary]]\nname = \"{0}\"\ntype = \"traction\"\npart = \"{0}\"\nvalue = \"exact\"\n", face);
  return fmt::format(R"([domain]
box = [[0, 0, 0], [1, 0.6, 0.8]]

[nodes]
cloud = "perturbed"
spacing = 0.2

[kernel]
order = "{}"

[material]
model = "linear_elastic"
youngs_modulus = 1.0
poisson_ratio = 0.3

[exact]
displacement = ["0.01 + 0.02 * x - 0.01 * y + 0.03 * z", "-0.02 + 0.01 * x + 0.015 * y", "0.005 * x - 0.01 * z"]
gradient = [0.02, -0.01, 0.03, 0.01, 0.015, 0, 0.005, 0, -0.01]

[[boundary]]
name = "clamp"
type = "displacement"
region = [[-1, -1, -1], [0, 1, 1]]
value = "exact"

[[boundary]]
name = "floor"
type = "slip"
part = "y_min"
value = "exact"
{}

[output]
folder = "{}"
fields = ["displacement", "stress", "von_mises", "error"]
probe = [0.5, 0.3, 0.4]
{})",
                     order, sides, folder, extra);
}

std::filesystem::path write_scene(const testing::ScratchFolder& folder, const std::string& text,
                                  const std::string& name = "scene.toml") {
  const auto path = folder.path / name;
  std::ofstream(path) << text;
  return path;
}

std::string refusal(const std::string& text) {
  static const testing::ScratchFolder folder("solid_scene_refusals");
  const auto path = write_scene(folder, text, "bad.toml");
  return testing::message_of<InputError>([&] { (void)read_solid_scene(path); });
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return std::regex_replace(text, std::regex(from), to);
}

}  // namespace

TEST_CASE("solid scenes: formulas take z in a solid and refuse it in the plane", "[io][solid]") {
  const Formula f("x + 2 * y + 3 * Z - t", {}, "f", 3);
  CHECK(f(Vec3(1.0, 2.0, 3.0), 0.5) == 1.0 + 4.0 + 9.0 - 0.5);
  const std::string plane = testing::message_of<InputError>([] { (void)Formula("x + z", {}, "g"); });
  CHECK_THAT(plane, Catch::Contains("names \"z\"") && Catch::Contains("variables are x, y, X, Y, t"));
  // A plane scene may name a constant z; a solid's formulas may not.
  CHECK(Formula("x + z", {{"z", 2.0}}, "h")(Vec2(1.0, 0.0)) == 3.0);
  CHECK_THAT(testing::message_of<InputError>([] {
               (void)Formula("x + z", {{"z", 2.0}}, "k", 3);
             }),
             Catch::Contains("would hide the variable z"));
}

// [heavy]: 2.4 s in Release, 118 s under the sanitizers; the checked build runs a solid scene
// through the program in the cli tier, and the 3D patch tests' quadratic RK.
TEST_CASE("solid scenes: a linear field on a box is reproduced to round-off, in the fields written too",
          "[io][solid][heavy]") {
  const testing::ScratchFolder folder("solid_scene_patch");
  for (const char* order : {"linear", "quadratic"}) {
    const auto out = folder.path / fmt::format("out_{}", order);
    const auto path = write_scene(folder, box_scene(out.string(), order), fmt::format("{}.toml", order));
    const SolidScene scene = read_solid_scene(path);
    REQUIRE(scene.selected.size() == 6);
    CHECK(scene.selected[0].area == Approx(0.48).epsilon(1e-14));  // the region holds x_min alone
    REQUIRE(run_solid_scene(path, {}) == 0);
    const std::string summary = [&] {
      std::ifstream in(out / "summary.json");
      return std::string{std::istreambuf_iterator<char>(in), {}};
    }();
    const std::smatch l2 = [&] {
      std::smatch m;
      REQUIRE(std::regex_search(summary, m, std::regex("\"l2_displacement\": ([0-9.e+-]+)")));
      return m;
    }();
    WARN(fmt::format("{} RK: relative L2 error {}", order, l2[1].str()));
    CHECK(std::stod(l2[1].str()) < 1e-10);
    // Uniform stress: the reactions of the clamp and the floor balance the tractions to
    // round-off, forces and moments (galerkin/reactions.hpp: VCI's imbalance vanishes then).
    for (const char* key : {"imbalance", "moment_imbalance"}) {
      std::smatch m;
      REQUIRE(std::regex_search(summary, m, std::regex(fmt::format("\"{}\": ([0-9.e+-]+)", key))));
      CHECK(std::stod(m[1].str()) < 1e-10);
    }
    const VtuContents volume = read_vtu(out / "volume.vtu");
    CHECK(volume.cells == 6 * 5 * 3 * 4);  // six tetrahedra in each cube of the spacing
    REQUIRE(volume.z.size() == volume.points.size());
    double worst = 0.0, largest = 0.0;
    for (std::size_t i = 0; i < volume.points.size(); ++i)
      for (int c = 0; c < 3; ++c) {
        worst = std::max(worst, std::abs(volume.arrays.at("error")[3 * i + static_cast<std::size_t>(c)]));
        largest = std::max(largest,
                           std::abs(volume.arrays.at("displacement")[3 * i + static_cast<std::size_t>(c)]));
      }
    CHECK(worst < 1e-10 * largest);
    // sigma_xx = lambda tr(eps) + 2 mu eps_xx with tr = 0.025, eps_xx = 0.02 (E = 1, nu = 0.3).
    const double lambda = 0.3 / (1.3 * 0.4), mu = 1.0 / 2.6;
    CHECK(volume.arrays.at("stress")[0] == Approx(lambda * 0.025 + 2 * mu * 0.02).epsilon(1e-9));
    CHECK(volume.components.at("stress") == 6);
    const VtuContents surface = read_vtu(out / "surface.vtu");
    CHECK(surface.cells == 2 * 2 * (5 * 3 + 5 * 4 + 3 * 4));  // two triangles per square of each face
    CHECK(surface.points.size() == volume.points.size());
  }
}

TEST_CASE(
    "solid scenes: what a solid does not take, and selections that select nothing or overlap, are refused",
    "[io][solid]") {
  const std::string ok = box_scene("out");
  CHECK_THAT(refusal(replace(ok, "linear_elastic", "plane_strain")),
             Catch::Contains("model") && Catch::Contains("linear_elastic"));
  CHECK_THAT(refusal(replace(ok, "linear_elastic\"", "neo_hookean\"")),
             Catch::Contains("exact") && Catch::Contains("linear_elastic"));
  CHECK_THAT(refusal(replace(ok, "part = \"y_min\"", "region = [[2, 2, 2], [3, 3, 3]]")),
             Catch::Contains("selects no part of the surface"));
  CHECK_THAT(refusal(replace(ok, "part = \"y_min\"", "part = \"x_min\"")),
             Catch::Contains("overlaps boundary 'clamp'"));
  CHECK_THAT(refusal(replace(ok, "part = \"y_min\"", "region = [[0.5, -1, -1], [2, 2, 2]]")),
             Catch::Contains("overlaps boundary"));
  CHECK_THAT(refusal(replace(ok, "part = \"y_min\"", "part = \"bottom\"")),
             Catch::Contains("y_min") && Catch::Contains("bottom"));
  // A box round x_min a little too deep clips strips off the four faces round it.
  const std::string deep =
      replace(ok, "region = \\[\\[-1, -1, -1\\], \\[0, 1, 1\\]\\]", "region = [[-1, -1, -1], [0.02, 1, 1]]");
  CHECK_THAT(refusal(deep), Catch::Contains("thin across x") && Catch::Contains("allow_small_selection"));
  CHECK_THAT(refusal(replace(deep, "region = \\[\\[-1, -1, -1\\], \\[0.02, 1, 1\\]\\]",
                             "region = [[-1, -1, -1], [0.02, 1, 1]]\nallow_small_selection = true")),
             Catch::Contains("overlaps boundary"));  // the strips then meet the other conditions
  CHECK_THAT(refusal(ok + "\n[dynamics]\nscheme = \"newmark\"\n"), Catch::Contains("built-in motion"));
  CHECK_THAT(refusal(replace(ok, "probe = \\[0.5, 0.3, 0.4\\]", "probe = [0.5, 0.3, 1.4]")),
             Catch::Contains("outside the solid"));
  CHECK_THAT(refusal(replace(ok, "\\[kernel\\]", "[quadrature]\nscheme = \"gauss_cells\"\n[kernel]")),
             Catch::Contains("plane only so far"));
  CHECK_THAT(refusal(replace(ok, "\\[kernel\\]", "[kernel]\nsupport_rule = \"geodesic\"")),
             Catch::Contains("plane only"));
  CHECK_THAT(refusal(replace(ok, "0.005 \\* x", "0.005 * t")), Catch::Contains("uses t"));
  CHECK_THAT(refusal(replace(ok, "0.005 \\* x", "0.005 * w")),
             Catch::Contains("variables are x, y, z, X, Y, Z, t"));
  CHECK_THAT(
      refusal(replace(ok, "box = \\[\\[0, 0, 0\\], \\[1, 0.6, 0.8\\]\\]", "box = [[0, 0, 0], [1, 0.6, 0]]")),
      Catch::Contains("differ in x, y and z"));
  CHECK_THAT(refusal(replace(ok, "box = \\[\\[0, 0, 0\\], \\[1, 0.6, 0.8\\]\\]", "solid = \"missing.step\"")),
             Catch::Contains("missing.step"));
}

TEST_CASE("solid scenes: a problem that leaves a rigid-body motion free is refused before it is solved",
          "[io][solid]") {
  const testing::ScratchFolder folder("solid_scene_free");
  // Slip on y_min alone: translations in x and z and the rotation about y are free.
  std::string text =
      replace(box_scene((folder.path / "out").string()), "name = \"clamp\"\ntype = \"displacement\"",
              "name = \"clamp\"\ntype = \"traction\"");
  const auto path = write_scene(folder, text);
  CHECK_THAT(testing::message_of<InputError>([&] { (void)run_solid_scene(path, {}); }),
             Catch::Contains("not well posed"));
  CHECK(!std::filesystem::exists(folder.path / "out"));
}

TEST_CASE("solid scenes: a free vibration by central differences and Newmark keeps its energy, in frames",
          "[io][solid]") {
  const testing::ScratchFolder folder("solid_scene_dynamics");
  for (const char* scheme : {"central_difference", "newmark"}) {
    const auto out = folder.path / scheme;
    const auto path = write_scene(folder,
                                  fmt::format(R"([domain]
box = [[0, 0, 0], [1, 0.2, 0.2]]

[nodes]
cloud = "lattice"
spacing = 0.1

[kernel]
order = "linear"

[material]
model = "neo_hookean"
youngs_modulus = 1000.0
poisson_ratio = 0.3
density = 1.0

[[boundary]]
name = "clamp"
type = "displacement"
part = "x_min"
value = [0, 0, 0]

[dynamics]
scheme = "{}"
time_step = 0.005
end_time = 0.1
frames = 5
initial_velocity = [0, "0.5 * x", 0]

[output]
folder = "{}"
fields = ["displacement", "velocity"]
)",
                                              scheme, out.string()),
                                  fmt::format("{}.toml", scheme));
    if (std::string(scheme) == "central_difference") {
      std::string text;
      {
        std::ifstream in(path);
        text = {std::istreambuf_iterator<char>(in), {}};
      }
      std::ofstream(path) << replace(text, "time_step = 0.005\n", "");
    }
    REQUIRE(run_solid_scene(path, {}) == 0);
    std::ifstream in(out / "summary.json");
    const std::string summary{std::istreambuf_iterator<char>(in), {}};
    std::smatch m;
    REQUIRE(std::regex_search(summary, m, std::regex("\"energy_balance_relative\": ([0-9.e+-]+)")));
    WARN(fmt::format("{}: energy balance {} of the largest energy", scheme, m[1].str()));
    CHECK(std::stod(m[1].str()) <
          2e-3);  // measured to t = 0.1: 4.4e-4 (central differences), 1.5e-4 (Newmark)
    for (int k = 0; k <= 5; ++k) CHECK(std::filesystem::exists(out / fmt::format("volume_{:04d}.vtu", k)));
    const VtuContents last = read_vtu(out / "volume_0005.vtu");
    CHECK(last.components.at("velocity") == 3);
  }
}

TEST_CASE("solid scenes: the vibration motion of a cube, and what it does not take", "[io][solid]") {
  const std::string ok = [] {
    std::ifstream in(testing::source_dir() + "/verification/vibration-cube/vibration_cube.toml");
    return std::string{std::istreambuf_iterator<char>(in), {}};
  }();
  const testing::ScratchFolder folder("solid_scene_motion");
  const SolidScene scene = read_solid_scene(write_scene(folder, ok));
  REQUIRE(scene.motion);
  REQUIRE(scene.dynamics);
  CHECK(scene.dynamics->error_times == std::vector<double>{0.25, 0.5, 0.75, 1.0});
  // The body force is rho0 b of the motion, per unit reference volume.
  const Point<3> x(0.3, 0.6, 0.8);
  const Point<3> rho_b = 1000.0 * scene.motion->body_force(x, 0.004);
  CHECK(rho_b.norm() > 1e3);
  CHECK((scene.problem.body_force(x, 0.004) - rho_b).norm() <= 1e-15 * rho_b.norm());
  CHECK(scene.study->time.schemes ==
        std::vector<TimeScheme>{TimeScheme::central_difference, TimeScheme::newmark});
  CHECK(scene.study->time.steps == std::vector<double>{2.5e-5, 2.5e-4});

  CHECK_THAT(refusal(replace(ok, "box = \\[\\[0, 0, 0\\], \\[1, 1, 1\\]\\]", "box = [[0, 0, 0], [1, 1, 2]]")),
             Catch::Contains("[[0, 0, 0], [L, L, L]]"));
  CHECK_THAT(refusal(replace(ok, "neo_hookean", "st_venant_kirchhoff")), Catch::Contains("neo_hookean"));
  CHECK_THAT(refusal(replace(ok, "amplitude = 0.05", "amplitude = 0.2")),
             Catch::Contains("inverts the material"));
  CHECK_THAT(refusal(replace(ok, "\\[exact\\]", "[loads]\ngravity = [0, 0, -9.81]\n\n[exact]")),
             Catch::Contains("sets the body force"));
  CHECK_THAT(refusal(replace(ok, "frames = 8", "frames = 8\ninitial_velocity = [1, 0, 0]")),
             Catch::Contains("sets the initial state"));
  CHECK_THAT(
      refusal(replace(ok, "solution = \"vibration\"", "solution = \"vibration\"\ndisplacement = [0, 0, 0]")),
      Catch::Contains("built-in motion"));
  CHECK_THAT(refusal(replace(ok, "\"von_mises\"", "\"error\"")), Catch::Contains("error_times"));
  CHECK_THAT(refusal(replace(ok, "time_schemes", "orders = [\"linear\"]\ntime_schemes")),
             Catch::Contains("for statics"));
  // Without the motion: no error times, no study.
  const std::string free = replace(ok, "\\[exact\\]\nsolution = \"vibration\"\namplitude = 0.05\n", "");
  CHECK_THAT(refusal(free), Catch::Contains("errors are measured against an [exact] motion"));
  CHECK_THAT(refusal(replace(free, "error_times = .*\n", "")), Catch::Contains("exact motion"));
  // A static scene takes no time keys in its study.
  CHECK_THAT(
      refusal(box_scene("out", "linear", "\n[study]\nspacings = [0.2]\ntime_schemes = [\"newmark\"]\n")),
      Catch::Contains("needs a [dynamics] section"));
}

TEST_CASE("solid scenes: several materials, one per region of a gmsh part, and what they may not do",
          "[io][solid]") {
  const std::string ok = [] {
    std::ifstream in(testing::source_dir() + "/verification/two-layer-sphere/two_layer_sphere.toml");
    return replace(std::string{std::istreambuf_iterator<char>(in), {}}, "\\.\\./\\.\\./meshes",
                   testing::source_dir() + "/meshes");
  }();
  const testing::ScratchFolder folder("solid_scene_materials");
  const SolidScene scene = read_solid_scene(write_scene(folder, ok));
  REQUIRE(scene.problem.region_materials.size() == 2);
  CHECK(scene.model == "linear_elastic");
  const auto young = [&](const Point<3>& x) {
    return std::get<LinearElastic>(scene.problem.law_at(scene.solid, x)).youngs_modulus;
  };
  CHECK(young(Point<3>(0.7, 0.7, 0.7)) == 1000.0);  // r = 1.21: the stiff core
  CHECK(young(Point<3>(1.0, 1.0, 1.0)) == 200.0);   // r = 1.73: the soft shell
  CHECK(scene.lame_at(Point<3>(1.0, 1.0, 1.0)).mu == Approx(200.0 / 2.7).epsilon(1e-15));

  // Gravity weighs each region with its own density.
  const std::string heavy =
      replace(replace(ok, "poisson_ratio = 0.3\n", "poisson_ratio = 0.3\ndensity = 1000.0\n"),
              "poisson_ratio = 0.35\n", "poisson_ratio = 0.35\ndensity = 3000.0\n") +
      "\n[loads]\ngravity = [0, 0, -10]\n";
  const SolidScene weighed = read_solid_scene(write_scene(folder, heavy, "heavy.toml"));
  CHECK(weighed.problem.body_force(Point<3>(0.7, 0.7, 0.7), 0.0).z() == -1e4);
  CHECK(weighed.problem.body_force(Point<3>(1.0, 1.0, 1.0), 0.0).z() == -3e4);

  CHECK_THAT(refusal(replace(ok, "regions = \\[\"outer\"\\]", "regions = [\"shell\"]")),
             Catch::Contains("'shell'") && Catch::Contains("inner"));
  CHECK_THAT(refusal(replace(ok, "regions = \\[\"outer\"\\]", "regions = [\"inner\"]")),
             Catch::Contains("region 'inner' has a law already ([[material]] 'stiff core')"));
  CHECK_THAT(
      refusal(replace(ok,
                      "\\[\\[material\\]\\]\nname = \"soft shell\"\nregions = \\[\"outer\"\\]\nmodel = "
                      "\"linear_elastic\"\nyoungs_modulus = 200.0\npoisson_ratio = 0.35\n",
                      "")),
      Catch::Contains("region 'outer' has no law"));
  CHECK_THAT(refusal(replace(ok, "poisson_ratio = 0.35\n", "poisson_ratio = 0.35\ndensity = 10.0\n")),
             Catch::Contains("'soft shell' gives a density and 'stiff core' does not"));
  CHECK_THAT(refusal(replace(ok, "model = \"linear_elastic\"\nyoungs_modulus = 200.0",
                             "model = \"neo_hookean\"\nyoungs_modulus = 200.0")),
             Catch::Contains("errors against an exact solution are those of the small-strain law") &&
                 Catch::Contains("neo_hookean"));
  // A box is one region.
  CHECK_THAT(
      refusal(replace(box_scene("out"), "\\[material\\]", "[[material]]\nname = \"steel\"\nregions = []")),
      Catch::Contains("this solid has one region: use one [material] table"));
}
