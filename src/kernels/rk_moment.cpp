#include "mfree/kernels/rk_moment.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <cmath>

namespace mfree {

namespace {

/// L1 norm (largest column sum) of a small matrix.
template <class Matrix>
double norm1(const Matrix& m) {
  return m.cwiseAbs().colwise().sum().maxCoeff();
}

}  // namespace

template <int dim, int Order, class Scalar>
double RKMoment<dim, Order, Scalar>::invert(Matrix& inverse) const requires std::is_arithmetic_v<Scalar> {
  const Matrix m = matrix();
  if constexpr (nb <= 4) {
    if (!(std::abs(m.determinant()) > 0.0)) return -1.0;
    inverse = m.inverse();
  } else {
    const Eigen::LLT<Matrix> llt(m);
    if (llt.info() != Eigen::Success) return -1.0;
    inverse = llt.solve(Matrix::Identity());
  }
  return 1.0 / (norm1(m) * norm1(inverse));
}

template class RKMoment<2, 1>;
template class RKMoment<2, 2>;
template class RKMoment<3, 1>;
template class RKMoment<3, 2>;

}  // namespace mfree
