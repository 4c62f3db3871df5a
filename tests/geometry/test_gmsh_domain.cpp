#include <signal.h>

#include <catch2/catch.hpp>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/geometry/boundary_selection.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/geometry/gmsh_domain.hpp"
#include "mfree/geometry/polygon_integrals.hpp"

using mfree::BoundarySegment;
using mfree::Domain;
using mfree::Vec2;

namespace {

const double pi = std::acos(-1.0);

std::string mesh_path(const std::string& name) { return mfree::testing::source_dir() + "/meshes/" + name; }

Domain mesh(const std::string& name) { return Domain::from_file(mesh_path(name)); }

/// Writes text to folder/name and returns the path.
std::string write_file(const mfree::testing::ScratchFolder& folder, const std::string& name,
                       const std::string& text) {
  const std::string path = (folder.path / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string input_error_message(const std::string& path) {
  return mfree::testing::message_of<mfree::InputError>([&] { (void)Domain::from_file(path); });
}

/// Total length and number of segments of every named part.
struct PartSum {
  double length = 0.0;
  int segments = 0;
};

std::map<std::string, PartSum> part_sums(const Domain& d) {
  std::map<std::string, PartSum> out;
  for (const BoundarySegment& s : d.boundary()) {
    PartSum& p = out[s.part < 0 ? std::string("<none>") : d.part_names()[s.part]];
    p.length += s.length;
    p.segments += 1;
  }
  return out;
}

/// Area of the polygon inscribed in a quarter circle of radius r with n equal pieces, closed
/// through the centre: n triangles of area r^2 sin(pi / (2n)) / 2.
double quarter_fan_area(double r, int n) { return 0.5 * n * r * r * std::sin(pi / (2 * n)); }

/// Length of n equal chords of a quarter circle of radius r.
double quarter_chords(double r, int n) { return n * 2 * r * std::sin(pi / (4 * n)); }

}  // namespace

TEST_CASE("gmsh quarter annulus: area of the inscribed polygon and of the annulus", "[geometry]") {
  // meshes/quarter_annulus.geo: a = 1 <= r <= b = 2, 64 pieces on the outer arc and, with the
  // same element size, 32 on the inner one.
  const double a = 1, b = 2;
  const Domain d = mesh("quarter_annulus.geo");
  REQUIRE(d.rings().size() == 1);
  const std::map<std::string, PartSum> parts = part_sums(d);
  REQUIRE(parts.count("outer") == 1);
  REQUIRE(parts.count("inner") == 1);
  const int nb = parts.at("outer").segments, na = parts.at("inner").segments;
  CHECK(nb == 64);
  CHECK(na == 32);

  // The polygon: the outer fan minus the inner fan (the straight edges lie on the axes).
  const double polygon = quarter_fan_area(b, nb) - quarter_fan_area(a, na);
  CHECK(d.area() == Approx(polygon).epsilon(1e-13));
  // Against the curved domain, pi (b^2 - a^2) / 4 = 3 pi / 4: each arc's chords cut off
  // pi r^2 / 4 - quarter_fan_area(r, n) (~ pi h^2 / 24 for the element size h, the same for
  // both arcs, so the two nearly cancel). Their sum bounds the error.
  const double exact = pi * (b * b - a * a) / 4;
  const double cut_outer = pi * b * b / 4 - quarter_fan_area(b, nb);
  const double cut_inner = pi * a * a / 4 - quarter_fan_area(a, na);
  CHECK(cut_outer == Approx(3.15e-4).epsilon(1e-2));
  CHECK(std::abs(d.area() - exact) <= cut_outer + cut_inner);
  // The near cancellation: 2.8e-8, against 3.2e-4 cut off by either arc.
  CHECK(std::abs(d.area() - exact) < 1e-3 * cut_outer);

  // The centroid lies on the diagonal (the domain is symmetric about y = x), to the accuracy
  // of gmsh's node placement: its chords are equal to about 1e-10, not to rounding.
  CHECK(d.first_moment().x() == Approx(d.first_moment().y()).epsilon(1e-10));
}

TEST_CASE("gmsh quarter annulus: lengths and segments of the named parts", "[geometry]") {
  const double a = 1, b = 2;
  const Domain d = mesh("quarter_annulus.geo");
  const std::vector<std::string>& names = d.part_names();
  CHECK(names.size() == 4);
  const std::map<std::string, PartSum> parts = part_sums(d);
  REQUIRE(parts.size() == 4);  // no segment without a part
  CHECK(parts.at("x_axis").length == Approx(1.0).epsilon(1e-14));
  CHECK(parts.at("y_axis").length == Approx(1.0).epsilon(1e-14));
  CHECK(parts.at("outer").length == Approx(quarter_chords(b, 64)).epsilon(1e-13));
  CHECK(parts.at("inner").length == Approx(quarter_chords(a, 32)).epsilon(1e-13));
  // The chords are shorter than the arcs, pi and pi / 2, by 1 - sin(t)/t ~ t^2 / 6.
  CHECK(parts.at("outer").length < pi * b / 2);
  CHECK(parts.at("outer").length == Approx(pi * b / 2).epsilon(1e-4));

  // Every segment's part agrees with where it lies.
  for (const BoundarySegment& s : d.boundary()) {
    INFO("segment " << s.edge << " from (" << s.a.x() << ", " << s.a.y() << ")");
    REQUIRE(s.part >= 0);
    const std::string& part = names[s.part];
    std::string where;
    if (s.a.y() == 0 && s.b.y() == 0) where = "x_axis";
    else if (s.a.x() == 0 && s.b.x() == 0) where = "y_axis";
    else if (std::abs(s.a.norm() - b) < 1e-14 && std::abs(s.b.norm() - b) < 1e-14) where = "outer";
    else if (std::abs(s.a.norm() - a) < 1e-14 && std::abs(s.b.norm() - a) < 1e-14) where = "inner";
    CHECK(part == where);
    // Outward normals: away from the centre on the outer arc, towards it on the inner one,
    // -y on the x axis and -x on the y axis.
    const Vec2 mid = 0.5 * (s.a + s.b);
    if (where == "outer") CHECK(s.normal.dot(mid) > 0.99 * mid.norm());
    if (where == "inner") CHECK(s.normal.dot(mid) < -0.99 * mid.norm());
    if (where == "x_axis") CHECK(s.normal == Vec2(0, -1));
    if (where == "y_axis") CHECK(s.normal == Vec2(-1, 0));
  }
}

TEST_CASE("gmsh quarter annulus: the .msh written by gmsh reads back to the same domain", "[geometry]") {
  // meshes/quarter_annulus.msh is `gmsh -1 quarter_annulus.geo` (see meshes/README.md). Its
  // coordinates are printed with 16 digits, so they match to about one rounding.
  const Domain geo = mesh("quarter_annulus.geo");
  const Domain msh = mesh("quarter_annulus.msh");
  CHECK(msh.part_names() == geo.part_names());
  REQUIRE(msh.rings().size() == geo.rings().size());
  REQUIRE(msh.boundary().size() == geo.boundary().size());
  for (std::size_t i = 0; i < geo.boundary().size(); ++i) {
    const BoundarySegment& s = geo.boundary()[i];
    const BoundarySegment& t = msh.boundary()[i];
    INFO("segment " << i);
    CHECK((s.a - t.a).norm() < 1e-15);
    CHECK((s.b - t.b).norm() < 1e-15);
    CHECK(s.part == t.part);
  }
  CHECK(msh.area() == Approx(geo.area()).epsilon(1e-14));
}

TEST_CASE("gmsh plate with a hole: .geo with named parts and its STEP export", "[geometry]") {
  const double r = 0.5;
  // The 64-gon hole of plate_with_hole.geo is the hole of plate_with_hole.wkt.
  const Domain plate = mesh("plate_with_hole.geo");
  REQUIRE(plate.rings().size() == 2);
  CHECK(plate.rings()[1].size() == 64);
  CHECK(plate.rings()[0].size() == 4 * 16);
  CHECK(plate.area() == Approx(16 - 8 * std::sin(pi / 32)).epsilon(1e-14));
  CHECK(plate.area() == Approx(mesh("plate_with_hole.wkt").area()).epsilon(1e-14));
  const std::map<std::string, PartSum> parts = part_sums(plate);
  REQUIRE(parts.size() == 5);
  for (const std::string side : {"left", "right", "bottom", "top"}) {
    INFO(side);
    CHECK(parts.at(side).length == Approx(4.0).epsilon(1e-14));
    CHECK(parts.at(side).segments == 16);
  }
  CHECK(parts.at("hole").length == Approx(64 * 2 * r * std::sin(pi / 64)).epsilon(1e-13));
  for (const BoundarySegment& s : plate.boundary()) CHECK((s.ring == 1) == (plate.part_names()[s.part] == "hole"));

  // The same geometry as CAD (exported by gmsh's OpenCASCADE kernel): no physical groups and no
  // element sizes, so no named parts and gmsh's default sizes: a coarser regular polygon.
  const Domain cad = mesh("plate_with_hole.step");
  CHECK(cad.part_names().empty());
  for (const BoundarySegment& s : cad.boundary()) CHECK(s.part == -1);
  REQUIRE(cad.rings().size() == 2);
  CHECK(mfree::ring_area(cad.rings()[0]) == Approx(16.0).epsilon(1e-14));
  const int n = static_cast<int>(cad.rings()[1].size());
  CHECK(n >= 8);
  for (const Vec2& x : cad.rings()[1]) CHECK(x.norm() == Approx(r).epsilon(1e-12));
  CHECK(cad.area() == Approx(16 - 0.5 * n * r * r * std::sin(2 * pi / n)).epsilon(1e-12));
}

TEST_CASE("gmsh domains: several surfaces, curves in any direction, unnamed groups", "[geometry]") {
  const mfree::testing::ScratchFolder folder("gmsh_surfaces");
  // Two unit squares sharing the curve x = 1 (interior, so not boundary); the curves run in
  // both directions. Group 7 has no name; curve 6 is in no group.
  const std::string path = write_file(folder, "two_squares.geo", R"(
    Point(1) = {0, 0, 0, 0.25}; Point(2) = {1, 0, 0, 0.25}; Point(3) = {2, 0, 0, 0.25};
    Point(4) = {2, 1, 0, 0.25}; Point(5) = {1, 1, 0, 0.25}; Point(6) = {0, 1, 0, 0.25};
    Line(1) = {2, 1}; Line(2) = {2, 3}; Line(3) = {4, 3}; Line(4) = {4, 5};
    Line(5) = {5, 6}; Line(6) = {1, 6}; Line(7) = {2, 5};
    Curve Loop(1) = {-1, 7, 5, -6}; Plane Surface(1) = {1};
    Curve Loop(2) = {2, -3, 4, -7}; Plane Surface(2) = {2};
    Physical Curve("bottom") = {1, 2};
    Physical Curve(7) = {3};
    Physical Curve("top") = {4, 5};
    Physical Curve("shared") = {7};
  )");
  const Domain d = Domain::from_file(path);
  REQUIRE(d.rings().size() == 1);
  CHECK(d.area() == Approx(2.0).epsilon(1e-15));
  // The shared curve is interior: its group names no boundary part.
  CHECK(d.part_names() == std::vector<std::string>{"bottom", "7", "top"});
  const std::map<std::string, PartSum> parts = part_sums(d);
  CHECK(parts.at("bottom").length == Approx(2.0).epsilon(1e-15));
  CHECK(parts.at("top").length == Approx(2.0).epsilon(1e-15));
  CHECK(parts.at("7").length == Approx(1.0).epsilon(1e-15));
  CHECK(parts.at("<none>").length == Approx(1.0).epsilon(1e-15));
  CHECK(parts.at("bottom").segments == 8);
}

TEST_CASE("gmsh domains: reads from several threads at once give the same domain", "[geometry]") {
  // gmsh is one global state; the reader serialises its sessions.
  const Domain reference = mesh("quarter_annulus.geo");
  std::vector<double> areas(4, 0.0);
  std::vector<std::thread> threads;
  for (std::size_t i = 0; i < areas.size(); ++i) {
    threads.emplace_back([&areas, i] {
      areas[i] = mesh(i % 2 == 0 ? "quarter_annulus.geo" : "quarter_annulus.msh").area();
    });
  }
  for (std::thread& t : threads) t.join();
  for (const double a : areas) CHECK(a == Approx(reference.area()).epsilon(1e-14));
}

TEST_CASE("gmsh domains: bad files are InputErrors naming the file", "[geometry]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_errors");

  const std::string bad = write_file(folder, "bad.geo", "Point(1) = {0, 0, 0};\nLine(1) = {1, 2 ;\n");
  CHECK_THAT(input_error_message(bad), Contains(bad) && Contains("gmsh cannot read it") && Contains("syntax error"));

  const std::string garbage = write_file(folder, "garbage.msh", "not a mesh\n");
  CHECK_THAT(input_error_message(garbage), Contains(garbage) && Contains("gmsh cannot read it"));

  const std::string missing = (folder.path / "missing.geo").string();
  CHECK_THAT(input_error_message(missing), Contains(missing) && Contains("does not exist"));

  const std::string unknown = write_file(folder, "shape.dxf", "0\nSECTION\n");
  CHECK_THAT(input_error_message(unknown),
             Contains(unknown) && Contains("unknown extension '.dxf'") && Contains(".wkt") && Contains(".geo") &&
                 Contains(".step"));
  CHECK_THAT(mfree::testing::message_of<mfree::InputError>([&] { (void)mfree::read_gmsh_domain(unknown); }),
             Contains(unknown) && Contains("unknown extension"));

  const std::string curves = write_file(folder, "curves.geo", R"(
    Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {0, 1, 0};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
  )");
  CHECK_THAT(input_error_message(curves), Contains(curves) && Contains("no 2D entity") && Contains("3 curves"));

  const std::string islands = write_file(folder, "islands.geo", R"(
    Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
    Point(5) = {3, 0, 0}; Point(6) = {4, 0, 0}; Point(7) = {4, 2, 0}; Point(8) = {3, 2, 0};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
    Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
    Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
    Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
  )");
  CHECK_THAT(input_error_message(islands), Contains(islands) && Contains("2 disconnected regions") &&
                                               Contains("[0, 1] x [0, 1]") && Contains("[3, 4] x [0, 2]"));

  const std::string twice = write_file(folder, "twice.geo", R"(
    Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {0, 1, 0};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
    Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
    Physical Curve("load") = {2};
    Physical Curve("wall") = {1, 2};
  )");
  CHECK_THAT(input_error_message(twice), Contains(twice) && Contains("curve 2") && Contains("'load' and 'wall'"));

  const std::string lifted = write_file(folder, "lifted.geo", R"(
    Point(1) = {0, 0, 1}; Point(2) = {1, 0, 1}; Point(3) = {0, 1, 1};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
    Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
  )");
  CHECK_THAT(input_error_message(lifted), Contains(lifted) && Contains("off the plane z = 0"));

  const std::string box = write_file(folder, "box.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n");
  CHECK_THAT(input_error_message(box), Contains(box) && Contains("1 3D volume"));

  // A triangle whose hypotenuse (curve 2, from node 2 to node 3) has one element from node 2
  // to its midpoint 4 only: the ring stops at nodes 3 and 4.
  const std::string open = write_file(folder, "open.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Entities
3 3 1 0
1 0 0 0 0
2 1 0 0 0
3 0 1 0 0
1 0 0 0 1 0 0 0 2 1 -2
2 0 0 0 1 1 0 0 2 2 -3
3 0 0 0 0 1 0 0 2 3 -1
1 0 0 0 1 1 0 0 3 1 2 3
$EndEntities
$Nodes
4 4 1 4
0 1 0 1
1
0 0 0
0 2 0 1
2
1 0 0
0 3 0 1
3
0 1 0
1 2 0 1
4
0.5 0.5 0
$EndNodes
$Elements
3 3 1 3
1 1 1 1
1 1 2
1 2 1 1
2 2 4
1 3 1 1
3 3 1
$EndElements
)");
  CHECK_THAT(input_error_message(open), Contains(open) && Contains("does not close") && Contains("(0, 1)"));
}

namespace {

/// A unit square whose point sizes are `size`: gmsh meshes its sides into 4 / size elements.
std::string square_geo(const std::string& size) {
  return "lc = " + size + R"(;
    Point(1) = {0, 0, 0, lc}; Point(2) = {1, 0, 0, lc}; Point(3) = {1, 1, 0, lc}; Point(4) = {0, 1, 0, lc};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
    Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
  )";
}

/// The InputError message of reading `path` under `limits`, and the seconds it took.
std::pair<std::string, double> timed_refusal(const std::string& path, const mfree::GmshReaderLimits& limits) {
  const auto start = std::chrono::steady_clock::now();
  const std::string message =
      mfree::testing::message_of<mfree::InputError>([&] { (void)mfree::read_gmsh_domain(path, limits); });
  return {message, std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()};
}

}  // namespace

