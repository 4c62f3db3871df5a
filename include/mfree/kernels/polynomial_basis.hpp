#pragma once
// Polynomial bases of the reproducing conditions, in the shifted, scaled variable
// z = (x - x_I) / s (SPEC section 1): far better conditioned than raw monomials.
//
//   2D, order 1 (linear):    H(z) = [1, z1, z2]                                   (3 terms)
//   2D, order 2 (quadratic): H(z) = [1, z1, z2, z1^2, z1 z2, z2^2]                (6 terms)
//   3D, order 1:             H(z) = [1, z1, z2, z3]                               (4 terms)
//   3D, order 2:             H(z) = [1, z1, z2, z3, z1^2, z1 z2, z1 z3, z2^2, z2 z3, z3^2]
//                                                                                 (10 terms)
//
// The terms are plain arrays of doubles of the scalars z1, z2 (z3): the RK kernel forms them
// once per neighbour and point, and scalars and arrays of a constant size stay in
// registers, where small Eigen vectors built element by element went through the stack
// (each a store-forwarding stall when read back as one packet: half the kernel's time).

#include <array>
#include <type_traits>

#include "mfree/core/types.hpp"

namespace mfree {

enum class RKOrder { linear = 1, quadratic = 2 };

/// 1 in the type of z: a double, or an Eigen array of ones.
template <class S>
S one_like(const S&) {
  if constexpr (std::is_arithmetic_v<S>) return 1.0;
  else return S::Ones();
}

/// value(z1, z2[, z3]) = H(z): the z doubles, or Eigen arrays with one point per lane (the
/// terms of several points at once); d1, d2 (d3): dH/dz1, dH/dz2 (dH/dz3).
template <int dim, int Order>
struct PolynomialBasis;

template <>
struct PolynomialBasis<2, 1> {
  static constexpr int size = 3;
  using Terms = std::array<double, size>;
  template <class S>
  static std::array<S, size> value(const S& z1, const S& z2) {
    return {one_like(z1), z1, z2};
  }
  /// dH/dz1 and dH/dz2.
  static Terms d1(double, double) { return {0.0, 1.0, 0.0}; }
  static Terms d2(double, double) { return {0.0, 0.0, 1.0}; }
};

template <>
struct PolynomialBasis<2, 2> {
  static constexpr int size = 6;
  using Terms = std::array<double, size>;
  template <class S>
  static std::array<S, size> value(const S& z1, const S& z2) {
    return {one_like(z1), z1, z2, z1 * z1, z1 * z2, z2 * z2};
  }
  static Terms d1(double z1, double z2) { return {0.0, 1.0, 0.0, 2.0 * z1, z2, 0.0}; }
  static Terms d2(double z1, double z2) { return {0.0, 0.0, 1.0, 0.0, z1, 2.0 * z2}; }
};

template <>
struct PolynomialBasis<3, 1> {
  static constexpr int size = 4;
  using Terms = std::array<double, size>;
  template <class S>
  static std::array<S, size> value(const S& z1, const S& z2, const S& z3) {
    return {one_like(z1), z1, z2, z3};
  }
  static Terms d1(double, double, double) { return {0.0, 1.0, 0.0, 0.0}; }
  static Terms d2(double, double, double) { return {0.0, 0.0, 1.0, 0.0}; }
  static Terms d3(double, double, double) { return {0.0, 0.0, 0.0, 1.0}; }
};

template <>
struct PolynomialBasis<3, 2> {
  static constexpr int size = 10;
  using Terms = std::array<double, size>;
  template <class S>
  static std::array<S, size> value(const S& z1, const S& z2, const S& z3) {
    return {one_like(z1), z1, z2, z3, z1 * z1, z1 * z2, z1 * z3, z2 * z2, z2 * z3, z3 * z3};
  }
  static Terms d1(double z1, double z2, double z3) {
    return {0.0, 1.0, 0.0, 0.0, 2.0 * z1, z2, z3, 0.0, 0.0, 0.0};
  }
  static Terms d2(double z1, double z2, double z3) {
    return {0.0, 0.0, 1.0, 0.0, 0.0, z1, 0.0, 2.0 * z2, z3, 0.0};
  }
  static Terms d3(double z1, double z2, double z3) {
    return {0.0, 0.0, 0.0, 1.0, 0.0, 0.0, z1, 0.0, z2, 2.0 * z3};
  }
};

/// a . b of two term arrays.
template <std::size_t n>
double dot_terms(const std::array<double, n>& a, const std::array<double, n>& b) {
  double s = 0.0;
  for (std::size_t i = 0; i < n; ++i) s += a[i] * b[i];
  return s;
}

}  // namespace mfree
