// VTK frames of an MPM run: the particle fields asked for (and no others) read back bit for
// bit, the grid velocity field and mass on the cell corners, and the .pvd series.

#include <catch2/catch.hpp>
#include <unistd.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "../test_support.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/mpm_output.hpp"
#include "mfree/io/vtk_output.hpp"

namespace fs = std::filesystem;
using namespace mfree;
using mfree::testing::same_bits;
using mfree::testing::ScratchFolder;

namespace {


const AxisAlignedVibration vibration{0.05, 1.0, 1e7, 0.3, 1000.0};
const ExactMotion<2> vibration_motion = vibration.motion<2>();
const Walls open_walls{Wall::open, Wall::open, Wall::open, Wall::open};

/// The small vibration run of the unit square: quadratic B-splines, 4 x 4 cells, 2 x 2
/// particles per cell, before its first step.
MPMSolver small_solver(MPMMethod method, int degree, Walls walls) {
  const Box unit{Vec2(0, 0), Vec2(1, 1)};
  MPMProblem problem{unit, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}}, {rectangle_body("block", unit)}, {}};
  const AxisAlignedVibration v = vibration;
  problem.body_force = [v](const Vec2& X, double t) { return v.body_force(X, t); };
  problem.bodies.front().initial_velocity = [v](const Vec2& X) { return v.velocity(X, 0.0); };
  MPMSettings s;
  s.method = method;
  s.degree = degree;
  s.cells = 4;
  s.particles_per_side = 2;
  s.end_time = 1e-4;
  s.time_step = 1e-5;
  s.walls = walls;
  return MPMSolver(problem, s);
}

/// (time, file) of every data set a .pvd lists.
std::vector<std::pair<double, std::string>> pvd_steps(const fs::path& path) {
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(path.c_str()));
  REQUIRE(root != nullptr);
  vtkXMLDataElement* collection = root->FindNestedElementWithName("Collection");
  REQUIRE(collection != nullptr);
  std::vector<std::pair<double, std::string>> steps;
  for (int k = 0; k < collection->GetNumberOfNestedElements(); ++k) {
    vtkXMLDataElement* dataset = collection->GetNestedElement(k);
    steps.emplace_back(std::stod(dataset->GetAttribute("timestep")), dataset->GetAttribute("file"));
  }
  return steps;
}

/// Number of values of `read` that differ in any bit from `expected`, and of sizes.
std::size_t mismatches(const std::vector<double>& read, const std::vector<double>& expected) {
  if (read.size() != expected.size()) return std::max(read.size(), expected.size());
  std::size_t count = 0;
  for (std::size_t k = 0; k < read.size(); ++k)
    if (!same_bits(read[k], expected[k])) ++count;
  return count;
}

}  // namespace

TEST_CASE("MPM frames: particle fields read back bit for bit, and the series lists the frames",
          "[io][mpm_output]") {
  ScratchFolder folder("mpm_frames", false);
  MPMSolver solver = small_solver(MPMMethod::bspline, 2, open_walls);
  const std::vector<MPMMaterial> material{{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}};
  MPMFrameFields fields;
  fields.displacement = fields.velocity = fields.stress = fields.von_mises = fields.error = true;
  MPMFrames frames(folder.path, fields, &vibration_motion, material);
  CHECK(fs::is_directory(folder.path));  // created by the constructor
  frames.write(solver);
  solver.step();
  frames.write(solver);
  CHECK(frames.frames() == 2);
  CHECK(frames.series() == folder.path / "series.pvd");

  const std::vector<std::pair<double, std::string>> listed = pvd_steps(frames.series());
  REQUIRE(listed.size() == 2);
  CHECK(listed[0] == std::pair<double, std::string>(0.0, "particles_0000.vtu"));
  CHECK(listed[1] == std::pair<double, std::string>(solver.time(), "particles_0001.vtu"));
  CHECK(solver.time() > 0.0);
  // No grid asked for: no grid files.
  CHECK_FALSE(fs::exists(folder.path / "grid.pvd"));
  CHECK_FALSE(fs::exists(folder.path / "grid_0001.vti"));

  const VtuContents read = read_vtu(folder.path / "particles_0001.vtu");
  const Particles& P = solver.particles();
  const auto n = static_cast<std::size_t>(P.size());
  REQUIRE(read.points.size() == n);
  CHECK(read.cells == P.size());
  CHECK(read.array_names == std::vector<std::string>{"displacement", "velocity", "stress", "von_mises",
                                                     "displacement_error", "stress_error"});
  // What each array must hold, computed here from the solver's particles (2D vectors are
  // read back with z = 0).
  std::vector<double> u, v, sigma, vm, ue, se;
  std::size_t point_mismatches = 0;
  for (std::size_t p = 0; p < n; ++p) {
    const Vec2 up = P.position[p] - P.reference[p];
    const Mat2& s = P.stress[p];
    const Vec2 eu = up - vibration.displacement(P.reference[p], solver.time());
    const Mat2 es = s - vibration.cauchy_stress(P.reference[p], solver.time());
    if (!same_bits(read.points[p].x(), P.position[p].x()) || !same_bits(read.points[p].y(), P.position[p].y()))
      ++point_mismatches;
    u.insert(u.end(), {up.x(), up.y(), 0.0});
    v.insert(v.end(), {P.velocity[p].x(), P.velocity[p].y(), 0.0});
    sigma.insert(sigma.end(), {s(0, 0), s(1, 1), s(0, 1)});
    vm.push_back(von_mises(s, out_of_plane_stress(material[P.material[p]].law, P.deformation[p])));
    ue.insert(ue.end(), {eu.x(), eu.y(), 0.0});
    se.insert(se.end(), {es(0, 0), es(1, 1), es(0, 1)});
  }
  CHECK(point_mismatches == 0);  // one vertex per particle, at x_p
  CHECK(mismatches(read.arrays.at("displacement"), u) == 0);
  CHECK(mismatches(read.arrays.at("velocity"), v) == 0);
  CHECK(mismatches(read.arrays.at("stress"), sigma) == 0);
  CHECK(mismatches(read.arrays.at("von_mises"), vm) == 0);
  CHECK(mismatches(read.arrays.at("displacement_error"), ue) == 0);
  CHECK(mismatches(read.arrays.at("stress_error"), se) == 0);
  // The motion has started, so the displacement is not trivially zero.
  CHECK(std::any_of(u.begin(), u.end(), [](double c) { return c != 0.0; }));
}

