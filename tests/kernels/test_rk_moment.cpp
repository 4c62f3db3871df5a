// The polynomial bases and the moment matrix of the RK construction in two and three
// dimensions (kernels/polynomial_basis.hpp, kernels/rk_moment.hpp): the functions
// phi_I = b . H(z_I) w_I, b = M^-1 H(0), reproduce every term of the basis at a point of a
// perturbed lattice, and the basis derivatives are those of its values.

#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mfree/kernels/rk_moment.hpp"
#include "mfree/kernels/window_function.hpp"

using namespace mfree;

namespace {

/// sum_I phi_I H(z_I) - H(0) at x for the nodes of a perturbed unit lattice in [-3, 3]^dim,
/// windows of radius a (cubic B-spline of |z|): the largest entry, and M's reciprocal
/// condition number.
template <int dim, int Order>
std::pair<double, double> reproduction_defect(double a) {
  using Moment = RKMoment<dim, Order>;
  using Basis = typename Moment::Basis;
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> jitter(-0.3, 0.3);
  std::vector<Eigen::Matrix<double, dim, 1>> nodes;
  const int n = 7;
  for (int i = 0; i < (dim == 2 ? n * n : n * n * n); ++i) {
    Eigen::Matrix<double, dim, 1> p;
    int rest = i;
    for (int c = 0; c < dim; ++c, rest /= n) p[c] = rest % n - 3 + jitter(rng);
    nodes.push_back(p);
  }
  Eigen::Matrix<double, dim, 1> x;
  for (int c = 0; c < dim; ++c) x[c] = 0.37 - 0.21 * c;
  const auto terms = [](const Eigen::Matrix<double, dim, 1>& z) {
    if constexpr (dim == 2)
      return Basis::value(z[0], z[1]);
    else
      return Basis::value(z[0], z[1], z[2]);
  };
  Moment m;
  std::vector<double> w;
  for (const auto& p : nodes) {
    const Eigen::Matrix<double, dim, 1> z = (x - p) / a;
    w.push_back(cubic_bspline(z.norm()).w);
    m.add(w.back(), terms(z));
  }
  typename Moment::Matrix inverse;
  const double rcond = m.invert(inverse);
  Eigen::Matrix<double, Moment::nb, 1> sum = Eigen::Matrix<double, Moment::nb, 1>::Zero();
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const Eigen::Matrix<double, dim, 1> z = (x - nodes[i]) / a;
    const auto h = terms(z);
    const Eigen::Map<const Eigen::Matrix<double, Moment::nb, 1>> hv(h.data());
    sum += inverse.col(0).dot(hv) * w[i] * hv;
  }
  sum[0] -= 1.0;  // H(0) = e_1
  return {sum.cwiseAbs().maxCoeff(), rcond};
}

/// The largest difference between the basis derivatives and central differences of its
/// values, at a few points.
template <int dim, int Order>
double derivative_defect() {
  using Basis = PolynomialBasis<dim, Order>;
  const double eps = 1e-6;
  double worst = 0.0;
  for (const double s : {-0.7, 0.2, 0.9}) {
    std::array<double, 3> z{s, 0.5 * s - 0.3, 0.4 - s};
    for (int axis = 0; axis < dim; ++axis) {
      std::array<double, 3> up = z, down = z;
      up[axis] += eps;
      down[axis] -= eps;
      typename Basis::Terms exact, plus, minus;
      if constexpr (dim == 2) {
        exact = axis == 0 ? Basis::d1(z[0], z[1]) : Basis::d2(z[0], z[1]);
        plus = Basis::value(up[0], up[1]);
        minus = Basis::value(down[0], down[1]);
      } else {
        exact = axis == 0 ? Basis::d1(z[0], z[1], z[2])
                          : (axis == 1 ? Basis::d2(z[0], z[1], z[2]) : Basis::d3(z[0], z[1], z[2]));
        plus = Basis::value(up[0], up[1], up[2]);
        minus = Basis::value(down[0], down[1], down[2]);
      }
      for (int j = 0; j < Basis::size; ++j)
        worst = std::max(worst, std::abs((plus[j] - minus[j]) / (2 * eps) - exact[j]));
    }
  }
  return worst;
}

}  // namespace

TEST_CASE("RK moment in 2D and 3D: the functions reproduce every basis term at round-off", "[kernels]") {
  const auto [l2, r2] = reproduction_defect<2, 1>(2.2);
  const auto [q2, s2] = reproduction_defect<2, 2>(3.2);
  const auto [l3, r3] = reproduction_defect<3, 1>(2.2);
  const auto [q3, s3] = reproduction_defect<3, 2>(3.2);
  CAPTURE(l2, q2, l3, q3, r2, s2, r3, s3);
  CHECK(l2 <= 1e-13);
  CHECK(q2 <= 1e-12);
  CHECK(l3 <= 1e-13);
  CHECK(q3 <= 1e-12);
  for (const double rcond : {r2, s2, r3, s3}) CHECK(rcond > 1e-4);
  // The terms and sizes of the 3D bases: 4 and 10.
  CHECK(PolynomialBasis<3, 1>::size == 4);
  CHECK(PolynomialBasis<3, 2>::size == 10);
  const auto h = PolynomialBasis<3, 2>::value(2.0, 3.0, 5.0);
  CHECK(h == std::array<double, 10>{1, 2, 3, 5, 4, 6, 10, 9, 15, 25});
}

TEST_CASE("RK moment: too few nodes make M singular", "[kernels]") {
  // Four nodes on one plane cannot hold a 3D linear basis: M has rank 3.
  RKMoment<3, 1> m;
  for (const auto& [a, b] : {std::pair{0.0, 0.0}, {1.0, 0.0}, {0.0, 1.0}, {1.0, 1.0}})
    m.add(1.0, PolynomialBasis<3, 1>::value(a, b, 0.0));
  RKMoment<3, 1>::Matrix inverse;
  CHECK(m.invert(inverse) == -1.0);
}

TEST_CASE("polynomial bases: the derivatives are those of the values", "[kernels]") {
  CHECK(derivative_defect<2, 1>() <= 1e-9);
  CHECK(derivative_defect<2, 2>() <= 1e-9);
  CHECK(derivative_defect<3, 1>() <= 1e-9);
  CHECK(derivative_defect<3, 2>() <= 1e-9);
}
