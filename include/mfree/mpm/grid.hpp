#pragma once
// The uniform background grid of the MPM: square cells of size h over a rectangle, and the
// tensor-product basis N_ij(x, y) = N_i(x) N_j(y) of two B-spline axes (bspline_basis.hpp).
// A grid "node" is one basis function; node (i, j) has index i + nx j and sits at the
// Greville point (x_i, y_j).
//
// The body's domain is the rectangle the grid is built for. B-spline grids cover exactly
// that rectangle (open knots at its edges). Grids for uGIMP and CPDI are padded by one cell
// on every side: a particle's domain near a wall may reach past it, and the averaged hats
// stay a partition of unity and linearly complete only where every hat they touch exists.
//
// Slip walls lie on the domain's edges: every node on or beyond a wall has the normal
// component of its velocity (and momentum and force) set to zero.

#include <array>
#include <vector>

#include "mfree/core/types.hpp"
#include "mfree/mpm/bspline_basis.hpp"

namespace mfree {

enum class Wall { left, right, bottom, top };

class Grid {
 public:
  /// cells per side of the domain (square cells need domain width / cells == height /
  /// rows, checked); degree of the B-splines; pad: extra cells on every side.
  Grid(const Box& domain, int cells_x, int degree, int pad);

  [[nodiscard]] const Box& domain() const { return domain_; }
  [[nodiscard]] const BSplineAxis& x_axis() const { return ax_; }
  [[nodiscard]] const BSplineAxis& y_axis() const { return ay_; }
  [[nodiscard]] double spacing() const { return ax_.spacing(); }
  [[nodiscard]] int cells_x() const { return cells_x_; }  ///< cells across the domain
  [[nodiscard]] int cells_y() const { return cells_y_; }
  [[nodiscard]] int nx() const { return ax_.size(); }
  [[nodiscard]] int ny() const { return ay_.size(); }
  [[nodiscard]] Index size() const { return nx() * ny(); }
  [[nodiscard]] Index index(int i, int j) const { return i + nx() * j; }
  [[nodiscard]] Vec2 node(Index n) const { return {ax_.node(n % nx()), ay_.node(n / nx())}; }
  /// The region the basis is defined on (the domain plus the padding).
  [[nodiscard]] Box extent() const { return {Vec2(ax_.lo(), ay_.lo()), Vec2(ax_.hi(), ay_.hi())}; }

  /// Per node, which velocity components the slip walls hold at zero (bit 0: x, bit 1: y).
  [[nodiscard]] std::vector<unsigned char> wall_mask(const std::vector<Wall>& walls) const;

 private:
  Box domain_;
  int cells_x_, cells_y_;
  BSplineAxis ax_, ay_;
};

}  // namespace mfree
