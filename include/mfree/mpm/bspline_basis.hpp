#pragma once
// One axis of an MPM background grid: the B-spline basis of degree p on a uniform
// partition x0 < x0 + h < ... < x0 + cells h, with the open knot vector (seed 000, eqs. 1-3)
//
//   xi = { x0 (p + 1 times), x0 + h, ..., x0 + (cells - 1) h, x0 + cells h (p + 1 times) },
//
// so n = cells + p functions N_0 .. N_{n-1}. Degree 1 gives the hat functions of Classic MPM
// (and, on a grid padded by one cell, the hats the GIMPs and CPDIs average); degrees 2 and 3 the
// quadratic and cubic B-splines. Only N_0 is non-zero at x0 and only N_{n-1} at the far end,
// where they equal 1: zeroing those coefficients fixes the field on the wall.
//
// The "node" of N_i is its Greville abscissa (xi_{i+1} + ... + xi_{i+p}) / p: with these
// nodes sum_i x_i N_i(x) = x (linear completeness). For open knot vectors they are not the
// knots (SPEC section 7): for quadratics, the walls and the cell centres.
//
// Lengths in the problem's unit; derivatives per unit length.

#include <algorithm>
#include <array>
#include <cmath>

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
  /// int N_i dx = (xi_{i+p+1} - xi_i) / (p + 1).
  [[nodiscard]] double integral(int i) const;

  /// The p + 1 functions non-zero on the cell holding x: N_{first + k}(x) = value[k] and
  /// their derivatives. x must lie in [lo(), hi()] (the far end belongs to the last cell);
  /// the caller checks (a point outside is not on the grid).
  struct Values {
    int first = 0;
    std::array<double, max_degree + 1> value{};
    std::array<double, max_degree + 1> derivative{};
  };
  /// By the closed form of the uniform B-spline on cells whose functions see no repeated
  /// knot (p - 1 <= cell <= cells - p), by cox_de_boor() on the others.
  [[nodiscard]] Values evaluate(double x) const {
    switch (p_) {
      case 1: return evaluate_as<1>(x);
      case 2: return evaluate_as<2>(x);
      default: return evaluate_as<3>(x);
    }
  }
  /// evaluate() for the degree p == degree() known at compile time: inline, so that the
  /// closed form unrolls into the particle loops (twice per particle and step).
  template <int p>
  [[nodiscard]] Values evaluate_as(double x) const {
    return evaluate_on<p>(cell_of(x), x);
  }
  /// The p + 1 functions of `cell` and their derivatives, as polynomials of that cell, at x
  /// (which may lie on or just outside the cell's ends): a piece of an integral over the cell
  /// stays on the cell's polynomials however x rounds.
  template <int p>
  [[nodiscard]] Values evaluate_on(int cell, double x) const {
    // The recursion and eq. (3) read the knots xi_{k-p+1} .. xi_{k+p} of span k = cell + p,
    // that is x0 + (cell - p + 1) h .. x0 + (cell + p) h clamped to the ends: equally spaced
    // unless the clamp acts, which it does for cell < p - 1 or cell > cells - p.
    if (cell < p - 1 || cell > cells_ - p) return cox_de_boor_on(cell, x);
    // s from the cell's own left knot, as the recursion measures: t - cell would carry the
    // rounding of t, up to cells ulps of 1.
    return uniform<p>(cell, (x - (x0_ + h_ * cell)) * inv_h_);
  }
  /// The cell holding x, clamped to [0, cells - 1] (the far end belongs to the last cell).
  [[nodiscard]] int cell_of(double x) const {
    return std::clamp(static_cast<int>(std::floor((x - x0_) / h_)), 0, cells_ - 1);
  }
  /// The same values by the Cox–de Boor recursion on the open knot vector, on every cell.
  [[nodiscard]] Values cox_de_boor(double x) const { return cox_de_boor_on(cell_of(x), x); }
  /// The recursion on the span of `cell`, at any x.
  [[nodiscard]] Values cox_de_boor_on(int cell, double x) const;

  /// Knot xi_j of the open knot vector, j in [0, cells + 2p].
  [[nodiscard]] double knot(int j) const;

 private:
  /// Equal knots: eqs. (2) and (3) reduce to the pieces of the uniform B-spline in the local
  /// coordinate s in [0, 1] of the cell (u = 1 - s), N_{cell} first; every derivative carries
  /// the chain-rule factor ds/dx = 1 / h.
  template <int p>
  [[nodiscard]] Values uniform(int cell, double s) const {
    const double u = 1.0 - s, d = inv_h_;
    Values out;
    out.first = cell;
    if constexpr (p == 1) {
      out.value = {u, s};
      out.derivative = {-d, d};
    } else if constexpr (p == 2) {
      out.value = {0.5 * u * u, 0.5 + s * u, 0.5 * s * s};
      out.derivative = {-u * d, (u - s) * d, s * d};
    } else {
      static_assert(p == 3);
      out.value = {u * u * u / 6.0, 2.0 / 3.0 - s * s * (1.0 - 0.5 * s), 2.0 / 3.0 - u * u * (1.0 - 0.5 * u),
                   s * s * s / 6.0};
      out.derivative = {-0.5 * u * u * d, s * (1.5 * s - 2.0) * d, u * (2.0 - 1.5 * u) * d, 0.5 * s * s * d};
    }
    return out;
  }

  double x0_;
  double h_;
  double inv_h_;
  int cells_;
  int p_;
};

}  // namespace mfree
