#pragma once
// Tetrahedra: volume, moments, and the part of one inside an axis-aligned box (the pieces the
// cut cells of a solid's background lattice are integrated on).

#include <array>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/geometry/solid.hpp"

namespace mfree {

/// The four vertices of a tetrahedron (either orientation).
using Tetrahedron = std::array<Point<3>, 4>;

/// |det(b - a, c - a, d - a)| / 6.
[[nodiscard]] double tetrahedron_volume(const Tetrahedron& t);

/// The mean of the vertices (the centroid).
[[nodiscard]] Point<3> tetrahedron_centroid(const Tetrahedron& t);

/// The second moments M_ij = integral over t of x_i x_j, in closed form:
/// |t| / 20 (sum_k v_k,i v_k,j + s_i s_j) with s the sum of the vertices.
[[nodiscard]] Tensor2<3> tetrahedron_second_moments(const Tetrahedron& t);

/// The part of t inside the closed box, as tetrahedra appended to `out`: t is clipped by the
/// box's six planes in turn, each cut keeping a tetrahedron (one vertex inside) or a prism
/// split into three (two or three inside). Pieces may have no volume where t only touches the
/// box. The pieces' volumes add up to |t intersect box| to round-off.
void clip_to_box(const Tetrahedron& t, const AlignedBox<3>& box, std::vector<Tetrahedron>& out);

}  // namespace mfree