TEST_CASE("gmsh domains: the reader's limits by default", "[geometry]") {
  const mfree::GmshReaderLimits limits = mfree::default_gmsh_reader_limits();
  CHECK(limits.wall_time == std::chrono::seconds(60));
  CHECK(limits.memory_bytes <= std::size_t{2} << 30);
  CHECK(static_cast<double>(limits.memory_bytes) <= 0.5 * mfree::available_memory().bytes);
  // Either figure is far above what gmsh needs for a usual file (below 100 MiB).
  CHECK(limits.memory_bytes > std::size_t{100} << 20);
}

TEST_CASE("gmsh domains: a usual file reads under small limits", "[geometry]") {
  // The quarter annulus takes gmsh 15 ms (a square of 40 000 boundary elements: 50 ms and
  // 11 MiB beyond what the reader inherits).
  const Domain d =
      mfree::read_gmsh_domain(mesh_path("quarter_annulus.geo"), {std::chrono::seconds(1), 64u << 20});
  CHECK(d.area() == Approx(mesh("quarter_annulus.geo").area()).epsilon(1e-15));
}

TEST_CASE("gmsh domains: a file that never ends is refused at the wall-time limit", "[geometry]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_time");
  const mfree::GmshReaderLimits limits{std::chrono::milliseconds(1000), std::size_t{1} << 30};
  for (const auto& [name, text] : std::vector<std::pair<std::string, std::string>>{
           {"loop.geo", "For i In {1:1e12}\nEndFor\n"},  // 10^12 empty iterations
           {"zero.geo", "Include \"/dev/zero\";\n"},     // a file without end
       }) {
    const std::string path = write_file(folder, name, text);
    const auto [message, seconds] = timed_refusal(path, limits);
    INFO(message);
    CHECK_THAT(message, Contains(path) && Contains("gmsh did not finish reading it within 1 s") &&
                            Contains("the limit of the gmsh reader; see README"));
    CHECK(seconds >= 1.0);
    CHECK(seconds < 1.5);
  }
}