TEST_CASE("MPM frames: only the fields asked for; errors need an exact solution", "[io][mpm_output]") {
  ScratchFolder folder("mpm_frames_some", false);
  MPMSolver solver = small_solver(MPMMethod::bspline, 2, open_walls);
  const std::vector<MPMMaterial> material{{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}};
  MPMFrameFields fields;
  fields.velocity = true;
  fields.von_mises = true;
  fields.body = true;
  MPMFrames frames(folder.path, fields, nullptr, material);
  frames.write(solver);
  const VtuContents some = read_vtu(folder.path / "particles_0000.vtu");
  CHECK(some.array_names == std::vector<std::string>{"velocity", "von_mises", "body"});
  CHECK(some.arrays.at("body") == std::vector<double>(static_cast<std::size_t>(solver.particles().size()), 0.0));

  // No fields at all: the particles alone.
  MPMFrames bare(folder.path / "bare", MPMFrameFields{}, nullptr, material);
  bare.write(solver);
  CHECK(read_vtu(folder.path / "bare" / "particles_0000.vtu").array_names.empty());

  MPMFrameFields with_error;
  with_error.error = true;
  const fs::path refused = folder.path / "refused";
  const auto construct = [&] { MPMFrames f(refused, with_error, nullptr, material); };
  CHECK_THROWS_AS(construct(), InputError);
  CHECK_THAT(testing::message_of(construct), Catch::Contains("exact solution") && Catch::Contains("refused"));
  CHECK_FALSE(fs::exists(refused));  // refused before anything was created
}

