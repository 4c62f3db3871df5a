#pragma once
// Polynomial bases of the reproducing conditions, in the shifted, scaled variable
// z = (x - x_I) / s (SPEC section 1): far better conditioned than raw monomials.
//
//   Order 1 (linear):    H(z) = [1, z1, z2]                       (3 terms)
//   Order 2 (quadratic): H(z) = [1, z1, z2, z1^2, z1 z2, z2^2]    (6 terms)

#include <Eigen/Core>

#include "mfree/core/types.hpp"

namespace mfree {

enum class RKOrder { linear = 1, quadratic = 2 };

template <int Order>
struct PolynomialBasis;

template <>
struct PolynomialBasis<1> {
  static constexpr int size = 3;
  using Vector = Eigen::Matrix<double, size, 1>;
  static Vector value(const Vec2& z) { return {1.0, z.x(), z.y()}; }
  /// dH/dz1 and dH/dz2.
  static Vector d1(const Vec2&) { return {0.0, 1.0, 0.0}; }
  static Vector d2(const Vec2&) { return {0.0, 0.0, 1.0}; }
};

template <>
struct PolynomialBasis<2> {
  static constexpr int size = 6;
  using Vector = Eigen::Matrix<double, size, 1>;
  static Vector value(const Vec2& z) {
    Vector h;
    h << 1.0, z.x(), z.y(), z.x() * z.x(), z.x() * z.y(), z.y() * z.y();
    return h;
  }
  static Vector d1(const Vec2& z) {
    Vector h;
    h << 0.0, 1.0, 0.0, 2.0 * z.x(), z.y(), 0.0;
    return h;
  }
  static Vector d2(const Vec2& z) {
    Vector h;
    h << 0.0, 0.0, 1.0, 0.0, z.x(), 2.0 * z.y();
    return h;
  }
};

}  // namespace mfree
