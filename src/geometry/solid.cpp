#include "mfree/geometry/solid.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <tuple>

#include "mfree/core/error.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"

namespace mfree {

Solid Solid::box(const Point<3>& lo, const Point<3>& hi) {
  if (!lo.allFinite() || !hi.allFinite() || !(lo.array() < hi.array()).all())
    throw InputError(
        fmt::format("solid box: the corners ({}) and ({}) do not span a box (each coordinate of the "
                    "first below the second, all finite)",
                    fmt::join(lo.begin(), lo.end(), ", "), fmt::join(hi.begin(), hi.end(), ", ")));
  const AlignedBox<3> box(lo, hi);
  // Face `side` (0: min, 1: max) normal to `axis`: its corners in the order (u, v) = (0, 0),
  // (1, 0), (1, 1), (0, 1) along the next two axes, turned so that the triangles face out.
  std::vector<SurfaceTriangle> surface;
  std::vector<std::string> parts;
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int part = static_cast<int>(parts.size());
      parts.push_back(fmt::format("{}_{}", "xyz"[axis], side == 0 ? "min" : "max"));
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      std::array<Point<3>, 4> c;
      for (int k = 0; k < 4; ++k) {
        c[k][axis] = side == 0 ? lo[axis] : hi[axis];
        c[k][u] = (k == 1 || k == 2) ? hi[u] : lo[u];
        c[k][v] = k >= 2 ? hi[v] : lo[v];
      }
      // e_u x e_v = e_axis: counter-clockwise in (u, v) faces +axis, the max side.
      if (side == 0) std::swap(c[1], c[3]);
      surface.push_back({{c[0], c[1], c[2]}, part});
      surface.push_back({{c[0], c[2], c[3]}, part});
    }
  return Solid(box, std::move(surface), std::move(parts));
}

namespace {

/// The faces two tetrahedra of different regions share, oriented out of the one of the lower
/// region (by its fourth vertex) into the other.
std::vector<InterfaceTriangle> region_faces(const TetrahedralMesh& mesh) {
  std::vector<InterfaceTriangle> out;
  if (mesh.size() == 0) return out;
  bool several = false;
  for (Index k = 1; k < mesh.size() && !several; ++k) several = mesh.region(k) != mesh.region(0);
  if (!several) return out;
  // Each face as its sorted node indices, with the tetrahedron and the vertex opposite it.
  struct Face {
    std::array<Index, 3> key;
    Index tet;
    int opposite;
  };
  std::vector<Face> faces;
  faces.reserve(4 * static_cast<std::size_t>(mesh.size()));
  for (Index k = 0; k < mesh.size(); ++k)
    for (int o = 0; o < 4; ++o) {
      std::array<Index, 3> key;
      for (int v = 0, n = 0; v < 4; ++v)
        if (v != o) key[static_cast<std::size_t>(n++)] = mesh.tetrahedra()[static_cast<std::size_t>(k)][v];
      std::sort(key.begin(), key.end());
      faces.push_back({key, k, o});
    }
  std::sort(faces.begin(), faces.end(),
            [](const Face& a, const Face& b) { return std::tie(a.key, a.tet) < std::tie(b.key, b.tet); });
  for (std::size_t f = 0; f + 1 < faces.size(); ++f) {
    const Face &a = faces[f], &b = faces[f + 1];
    if (a.key != b.key || mesh.region(a.tet) == mesh.region(b.tet)) continue;
    const Face& low = mesh.region(a.tet) < mesh.region(b.tet) ? a : b;  // the face's `from` side
    InterfaceTriangle t;
    for (int v = 0; v < 3; ++v)
      t.vertices[static_cast<std::size_t>(v)] = mesh.nodes()[static_cast<std::size_t>(a.key[v])];
    t.from = mesh.region(low.tet);
    t.to = mesh.region((&low == &a ? b : a).tet);
    const Point<3> inner = mesh.nodes()[static_cast<std::size_t>(
        mesh.tetrahedra()[static_cast<std::size_t>(low.tet)][low.opposite])];
    if ((inner - t.vertices[0]).dot(t.area_normal()) > 0.0) std::swap(t.vertices[1], t.vertices[2]);
    out.push_back(t);
  }
  return out;
}

}  // namespace

