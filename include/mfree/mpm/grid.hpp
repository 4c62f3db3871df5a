#pragma once
// The uniform background grid of the MPM: square cells of size h over a rectangle, and the
// tensor-product basis N_ij(x, y) = N_i(x) N_j(y) of two B-spline axes (bspline_basis.hpp).
// A grid "node" is one basis function; node (i, j) has index i + nx j and sits at the
// Greville point (x_i, y_j).
//
// The grid box is the rectangle the grid is built for; the bodies lie in it (and may leave
// cells empty). B-spline grids cover exactly that rectangle (open knots at its edges). Grids
// for the methods with particle domains (the GIMPs and CPDIs, uses_domains() in
// particle_basis.hpp) are padded by one cell on every side: a particle's domain near a wall
// may reach past it, and the averaged hats stay a partition of unity and linearly complete
// only where every hat they touch exists.
//
// Walls lie on the box's sides, one kind per side: on a slip wall every node on or beyond it
// has the normal component of its velocity (and momentum and force) set to zero, on a fixed
// wall both components; an open side holds nothing (a particle that reaches it leaves the
// grid, an error).

#include <array>
#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/mpm/bspline_basis.hpp"

namespace mfree {

/// The sides of the grid box, in the order Walls lists them.
enum class Side { left, right, bottom, top };
/// What a side of the grid box holds.
enum class Wall { open, slip, fixed };
/// The wall of every side, indexed by Side.
using Walls = std::array<Wall, 4>;

/// The sides by name: left, right, bottom, top.
const NameTable<Side>& side_names();
/// The wall kinds by name: open, slip, fixed.
const NameTable<Wall>& wall_names();

class Grid {
 public:
  /// cells across the box's width (square cells need box width / cells == height / rows,
  /// checked); degree of the B-splines; pad: extra cells on every side.
  Grid(const Box& box, int cells_x, int degree, int pad);

  [[nodiscard]] const Box& box() const { return box_; }
  [[nodiscard]] const BSplineAxis& x_axis() const { return ax_; }
  [[nodiscard]] const BSplineAxis& y_axis() const { return ay_; }
  [[nodiscard]] double spacing() const { return ax_.spacing(); }
  [[nodiscard]] int cells_x() const { return cells_x_; }  ///< cells across the box
  [[nodiscard]] int cells_y() const { return cells_y_; }
  [[nodiscard]] int nx() const { return ax_.size(); }
  [[nodiscard]] int ny() const { return ay_.size(); }
  [[nodiscard]] Index size() const { return nx() * ny(); }
  [[nodiscard]] Index index(int i, int j) const { return i + nx() * j; }
  [[nodiscard]] Vec2 node(Index n) const { return {ax_.node(n % nx()), ay_.node(n / nx())}; }
  /// The region the basis is defined on (the box plus the padding).
  [[nodiscard]] Box extent() const { return {Vec2(ax_.lo(), ay_.lo()), Vec2(ax_.hi(), ay_.hi())}; }

  /// Per node, which velocity components the walls hold at zero (bit 0: x, bit 1: y).
  [[nodiscard]] std::vector<unsigned char> wall_mask(const Walls& walls) const;

 private:
  Box box_;
  int cells_x_, cells_y_;
  BSplineAxis ax_, ay_;
};

}  // namespace mfree
