#include "mfree/geometry/gmsh_solid.hpp"

#include <fmt/format.h>
#include <gmsh.h>

#include <algorithm>
#include <array>
#include <map>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

#include "gmsh_reader.hpp"
#include "mfree/core/error.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"

namespace mfree {

namespace {

/// What is read from gmsh: the nodes, the tetrahedra's corners and regions (their physical
/// volumes', when the volumes are in physical volumes) and the triangles of the boundary
/// surfaces in physical groups (corner nodes, part), nodes numbered from 0.
struct VolumeMesh {
  std::vector<Point<3>> nodes;
  std::vector<std::array<Index, 4>> tetrahedra;
  std::vector<int> tetrahedron_regions;  ///< empty: one region
  std::vector<std::string> region_names;
  std::vector<std::array<Index, 3>> triangles;
  std::vector<int> triangle_parts;
  std::vector<std::string> part_names;
};

/// The elements of dimension `dim` on entity `tag` (-1: all) as their first `corners` nodes
/// (gmsh tags), after checking that each element type's name begins with `family`.
std::vector<std::size_t> corner_nodes(int dim, int tag, int corners, std::string_view family,
                                      const std::string& file) {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, dim, tag);
  std::vector<std::size_t> out;
  for (std::size_t t = 0; t < types.size(); ++t) {
    std::string name;
    int element_dim, order, nodes_per_element, primary;
    std::vector<double> local;
    gmsh::model::mesh::getElementProperties(types[t], name, element_dim, order, nodes_per_element, local,
                                            primary);
    if (name.compare(0, family.size(), family) != 0)
      throw InputError(fmt::format("{}: {} {} is meshed with {} elements ({}); mfree takes {}s only", file,
                                   dim == 3 ? "volume" : "surface", tag, element_tags[t].size(), name,
                                   family));
    for (std::size_t e = 0; e < element_tags[t].size(); ++e)
      for (int k = 0; k < corners; ++k)
        out.push_back(
            node_tags[t][e * static_cast<std::size_t>(nodes_per_element) + static_cast<std::size_t>(k)]);
  }
  return out;
}

/// Opens the file in the current gmsh session, meshes it in 3D unless it holds a 3D mesh, and
/// reads the tetrahedra and the named boundary triangles.
VolumeMesh read_volume_mesh(const std::string& file) {
  gmsh::open(file);
  gmsh::vectorpair volumes, surfaces;
  gmsh::model::getEntities(volumes, 3);
  gmsh::model::getEntities(surfaces, 2);
  if (volumes.empty())
    throw InputError(
        fmt::format("{}: no 3D entity (volume) to take as the solid; the file defines {} surface(s) "
                    "and no volume",
                    file, surfaces.size()));
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> element_tags, node_tags;
  gmsh::model::mesh::getElements(types, element_tags, node_tags, 3, -1);
  if (types.empty()) {
    if (gmsh_reader::lower_case(std::filesystem::path(file).extension().string()) == ".msh")
      throw InputError(
          fmt::format("{}: the mesh holds no tetrahedra (a .msh file holds only the elements of "
                      "physical groups unless written with Mesh.SaveAll = 1: put the volumes in a "
                      "physical volume)",
                      file));
    gmsh::model::mesh::generate(3);
  }
  VolumeMesh mesh;
  std::unordered_map<std::size_t, Index> index;  // gmsh node tag -> mesh.nodes
  {
    std::vector<std::size_t> tags;
    std::vector<double> xyz, parametric;
    gmsh::model::mesh::getNodes(tags, xyz, parametric, -1, -1, /*includeBoundary=*/false,
                                /*returnParametricCoord=*/false);
    for (std::size_t i = 0; i < tags.size(); ++i) {
      index.emplace(tags[i], static_cast<Index>(mesh.nodes.size()));
      mesh.nodes.emplace_back(xyz[3 * i], xyz[3 * i + 1], xyz[3 * i + 2]);
    }
  }
  const auto node = [&](std::size_t tag) {
    const auto it = index.find(tag);
    if (it == index.end())
      throw InputError(fmt::format("{}: an element names node {}, which the mesh lacks", file, tag));
    return it->second;
  };
  // Regions: the physical volumes, when there are any (then every volume is in one).
  const std::map<int, int> region = gmsh_reader::entity_parts(3, volumes, mesh.region_names, file, "volume");
  for (const auto& [dim, volume] : volumes) {
    const int r = region.at(volume);
    if (r < 0 && !mesh.region_names.empty())
      throw InputError(
          fmt::format("{}: volume {} is in no physical volume, and others are in {}: put every "
                      "volume of the solid in a physical volume (its region), or none",
                      file, volume, gmsh_reader::quoted_list(mesh.region_names)));
    const std::vector<std::size_t> corners = corner_nodes(3, volume, 4, "Tetrahedron", file);
    for (std::size_t e = 0; e < corners.size(); e += 4) {
      mesh.tetrahedra.push_back(
          {node(corners[e]), node(corners[e + 1]), node(corners[e + 2]), node(corners[e + 3])});
      if (r >= 0) mesh.tetrahedron_regions.push_back(r);
    }
  }
  gmsh::vectorpair boundary;
  gmsh::model::getBoundary(volumes, boundary, /*combined=*/true, /*oriented=*/false, /*recursive=*/false);
  const std::map<int, int> part =
      gmsh_reader::entity_parts(2, boundary, mesh.part_names, file, "boundary surface");
  for (const auto& [dim, surface] : boundary) {
    const int p = part.at(surface);
    if (p < 0) continue;
    const std::vector<std::size_t> corners = corner_nodes(2, surface, 3, "Triangle", file);
    for (std::size_t e = 0; e < corners.size(); e += 3) {
      mesh.triangles.push_back({node(corners[e]), node(corners[e + 1]), node(corners[e + 2])});
      mesh.triangle_parts.push_back(p);
    }
  }
  return mesh;
}

// The mesh through the pipe: 'M', then nodes (x, y, z), tetrahedra, triangles, their parts and
// the part names, each list after its count.

template <class T>
void put_list(std::string& out, const std::vector<T>& list) {
  gmsh_reader::put(out, list.size());
  for (const T& item : list) gmsh_reader::put(out, item);
}

std::string serialise(const VolumeMesh& mesh) {
  std::string out = "M";
  put_list(out, mesh.nodes);
  put_list(out, mesh.tetrahedra);
  put_list(out, mesh.tetrahedron_regions);
  gmsh_reader::put_names(out, mesh.region_names);
  put_list(out, mesh.triangles);
  put_list(out, mesh.triangle_parts);
  gmsh_reader::put_names(out, mesh.part_names);
  return out;
}

template <class T>
void take_list(gmsh_reader::MessageReader& in, std::vector<T>& list) {
  list.resize(in.count());
  for (T& item : list) item = in.take<T>();
}

VolumeMesh deserialise(const std::string& bytes, const std::string& file) {
  gmsh_reader::MessageReader in(bytes, file);
  VolumeMesh mesh;
  take_list(in, mesh.nodes);
  take_list(in, mesh.tetrahedra);
  take_list(in, mesh.tetrahedron_regions);
  mesh.region_names = in.names();
  take_list(in, mesh.triangles);
  take_list(in, mesh.triangle_parts);
  mesh.part_names = in.names();
  in.finish();
  const auto parts = static_cast<int>(mesh.part_names.size());
  const auto nodes = static_cast<Index>(mesh.nodes.size());
  const bool known = mesh.triangle_parts.size() == mesh.triangles.size() &&
                     std::all_of(mesh.triangle_parts.begin(), mesh.triangle_parts.end(),
                                 [&](int p) { return p >= 0 && p < parts; }) &&
                     std::all_of(mesh.triangles.begin(), mesh.triangles.end(), [&](const auto& t) {
                       return std::all_of(t.begin(), t.end(), [&](Index v) { return v >= 0 && v < nodes; });
                     });
  const auto regions = static_cast<int>(mesh.region_names.size());
  const bool regions_known = mesh.tetrahedron_regions.size() == (regions > 0 ? mesh.tetrahedra.size() : 0) &&
                             std::all_of(mesh.tetrahedron_regions.begin(), mesh.tetrahedron_regions.end(),
                                         [&](int r) { return r >= 0 && r < regions; });
  if (!known || !regions_known)
    throw Error(fmt::format("{}: the gmsh reader process sent a malformed mesh", file));
  return mesh;
}

using Face = std::array<Index, 3>;

Face sorted(Face f) {
  std::sort(f.begin(), f.end());
  return f;
}

/// The faces of the tetrahedra that belong to one only, oriented outward, with the part of
/// the named triangle on each (-1: none).
std::vector<SurfaceTriangle> boundary_faces(const VolumeMesh& mesh, const TetrahedralMesh& tets) {
  struct TetFace {
    Face key;
    Index tet;
    int opposite;  // the local vertex not on the face
  };
  std::vector<TetFace> faces;
  faces.reserve(4 * mesh.tetrahedra.size());
  for (std::size_t t = 0; t < mesh.tetrahedra.size(); ++t) {
    const auto& v = mesh.tetrahedra[t];
    for (int k = 0; k < 4; ++k)
      faces.push_back({sorted({v[(k + 1) % 4], v[(k + 2) % 4], v[(k + 3) % 4]}), static_cast<Index>(t), k});
  }
  std::sort(faces.begin(), faces.end(), [](const TetFace& a, const TetFace& b) {
    return a.key != b.key ? a.key < b.key : a.tet < b.tet;
  });
  std::map<Face, int> named;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t)
    named.emplace(sorted(mesh.triangles[t]), mesh.triangle_parts[t]);
  std::vector<SurfaceTriangle> out;
  for (std::size_t i = 0; i < faces.size();) {
    std::size_t j = i + 1;
    while (j < faces.size() && faces[j].key == faces[i].key) ++j;
    if (j == i + 1) {
      const TetFace& f = faces[i];
      const auto& v = mesh.tetrahedra[static_cast<std::size_t>(f.tet)];
      SurfaceTriangle tri;
      for (int k = 0; k < 3; ++k) tri.vertices[k] = tets.nodes()[v[(f.opposite + 1 + k) % 4]];
      // Outward: away from the vertex opposite the face.
      if (tri.area_normal().dot(tets.nodes()[v[f.opposite]] - tri.vertices[0]) > 0.0)
        std::swap(tri.vertices[1], tri.vertices[2]);
      const auto it = named.find(f.key);
      tri.part = it == named.end() ? -1 : it->second;
      out.push_back(tri);
    }
    i = j;
  }
  return out;
}

}  // namespace

Solid read_gmsh_solid(const std::filesystem::path& file, const GmshReaderLimits& limits, bool tied) {
  const std::string source = file.string();
  gmsh_reader::check_file(file);
  VolumeMesh mesh = deserialise(
      gmsh_reader::read_in_child(source, limits, [&source] { return serialise(read_volume_mesh(source)); }),
      source);
  TetrahedralMesh tets(mesh.nodes, mesh.tetrahedra, source, mesh.tetrahedron_regions);
  std::vector<SurfaceTriangle> surface = boundary_faces(mesh, tets);
  return Solid::from_mesh(std::move(tets), std::move(surface), std::move(mesh.part_names), source,
                          std::move(mesh.region_names), tied);
}

}  // namespace mfree