TEST_CASE("gmsh domains: a .geo file runs no command and writes no file", "[geometry]") {
  // gmsh runs SystemCall through the shell and carries out Printf > "file", Save and
  // CreateDir; the reader's child may start no program and change no file, so each file
  // below is refused (gmsh finds no shell, or cannot open its output) or reads without the
  // folder appearing, and nothing appears in the scratch folder.
  const mfree::testing::ScratchFolder folder("gmsh_confined");
  std::ifstream annulus_file(mesh_path("quarter_annulus.geo"));
  const std::string annulus((std::istreambuf_iterator<char>(annulus_file)), std::istreambuf_iterator<char>());
  const std::string out = (folder.path / "made").string();
  for (const auto& [name, command, refusal] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"call.geo", "SystemCall \"touch " + out + "\";", "system call"},
           {"printf.geo", "Printf(\"x\") > \"" + out + "\";", "Unable to open file"},
           {"save.geo", "Save \"" + out + ".msh\";", "Unable to open file"},
           {"folder.geo", "CreateDir \"" + out + "\";", ""}}) {
    const std::string path = write_file(folder, name, command + "\n" + annulus);
    const auto read = [&] { return mfree::read_gmsh_domain(path, {std::chrono::seconds(5), 256u << 20}); };
    INFO(name);
    if (refusal.empty()) {
      CHECK(read().area() == Approx(mesh("quarter_annulus.geo").area()).epsilon(1e-15));
    } else {
      CHECK_THAT(mfree::testing::message_of<mfree::InputError>(read),
                 Catch::Contains(path) && Catch::Contains(refusal));
    }
    std::error_code ec;
    CHECK_FALSE(std::filesystem::exists(out, ec));
    CHECK_FALSE(std::filesystem::exists(out + ".msh", ec));
  }
}