TEST_CASE("MPM frames: grid velocity field and mass at the cell corners", "[io][mpm_output]") {
  ScratchFolder folder("mpm_frames_grid", false);
  MPMSolver solver = small_solver(MPMMethod::bspline, 2, {Wall::slip, Wall::open, Wall::slip, Wall::open});
  MPMFrameFields fields;
  fields.grid = true;
  MPMFrames frames(folder.path, fields, nullptr, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}});
  // Before the first step the grid holds nothing: no grid file for frame 0.
  frames.write(solver);
  CHECK_FALSE(fs::exists(folder.path / "grid_0000.vti"));
  solver.step();
  frames.write(solver);
  solver.step();
  frames.write(solver);

  CHECK(pvd_steps(frames.series()).size() == 3);
  const std::vector<std::pair<double, std::string>> grid_listed = pvd_steps(frames.grid_series());
  REQUIRE(grid_listed.size() == 2);
  CHECK(grid_listed[0].second == "grid_0001.vti");
  CHECK(grid_listed[1] == std::pair<double, std::string>(solver.time(), "grid_0002.vti"));

  const VtiContents read = read_vti(folder.path / "grid_0002.vti");
  const Grid& grid = solver.grid();
  // B-spline grids cover the domain exactly: 4 cells, 5 corners per side.
  CHECK(read.nx == 5);
  CHECK(read.ny == 5);
  CHECK(read.origin == Vec2(0.0, 0.0));
  CHECK(read.spacing == grid.spacing());
  CHECK(read.array_names == std::vector<std::string>{"velocity", "mass"});
  const std::vector<double>& v = read.arrays.at("velocity");
  const std::vector<double>& m = read.arrays.at("mass");
  REQUIRE(v.size() == 3 * 25);
  REQUIRE(m.size() == 25);

  // Slip walls: the normal velocity vanishes along the left and bottom edges, the other
  // component does not in general.
  bool left_held = true, bottom_held = true, moving = false;
  for (int k = 0; k < 5; ++k) {
    left_held = left_held && v[3 * (5 * k)] == 0.0;
    bottom_held = bottom_held && v[3 * k + 1] == 0.0;
    moving = moving || v[3 * (5 * k) + 1] != 0.0;
  }
  CHECK(left_held);
  CHECK(bottom_held);
  CHECK(moving);

  // At the far corner only the last basis function is non-zero, and it is 1 there: the field
  // is that node's velocity and mass / h^2 exactly. That corner has no wall.
  const auto last = static_cast<std::size_t>(grid.size() - 1);
  const double h = grid.spacing();
  CHECK(same_bits(v[3 * 24], solver.grid_velocity()[last].x()));
  CHECK(same_bits(v[3 * 24 + 1], solver.grid_velocity()[last].y()));
  CHECK(solver.grid_velocity()[last].x() != 0.0);
  CHECK(same_bits(m[24], solver.grid_mass()[last] / (h * h)));
  // In the middle of the body the mass field is close to the density.
  CHECK(m[2 + 5 * 2] == Approx(1000.0).epsilon(0.05));
}

TEST_CASE("MPM frames: the grid image spans the padding of hat-function grids", "[io][mpm_output]") {
  ScratchFolder folder("mpm_frames_padded", false);
  MPMSolver solver = small_solver(MPMMethod::ugimp, 1, open_walls);
  solver.step();
  MPMFrameFields fields;
  fields.grid = true;
  MPMFrames frames(folder.path, fields, nullptr, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}});
  frames.write(solver);
  const VtiContents read = read_vti(folder.path / "grid_0000.vti");
  // One cell of padding on every side: 6 cells, 7 corners per side, from (-h, -h).
  CHECK(read.nx == 7);
  CHECK(read.ny == 7);
  CHECK(read.origin == Vec2(-0.25, -0.25));
  // No particle reaches the outer corners; the centre holds about the density.
  const std::vector<double>& m = read.arrays.at("mass");
  CHECK(m[0] == 0.0);
  CHECK(m[48] == 0.0);
  CHECK(m[3 + 7 * 3] == Approx(1000.0).epsilon(0.05));
}

TEST_CASE("MPM frames: the particle domains as quadrilaterals, CPDI2's tracked corners bit for bit", "[io][mpm_output]") {
  ScratchFolder folder("mpm_frames_domains", false);
  MPMSolver solver = small_solver(MPMMethod::cpdi2, 1, open_walls);
  MPMFrameFields fields;
  fields.domains = true;
  MPMFrames frames(folder.path, fields, nullptr, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}});
  frames.write(solver);
  for (int n = 0; n < 5; ++n) solver.step();
  frames.write(solver);
  const std::vector<std::pair<double, std::string>> listed = pvd_steps(frames.domain_series());
  REQUIRE(listed.size() == 2);
  CHECK(listed[1] == std::pair<double, std::string>(solver.time(), "domains_0001.vtu"));
  const VtuContents read = read_vtu(folder.path / "domains_0001.vtu");
  const Particles& P = solver.particles();
  CHECK(read.cells == P.size());
  REQUIRE(read.points.size() == 4 * P.corners.size());
  std::size_t mismatched = 0;
  double moved = 0.0;
  for (std::size_t p = 0; p < P.corners.size(); ++p)
    for (std::size_t k = 0; k < 4; ++k) {
      const Vec2& c = P.corners[p][k];
      const Vec2& r = read.points[4 * p + k];
      if (!same_bits(r.x(), c.x()) || !same_bits(r.y(), c.y())) ++mismatched;
      moved = std::max(moved, (c - parallelogram_corners(P.reference[p], Mat2::Identity(), P.half_size[p])[k]).norm());
    }
  CHECK(mismatched == 0);
  CHECK(moved > 1e-6);  // the corners moved with the motion
  CHECK(read.arrays.at("body") == std::vector<double>(4 * P.corners.size(), 0.0));

  // A method without particle domains has none to write.
  ScratchFolder other("mpm_frames_no_domains", false);
  MPMFrames none(other.path, fields, nullptr, {{"rubber", make_material("neo_hookean", 1e7, 0.3), 1000.0}});
  CHECK_THROWS_WITH(none.write(small_solver(MPMMethod::bspline, 2, open_walls)),
                    Catch::Contains("method bspline has no particle domains"));
}
