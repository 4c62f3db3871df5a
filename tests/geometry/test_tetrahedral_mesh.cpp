// A mesh of tetrahedra as a solid: the inside test on faces, edges and vertices shared by
// tetrahedra, the volume, the checks of the input, and Solid::from_mesh's surface check.
#include <catch2/catch.hpp>

#include "mfree/core/error.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;

/// The unit cube as the six tetrahedra round its diagonal (0,0,0)-(1,1,1) (Kuhn's).
TetrahedralMesh kuhn_cube() {
  std::vector<P3> nodes;
  for (int k = 0; k < 8; ++k) nodes.emplace_back(k & 1, (k >> 1) & 1, (k >> 2) & 1);
  std::vector<std::array<Index, 4>> tets;
  // Paths 0 -> 7 through the cube's vertices, one axis at a time.
  const int axes[6][3] = {{1, 2, 4}, {1, 4, 2}, {2, 1, 4}, {2, 4, 1}, {4, 1, 2}, {4, 2, 1}};
  for (const auto& a : axes) tets.push_back({0, a[0], a[0] + a[1], 7});
  return TetrahedralMesh(nodes, tets, "cube");
}

}  // namespace

TEST_CASE("Tetrahedral mesh: the inside test on shared faces, edges and vertices, and the volume",
          "[geometry][3d]") {
  const TetrahedralMesh cube = kuhn_cube();
  CHECK(cube.volume() == Approx(1.0).epsilon(1e-15));
  for (const P3& x : {P3(0.5, 0.5, 0.5), P3(0.3, 0.3, 0.3), P3(0.2, 0.7, 0.2), P3(0, 0, 0), P3(1, 1, 1),
                      P3(1, 0.5, 0.25), P3(0.5, 0.5, 0), P3(0.9, 0.1, 0.5), P3(0.1, 0.9, 0.999)})
    CHECK(cube.contains(x));
  for (const P3& x : {P3(-1e-9, 0.5, 0.5), P3(0.5, 1 + 1e-9, 0.5), P3(2, 2, 2), P3(0.5, 0.5, -0.1)})
    CHECK_FALSE(cube.contains(x));
  CHECK_FALSE(cube.contains(P3(std::nan(""), 0.5, 0.5)));
}

TEST_CASE("Tetrahedral mesh and meshed solid: bad input is refused, naming what", "[geometry][3d]") {
  const std::vector<P3> nodes{P3(0, 0, 0), P3(1, 0, 0), P3(0, 1, 0), P3(0, 0, 1), P3(1, 1, 0)};
  CHECK_THROWS_WITH(TetrahedralMesh(nodes, {}, "m"), Catch::Contains("no tetrahedron"));
  CHECK_THROWS_WITH(TetrahedralMesh(nodes, {{0, 1, 2, 5}}, "m"), Catch::Contains("names node 5"));
  CHECK_THROWS_WITH(TetrahedralMesh(nodes, {{0, 1, 2, 4}}, "m"),
                    Catch::Contains("tetrahedron 0") && Catch::Contains("has no volume"));
  // The unit tetrahedron's surface, outward; turned inward or missing a face it is refused.
  const TetrahedralMesh tet(nodes, {{0, 1, 2, 3}}, "m");
  std::vector<SurfaceTriangle> surface{{{nodes[0], nodes[2], nodes[1]}, 0},
                                       {{nodes[0], nodes[1], nodes[3]}, 0},
                                       {{nodes[0], nodes[3], nodes[2]}, 0},
                                       {{nodes[1], nodes[2], nodes[3]}, -1}};
  const Solid solid = Solid::from_mesh(tet, surface, {"walls"}, "m");
  CHECK(solid.measure() == Approx(1.0 / 6.0).epsilon(1e-15));
  CHECK(solid.contains(P3(0.1, 0.1, 0.1)));
  CHECK_FALSE(solid.contains(P3(0.5, 0.5, 0.5)));
  auto inward = surface;
  for (SurfaceTriangle& t : inward) std::swap(t.vertices[1], t.vertices[2]);
  CHECK_THROWS_WITH(Solid::from_mesh(tet, inward, {"walls"}, "m"),
                    Catch::Contains("does not bound the solid"));
  CHECK_THROWS_WITH(Solid::from_mesh(tet, {surface.begin(), surface.end() - 1}, {"walls"}, "m"),
                    Catch::Contains("does not bound the solid"));
  auto stray = surface;
  stray[0].part = 1;
  CHECK_THROWS_WITH(Solid::from_mesh(tet, stray, {"walls"}, "m"), Catch::Contains("is in part 1"));
}
