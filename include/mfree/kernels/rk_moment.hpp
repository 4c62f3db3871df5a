#pragma once
// The moment matrix of the RK / MLS construction at one point x of dimension dim (2 or 3;
// SPEC section 1),
//
//   M(x) = sum_I w_I H(z_I) H(z_I)^T,   z_I = (x - x_I) / a,
//
// summed neighbour by neighbour in its upper triangle (nb (nb + 1) / 2 scalars that stay in
// registers), and its inverse with the reciprocal condition number 1 / (|M|_1 |M^-1|_1)
// that decides whether the point is well posed. phi_I(x) = b . H(z_I) w_I with b = M^-1 H(0),
// H(0) = e_1 in the shifted basis: b is the first column of M^-1.
//
// Scalar = double sums the matrix of one point; Scalar = an Eigen array (Eigen::Array4d)
// sums the matrices of several points side by side, one per lane, and lane(q) hands out the
// matrix of point q. One definition for every user: the RK shape functions of
// rk_shape_functions.hpp (trial functions, quadrature clouds) and the MPM's MLS
// reconstruction, which sums the moments of the four Gauss points of a cell in one pass over
// the particles around them.

#include <Eigen/Core>
#include <array>
#include <type_traits>

#include "mfree/kernels/polynomial_basis.hpp"

namespace mfree {

template <int dim, int Order, class Scalar = double>
class RKMoment {
 public:
  using Basis = PolynomialBasis<dim, Order>;
  static constexpr int nb = Basis::size;
  static constexpr int entries = nb * (nb + 1) / 2;
  using Matrix = Eigen::Matrix<double, nb, nb>;

  RKMoment() {
    for (Scalar& u : upper_) {
      if constexpr (std::is_arithmetic_v<Scalar>) u = 0.0;
      else u.setZero();
    }
  }

  /// M += w H H^T.
  void add(const Scalar& w, const std::array<Scalar, nb>& h) {
    int e = 0;
    for (int i = 0; i < nb; ++i) {
      const Scalar wh = w * h[i];
      for (int j = i; j < nb; ++j) upper_[e++] += wh * h[j];
    }
  }

  /// The matrix of lane q (Scalar an Eigen array). A member template, so that the explicit
  /// instantiations of the scalar class leave it out.
  template <class S = Scalar>
  [[nodiscard]] RKMoment<dim, Order> lane(int q) const requires(!std::is_arithmetic_v<S>) {
    RKMoment<dim, Order> m;
    for (int e = 0; e < entries; ++e) m.upper_[e] = upper_[e][q];
    return m;
  }

  [[nodiscard]] Matrix matrix() const
    requires std::is_arithmetic_v<Scalar>
  {
    Matrix m;
    for (int i = 0, e = 0; i < nb; ++i)
      for (int j = i; j < nb; ++j, ++e) m(i, j) = m(j, i) = upper_[e];
    return m;
  }

  /// M^-1 into `inverse` (explicitly: 3 x 3 and 4 x 4 by cofactors, 6 x 6 and 10 x 10 by
  /// Cholesky) and the reciprocal condition number; -1 when M is singular (inverse then
  /// undefined).
  [[nodiscard]] double invert(Matrix& inverse) const
    requires std::is_arithmetic_v<Scalar>;

 private:
  template <int, int, class>
  friend class RKMoment;
  std::array<Scalar, entries> upper_;
};

extern template class RKMoment<2, 1>;
extern template class RKMoment<2, 2>;
extern template class RKMoment<3, 1>;
extern template class RKMoment<3, 2>;

}  // namespace mfree
