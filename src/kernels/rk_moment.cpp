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

template <int Order, class Scalar>
double RKMoment<Order, Scalar>::invert(Matrix& inverse) const
  requires std::is_arithmetic_v<Scalar>
{
  const Matrix m = matrix();
  if constexpr (nb == 3) {
    if (!(std::abs(m.determinant()) > 0.0)) return -1.0;
    inverse = m.inverse();
  } else {
    const Eigen::LLT<Matrix> llt(m);
    if (llt.info() != Eigen::Success) return -1.0;
    inverse = llt.solve(Matrix::Identity());
  }
  return 1.0 / (norm1(m) * norm1(inverse));
}

template class RKMoment<1>;
template class RKMoment<2>;

}  // namespace mfree