TEST_CASE("gmsh domains: a file whose mesh outgrows the memory limit is refused", "[geometry]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_memory");
  // Element size 1e-7: 4e7 line elements, about 15 GiB in gmsh (400 000 take 150 MiB); the
  // limit is passed after 0.1 s.
  const std::string path = write_file(folder, "fine.geo", square_geo("1e-7"));
  const auto [message, seconds] = timed_refusal(path, {std::chrono::seconds(20), 64u << 20});
  INFO(message);
  CHECK_THAT(message, Contains(path) && Contains("gmsh used more than 64 MiB of memory reading it") &&
                          Contains("the limit of the gmsh reader; see README") && Contains("coarsen"));
  CHECK(seconds < 3.0);
}

TEST_CASE("gmsh domains: a reader killed from outside is not called a malformed file", "[geometry]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_killed");
  const std::string path = write_file(folder, "loop.geo", "For i In {1:1e12}\nEndFor\n");
  // After 300 ms, SIGKILL to every child of this process (the reader, as the system's
  // out-of-memory killer would).
  std::thread killer([] {
    std::this_thread::sleep_for(std::chrono::milliseconds(300));
    for (const auto& task : std::filesystem::directory_iterator("/proc/self/task")) {
      std::ifstream children(task.path() / "children");
      for (pid_t pid = 0; children >> pid;) ::kill(pid, SIGKILL);
    }
  });
  std::string message;
  try {
    (void)mfree::read_gmsh_domain(path, {std::chrono::seconds(10), std::size_t{1} << 30});
  } catch (const mfree::InputError& e) {
    message = std::string("InputError: ") + e.what();
  } catch (const mfree::Error& e) {
    message = e.what();
  }
  killer.join();
  CHECK_THAT(message, Contains(path) && Contains("ended from outside by signal 9") &&
                          Contains("lack of memory") && !Contains("malformed") && !Contains("InputError"));
}

namespace {

/// K_I, K_II at every tip of a plate [-1, 1]^2 clamped on y = -1 and pulled by a unit traction
/// on y = 1 (plane strain, E = 1, nu = 0.3, lattice of spacing 0.1, the default scheme).
std::vector<mfree::TipIntensity> pulled_plate_tips(const Domain& d) {
  mfree::ElasticitySettings s;
  s.nodes.spacing = 0.1;
  s.problem.material = mfree::LinearElastic{1.0, 0.3, mfree::PlaneModel::strain};
  s.problem.spacing = 0.1;
  const auto zero = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); };
  const auto pull = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 1.0); };
  using Type = mfree::BoundaryCondition<2>::Type;
  s.problem.conditions = {
      {Type::displacement, mfree::select_box(d, mfree::Box{Vec2(-2, -1.01), Vec2(2, -0.99)}), zero, "clamp"},
      {Type::traction, mfree::select_box(d, mfree::Box{Vec2(-2, 0.99), Vec2(2, 1.01)}), pull, "pull"}};
  return mfree::solve_elasticity(d, s, nullptr).tips;
}

/// The gmsh domain has the WKT domain's rings and cracks (points, tips, names, faces), exactly.
void check_same_cracks(const Domain& gmsh, const Domain& wkt) {
  CHECK(gmsh.rings() == wkt.rings());
  CHECK(gmsh.area() == wkt.area());
  REQUIRE(gmsh.cracks().size() == wkt.cracks().size());
  for (std::size_t c = 0; c < wkt.cracks().size(); ++c) {
    INFO("crack " << c);
    CHECK(gmsh.cracks()[c].name == wkt.cracks()[c].name);
    CHECK(gmsh.cracks()[c].points == wkt.cracks()[c].points);
    CHECK(gmsh.cracks()[c].tip[0] == wkt.cracks()[c].tip[0]);
    CHECK(gmsh.cracks()[c].tip[1] == wkt.cracks()[c].tip[1]);
  }
  REQUIRE(gmsh.boundary().size() == wkt.boundary().size());
  for (std::size_t i = 0; i < wkt.boundary().size(); ++i) {
    const BoundarySegment &s = gmsh.boundary()[i], &t = wkt.boundary()[i];
    INFO("segment " << i);
    CHECK(s.a == t.a);
    CHECK(s.b == t.b);
    CHECK(s.normal == t.normal);
    CHECK(s.crack == t.crack);
    if (s.crack >= 0) CHECK(gmsh.part_names()[s.part] == wkt.part_names()[t.part]);
  }
}

}  // namespace

