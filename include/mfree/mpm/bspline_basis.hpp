#pragma once
// One axis of an MPM background grid: the B-spline basis of degree p on a uniform
// partition x0 < x0 + h < ... < x0 + cells h, with the open knot vector (seed 000, eqs. 1-3)
//
//   xi = { x0 (p + 1 times), x0 + h, ..., x0 + (cells - 1) h, x0 + cells h (p + 1 times) },
//
// so n = cells + p functions N_0 .. N_{n-1}. Degree 1 gives the hat functions of Classic MPM
// (and, on a grid padded by one cell, the hats uGIMP and CPDI average); degrees 2 and 3 the
// quadratic and cubic B-splines. Only N_0 is non-zero at x0 and only N_{n-1} at the far end,
// where they equal 1: zeroing those coefficients fixes the field on the wall.
//
// The "node" of N_i is its Greville abscissa (xi_{i+1} + ... + xi_{i+p}) / p: with these
// nodes sum_i x_i N_i(x) = x (linear completeness). For open knot vectors they are not the
// knots (SPEC section 7): for quadratics, the walls and the cell centres.
//
// Lengths in the problem's unit; derivatives per unit length.

#include <array>

#include "mfree/core/types.hpp"

namespace mfree {

class BSplineAxis {
 public:
  static constexpr int max_degree = 3;

  /// Throws InputError for h <= 0, cells < 1 or a degree outside [1, 3].
  BSplineAxis(double x0, double h, int cells, int degree);

  [[nodiscard]] int degree() const { return p_; }
  [[nodiscard]] int cells() const { return cells_; }
  [[nodiscard]] double spacing() const { return h_; }
  [[nodiscard]] double lo() const { return x0_; }
  [[nodiscard]] double hi() const { return x0_ + cells_ * h_; }
  [[nodiscard]] int size() const { return cells_ + p_; }  ///< number of functions n
  /// Greville abscissa of N_i.
  [[nodiscard]] double node(int i) const;

  /// The p + 1 functions non-zero on the cell holding x: N_{first + k}(x) = value[k] and
  /// their derivatives. x must lie in [lo(), hi()] (the far end belongs to the last cell);
  /// the caller checks (a point outside is not on the grid).
  struct Values {
    int first = 0;
    std::array<double, max_degree + 1> value{};
    std::array<double, max_degree + 1> derivative{};
  };
  [[nodiscard]] Values evaluate(double x) const;

  /// Knot xi_j of the open knot vector, j in [0, cells + 2p].
  [[nodiscard]] double knot(int j) const;

 private:
  double x0_;
  double h_;
  int cells_;
  int p_;
};

}  // namespace mfree
