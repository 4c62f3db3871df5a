// Solids from gmsh files: the octant of a thick sphere (meshes/thick_sphere_octant.geo) read
// as tetrahedra with named surface parts (and regions: the two-layer sphere); its volume and areas converging
// to the curved solid's at second order in the element size; the surface closed and outward; the inside test;
// the faces between regions (tied interfaces) and the points on them split in two; and the
// files refused, each naming what is wrong.
#include <fmt/format.h>

#include <catch2/catch.hpp>
#include <cmath>
#include <fstream>
#include <map>
#include <numbers>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/boundary_selection.hpp"
#include "mfree/geometry/gmsh_solid.hpp"
#include "mfree/geometry/interface_faces.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;
const double pi = std::acos(-1.0);

std::string write_file(const testing::ScratchFolder& folder, const std::string& name,
                       const std::string& text) {
  const std::string path = (folder.path / name).string();
  std::ofstream(path) << text;
  return path;
}

std::string input_error(const std::string& path) {
  return testing::message_of<InputError>([&] { (void)read_gmsh_solid(path); });
}

}  // namespace

TEST_CASE("gmsh solid: the thick sphere's octant, its parts, closed surface and second-order geometry",
          "[geometry][3d]") {
  // Exact: volume (b^3 - a^3) pi / 6, the bore's area pi a^2 / 2, the outside's pi b^2 / 2,
  // each symmetry face a quarter annulus pi (b^2 - a^2) / 4.
  const std::map<std::string, double> exact_area{{"bore", pi / 2},
                                                 {"outside", 2 * pi},
                                                 {"x_sym", 3 * pi / 4},
                                                 {"y_sym", 3 * pi / 4},
                                                 {"z_sym", 3 * pi / 4}};
  const double exact_volume = 7 * pi / 6;
  std::vector<double> volume_error, bore_error;
  for (const double size : {0.2, 0.1}) {
    const Solid solid = testing::thick_sphere_octant(size);
    REQUIRE(solid.parts() == std::vector<std::string>{"bore", "outside", "x_sym", "y_sym", "z_sym"});
    P3 closed = P3::Zero();
    double enclosed = 0.0;
    for (const SurfaceTriangle& t : solid.surface()) {
      REQUIRE(t.part >= 0);  // every boundary surface is named
      closed += t.area_normal() / 2;
      enclosed += t.vertices[0].dot(t.area_normal()) / 6;
    }
    CHECK(closed.norm() <= 1e-13);
    CHECK(enclosed == Approx(solid.measure()).epsilon(1e-13));
    for (const auto& [name, area] : exact_area) {
      const double a = selection_area(solid, select_part(solid, name));
      CAPTURE(name, size, a, area);
      CHECK(std::abs(a - area) <= 0.01 * area);
    }
    volume_error.push_back(exact_volume - solid.measure());
    bore_error.push_back(pi / 2 - selection_area(solid, select_part(solid, "bore")));
    CHECK(solid.contains(P3(0.9, 0.9, 0.3)));          // r = 1.31
    CHECK_FALSE(solid.contains(P3(0.5, 0.5, 0.5)));    // r = 0.87: in the bore
    CHECK_FALSE(solid.contains(P3(1.2, 1.2, 1.2)));    // r = 2.08: outside
    CHECK_FALSE(solid.contains(P3(-0.01, 1.5, 0.1)));  // beyond x = 0
    CHECK(solid.contains(P3(0.0, 1.5, 0.0)));          // on two symmetry faces
  }
  // Inscribed flat triangles: the errors are positive and fall at second order.
  WARN(fmt::format("volume error {:.3e}, {:.3e}; bore area error {:.3e}, {:.3e}", volume_error[0],
                   volume_error[1], bore_error[0], bore_error[1]));
  CHECK(volume_error[1] > 0.0);
  CHECK(std::log2(volume_error[0] / volume_error[1]) >= 1.8);
  CHECK(std::log2(bore_error[0] / bore_error[1]) >= 1.8);
}

