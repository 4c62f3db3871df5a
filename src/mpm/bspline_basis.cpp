#include "mfree/mpm/bspline_basis.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"

namespace mfree {

BSplineAxis::BSplineAxis(double x0, double h, int cells, int degree)
    : x0_(x0), h_(h), inv_h_(1.0 / h), cells_(cells), p_(degree) {
  if (!(h > 0.0)) throw InputError(fmt::format("B-spline axis: the cell size must be positive (got {})", h));
  if (cells < 1) throw InputError(fmt::format("B-spline axis: needs at least one cell (got {})", cells));
  if (degree < 1 || degree > max_degree)
    throw InputError(fmt::format("B-spline axis: the degree must be 1, 2 or 3 (got {})", degree));
}

double BSplineAxis::knot(int j) const { return x0_ + h_ * std::clamp(j - p_, 0, cells_); }

double BSplineAxis::integral(int i) const { return (knot(i + p_ + 1) - knot(i)) / (p_ + 1); }

double BSplineAxis::node(int i) const {
  double s = 0.0;
  for (int k = 1; k <= p_; ++k) s += knot(i + k);
  return s / p_;
}

BSplineAxis::Values BSplineAxis::cox_de_boor_on(int cell, double x) const {
  // Knot span k = cell + p, xi_k <= x < xi_{k+1} for x on the cell; the functions non-zero
  // there are N_{k-p} .. N_k.
  const int k = cell + p_;
  // Cox–de Boor (seed 000 eq. 2) bottom-up, with eq. (1) read the right way round
  // (N_{k,0} = 1 on the span, SPEC section 7): n[d][m] = N_{k-d+m, d}, m = 0..d.
  double n[max_degree + 1][max_degree + 1] = {};
  n[0][0] = 1.0;
  for (int d = 1; d <= p_; ++d)
    for (int m = 0; m <= d; ++m) {
      const int i = k - d + m;
      double v = 0.0;
      if (m >= 1) {  // N_{i,d-1} = n[d-1][m-1]
        const double den = knot(i + d) - knot(i);
        if (den > 0.0) v += (x - knot(i)) / den * n[d - 1][m - 1];
      }
      if (m <= d - 1) {  // N_{i+1,d-1} = n[d-1][m]
        const double den = knot(i + d + 1) - knot(i + 1);
        if (den > 0.0) v += (knot(i + d + 1) - x) / den * n[d - 1][m];
      }
      n[d][m] = v;
    }
  Values out;
  out.first = k - p_;
  for (int m = 0; m <= p_; ++m) {
    out.value[m] = n[p_][m];
    // eq. (3) with the minus sign restored (SPEC section 7):
    // N'_{i,p} = p / (xi_{i+p} - xi_i) N_{i,p-1} - p / (xi_{i+p+1} - xi_{i+1}) N_{i+1,p-1}.
    const int i = k - p_ + m;
    double dv = 0.0;
    if (m >= 1) {
      const double den = knot(i + p_) - knot(i);
      if (den > 0.0) dv += p_ / den * n[p_ - 1][m - 1];
    }
    if (m <= p_ - 1) {
      const double den = knot(i + p_ + 1) - knot(i + 1);
      if (den > 0.0) dv -= p_ / den * n[p_ - 1][m];
    }
    out.derivative[m] = dv;
  }
  return out;
}

}  // namespace mfree
