#include <catch2/catch.hpp>
#include <filesystem>
#include <fstream>
#include <regex>

#include "../test_support.hpp"
#include "mfree/io/solid_output.hpp"
#include "mfree/io/vtk_output.hpp"

using namespace mfree;

namespace {

/// The vibration scene on a coarse cloud, stored in `folder`, writing the fields listed into
/// `folder`/frames.
ElasticityScene vibration_scene(const std::filesystem::path& folder, const std::string& fields) {
  const auto dir = folder / "frames";
  std::ifstream in(mfree::testing::source_dir() + "/verification/vibration/vibration.toml");
  std::string text{std::istreambuf_iterator<char>(in), {}};
  text = std::regex_replace(text, std::regex("spacing = 0.0625"), "spacing = 0.25");
  text = std::regex_replace(text, std::regex("folder = \"results/vibration\""), "folder = \"" + dir.string() + "\"");
  text = std::regex_replace(text, std::regex("fields = \\[.*\\]"), "fields = [" + fields + "]");
  const auto path = folder / "scene.toml";
  std::ofstream(path) << text;
  return read_elasticity_scene(path, false);
}

/// A scratch folder of this test process, the coarse vibration scene writing the fields into
/// its `frames` subfolder, and its discretisation.
struct FramesCase {
  testing::ScratchFolder folder;
  ElasticityScene scene;
  std::filesystem::path dir;
  Discretisation<2> disc;
  FramesCase(const std::string& name, const std::string& fields)
      : folder(name), scene(vibration_scene(folder.path, fields)), dir(scene.output.folder) {
    StageTimer timer;
    disc = discretise(scene.domain, scene.settings, timer);
  }
};

}  // namespace

TEST_CASE("VTK frames: a .pvd series of .vtu files holding the fields asked for and no others", "[io]") {
  const FramesCase fc("frames", "\"displacement\", \"velocity\"");
  const auto& [folder, scene, dir, disc] = fc;
  SolidFrames frames(scene, disc, nullptr);
  Eigen::VectorXd d = Eigen::VectorXd::Zero(2 * disc.node_count()), v = d;
  for (Index i = 0; i < disc.node_count(); ++i) d.segment<2>(2 * i) = Vec2(0.01, -0.02);  // a translation
  frames.write(0.0, Eigen::VectorXd::Zero(d.size()), &v);
  frames.write(0.001, d, &v);
  REQUIRE(frames.frames() == 2);
  const VtuContents f = read_vtu(dir / "field_0001.vtu");
  CHECK(f.arrays.count("displacement") == 1);
  CHECK(f.arrays.count("velocity") == 1);
  CHECK(f.arrays.count("cauchy_stress_xx_yy_xy") == 0);
  CHECK(f.arrays.count("von_mises") == 0);
  // u^h = sum phi_I d_I reproduces the translation (partition of unity) at every point.
  const auto& u = f.arrays.at("displacement");
  const int c = f.components.at("displacement");
  for (std::size_t k = 0; k < f.points.size(); ++k) {
    CHECK(std::abs(u[c * k] - 0.01) <= 1e-13);
    CHECK(std::abs(u[c * k + 1] + 0.02) <= 1e-13);
  }
  std::ifstream pvd(dir / "series.pvd");
  const std::string text{std::istreambuf_iterator<char>(pvd), {}};
  CHECK(text.find("field_0000.vtu") != std::string::npos);
  CHECK(text.find("field_0001.vtu") != std::string::npos);
  CHECK(text.find("timestep=\"0.001\"") != std::string::npos);
}

TEST_CASE("VTK frames: stress is the Cauchy stress of F = I + grad u^h, zero for a rigid motion", "[io]") {
  const FramesCase fc("frames_stress", "\"stress\", \"von_mises\"");
  const auto& [folder, scene, dir, disc] = fc;
  SolidFrames frames(scene, disc, nullptr);
  // A rigid rotation by 0.7 rad about the origin: u = (R - I) X, stress free for Neo-Hookean.
  Mat2 r;
  r << std::cos(0.7), -std::sin(0.7), std::sin(0.7), std::cos(0.7);
  Eigen::VectorXd d(2 * disc.node_count());
  for (Index i = 0; i < disc.node_count(); ++i) d.segment<2>(2 * i) = (r - Mat2::Identity()) * disc.nodes[i];
  frames.write(0.0, d, nullptr);
  const VtuContents f = read_vtu(dir / "field_0000.vtu");
  REQUIRE(f.arrays.count("cauchy_stress_xx_yy_xy") == 1);
  CHECK(f.arrays.count("displacement") == 0);
  double worst = 0.0;
  for (double s : f.arrays.at("cauchy_stress_xx_yy_xy")) worst = std::max(worst, std::abs(s));
  for (double s : f.arrays.at("von_mises")) worst = std::max(worst, std::abs(s));
  CHECK(worst <= 1e-6);  // Pa, against E = 1e7: round-off of a rotation reproduced by linear RK
}

TEST_CASE("VTK frames of a law with history: stress and plastic strain at the quadrature points, where they live",
          "[io][plasticity]") {
  const testing::ScratchFolder folder("frames_history");
  const ElasticityScene scene = read_elasticity_scene(
      mfree::testing::source_dir() + "/verification/plastic-cylinder/cylinder.toml", false,
      {"nodes.spacing=0.2", "output.folder=\"" + (folder.path / "out").string() + "\"",
       "output.fields=[\"displacement\", \"stress\", \"plastic_strain\"]"});
  StageTimer timer;
  const Discretisation<2> disc = discretise(scene.domain, scene.settings, timer);
  TotalLagrangian<2> model(scene.solid_problem(), scene.domain, disc.node_count(), disc.quadrature,
                           disc.test(), disc.boundary, disc.at_boundary);
  // A radial expansion u = 0.004 X, yielding near the inner radius, committed.
  Eigen::VectorXd d(model.dofs());
  for (Index i = 0; i < disc.node_count(); ++i) d.segment<2>(2 * i) = 0.004 * disc.nodes[i] / disc.nodes[i].squaredNorm();
  model.commit(d);
  SolidFrames frames(scene, disc, nullptr, &model);
  frames.write(1.0, d, nullptr);
  const VtuContents triangles = read_vtu(scene.output.folder / "field_0000.vtu");
  CHECK(triangles.arrays.count("displacement") == 1);
  CHECK(triangles.arrays.count("cauchy_stress_xx_yy_xy") == 0);  // not recomputed from F where no state lives
  const VtuContents points = read_vtu(scene.output.folder / "points_0000.vtu");
  REQUIRE(points.points.size() == static_cast<std::size_t>(disc.quadrature.size()));
  const std::vector<double>& alpha = points.arrays.at("plastic_strain");
  double yielded = 0.0, worst = 0.0;
  for (Index k = 0; k < disc.quadrature.size(); ++k) {
    yielded = std::max(yielded, alpha[k]);
    worst = std::max(worst, std::abs(alpha[k] - model.history().domain[k].alpha));
  }
  CHECK(yielded > 0.0);
  CHECK(worst <= 1e-12 * yielded);  // the committed state (its update at the same F changes nothing)
  CHECK(points.arrays.count("cauchy_stress_xx_yy_xy") == 1);
  CHECK(std::filesystem::exists(frames.point_series()));
}