Solid Solid::from_mesh(TetrahedralMesh mesh, std::vector<SurfaceTriangle> surface,
                       std::vector<std::string> parts, const std::string& source,
                       std::vector<std::string> regions, bool tied) {
  if (surface.empty()) throw InputError(fmt::format("{}: the solid has no surface triangle", source));
  for (Index k = 0; k < mesh.size(); ++k)
    if (mesh.region(k) >= std::max<int>(1, static_cast<int>(regions.size())))
      throw InputError(fmt::format("{}: tetrahedron {} is in region {}, not one of the {} regions", source, k,
                                   mesh.region(k), std::max<std::size_t>(1, regions.size())));
  // Divergence theorem: the volume enclosed by the outward surface, about its box's centre.
  const Point<3> centre = mesh.bounding_box().center();
  double enclosed = 0.0;
  for (std::size_t t = 0; t < surface.size(); ++t) {
    const SurfaceTriangle& tri = surface[t];
    if (tri.part < -1 || tri.part >= static_cast<int>(parts.size()))
      throw InputError(fmt::format("{}: surface triangle {} is in part {}, not one of the {} parts", source,
                                   t, tri.part, parts.size()));
    const Point<3> mid = (tri.vertices[0] + tri.vertices[1] + tri.vertices[2]) / 3.0 - centre;
    enclosed += mid.dot(tri.area_normal()) / 6.0;
  }
  if (!(std::abs(enclosed - mesh.volume()) <= 1e-9 * mesh.volume()))
    throw InputError(
        fmt::format("{}: the surface encloses a volume of {:.10g}, its tetrahedra fill {:.10g}: the "
                    "surface does not bound the solid (triangles missing or facing inward)",
                    source, enclosed, mesh.volume()));
  // A face with the solid on both sides: volumes that touch without sharing their faces (a
  // mesh that does not conform there), whose touching faces would be taken as surface. A
  // point just off the face (1e-4 of its size) on its outer side must lie outside.
  for (std::size_t t = 0; t < surface.size(); ++t) {
    const SurfaceTriangle& tri = surface[t];
    const Point<3> an = tri.area_normal();
    const double size = std::sqrt(an.norm());
    const Point<3> centroid = (tri.vertices[0] + tri.vertices[1] + tri.vertices[2]) / 3.0;
    if (mesh.contains(centroid + 1e-4 * size * an.normalized()))
      throw InputError(fmt::format(
          "{}: surface triangle {} (centroid ({:.6g}, {:.6g}, {:.6g})) has the solid on both sides: volumes "
          "touch there without sharing their faces; make the mesh conform (BooleanFragments or Coherence "
          "in the .geo)",
          source, t, centroid.x(), centroid.y(), centroid.z()));
  }
  std::vector<InterfaceTriangle> interfaces = tied ? region_faces(mesh) : std::vector<InterfaceTriangle>{};
  const AlignedBox<3> box = mesh.bounding_box();
  Solid solid(box, std::move(surface), std::move(parts),
              std::make_shared<const TetrahedralMesh>(std::move(mesh)), std::move(regions));
  solid.interfaces_ = std::move(interfaces);
  return solid;
}

bool Solid::contains(const Point<3>& x) const { return mesh_ ? mesh_->contains(x) : box_.contains(x); }

int Solid::region_at(const Point<3>& x) const {
  if (!mesh_) return box_.contains(x) ? 0 : -1;
  const Index t = mesh_->locate(x);
  return t < 0 ? -1 : mesh_->region(t);
}

double Solid::measure() const { return mesh_ ? mesh_->volume() : box_.volume(); }

}  // namespace mfree
