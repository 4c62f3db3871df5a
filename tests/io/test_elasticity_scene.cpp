#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/elasticity_output.hpp"
#include "mfree/io/elasticity_scene.hpp"
#include "mfree/io/vtk_output.hpp"

using namespace mfree;

namespace {

std::string cantilever_text() {
  std::ifstream in(mfree::testing::source_dir() + "/verification/cantilever/cantilever.toml");
  return {std::istreambuf_iterator<char>(in), {}};
}

/// The error message for a scene text, "" when it parses.
std::string scene_error(const std::string& text, const std::string& name = "scene.toml") {
  static const testing::ScratchFolder folder("elasticity_scene");  // one per test process
  const auto path = folder.path / name;
  std::ofstream(path) << text;
  try {
    (void)read_elasticity_scene(path, false);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string replace(std::string text, const std::string& from, const std::string& to) {
  return std::regex_replace(text, std::regex(from), to);
}

}  // namespace

TEST_CASE("elasticity scenes: bad input is refused naming the key and line", "[io]") {
  const std::string good = cantilever_text();
  CHECK(scene_error(good).empty());
  CHECK_THAT(scene_error(replace(good, "youngs_modulus = 3.0e7", "youngs_modulus = -3.0e7")),
             Catch::Contains("material.youngs_modulus") && Catch::Contains("scene.toml:"));
  CHECK_THAT(scene_error(replace(good, "poisson_ratio = 0.3", "poisson_ratio = 0.5")),
             Catch::Contains("material.poisson_ratio"));
  CHECK_THAT(scene_error(replace(good, "spacing = 1.5", "spacing = 'fine'")),
             Catch::Contains("nodes.spacing") && Catch::Contains("expected a number"));
  CHECK_THAT(scene_error(replace(good, "beta = 100.0", "betta = 100.0")),
             Catch::Contains("nitsche.betta") && Catch::Contains("unknown key"));
  CHECK_THAT(scene_error(replace(good, "cloud = \"lattice\"", "cloud = \"hexagonal\"")),
             Catch::Contains("nodes.cloud") && Catch::Contains("not one of"));
  CHECK_THAT(scene_error(replace(good, "rectangle = \\[\\[0.0, -6.0\\], \\[48.0, 6.0\\]\\]", "mesh = \"no/such.wkt\"")),
             Catch::Contains("no/such.wkt"));
  CHECK_THAT(scene_error(replace(replace(good, "\\[exact\\]\nsolution = \"timoshenko_beam\"\nload = 1000.0\n", ""), "\"error\", ", "")),
             Catch::Contains("boundary[0].value") && Catch::Contains("needs a static [exact] solution"));
  CHECK_THAT(scene_error(replace(good, "part = \"left\"", "region = [[-0.001, -6.001]]")),
             Catch::Contains("boundary[0].region") && Catch::Contains("2 points"));
  // Total-Lagrangian keys.
  // (Dynamics takes no static [exact] solution: the beam's tractions become given values.)
  const std::string dyn = replace(replace(replace(good, "\\[exact\\]\nsolution = \"timoshenko_beam\"\nload = 1000.0\n", ""),
                                          "value = \"exact\"", "value = [0.0, 0.0]"),
                                  "\"error\", ", "") +
                          "\n[dynamics]\nscheme = \"newmark\"\nend_time = 0.01\n";
  CHECK_THAT(scene_error(good + "\n[dynamics]\nscheme = \"newmark\"\nend_time = 0.01\ntime_step = 1e-4\n"),
             Catch::Contains("exact.solution") && Catch::Contains("timoshenko_beam solution is static"));
  CHECK_THAT(scene_error(dyn), Catch::Contains("dynamics.scheme") && Catch::Contains("newmark needs a time_step"));
  CHECK_THAT(scene_error(dyn + "time_step = 1e-4\n"),
             Catch::Contains("dynamics.scheme") && Catch::Contains("needs the material's density"));
  CHECK_THAT(scene_error(good + "\n[newton]\nload_factors = [0.5, 0.25, 1.0]\n"),
             Catch::Contains("newton.load_factors") && Catch::Contains("must increase"));
  CHECK_THAT(scene_error(good + "\n[newton]\nload_factors = [0.5, 0.75]\n"), Catch::Contains("must end at 1"));
  CHECK_THAT(scene_error(replace(good, "model = \"plane_stress\"", "model = \"mooney_rivlin\"")),
             Catch::Contains("material.model") && Catch::Contains("not one of"));
  CHECK_THAT(scene_error(replace(good, "solution = \"timoshenko_beam\"\nload = 1000.0",
                                 "solution = \"vibration\"\namplitude = 0.05")),
             Catch::Contains("exact.solution") && Catch::Contains("vibration solution is a motion"));
  const std::string quadratic =
      "solution = \"quadratic\"\noffset = [0.0, 0.0]\ngradient = [[0.0, 0.0], [0.0, 0.0]]\n"
      "hessian_x = [[1.0, 0.5], [0.5, 2.0]]\nhessian_y = [[0.0, 1.0], [-1.0, 0.0]]";
  CHECK_THAT(scene_error(replace(good, "solution = \"timoshenko_beam\"\nload = 1000.0", quadratic)),
             Catch::Contains("exact.hessian_y") && Catch::Contains("symmetric"));
}

TEST_CASE("elasticity scenes: [quadrature] is optional, and its keys of other schemes are refused", "[io]") {
  const std::string good = cantilever_text();
  // Without [quadrature] the scene reads with the defaults: Gauss cells with VCI.
  const std::string bare = replace(replace(good, "\\[quadrature\\]\nscheme = \"projected\"\nratio = 4.0\norder = \"linear\"\nlattice_refinement = 2\n", ""),
                                   "schemes = \\[\"projected\", \"gauss_cells\", \"nodal\"\\]", "schemes = [\"gauss_cells\"]");
  REQUIRE(bare.find("[quadrature]") == std::string::npos);
  CHECK(scene_error(bare).empty());
  // A projected-scheme key in a scene that never runs that scheme is not silently ignored.
  CHECK_THAT(scene_error(bare + "\n[quadrature]\nratio = 9.0\n"),
             Catch::Contains("quadrature.ratio") && Catch::Contains("projected scheme only"));
  CHECK_THAT(scene_error(bare + "\n[quadrature]\nlattice_refinement = 3\n"), Catch::Contains("quadrature.lattice_refinement"));
  CHECK(scene_error(bare + "\n[quadrature]\ngauss_points = 4\n").empty());
  // The cantilever's own study runs every scheme: each key has a reader.
  CHECK(scene_error(replace(good, "lattice_refinement = 2", "lattice_refinement = 2\ngauss_points = 4")).empty());
  CHECK_THAT(scene_error(replace(replace(good, "schemes = \\[\"projected\", \"gauss_cells\", \"nodal\"\\]", "schemes = [\"projected\"]"),
                                 "lattice_refinement = 2", "lattice_refinement = 2\ngauss_points = 4")),
             Catch::Contains("quadrature.gauss_points") && Catch::Contains("gauss_cells scheme only"));
}

TEST_CASE("elasticity scenes: the quadratic exact field and its body force", "[io]") {
  const std::string text = replace(cantilever_text(), "solution = \"timoshenko_beam\"\nload = 1000.0",
                                   "solution = \"quadratic\"\noffset = [0.1, 0.2]\ngradient = [[0.0, 0.0], [0.0, 0.0]]\n"
                                   "hessian_x = [[2.0, 0.0], [0.0, 0.0]]\nhessian_y = [[0.0, 0.0], [0.0, 0.0]]");
  const testing::ScratchFolder folder("quadratic_exact");
  std::ofstream(folder.path / "scene.toml") << text;
  const ElasticityScene scene = read_elasticity_scene(folder.path / "scene.toml", false);
  const ExactElasticity exact = *scene.exact();
  // u_x = 0.1 + x^2: eps_xx = 2x, so sigma_xx = E / (1 - nu^2) 2x and b_x = -2E / (1 - nu^2)
  // in plane stress; b_y = -d sigma_xy / dx - d sigma_yy / dy = 0.
  const double e = 3.0e7, nu = 0.3;
  CHECK(exact.displacement(Vec2(3.0, 1.0)).isApprox(Vec2(9.1, 0.2), 1e-15));
  CHECK(std::abs(exact.stress(Vec2(3.0, 1.0))[0] - e / (1 - nu * nu) * 6.0) <= 1e-6);
  CHECK(std::abs(exact.body_force(Vec2(3.0, 1.0)).x() + 2.0 * e / (1 - nu * nu)) <= 1e-6);
  CHECK(exact.body_force(Vec2(3.0, 1.0)).y() == 0.0);
  CHECK(scene.settings.problem.body_force(Vec2(1.0, 1.0)).x() == exact.body_force(Vec2(1.0, 1.0)).x());
}

TEST_CASE("elasticity output: VTK files read back with the arrays asked for", "[io]") {
  const testing::ScratchFolder folder("elasticity_output");
  const auto dir = folder.path / "out";
  std::string text = replace(cantilever_text(), "spacing = 1.5", "spacing = 3.0");
  text = replace(text, "folder = \"results/cantilever\"", "folder = \"" + dir.string() + "\"");
  std::ofstream(folder.path / "scene.toml") << text;
  const ElasticityScene scene = read_elasticity_scene(folder.path / "scene.toml", false);
  const ExactElasticity exact = *scene.exact();
  const ElasticityResult r = solve_elasticity(scene.domain, scene.settings, &exact);
  const auto files = write_elasticity_fields(scene, r);
  REQUIRE(files.size() == 3);
  const VtuContents nodes = read_vtu(dir / "nodes.vtu");
  CHECK(nodes.points.size() == r.nodes.size());
  for (const char* a : {"displacement", "exact_displacement", "displacement_error", "stress_xx_yy_xy", "von_mises"})
    CHECK(nodes.arrays.count(a) == 1);
  // u^h at the nodes, not the coefficients: displacement - exact = error, and u^h != d.
  const auto& u = nodes.arrays.at("displacement");
  const auto& ue = nodes.arrays.at("exact_displacement");
  const auto& e = nodes.arrays.at("displacement_error");
  const int c = nodes.components.at("displacement");
  double max_diff = 0.0, max_coef_gap = 0.0;
  for (std::size_t i = 0; i < r.nodes.size(); ++i)
    for (int k = 0; k < 2; ++k) {
      max_diff = std::max(max_diff, std::abs(u[c * i + k] - ue[c * i + k] - e[c * i + k]));
      max_coef_gap = std::max(max_coef_gap, std::abs(u[c * i + k] - r.coefficients[2 * i + k]));
    }
  CHECK(max_diff <= 1e-15);
  CHECK(max_coef_gap > 1e-8);
  const VtuContents q = read_vtu(dir / "quadrature.vtu");
  REQUIRE(q.arrays.count("weight") == 1);
  double sum = 0.0;
  for (double w : q.arrays.at("weight")) sum += w;
  CHECK(sum == Approx(48.0 * 12.0).epsilon(1e-12));
  const VtuContents f = read_vtu(dir / "field.vtu");
  CHECK(f.cells > 0);
  CHECK(f.arrays.count("von_mises") == 1);
}
