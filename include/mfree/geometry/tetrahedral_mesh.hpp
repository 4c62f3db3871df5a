#pragma once
// A conforming mesh of tetrahedra filling a solid Omega_h (gmsh's volume mesh): the inside
// test and the volume of a solid bounded by curved surfaces, and the pieces its cut cells are
// integrated on (quadrature/background_lattice.hpp).
//
// The inside test locates a point in the tetrahedra (barycentric coordinates, each >= -1e-12)
// through a bucket grid of their bounding boxes. Unlike a ray cast against the surface, it has
// no degenerate cases (rays through edges or vertices of the surface, a surface that is not
// quite closed where gmsh's patches meet): a point on a face shared by two tetrahedra is in
// either, a point on the surface in its tetrahedron, within 1e-12 of its barycentric
// coordinates.

#include <array>
#include <string>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/solid.hpp"
#include "mfree/geometry/tetrahedron.hpp"

namespace mfree {

class TetrahedralMesh {
 public:
  /// Nodes and tetrahedra (four node indices each), and the region of each tetrahedron (empty:
  /// all in region 0). Throws InputError naming `source` when there is no tetrahedron, an
  /// index is out of range, a node is not finite, a tetrahedron has no volume (below 1e-14 of
  /// its bounding box's), or the regions are not one per tetrahedron, each 0 or more.
  TetrahedralMesh(std::vector<Point<3>> nodes, std::vector<std::array<Index, 4>> tetrahedra,
                  const std::string& source, std::vector<int> regions = {});

  [[nodiscard]] const std::vector<Point<3>>& nodes() const { return nodes_; }
  [[nodiscard]] const std::vector<std::array<Index, 4>>& tetrahedra() const { return tetrahedra_; }
  [[nodiscard]] Index size() const { return static_cast<Index>(tetrahedra_.size()); }
  [[nodiscard]] Tetrahedron tetrahedron(Index k) const;
  [[nodiscard]] const AlignedBox<3>& bounding_box() const { return box_; }
  /// The sum of the tetrahedra's volumes.
  [[nodiscard]] double volume() const { return volume_; }
  /// Whether x lies in a tetrahedron (above).
  [[nodiscard]] bool contains(const Point<3>& x) const { return locate(x) >= 0; }
  /// A tetrahedron holding x (of the two or more sharing a face, edge or vertex x lies on,
  /// one of them); -1 for none.
  [[nodiscard]] Index locate(const Point<3>& x) const;
  /// The region of tetrahedron k.
  [[nodiscard]] int region(Index k) const {
    return regions_.empty() ? 0 : regions_[static_cast<std::size_t>(k)];
  }

 private:
  std::vector<Point<3>> nodes_;
  std::vector<std::array<Index, 4>> tetrahedra_;
  std::vector<int> regions_;  ///< per tetrahedron; empty: all 0
  AlignedBox<3> box_;
  double volume_ = 0.0;
  // The bucket grid: cells of side cell_ from box_.min(), counts_ per axis; the tetrahedra
  // whose bounding boxes meet cell c are bucket_[start_[c] .. start_[c + 1]).
  double cell_ = 1.0;
  std::array<Index, 3> counts_{};
  std::vector<Index> start_;
  std::vector<Index> bucket_;
  [[nodiscard]] std::array<Index, 3> cell_of(const Point<3>& x) const;
};

}  // namespace mfree
