// The one test source compiled with the source tree's path (MFREE_SOURCE_DIR).
#include "test_support.hpp"

#include <fmt/format.h>

#include <fstream>

#include "mfree/geometry/gmsh_solid.hpp"

namespace mfree::testing {

std::string source_dir() { return MFREE_SOURCE_DIR; }

Solid thick_sphere_octant(double size) {
  const ScratchFolder folder("thick_sphere_octant");
  const auto geo = folder.path / "sphere.geo";
  std::ofstream(geo) << fmt::format("size = {};\nInclude \"{}/meshes/thick_sphere_octant.geo\";\n", size,
                                    source_dir());
  return read_gmsh_solid(geo);
}

}  // namespace mfree::testing
