#include "mfree/io/solid_scene_output.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/io/vtk_output.hpp"
#include "mfree/materials/finite_strain.hpp"

namespace mfree {

namespace {

/// The volume mesh the fields are shown on: its vertices, tetrahedra and surface faces, and
/// per vertex where the fields are sampled and the region whose law gives the stress (empty:
/// the law at the vertex).
struct Cells3 {
  std::vector<Point<3>> points;
  std::vector<std::array<Index, 4>> tetrahedra;
  std::vector<std::array<Index, 3>> faces;
  std::vector<Point<3>> samples;
  std::vector<int> regions;
};

/// The box [lo, hi] in n_x n_y n_z cubes of about `spacing`, each split into the six
/// tetrahedra round its diagonal (Kuhn's subdivision: one per order of the axes).
Cells3 box_tetrahedra(const AlignedBox<3>& box, double spacing) {
  std::array<Index, 3> n{};
  for (int a = 0; a < 3; ++a)
    n[a] = std::max<Index>(1, static_cast<Index>(std::ceil(box.sizes()[a] / spacing - 1e-9)));
  Cells3 c;
  const auto id = [&](Index i, Index j, Index k) { return i + (n[0] + 1) * (j + (n[1] + 1) * k); };
  for (Index k = 0; k <= n[2]; ++k)
    for (Index j = 0; j <= n[1]; ++j)
      for (Index i = 0; i <= n[0]; ++i)
        c.points.push_back(box.min() + box.sizes().cwiseProduct(Point<3>(static_cast<double>(i) / n[0],
                                                                         static_cast<double>(j) / n[1],
                                                                         static_cast<double>(k) / n[2])));
  std::array<int, 3> axes{0, 1, 2};
  for (Index k = 0; k < n[2]; ++k)
    for (Index j = 0; j < n[1]; ++j)
      for (Index i = 0; i < n[0]; ++i) do {
          std::array<Index, 3> at{i, j, k};
          std::array<Index, 4> tet{};
          tet[0] = id(at[0], at[1], at[2]);
          for (int s = 0; s < 3; ++s) {
            ++at[static_cast<std::size_t>(axes[static_cast<std::size_t>(s)])];
            tet[static_cast<std::size_t>(s + 1)] = id(at[0], at[1], at[2]);
          }
          c.tetrahedra.push_back(tet);
        } while (std::next_permutation(axes.begin(), axes.end()));
  return c;
}

/// The faces of the tetrahedra that belong to one of them: the surface of the volume mesh,
/// each as the vertices of `shown` (the same tetrahedra, some vertices replaced by copies).
std::vector<std::array<Index, 3>> boundary_faces(const std::vector<std::array<Index, 4>>& tetrahedra,
                                                 const std::vector<std::array<Index, 4>>& shown) {
  std::map<std::array<Index, 3>, std::pair<int, std::array<Index, 3>>>
      faces;  // sorted corners -> count, face
  for (std::size_t t = 0; t < tetrahedra.size(); ++t)
    for (int skip = 0; skip < 4; ++skip) {
      std::array<Index, 3> key{}, face{};
      for (int v = 0, k = 0; v < 4; ++v)
        if (v != skip) {
          key[static_cast<std::size_t>(k)] = tetrahedra[t][static_cast<std::size_t>(v)];
          face[static_cast<std::size_t>(k++)] = shown[t][static_cast<std::size_t>(v)];
        }
      std::sort(key.begin(), key.end());
      auto& [count, kept] = faces[key];
      ++count;
      kept = face;
    }
  std::vector<std::array<Index, 3>> out;
  for (const auto& [key, entry] : faces)
    if (entry.first == 1) out.push_back(entry.second);
  return out;
}

/// The volume mesh of the scene's solid (a box: box_tetrahedra at the node spacing). Where
/// tied interfaces make the fields jump, a vertex that tetrahedra of several regions share is
/// one vertex per region, sampled crack_offset h into that region (towards the centroid of
/// its first tetrahedron there), its stress by that region's law.
Cells3 volume_cells(const SolidScene& scene) {
  const Solid& solid = scene.solid;
  const double h = scene.settings.nodes.spacing;
  Cells3 c;
  if (!solid.mesh()) {
    c = box_tetrahedra(solid.bounding_box(), h);
  } else {
    c.points = solid.mesh()->nodes();
    c.tetrahedra = solid.mesh()->tetrahedra();
  }
  c.samples = c.points;
  if (solid.interfaces().empty()) {
    c.faces = boundary_faces(c.tetrahedra, c.tetrahedra);
    return c;
  }
  const TetrahedralMesh& mesh = *solid.mesh();
  std::vector<int> region(c.points.size(), -1);
  std::vector<char> shared(c.points.size(), 0);
  for (Index k = 0; k < mesh.size(); ++k)
    for (const Index v : c.tetrahedra[static_cast<std::size_t>(k)]) {
      int& r = region[static_cast<std::size_t>(v)];
      if (r < 0) r = mesh.region(k);
      if (r != mesh.region(k)) shared[static_cast<std::size_t>(v)] = 1;
    }
  c.regions = region;
  std::vector<std::array<Index, 4>> shown = c.tetrahedra;
  std::map<std::pair<Index, int>, Index> copies;
  for (Index k = 0; k < mesh.size(); ++k) {
    const int r = mesh.region(k);
    const Point<3> centroid = tetrahedron_centroid(mesh.tetrahedron(k));
    for (Index& v : shown[static_cast<std::size_t>(k)]) {
      if (!shared[static_cast<std::size_t>(v)]) continue;
      const Point<3> x = c.points[static_cast<std::size_t>(v)];
      const auto [it, added] = copies.try_emplace({v, r}, static_cast<Index>(c.points.size()));
      if (added) {
        c.points.push_back(x);
        c.samples.push_back(x + crack_offset * h * (centroid - x).normalized());
        c.regions.push_back(r);
      }
      v = it->second;
    }
  }
  c.faces = boundary_faces(c.tetrahedra, shown);
  c.tetrahedra = std::move(shown);
  return c;
}

void append_tensor(std::vector<double>& out, const Tensor2<3>& s) {
  out.insert(out.end(), {s(0, 0), s(1, 1), s(2, 2), s(1, 2), s(0, 2), s(0, 1)});
}

/// The fields at the vertices of `cells` (the header's), those a law with history has
/// elsewhere left out.
std::vector<PointField> fields_at(const SolidScene& scene, const Discretisation<3>& disc,
                                  const Eigen::VectorXd& d, const Eigen::VectorXd* v, const Cells3& cells) {
  const SolidOutput& o = scene.output;
  const std::vector<Point<3>>& points = cells.samples;
  const bool stresses = !scene.problem.any_history() && (o.wants("stress") || o.wants("von_mises"));
  const GalerkinQuadrature<3> at = sample_shape_functions(*disc.trial, points, stresses);
  PointField u{"displacement", 3, {}}, velocity{"velocity", 3, {}}, stress{"stress", 6, {}},
      mises{"von_mises", 1, {}}, error{"error", 3, {}};
  for (Index k = 0; k < at.size(); ++k) {
    const Point<3> uh = displacement_at(at, k, d);
    u.values.insert(u.values.end(), uh.data(), uh.data() + 3);
    if (v && o.wants("velocity")) {
      const Point<3> vh = displacement_at(at, k, *v);
      velocity.values.insert(velocity.values.end(), vh.data(), vh.data() + 3);
    }
    if (o.wants("error")) {
      const Point<3> e = uh - scene.exact->displacement(points[static_cast<std::size_t>(k)]);
      error.values.insert(error.values.end(), e.data(), e.data() + 3);
    }
    if (!stresses) continue;
    Tensor2<3> f = Tensor2<3>::Identity();
    for (Index j = at.row_begin(k); j < at.row_end(k); ++j)
      f += d.segment<3>(3 * at.nodes[j]) * at.grad[j].transpose();
    // The law of the vertex's region (on a face between bonded regions, either's).
    const auto vertex = static_cast<std::size_t>(k);
    const Tensor2<3> sigma =
        cauchy_stress<3>(cells.regions.empty() ? scene.problem.law_at(scene.solid, points[vertex])
                                               : scene.problem.law(cells.regions[vertex]),
                         f);
    append_tensor(stress.values, sigma);
    mises.values.push_back(von_mises(sigma));
  }
  std::vector<PointField> fields;
  if (o.wants("displacement")) fields.push_back(std::move(u));
  if (v && o.wants("velocity")) fields.push_back(std::move(velocity));
  if (stresses && o.wants("stress")) fields.push_back(std::move(stress));
  if (stresses && o.wants("von_mises")) fields.push_back(std::move(mises));
  if (o.wants("error")) fields.push_back(std::move(error));
  return fields;
}

}  // namespace

std::vector<std::filesystem::path> write_solid_fields(const SolidScene& scene, const Discretisation<3>& disc,
                                                      const TotalLagrangian<3>& model,
                                                      const Eigen::VectorXd& d, const Eigen::VectorXd* v,
                                                      const std::string& suffix) {
  const std::filesystem::path& folder = scene.output.folder;
  std::vector<std::filesystem::path> files;
  const Cells3 volume = volume_cells(scene);
  if (const std::vector<PointField> fields = fields_at(scene, disc, d, v, volume); !fields.empty()) {
    files.push_back(folder / ("volume" + suffix + ".vtu"));
    write_tetrahedra_vtu(files.back(), volume.points, volume.tetrahedra, fields);
    files.push_back(folder / ("surface" + suffix + ".vtu"));
    write_triangles_vtu(files.back(), volume.points, volume.faces, fields);
  }

  const SolidOutput& o = scene.output;
  if (scene.problem.any_history() &&
      (o.wants("stress") || o.wants("von_mises") || o.wants("plastic_strain"))) {
    const GalerkinQuadrature<3>& q = disc.quadrature;
    PointField u{"displacement", 3, {}}, stress{"stress", 6, {}}, mises{"von_mises", 1, {}},
        alpha{"plastic_strain", 1, {}};
    for (Index k = 0; k < q.size(); ++k) {
      const Point<3> uh = displacement_at(q, k, d);
      u.values.insert(u.values.end(), uh.data(), uh.data() + 3);
      const auto r = model.response(k, d);
      append_tensor(stress.values, r.cauchy);
      mises.values.push_back(von_mises(r.cauchy));
      alpha.values.push_back(r.state.alpha);
    }
    std::vector<PointField> fields{std::move(u)};
    if (o.wants("stress")) fields.push_back(std::move(stress));
    if (o.wants("von_mises")) fields.push_back(std::move(mises));
    if (o.wants("plastic_strain")) fields.push_back(std::move(alpha));
    files.push_back(folder / ("points" + suffix + ".vtu"));
    write_point_cloud_vtu(files.back(), q.points, fields);
  }
  return files;
}

}  // namespace mfree
