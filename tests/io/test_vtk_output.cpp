#include <sys/resource.h>
#include <unistd.h>
#include <vtkSmartPointer.h>
#include <vtkXMLDataElement.h>
#include <vtkXMLUtilities.h>

#include <algorithm>
#include <array>
#include <catch2/catch.hpp>
#include <cmath>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/io/vtk_output.hpp"

namespace fs = std::filesystem;
using mfree::Index;
using mfree::PointField;
using mfree::Vec2;
using mfree::testing::same_bits;
using mfree::testing::ScratchFolder;

namespace {


/// Points built one by one: GCC 12 at -O2 with -march=native on AVX-512 processors copies
/// the elements of a std::vector<Vec2> initializer list wrongly.
std::vector<Vec2> points_of(std::initializer_list<std::array<double, 2>> xy) {
  std::vector<Vec2> points;
  for (const auto& p : xy) points.emplace_back(p[0], p[1]);
  return points;
}

/// Values that exercise every bit of a double: random mantissas over many decades, both
/// signs, negative zero, subnormals and the extremes.
std::vector<double> awkward_values(std::size_t n, std::mt19937_64& rng) {
  std::uniform_real_distribution<double> mantissa(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-300, 300);
  std::vector<double> v(n);
  for (double& x : v) x = std::ldexp(mantissa(rng), exponent(rng));
  const double specials[] = {-0.0, 0.0, std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::lowest(), 1.0 / 3.0};
  for (std::size_t k = 0; k < std::size(specials) && k < n; ++k) v[k] = specials[k];
  return v;
}

using mfree::testing::message_of;

}  // namespace

TEST_CASE("vtu point cloud: scalar, vector and tensor fields read back bit for bit", "[io]") {
  ScratchFolder folder("vtu_cloud");
  std::mt19937_64 rng(7);
  const std::size_t n = 1000;
  std::vector<Vec2> points;
  std::uniform_real_distribution<double> coordinate(-3.0, 3.0);
  for (std::size_t i = 0; i < n; ++i) points.emplace_back(coordinate(rng), coordinate(rng));

  const std::vector<PointField> fields = {
      {"temperature", 1, awkward_values(n, rng)},
      {"displacement", 2, awkward_values(2 * n, rng)},
      {"stress", 3, awkward_values(3 * n, rng)},
  };
  const fs::path path = folder.path / "cloud.vtu";
  mfree::write_point_cloud_vtu(path, points, fields);
  CHECK(folder.entries() == std::vector<std::string>{"cloud.vtu"});

  const mfree::VtuContents read = mfree::read_vtu(path);
  REQUIRE(read.points.size() == n);
  CHECK(read.cells == static_cast<Index>(n));
  bool points_exact = true;
  for (std::size_t i = 0; i < n; ++i)
    points_exact = points_exact && same_bits(read.points[i].x(), points[i].x()) &&
                   same_bits(read.points[i].y(), points[i].y());
  CHECK(points_exact);

  CHECK(read.array_names == std::vector<std::string>{"temperature", "displacement", "stress"});
  CHECK(read.components.at("temperature") == 1);
  CHECK(read.components.at("displacement") == 3);  // 2D vector padded with z = 0
  CHECK(read.components.at("stress") == 3);

  const std::vector<double>& t = read.arrays.at("temperature");
  const std::vector<double>& u = read.arrays.at("displacement");
  const std::vector<double>& s = read.arrays.at("stress");
  REQUIRE(t.size() == n);
  REQUIRE(u.size() == 3 * n);
  REQUIRE(s.size() == 3 * n);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!same_bits(t[i], fields[0].values[i])) ++mismatches;
    if (!same_bits(u[3 * i], fields[1].values[2 * i])) ++mismatches;
    if (!same_bits(u[3 * i + 1], fields[1].values[2 * i + 1])) ++mismatches;
    if (!same_bits(u[3 * i + 2], 0.0)) ++mismatches;
    for (std::size_t c = 0; c < 3; ++c)
      if (!same_bits(s[3 * i + c], fields[2].values[3 * i + c])) ++mismatches;
  }
  CHECK(mismatches == 0);
  // The negative zero survives as such.
  CHECK(std::signbit(t[0]));
}

