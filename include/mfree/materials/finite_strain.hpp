#pragma once
// Shared conventions of the materials: deformation gradient F (dim x dim, dimensionless),
// first Piola–Kirchhoff stress P (force per reference area in 2D, per reference area of a
// unit thickness; force per reference area in 3D) and its tangent
//
//     A_iJkL = dP_iJ / dF_kL,  stored as a dim^2 x dim^2 matrix A(dim i + J, dim k + L),
//
// strain energy W per reference volume. Plane laws (dim = 2) are plane strain (F_zz = 1)
// unless they say otherwise; in 3D every law is the full law. A material is a small value type
// (its constants) with energy(F), stress(F) and tangent(F); history, where a model has it,
// lives in the solver's per-point arrays. The Galerkin solver and the MPM use the same types.

#include <Eigen/Core>
#include <Eigen/LU>
#include <cmath>

#include "mfree/core/types.hpp"

namespace mfree {

template <int dim>
using Tangent = Eigen::Matrix<double, dim * dim, dim * dim>;

/// Row/column of A for the component (i, J) of a dim x dim tensor.
template <int dim>
constexpr int tensor_index(int i, int j) {
  return dim * i + j;
}

/// Lamé constants of (E, nu): lambda = E nu / ((1 + nu)(1 - 2 nu)), mu = E / (2 (1 + nu)).
struct Lame {
  double lambda;
  double mu;
};
inline Lame lame_constants(double youngs_modulus, double poisson_ratio) {
  const double e = youngs_modulus, nu = poisson_ratio;
  return {e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu)), e / (2.0 * (1.0 + nu))};
}

/// Von Mises stress of a plane state: in-plane Cauchy stress sigma (symmetric) and sigma_zz.
inline double von_mises(const Mat2& s, double szz) {
  const double a = s(0, 0) - s(1, 1), b = s(1, 1) - szz, c = szz - s(0, 0);
  const double shear = 0.5 * (s(0, 1) + s(1, 0));
  return std::sqrt(0.5 * (a * a + b * b + c * c) + 3.0 * shear * shear);
}

/// Von Mises stress of a 3D Cauchy stress (symmetric).
inline double von_mises(const Tensor2<3>& s) {
  const double a = s(0, 0) - s(1, 1), b = s(1, 1) - s(2, 2), c = s(2, 2) - s(0, 0);
  return std::sqrt(0.5 * (a * a + b * b + c * c) +
                   3.0 * (s(0, 1) * s(0, 1) + s(0, 2) * s(0, 2) + s(1, 2) * s(1, 2)));
}

/// J = det F, throwing NumericalError ("J = ... <= 0 (F = ...)") when the material is
/// inverted or collapsed; the solver that called adds where and when.
template <int dim>
double checked_jacobian(const Tensor2<dim>& f, const char* model);

}  // namespace mfree