TEST_CASE("gmsh cracks: embedded physical curves are the cracks of the equivalent WKT", "[geometry][crack]") {
  const mfree::testing::ScratchFolder folder("gmsh_cracks");
  // meshes/centre_crack.geo: a centre crack with two tips; meshes/edge_crack.geo: an edge crack
  // (mouth on x = -1, tip at (-0.25, 0)) of two curves, the second drawn backwards.
  const std::string centre_wkt = write_file(folder, "centre.wkt",
                                            "GEOMETRYCOLLECTION(POLYGON((-1 -1, 1 -1, 1 1, -1 1)), "
                                            "LINESTRING(-0.25 0, 0.25 0))");
  const std::string edge_wkt = write_file(folder, "edge.wkt",
                                          "GEOMETRYCOLLECTION(POLYGON((-1 -1, 1 -1, 1 1, -1 1, -1 0)), "
                                          "LINESTRING(-1 0, -0.5 0, -0.25 0))");
  for (const auto& [geo, wkt_path, tips] : std::vector<std::tuple<std::string, std::string, int>>{
           {"centre_crack.geo", centre_wkt, 2}, {"edge_crack.geo", edge_wkt, 1}}) {
    INFO(geo);
    const Domain gmsh = mesh(geo), wkt = Domain::from_file(wkt_path);
    REQUIRE(gmsh.cracks().size() == 1);
    CHECK(gmsh.cracks()[0].tip[0] == (tips == 2));  // the edge crack runs from its mouth
    CHECK(gmsh.cracks()[0].tip[1]);
    CHECK(gmsh.part_names() == std::vector<std::string>{"bottom", "right", "top", "left", "crack1"});
    check_same_cracks(gmsh, wkt);

    // The same solve on both: the same K at the same tips.
    const std::vector<mfree::TipIntensity> a = pulled_plate_tips(gmsh), b = pulled_plate_tips(wkt);
    REQUIRE(a.size() == static_cast<std::size_t>(tips));
    REQUIRE(b.size() == a.size());
    for (std::size_t t = 0; t < a.size(); ++t) {
      INFO("tip " << t << ": K_I " << a[t].k.k1 << ", K_II " << a[t].k.k2);
      CHECK(a[t].crack == "crack1");
      CHECK(a[t].frame.position == b[t].frame.position);
      // Under tension the crack opens: K_I = 0.935 at the centre crack's tips, 1.198 at the edge
      // crack's (sigma sqrt(pi a) = 0.886 and 1.535; the clamp and the finite plate change them).
      CHECK(a[t].k.k1 > 0.5);
      CHECK(std::abs(a[t].k.k1 - b[t].k.k1) <= 1e-10 * std::abs(b[t].k.k1));
      CHECK(std::abs(a[t].k.k2 - b[t].k.k2) <= 1e-10 * std::abs(b[t].k.k1));
    }
  }
  // The .msh written from centre_crack.geo (which records no embedding): its physical curve
  // that bounds no surface is the crack all the same.
  check_same_cracks(mesh("centre_crack.msh"), Domain::from_file(centre_wkt));
}

TEST_CASE("gmsh cracks: an OpenCASCADE fragment and several physical curves", "[geometry][crack]") {
  const mfree::testing::ScratchFolder folder("gmsh_crack_kinds");
  // A line fragmented into the rectangle [0, 2] x [0, 1] is embedded in it, its end (0, 0.5)
  // shared with the left side: an edge crack of gmsh's default element size.
  const Domain occ = Domain::from_file(write_file(folder, "occ.geo", R"(
    SetFactory("OpenCASCADE");
    Rectangle(1) = {0, 0, 0, 2, 1};
    Point(5) = {0, 0.5, 0}; Point(6) = {0.5, 0.5, 0};
    Line(5) = {5, 6};
    BooleanFragments{ Surface{1}; Delete; }{ Curve{5}; Delete; }
    Physical Curve("notch") = {5};
  )"));
  REQUIRE(occ.cracks().size() == 1);
  const mfree::Crack& notch = occ.cracks()[0];
  CHECK(notch.name == "notch");
  CHECK(notch.points.front() == Vec2(0, 0.5));
  CHECK(notch.points.back() == Vec2(0.5, 0.5));
  CHECK(notch.points.size() >= 3);  // gmsh's default size meshes it in pieces
  CHECK(!notch.tip[0]);
  CHECK(notch.tip[1]);

  // Two physical embedded curves are two cracks, in the order of their groups; an unnamed
  // group names its crack by number, and a free curve in no group is left out.
  const Domain two = Domain::from_file(write_file(folder, "two.geo", square_geo("1") + R"(
    Point(5) = {0.2, 0.3, 0, 0.1}; Point(6) = {0.6, 0.3, 0, 0.1};
    Point(7) = {0.3, 0.7, 0, 0.1}; Point(8) = {0.7, 0.7, 0, 0.1};
    Point(9) = {3, 3, 0}; Point(10) = {4, 3, 0};
    Line(5) = {5, 6}; Line(6) = {7, 8}; Line(7) = {9, 10};
    Curve{5, 6} In Surface{1};
    Physical Curve(12) = {5};
    Physical Curve("upper", 3) = {6};
  )"));
  REQUIRE(two.cracks().size() == 2);
  CHECK(two.cracks()[0].name == "upper");  // group 3 before group 12
  CHECK(two.cracks()[1].name == "12");
  CHECK(two.cracks()[0].points.size() == 5);  // 0.4 long at size 0.1
  CHECK(two.cracks()[1].points.front() == Vec2(0.2, 0.3));
  CHECK(two.cracks()[1].points.back() == Vec2(0.6, 0.3));
  for (const mfree::Crack& c : two.cracks()) CHECK((c.tip[0] && c.tip[1]));
}

TEST_CASE("gmsh cracks: embedded curves that are not cracks are InputErrors naming the curve",
          "[geometry][crack]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_crack_errors");
  // The unit square of size-1 elements, then the embedded curves of each case (of one element
  // where the points have size 1).
  const auto refusal = [&](const std::string& name, const std::string& curves) {
    const std::string path = write_file(folder, name, square_geo("1") + curves);
    const std::string message = input_error_message(path);
    return std::make_pair(path, message);
  };
  {
    const auto [path, message] = refusal("loop.geo", R"(
      Point(5) = {0.2, 0.2, 0}; Point(6) = {0.8, 0.2, 0}; Point(7) = {0.5, 0.8, 0};
      Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 5};
      Curve{5, 6, 7} In Surface{1};
      Physical Curve("ring") = {5, 6, 7};
    )");
    CHECK_THAT(message, Contains(path) && Contains("embedded curves 5, 6 and 7: a closed loop") &&
                            Contains("put its curve loop in the surface"));
  }
  {
    const auto [path, message] = refusal("cross.geo", R"(
      Point(5) = {0.2, 0.5, 0, 1}; Point(6) = {0.8, 0.5, 0, 1}; Point(7) = {0.5, 0.2, 0, 1}; Point(8) = {0.5, 0.8, 0, 1};
      Line(5) = {5, 6}; Line(6) = {7, 8};
      Curve{5, 6} In Surface{1};
      Physical Curve("a") = {5};
      Physical Curve("b") = {6};
    )");
    CHECK_THAT(message, Contains(path) && Contains("crack 'b', segment 1 meets crack 'a'") &&
                            Contains("crack 'a' is the embedded curve 5") &&
                            Contains("crack 'b' is the embedded curve 6"));
  }
  {
    // Four curves from a shared centre point: a branching network.
    const auto [path, message] = refusal("branch.geo", R"(
      Point(5) = {0.5, 0.5, 0}; Point(6) = {0.2, 0.5, 0}; Point(7) = {0.8, 0.5, 0}; Point(8) = {0.5, 0.8, 0};
      Line(5) = {5, 6}; Line(6) = {5, 7}; Line(7) = {5, 8};
      Curve{5, 6, 7} In Surface{1};
      Physical Curve("t") = {5, 6, 7};
    )");
    CHECK_THAT(message, Contains(path) &&
                            Contains("embedded curves 5, 6 and 7: a branch point at (0.5, 0.5)") &&
                            Contains("3 of their line elements end"));
  }
  {
    const auto [path, message] = refusal("leaves.geo", R"(
      Point(5) = {0.5, 0.5, 0, 1}; Point(6) = {1.5, 0.5, 0, 1};
      Line(5) = {5, 6};
      Curve{5} In Surface{1};
      Physical Curve("long") = {5};
    )");
    CHECK_THAT(message, Contains(path) &&
                            Contains("crack 'long', point 2 (1.5, 0.5) lies outside the domain") &&
                            Contains("crack 'long' is the embedded curve 5"));
  }
  {
    const auto [path, message] = refusal("unnamed.geo", R"(
      Point(5) = {0.2, 0.5, 0}; Point(6) = {0.8, 0.5, 0};
      Line(5) = {5, 6};
      Curve{5} In Surface{1};
    )");
    CHECK_THAT(message, Contains(path) && Contains("embedded curve 5 belongs to no physical curve") &&
                            Contains("Physical Curve(\"crack\") = {5};"));
  }
  {
    const auto [path, message] = refusal("two_names.geo", R"(
      Point(5) = {0.2, 0.5, 0}; Point(6) = {0.5, 0.5, 0}; Point(7) = {0.8, 0.5, 0};
      Line(5) = {5, 6}; Line(6) = {6, 7};
      Curve{5, 6} In Surface{1};
      Physical Curve("a") = {5};
      Physical Curve("b") = {6};
    )");
    CHECK_THAT(message, Contains(path) &&
                            Contains("embedded curves 5 and 6: one line in the physical curves 'a' and 'b'"));
  }
  {
    const auto [path, message] = refusal("two_lines.geo", R"(
      Point(5) = {0.2, 0.3, 0}; Point(6) = {0.8, 0.3, 0}; Point(7) = {0.2, 0.7, 0}; Point(8) = {0.8, 0.7, 0};
      Line(5) = {5, 6}; Line(6) = {7, 8};
      Curve{5, 6} In Surface{1};
      Physical Curve("slits") = {5, 6};
    )");
    CHECK_THAT(message,
               Contains(path) && Contains("the physical curve 'slits' holds two separate lines (embedded "
                                          "curve 5 and curve 6)"));
  }
  {
    // A boundary part's name given to a crack.
    const auto [path, message] = refusal("part_name.geo", R"(
      Point(5) = {0.2, 0.5, 0}; Point(6) = {0.8, 0.5, 0};
      Line(5) = {5, 6};
      Curve{5} In Surface{1};
      Physical Curve("edge") = {1, 5};
    )");
    CHECK_THAT(message, Contains(path) && Contains("crack name 'edge' is already a part name") &&
                            Contains("crack 'edge' is the embedded curve 5"));
  }
}