TEST_CASE("vtu triangles: cells and fields read back", "[io]") {
  ScratchFolder folder("vtu_triangles");
  // Unit square split along its diagonal, and 4 components per point to cover other counts.
  const std::vector<Vec2> points = points_of({{0, 0}, {1, 0}, {1, 1}, {0, 1}});
  const std::vector<std::array<Index, 3>> triangles = {{0, 1, 2}, {0, 2, 3}};
  const std::vector<PointField> fields = {
      {"p", 1, {1.0, 2.0, 3.0, 4.0}},
      {"q", 4, {0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15}},
  };
  const fs::path path = folder.path / "sub" / "square.vtu";  // the missing folder is created
  mfree::write_triangles_vtu(path, points, triangles, fields);
  const mfree::VtuContents read = mfree::read_vtu(path);
  CHECK(read.cells == 2);
  CHECK(read.points.size() == 4);
  CHECK(read.points[2] == Vec2(1, 1));
  CHECK(read.components.at("q") == 4);
  CHECK(read.arrays.at("q") == fields[1].values);
  CHECK(read.arrays.at("p") == fields[0].values);

  const auto bad_index = [&] {
    mfree::write_triangles_vtu(path, points, {{0, 1, 4}}, fields);
  };
  CHECK_THROWS_AS(bad_index(), mfree::InputError);
  CHECK_THAT(message_of(bad_index), Catch::Contains("triangle 0 refers to point 4"));
}

TEST_CASE("vtu: a non-finite value throws and leaves no file behind", "[io]") {
  ScratchFolder folder("vtu_nan");
  const std::vector<Vec2> points = points_of({{0, 0}, {1, 0}, {2, 0}});
  const fs::path path = folder.path / "bad.vtu";
  std::vector<PointField> fields = {{"u", 2, {0, 0, 1, 1, 2, std::nan("")}}};

  const auto write = [&] { mfree::write_point_cloud_vtu(path, points, fields); };
  CHECK_THROWS_AS(write(), mfree::NumericalError);
  const std::string message = message_of(write);
  CHECK_THAT(message, Catch::Contains("bad.vtu"));
  CHECK_THAT(message, Catch::Contains("field 'u'"));
  CHECK_THAT(message, Catch::Contains("point 2"));
  CHECK(folder.entries().empty());

  fields[0].values[5] = 0.0;
  fields[0].values[0] = -std::numeric_limits<double>::infinity();
  CHECK_THAT(message_of(write), Catch::Contains("point 0"));
  CHECK(folder.entries().empty());

  // A failed write leaves an earlier file at the path as it was.
  fields[0].values[0] = 0.0;
  write();
  const auto before = fs::file_size(path);
  fields[0].values[3] = std::numeric_limits<double>::infinity();
  CHECK_THROWS_AS(write(), mfree::NumericalError);
  CHECK(folder.entries() == std::vector<std::string>{"bad.vtu"});
  CHECK(fs::file_size(path) == before);
  CHECK(mfree::read_vtu(path).arrays.at("u")[4] == 1.0);

  // Non-finite coordinates are refused too.
  const auto bad_point = [&] {
    mfree::write_point_cloud_vtu(folder.path / "p.vtu", points_of({{0, 0}, {0, INFINITY}}), {});
  };
  CHECK_THROWS_AS(bad_point(), mfree::NumericalError);
  CHECK_THAT(message_of(bad_point), Catch::Contains("point 1"));
}