TEST_CASE("gmsh solid: files that are not solids of tetrahedra are refused, naming the file and the reason",
          "[geometry][3d]") {
  const testing::ScratchFolder folder("gmsh_solid_bad");
  const std::string plane =
      write_file(folder, "plane.geo", "SetFactory(\"OpenCASCADE\");\nRectangle(1) = {0, 0, 0, 1, 1};\n");
  CHECK_THAT(input_error(plane), Catch::Contains("plane.geo") && Catch::Contains("no 3D entity (volume)"));
  const std::string hexahedra = write_file(folder, "hex.geo",
                                           "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                           "Transfinite Curve{:} = 3;\nTransfinite Surface{:};\n"
                                           "Recombine Surface{:};\nTransfinite Volume{1};\n");
  CHECK_THAT(input_error(hexahedra), Catch::Contains("hex.geo: volume 1") && Catch::Contains("Hexahedron") &&
                                         Catch::Contains("takes Tetrahedrons only"));
  const std::string twice = write_file(folder, "twice.geo",
                                       "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                       "Physical Surface(\"a\") = {1};\nPhysical Surface(\"b\") = {1, 2};\n");
  CHECK_THAT(input_error(twice),
             Catch::Contains("boundary surface 1 belongs to the physical surfaces 'a' and 'b'"));
  CHECK_THAT(input_error(write_file(folder, "box.txt", "")), Catch::Contains("unknown extension '.txt'"));
  CHECK_THAT(input_error((folder.path / "missing.geo").string()), Catch::Contains("does not exist"));
  CHECK_THAT(input_error(write_file(folder, "broken.geo", "Box(1) = {0, 0;\n")),
             Catch::Contains("broken.geo: gmsh cannot read it"));
  // A box without names: one solid of tetrahedra, its faces in no part.
  const Solid box = read_gmsh_solid(
      write_file(folder, "box.geo", "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 2, 3};\n"));
  CHECK(box.measure() == Approx(6.0).epsilon(1e-12));
  CHECK(box.parts().empty());
  for (const SurfaceTriangle& t : box.surface()) CHECK(t.part == -1);
}

TEST_CASE(
    "gmsh solid: a STEP part (the notched block exported by OpenCASCADE) is meshed and closed, its faces in "
    "no part",
    "[geometry][gmsh]") {
  const Solid solid = read_gmsh_solid(testing::source_dir() + "/meshes/notched_block.step");
  // 1 x 0.8 x 0.6 less the notch 0.4 x 0.35 x 0.6 and the hole pi 0.15^2 0.6; the facets of the
  // hole (inscribed) remove less of it.
  const double exact = 0.48 - 0.084 - std::numbers::pi * 0.15 * 0.15 * 0.6;
  CHECK(solid.measure() > exact);
  CHECK(solid.measure() < exact * 1.02);  // measured: 0.357544, 1.1 % above
  Point<3> closure = Point<3>::Zero();
  for (const SurfaceTriangle& t : solid.surface()) {
    closure += t.area_normal();
    CHECK(t.part == -1);  // a STEP file names no physical surfaces
  }
  CHECK(closure.norm() < 1e-12);
  CHECK(solid.parts().empty());
  // The faces are reached by boxes: x = 0 has area 0.48.
  CHECK(selection_area(solid, select_box(solid, AlignedBox<3>(Point<3>(-1, -1, -1), Point<3>(0, 2, 2)))) ==
        Approx(0.48).epsilon(1e-12));
}

TEST_CASE("gmsh solid: the faces between regions are its tied interfaces, points on them split in two",
          "[geometry][3d]") {
  // The two-layer sphere's octant: the interface r = 1.5, an eighth of a sphere (inscribed
  // triangles: a little less than pi c^2 / 2), each triangle once, its normal from the inner
  // region into the outer one (radially outward).
  const Solid solid = read_gmsh_solid(testing::source_dir() + "/meshes/two_layer_sphere_octant.geo");
  REQUIRE_FALSE(solid.interfaces().empty());
  double area = 0.0;
  for (const InterfaceTriangle& t : solid.interfaces()) {
    CHECK(t.from == 0);
    CHECK(t.to == 1);
    const P3 centroid = (t.vertices[0] + t.vertices[1] + t.vertices[2]) / 3.0;
    CHECK(centroid.norm() == Approx(1.5).epsilon(0.01));
    CHECK(t.area_normal().normalized().dot(centroid.normalized()) > 0.99);
    area += 0.5 * t.area_normal().norm();
  }
  CHECK(area < pi * 1.5 * 1.5 / 2);
  CHECK(area == Approx(pi * 1.5 * 1.5 / 2).epsilon(0.01));
  // Bonded regions (interfaces = "smooth"): none.
  CHECK(read_gmsh_solid(testing::source_dir() + "/meshes/two_layer_sphere_octant.geo",
                        default_gmsh_reader_limits(), false)
            .interfaces()
            .empty());
  CHECK(testing::thick_sphere_octant(0.3).interfaces().empty());

  // The bar of two materials: the points on the face x = 1 become two, 1e-7 h off it, steel's
  // (x < 1) first; the others stay as they are.
  const Solid bar =
      read_gmsh_solid(testing::source_dir() + "/verification/two-layer-sphere/bimaterial_bar.geo");
  REQUIRE_FALSE(bar.interfaces().empty());
  const double h = 0.05;
  const std::vector<P3> points{P3(1.0, 0.1, 0.1), P3(0.5, 0.1, 0.1), P3(1.0, 0.0, 0.2),
                               P3(1.0 + 1e-3, 0.1, 0.1)};
  const std::vector<P3> split = split_on_interfaces(bar, points, h);
  REQUIRE(split.size() == 6);
  CHECK((split[0] - P3(1.0 - 1e-7 * h, 0.1, 0.1)).norm() < 1e-15);
  CHECK((split[1] - P3(1.0 + 1e-7 * h, 0.1, 0.1)).norm() < 1e-15);
  CHECK(split[2] == points[1]);
  CHECK((split[3] - P3(1.0 - 1e-7 * h, 0.0, 0.2)).norm() < 1e-15);  // on the face's edge
  CHECK((split[4] - P3(1.0 + 1e-7 * h, 0.0, 0.2)).norm() < 1e-15);
  CHECK(split[5] == points[3]);
  CHECK(bar.region_at(split[0]) == 0);
  CHECK(bar.region_at(split[1]) == 1);
}

TEST_CASE("gmsh solid: physical volumes are the solid's regions (the two-layer sphere's octant)",
          "[geometry][3d]") {
  const Solid solid = read_gmsh_solid(testing::source_dir() + "/meshes/two_layer_sphere_octant.geo");
  REQUIRE(solid.regions() == std::vector<std::string>{"inner", "outer"});
  REQUIRE(solid.parts() == std::vector<std::string>{"bore", "outside", "x_sym", "y_sym", "z_sym"});
  // The interface r = c is inside: no surface triangle on it, the outside a whole sphere's eighth.
  CHECK(selection_area(solid, select_part(solid, "outside")) == Approx(2 * pi).epsilon(0.01));
  for (const SurfaceTriangle& t : solid.surface()) CHECK(t.part >= 0);
  // Each region's volume (inscribed spheres: a little less than the layer's).
  const TetrahedralMesh& mesh = *solid.mesh();
  std::array<double, 2> volume{};
  for (Index k = 0; k < mesh.size(); ++k) volume[mesh.region(k)] += tetrahedron_volume(mesh.tetrahedron(k));
  const double inner = (1.5 * 1.5 * 1.5 - 1) * pi / 6, outer = (8 - 1.5 * 1.5 * 1.5) * pi / 6;
  CHECK(volume[0] < inner);
  CHECK(volume[0] > 0.99 * inner);
  CHECK(volume[1] == Approx(outer).epsilon(0.01));
  CHECK(solid.region_at(P3(0.7, 0.7, 0.7)) == 0);   // r = 1.21
  CHECK(solid.region_at(P3(1.0, 1.0, 1.0)) == 1);   // r = 1.73
  CHECK(solid.region_at(P3(0.5, 0.5, 0.5)) == -1);  // in the bore
  CHECK(solid.region_at(P3(1.2, 1.2, 1.2)) == -1);  // outside
  // A box is one region.
  CHECK(Solid::box(P3(0, 0, 0), P3(1, 1, 1)).regions().empty());
  CHECK(Solid::box(P3(0, 0, 0), P3(1, 1, 1)).region_at(P3(0.5, 0.5, 0.5)) == 0);

  // Some volumes in physical volumes and others in none: refused.
  const testing::ScratchFolder folder("gmsh_solid_regions");
  const std::string half = write_file(folder, "half.geo",
                                      "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                      "Box(2) = {1, 0, 0, 1, 1, 1};\nCoherence;\n"
                                      "Physical Volume(\"left\") = {1};\n");
  CHECK_THAT(input_error(half), Catch::Contains("half.geo: volume 2 is in no physical volume, and others are "
                                                "in 'left'"));
  // Two volumes touching without a conforming mesh: the faces between them are not surface.
  const std::string loose = write_file(folder, "loose.geo",
                                       "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                       "Box(2) = {1, 0, 0, 1, 1, 1};\nPhysical Volume(\"left\") = {1};\n"
                                       "Physical Volume(\"right\") = {2};\n");
  CHECK_THAT(input_error(loose), Catch::Contains("loose.geo: surface triangle") &&
                                     Catch::Contains("has the solid on both sides") &&
                                     Catch::Contains("BooleanFragments or Coherence"));
  const std::string twice = write_file(folder, "twice_volume.geo",
                                       "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n"
                                       "Physical Volume(\"a\") = {1};\nPhysical Volume(\"b\") = {1};\n");
  CHECK_THAT(input_error(twice), Catch::Contains("volume 1 belongs to the physical volumes 'a' and 'b'"));
}