namespace {

/// The area of each region of the domain (its rings' signed areas added).
std::vector<double> region_areas(const Domain& d) {
  std::vector<double> out;
  for (const mfree::Region& r : d.regions()) {
    double area = 0.0;
    for (const mfree::Ring& ring : r.rings) area += mfree::ring_area(ring);
    out.push_back(area);
  }
  return out;
}

}  // namespace

TEST_CASE("gmsh regions: physical surfaces are the regions, the curve they share an interface",
          "[geometry][gmsh][regions]") {
  const mfree::testing::ScratchFolder folder("gmsh_regions");
  // core [0, 1] x [0, 1] and shell [1, 3] x [0, 1] share curve 7 (x = 1, in no physical curve);
  // the outer curves are named, bottom and top in two pieces each; element size 0.25.
  const std::string rectangles = R"(
    h = 0.25;
    Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h}; Point(3) = {3, 0, 0, h};
    Point(4) = {3, 1, 0, h}; Point(5) = {1, 1, 0, h}; Point(6) = {0, 1, 0, h};
    Line(1) = {1, 2}; Line(2) = {3, 2}; Line(3) = {3, 4}; Line(4) = {4, 5};
    Line(5) = {6, 5}; Line(6) = {6, 1}; Line(7) = {5, 2};
    Curve Loop(1) = {1, -7, -5, 6}; Plane Surface(1) = {1};
    Curve Loop(2) = {-2, 3, 4, 7}; Plane Surface(2) = {2};
    Physical Surface("core") = {1};
    Physical Surface("shell") = {2};
    Physical Curve("bottom") = {1, 2};
    Physical Curve("right") = {3};
    Physical Curve("top") = {4, 5};
    Physical Curve("left") = {6};
  )";
  const std::string path = write_file(folder, "two_rectangles.geo", rectangles);
  const Domain d = Domain::from_file(path);
  REQUIRE(d.regions().size() == 2);
  CHECK(d.regions()[0].name == "core");
  CHECK(d.regions()[1].name == "shell");
  const std::vector<double> areas = region_areas(d);
  CHECK(areas[0] == Approx(1.0).epsilon(1e-15));
  CHECK(areas[1] == Approx(2.0).epsilon(1e-15));
  CHECK(std::abs(areas[0] + areas[1] - d.area()) <= 1e-14 * d.area());
  CHECK(d.area() == Approx(3.0).epsilon(1e-15));
  // The union's ring keeps every node of the boundary curves: 12 + 4 + 12 + 4.
  REQUIRE(d.rings().size() == 1);
  CHECK(d.rings()[0].size() == 32);

  // The interface: curve 7, oriented along core's counter-clockwise boundary (core on its left).
  REQUIRE(d.cracks().size() == 1);
  const mfree::Crack& c = d.cracks()[0];
  CHECK(c.name == "core/shell");
  CHECK(c.interface());
  CHECK(c.left == 0);
  CHECK(c.right == 1);
  CHECK(!c.tip[0]);
  CHECK(!c.tip[1]);
  REQUIRE(c.points.size() == 5);
  CHECK(c.points.front() == Vec2(1, 0));
  CHECK(c.points.back() == Vec2(1, 1));
  for (const Vec2& x : c.points) CHECK(x.x() == 1.0);
  CHECK(d.region_at(Vec2(0.5, 0.5)) == 0);
  CHECK(d.region_at(Vec2(2.0, 0.5)) == 1);
  CHECK(d.region_at(Vec2(-0.5, 0.5)) == -1);

  // The physical curves name the union's edges; the interface carries none of them.
  const std::map<std::string, PartSum> parts = part_sums(d);
  CHECK(parts.at("bottom").length == Approx(3.0).epsilon(1e-15));
  CHECK(parts.at("bottom").segments == 12);
  CHECK(parts.at("top").length == Approx(3.0).epsilon(1e-15));
  CHECK(parts.at("right").length == Approx(1.0).epsilon(1e-15));
  CHECK(parts.at("left").length == Approx(1.0).epsilon(1e-15));
  CHECK(parts.at("left").segments == 4);
  CHECK(parts.count("<none>") == 0);
  for (const BoundarySegment& s : d.boundary()) {
    if (s.ring < 0) continue;
    INFO("segment " << s.edge << " from (" << s.a.x() << ", " << s.a.y() << ")");
    REQUIRE(s.part >= 0);
    CHECK((d.part_names()[s.part] == "left") == (s.a.x() == 0 && s.b.x() == 0));
    CHECK((d.part_names()[s.part] == "right") == (s.a.x() == 3 && s.b.x() == 3));
    CHECK((d.part_names()[s.part] == "bottom") == (s.a.y() == 0 && s.b.y() == 0));
  }

  // Without interfaces: the same regions and parts, curve 7 inside the domain.
  const Domain smooth = Domain::from_file(path, mfree::RegionOptions{{}, false});
  REQUIRE(smooth.regions().size() == 2);
  CHECK(smooth.regions()[1].name == "shell");
  CHECK(smooth.cracks().empty());
  CHECK(smooth.area() == Approx(3.0).epsilon(1e-15));
  CHECK(smooth.rings() == d.rings());
  CHECK(smooth.region_at(Vec2(2.0, 0.5)) == 1);

  // An embedded crack in the shell comes on top of the interface.
  const std::string cracked = write_file(folder, "cracked.geo", rectangles + R"(
    Point(7) = {2, 0.25, 0, h}; Point(8) = {2, 0.75, 0, h};
    Line(8) = {7, 8};
    Curve{8} In Surface{2};
    Physical Curve("crack") = {8};
  )");
  const Domain with_crack = Domain::from_file(cracked);
  REQUIRE(with_crack.cracks().size() == 2);
  CHECK(with_crack.cracks()[0].name == "core/shell");
  CHECK(with_crack.cracks()[1].name == "crack");
  CHECK(!with_crack.cracks()[1].interface());
  CHECK(with_crack.cracks()[1].tip[0]);
  CHECK(with_crack.cracks()[1].tip[1]);
  CHECK(with_crack.cracks()[1].points.front() == Vec2(2, 0.25));
  CHECK(with_crack.cracks()[1].points.back() == Vec2(2, 0.75));
}