TEST_CASE("vtu: mismatched fields and failed writes are errors naming the path", "[io]") {
  ScratchFolder folder("vtu_errors");
  const std::vector<Vec2> points = points_of({{0, 0}, {1, 0}});
  const fs::path path = folder.path / "out.vtu";

  const auto short_field = [&] {
    mfree::write_point_cloud_vtu(path, points, {{"s", 3, {1, 2, 3, 4, 5}}});
  };
  CHECK_THROWS_AS(short_field(), mfree::InputError);
  CHECK_THAT(message_of(short_field), Catch::Contains("out.vtu") && Catch::Contains("'s' has 5 values"));
  const auto twice = [&] {
    mfree::write_point_cloud_vtu(path, points, {{"a", 1, {1, 2}}, {"a", 1, {1, 2}}});
  };
  CHECK_THROWS_AS(twice(), mfree::InputError);

  // The target is a folder: the temporary file is written, but cannot replace it.
  fs::create_directories(path / "inside");
  const auto onto_folder = [&] { mfree::write_point_cloud_vtu(path, points, {}); };
  CHECK_THROWS_AS(onto_folder(), mfree::Error);
  CHECK_THAT(message_of(onto_folder), Catch::Contains("out.vtu"));
  CHECK(folder.entries() == std::vector<std::string>{"out.vtu"});

  // The parent "folder" is a file.
  std::ofstream(folder.path / "plain") << "x";
  CHECK_THROWS_AS(mfree::write_point_cloud_vtu(folder.path / "plain" / "a.vtu", points, {}),
                  mfree::Error);
}

TEST_CASE("vtu and vti: a write cut short by a file-size limit is an error; no file is left", "[io][vtk]") {
  // VTK reports a failed write through its executive and error code, not Write()'s value.
  ScratchFolder folder("vtu_file_size");
  std::mt19937_64 rng(7);
  const std::size_t n = 20000;  // 20000 points x 4 fields: about 1 MB, past a 64 KiB limit
  std::vector<Vec2> points(n);
  for (std::size_t i = 0; i < n; ++i) points[i] = Vec2(double(i), std::sqrt(double(i)));
  const std::vector<PointField> fields{{"a", 1, awkward_values(n, rng)},
                                       {"b", 2, awkward_values(2 * n, rng)},
                                       {"c", 3, awkward_values(3 * n, rng)}};
  rlimit before{};
  REQUIRE(::getrlimit(RLIMIT_FSIZE, &before) == 0);
  const auto old_handler = std::signal(SIGXFSZ, SIG_IGN);  // writes past the limit fail with EFBIG
  rlimit small = before;
  small.rlim_cur = 64 * 1024;
  REQUIRE(::setrlimit(RLIMIT_FSIZE, &small) == 0);
  const auto cloud = [&] { mfree::write_point_cloud_vtu(folder.path / "cloud.vtu", points, fields); };
  const std::string message = message_of(cloud);
  const auto image = [&] {
    mfree::write_image_vti(folder.path / "grid.vti", Vec2(0, 0), 1.0, 200, 100, fields);
  };
  const std::string image_message = message_of(image);
  ::setrlimit(RLIMIT_FSIZE, &before);
  std::signal(SIGXFSZ, old_handler);
  CHECK_THAT(message, Catch::Contains("cannot write") && Catch::Contains("cloud.vtu"));
  CHECK_THAT(image_message, Catch::Contains("cannot write") && Catch::Contains("grid.vti"));
  CHECK(folder.entries().empty());
  // Without the limit the same writes succeed.
  cloud();
  image();
  std::vector<std::string> written = folder.entries();
  std::sort(written.begin(), written.end());
  CHECK(written == std::vector<std::string>{"cloud.vtu", "grid.vti"});
}

TEST_CASE("read_vtu: missing and invalid files are input errors naming them", "[io]") {
  ScratchFolder folder("vtu_read");
  const fs::path missing = folder.path / "missing.vtu";
  CHECK_THROWS_AS(mfree::read_vtu(missing), mfree::InputError);
  CHECK_THAT(message_of([&] { mfree::read_vtu(missing); }), Catch::Contains("missing.vtu"));

  const fs::path garbage = folder.path / "garbage.vtu";
  std::ofstream(garbage) << "not a VTK file\n";
  CHECK_THROWS_AS(mfree::read_vtu(garbage), mfree::InputError);
  CHECK_THAT(message_of([&] { mfree::read_vtu(garbage); }), Catch::Contains("garbage.vtu"));

  // A valid file cut short: the header parses, the appended data is missing.
  const fs::path whole = folder.path / "whole.vtu";
  std::vector<double> values(3000, 1.5);
  std::vector<Vec2> points(1000, Vec2(0.25, 0.5));
  mfree::write_point_cloud_vtu(whole, points, {{"v", 3, values}});
  std::string text;
  {
    std::ifstream in(whole, std::ios::binary);
    text.assign(std::istreambuf_iterator<char>(in), {});
  }
  const fs::path cut = folder.path / "cut.vtu";
  std::ofstream(cut, std::ios::binary) << text.substr(0, text.find("<AppendedData") + 40);
  CHECK_THROWS_AS(mfree::read_vtu(cut), mfree::InputError);
}