TEST_CASE("gmsh regions: a quarter annulus in two layers (OpenCASCADE), the interface an arc",
          "[geometry][gmsh][regions]") {
  const mfree::testing::ScratchFolder folder("gmsh_layers");
  // The quarter annulus 1 <= r <= 2 split by the arc r = 1.5 (a fragment); the inner layer is the
  // surface within the box [0, 1.5]^2.
  const std::string path = write_file(folder, "layers.geo", R"(
    SetFactory("OpenCASCADE");
    Mesh.MeshSizeMin = 0.05; Mesh.MeshSizeMax = 0.05;
    Disk(1) = {0, 0, 0, 2};
    Disk(2) = {0, 0, 0, 1};
    Rectangle(3) = {0, 0, 0, 2, 2};
    BooleanDifference(4) = {Surface{1}; Delete;}{Surface{2}; Delete;};
    BooleanIntersection(5) = {Surface{4}; Delete;}{Surface{3}; Delete;};
    Circle(20) = {0, 0, 0, 1.5, 0, Pi / 2};
    BooleanFragments{Surface{5}; Delete;}{Curve{20}; Delete;}
    inner() = Surface In BoundingBox{-0.1, -0.1, -0.1, 1.6, 1.6, 0.1};
    outer() = Surface{:};
    outer() -= inner();
    Physical Surface("inner") = inner();
    Physical Surface("outer") = outer();
  )");
  const Domain d = Domain::from_file(path);
  REQUIRE(d.regions().size() == 2);
  CHECK(d.regions()[0].name == "inner");
  CHECK(d.regions()[1].name == "outer");
  const std::vector<double> areas = region_areas(d);
  CHECK(std::abs(areas[0] + areas[1] - d.area()) <= 1e-14 * d.area());
  // Inscribed in the curved layers: within 0.1 % of pi (c^2 - a^2) / 4 and pi (b^2 - c^2) / 4.
  CHECK(areas[0] == Approx(pi * (1.5 * 1.5 - 1) / 4).epsilon(1e-3));
  CHECK(areas[1] == Approx(pi * (4 - 1.5 * 1.5) / 4).epsilon(1e-3));

  // The interface runs along the inner layer's counter-clockwise boundary, from the x axis to
  // the y axis, its vertices on r = 1.5.
  REQUIRE(d.cracks().size() == 1);
  const mfree::Crack& c = d.cracks()[0];
  CHECK(c.name == "inner/outer");
  CHECK(c.left == 0);
  CHECK(c.right == 1);
  CHECK(!c.tip[0]);
  CHECK(!c.tip[1]);
  CHECK(c.points.size() >= 40);
  for (const Vec2& x : c.points) CHECK(x.norm() == Approx(1.5).epsilon(1e-12));
  CHECK(c.points.front().x() == Approx(1.5).epsilon(1e-12));
  CHECK(std::abs(c.points.front().y()) < 1e-12);
  CHECK(std::abs(c.points.back().x()) < 1e-12);
  CHECK(c.points.back().y() == Approx(1.5).epsilon(1e-12));

  // Either side of the arc, on the diagonal and near the axes; outside the annulus.
  for (const double t : {0.05, pi / 4, pi / 2 - 0.05}) {
    INFO("theta " << t);
    const Vec2 e(std::cos(t), std::sin(t));
    CHECK(d.region_at(1.45 * e) == 0);
    CHECK(d.region_at(1.55 * e) == 1);
    CHECK(d.region_at(1.2 * e) == 0);
    CHECK(d.region_at(1.9 * e) == 1);
    CHECK(d.region_at(0.5 * e) == -1);
  }
}