TEST_CASE("pvd: a valid XML collection listing the steps", "[io]") {
  ScratchFolder folder("pvd");
  const std::vector<std::pair<double, std::string>> steps = {
      {0.0, "run_0000.vtu"}, {0.1, "run_0001.vtu"}, {1.0 / 3.0, "odd & <name>.vtu"},
      {2.5e-7, "steps/run_0003.vtu"}};
  const fs::path path = folder.path / "run.pvd";
  mfree::write_pvd(path, steps);
  CHECK(folder.entries() == std::vector<std::string>{"run.pvd"});

  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(path.c_str()));
  REQUIRE(root != nullptr);
  CHECK(std::string(root->GetName()) == "VTKFile");
  CHECK(std::string(root->GetAttribute("type")) == "Collection");
  REQUIRE(root->GetNumberOfNestedElements() == 1);
  vtkXMLDataElement* collection = root->GetNestedElement(0);
  CHECK(std::string(collection->GetName()) == "Collection");
  REQUIRE(collection->GetNumberOfNestedElements() == static_cast<int>(steps.size()));
  for (std::size_t s = 0; s < steps.size(); ++s) {
    vtkXMLDataElement* dataset = collection->GetNestedElement(static_cast<int>(s));
    CHECK(std::string(dataset->GetName()) == "DataSet");
    // The time is written exactly: it reads back to the same double.
    CHECK(std::stod(dataset->GetAttribute("timestep")) == steps[s].first);
    CHECK(std::string(dataset->GetAttribute("file")) == steps[s].second);
  }

  CHECK_THROWS_AS(mfree::write_pvd(path, {{std::nan(""), "x.vtu"}}), mfree::NumericalError);
  CHECK_THROWS_AS(mfree::write_pvd(path, {{0.0, ""}}), mfree::InputError);
}

TEST_CASE("vti image: vector and tensor fields read back bit for bit", "[io][vtk]") {
  ScratchFolder folder("vti_image");
  std::mt19937_64 rng(11);
  // Different sizes along x and y, so a transposed point order would show.
  const int nx = 7, ny = 5;
  const auto n = static_cast<std::size_t>(nx * ny);
  const Vec2 origin(-0.125, 2.0 / 3.0);
  const double spacing = 0.1;
  const std::vector<PointField> fields = {
      {"velocity", 2, awkward_values(2 * n, rng)},
      {"stress", 3, awkward_values(3 * n, rng)},
  };
  const fs::path path = folder.path / "grid.vti";
  mfree::write_image_vti(path, origin, spacing, nx, ny, fields);
  CHECK(folder.entries() == std::vector<std::string>{"grid.vti"});  // no temporary file left

  const mfree::VtiContents read = mfree::read_vti(path);
  CHECK(read.nx == nx);
  CHECK(read.ny == ny);
  CHECK(same_bits(read.origin.x(), origin.x()));
  CHECK(same_bits(read.origin.y(), origin.y()));
  CHECK(same_bits(read.spacing, spacing));
  CHECK(read.array_names == std::vector<std::string>{"velocity", "stress"});
  CHECK(read.components.at("velocity") == 3);  // 2D vector padded with z = 0
  CHECK(read.components.at("stress") == 3);

  const std::vector<double>& v = read.arrays.at("velocity");
  const std::vector<double>& s = read.arrays.at("stress");
  REQUIRE(v.size() == 3 * n);
  REQUIRE(s.size() == 3 * n);
  std::size_t mismatches = 0;
  for (std::size_t i = 0; i < n; ++i) {
    if (!same_bits(v[3 * i], fields[0].values[2 * i])) ++mismatches;
    if (!same_bits(v[3 * i + 1], fields[0].values[2 * i + 1])) ++mismatches;
    if (!same_bits(v[3 * i + 2], 0.0)) ++mismatches;
    for (std::size_t c = 0; c < 3; ++c)
      if (!same_bits(s[3 * i + c], fields[1].values[3 * i + c])) ++mismatches;
  }
  CHECK(mismatches == 0);
}

TEST_CASE("vti image: points are in grid order, x fastest", "[io][vtk]") {
  ScratchFolder folder("vti_order");
  const int nx = 3, ny = 2;
  // The field is each point's own index i + nx j.
  std::vector<double> index;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) index.push_back(i + nx * j);
  const fs::path path = folder.path / "order.vti";
  mfree::write_image_vti(path, Vec2(1.0, 2.0), 0.5, nx, ny, {{"index", 1, index}});

  // VTK's own view of the file: point k sits at origin + h (k % nx, k / nx).
  vtkSmartPointer<vtkXMLDataElement> root;
  root.TakeReference(vtkXMLUtilities::ReadElementFromFile(path.c_str()));
  REQUIRE(root != nullptr);
  CHECK(std::string(root->GetAttribute("type")) == "ImageData");
  vtkXMLDataElement* image = root->FindNestedElementWithName("ImageData");
  REQUIRE(image != nullptr);
  CHECK(std::string(image->GetAttribute("WholeExtent")) == "0 2 0 1 0 0");
  CHECK(std::string(image->GetAttribute("Origin")) == "1 2 0");
  CHECK(mfree::read_vti(path).arrays.at("index") == index);
}

TEST_CASE("vti image: bad fields and grids are refused and leave no file behind", "[io][vtk]") {
  ScratchFolder folder("vti_errors");
  const fs::path path = folder.path / "bad.vti";
  const int nx = 3, ny = 2;
  std::vector<PointField> fields = {{"v", 2, std::vector<double>(2 * nx * ny, 1.0)}};
  const auto write = [&] { mfree::write_image_vti(path, Vec2(0, 0), 1.0, nx, ny, fields); };

  fields[0].values[7] = std::nan("");
  CHECK_THROWS_AS(write(), mfree::NumericalError);
  const std::string message = message_of(write);
  CHECK_THAT(message, Catch::Contains("bad.vti") && Catch::Contains("field 'v'") &&
                          Catch::Contains("point 3"));
  CHECK(folder.entries().empty());

  // Wrong size: a 2-component field of 3 x 2 points needs 12 values.
  fields[0].values.assign(11, 1.0);
  CHECK_THROWS_AS(write(), mfree::InputError);
  CHECK_THAT(message_of(write), Catch::Contains("bad.vti") && Catch::Contains("'v' has 11 values") &&
                                    Catch::Contains("need 12"));
  CHECK(folder.entries().empty());

  // Empty grids, a spacing that is not positive and a non-finite origin.
  fields.clear();
  CHECK_THROWS_AS(mfree::write_image_vti(path, Vec2(0, 0), 1.0, 0, 2, fields), mfree::InputError);
  CHECK_THROWS_AS(mfree::write_image_vti(path, Vec2(0, 0), 0.0, 2, 2, fields), mfree::InputError);
  CHECK_THROWS_AS(mfree::write_image_vti(path, Vec2(0, 0), std::nan(""), 2, 2, fields),
                  mfree::InputError);
  CHECK_THROWS_AS(mfree::write_image_vti(path, Vec2(INFINITY, 0), 1.0, 2, 2, fields),
                  mfree::NumericalError);
  CHECK(folder.entries().empty());

  // read_vti: missing files and files of another kind are input errors naming them.
  CHECK_THAT(message_of<mfree::InputError>([&] { mfree::read_vti(path); }),
             Catch::Contains("bad.vti"));
  const fs::path cloud = folder.path / "cloud.vtu";
  mfree::write_point_cloud_vtu(cloud, points_of({{0, 0}}), {});
  CHECK_THAT(message_of<mfree::InputError>([&] { mfree::read_vti(cloud); }),
             Catch::Contains("cloud.vtu"));
}