TEST_CASE("gmsh regions: surfaces in no physical surface or two, a disconnected region, an inclusion",
          "[geometry][gmsh][regions]") {
  using Catch::Contains;
  const mfree::testing::ScratchFolder folder("gmsh_region_errors");
  // Three unit squares in a row, surfaces 1, 2 and 3.
  const std::string squares = R"(
    Point(1) = {0, 0, 0, 0.5}; Point(2) = {1, 0, 0, 0.5}; Point(3) = {2, 0, 0, 0.5}; Point(4) = {3, 0, 0, 0.5};
    Point(5) = {0, 1, 0, 0.5}; Point(6) = {1, 1, 0, 0.5}; Point(7) = {2, 1, 0, 0.5}; Point(8) = {3, 1, 0, 0.5};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4};
    Line(4) = {5, 6}; Line(5) = {6, 7}; Line(6) = {7, 8};
    Line(7) = {1, 5}; Line(8) = {2, 6}; Line(9) = {3, 7}; Line(10) = {4, 8};
    Curve Loop(1) = {1, 8, -4, -7}; Plane Surface(1) = {1};
    Curve Loop(2) = {2, 9, -5, -8}; Plane Surface(2) = {2};
    Curve Loop(3) = {3, 10, -6, -9}; Plane Surface(3) = {3};
  )";
  const std::string orphans =
      write_file(folder, "orphans.geo", squares + "Physical Surface(\"core\") = {2};\n");
  CHECK_THAT(input_error_message(orphans), Contains(orphans) &&
                                               Contains("surfaces 1 and 3 belong to no physical "
                                                        "surface") &&
                                               Contains("('core')"));
  const std::string twice =
      write_file(folder, "twice.geo",
                 squares + "Physical Surface(\"a\") = {1, 2};\nPhysical Surface(\"b\") = {2, 3};\n");
  CHECK_THAT(input_error_message(twice),
             Contains(twice) && Contains("surface 2 belongs to the physical surfaces 'a' and 'b'"));
  const std::string apart = write_file(
      folder, "apart.geo", squares + "Physical Surface(\"ends\") = {1, 3};\nPhysical Surface(7) = {2};\n");
  CHECK_THAT(input_error_message(apart), Contains(apart + ", physical surface 'ends': its surfaces form 2 "
                                                          "disconnected pieces"));
  // An unnamed group is named by its number; regions come in the order of their groups' tags.
  const Domain numbered = Domain::from_file(
      write_file(folder, "numbered.geo",
                 squares + "Physical Surface(\"two\", 8) = {1, 2};\nPhysical Surface(7) = {3};\n"));
  REQUIRE(numbered.regions().size() == 2);
  CHECK(numbered.regions()[0].name == "7");
  CHECK(numbered.regions()[1].name == "two");
  CHECK(region_areas(numbered)[0] == Approx(1.0).epsilon(1e-15));
  CHECK(region_areas(numbered)[1] == Approx(2.0).epsilon(1e-15));
  REQUIRE(numbered.cracks().size() == 1);
  CHECK(numbered.cracks()[0].name == "7/two");
  CHECK(numbered.cracks()[0].points.front() == Vec2(2, 1));  // along region 7's edge x = 2, downwards

  // A disk inside a square with a hole: the interface is a closed loop.
  const std::string inclusion = write_file(folder, "inclusion.geo", R"(
    Point(1) = {-1, -1, 0, 0.2}; Point(2) = {1, -1, 0, 0.2}; Point(3) = {1, 1, 0, 0.2}; Point(4) = {-1, 1, 0, 0.2};
    Point(5) = {0, 0, 0, 0.1}; Point(6) = {0.5, 0, 0, 0.1}; Point(7) = {-0.5, 0, 0, 0.1};
    Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
    Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 6};
    Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6};
    Plane Surface(1) = {1, 2}; Plane Surface(2) = {2};
    Physical Surface("matrix") = {1};
    Physical Surface("inclusion") = {2};
  )");
  const Domain tied = Domain::from_file(inclusion);
  REQUIRE(tied.cracks().size() == 1);
  CHECK(tied.cracks()[0].name == "matrix/inclusion");
  CHECK(tied.cracks()[0].closed());
  CHECK(tied.region_at(Vec2(0, 0)) == 1);
  CHECK(tied.area() == Approx(4.0).epsilon(1e-15));
  // Without interfaces the inclusion is a region like any other.
  const Domain smooth = Domain::from_file(inclusion, mfree::RegionOptions{{}, false});
  REQUIRE(smooth.regions().size() == 2);
  CHECK(smooth.rings().size() == 1);
  CHECK(smooth.area() == Approx(4.0).epsilon(1e-15));
  CHECK(smooth.region_at(Vec2(0, 0)) == 1);
  CHECK(smooth.region_at(Vec2(0.8, 0.8)) == 0);
}

TEST_CASE("gmsh regions: meshes/two_layer_cylinder.geo", "[geometry][gmsh][regions]") {
  const Domain d = mesh("two_layer_cylinder.geo");
  REQUIRE(d.regions().size() == 2);
  CHECK(d.regions()[0].name == "inner");
  CHECK(d.regions()[1].name == "outer");
  REQUIRE(d.cracks().size() == 1);
  const mfree::Crack& c = d.cracks()[0];
  CHECK(c.name == "inner/outer");
  CHECK(c.points.size() == 49);  // 48 pieces on r = 1.5
  for (const Vec2& x : c.points) CHECK(x.norm() == Approx(1.5).epsilon(1e-14));
  // The element size of quarter_annulus.geo: 32 pieces on the bore, 64 outside, and the same
  // polygon.
  const std::map<std::string, PartSum> parts = part_sums(d);
  CHECK(parts.at("bore").segments == 32);
  CHECK(parts.at("outside").segments == 64);
  CHECK(parts.at("x_axis").length == Approx(1.0).epsilon(1e-14));
  CHECK(parts.at("y_axis").length == Approx(1.0).epsilon(1e-14));
  CHECK(parts.at("outside").length == Approx(quarter_chords(2, 64)).epsilon(1e-13));
  CHECK(d.area() == Approx(quarter_fan_area(2, 64) - quarter_fan_area(1, 32)).epsilon(1e-13));
  CHECK(d.area() == Approx(mesh("quarter_annulus.geo").area()).epsilon(1e-13));
  const std::vector<double> areas = region_areas(d);
  CHECK(areas[0] == Approx(quarter_fan_area(1.5, 48) - quarter_fan_area(1, 32)).epsilon(1e-13));
  CHECK(areas[1] == Approx(quarter_fan_area(2, 64) - quarter_fan_area(1.5, 48)).epsilon(1e-13));
  CHECK(std::abs(areas[0] + areas[1] - d.area()) <= 1e-14 * d.area());
}
