#pragma once
// Compressible Neo-Hookean material (SPEC section 5; the model of seed 000), in 3D and in
// plane strain (dim = 2, C_zz = 1, so tr C - 3 = tr C_2 - 2):
//
//   W = mu/2 (tr C - dim) - mu ln J + lambda/2 (ln J)^2,     C = F^T F, J = det F
//   P = mu (F - F^-T) + lambda ln J F^-T
//   A_iJkL = mu d_ik d_JL + (mu - lambda ln J) Finv_Li Finv_Jk + lambda Finv_Ji Finv_Lk
//
// (seed 000 eq. (40) prints the transpose of P.) J <= 0 is a NumericalError.

#include "mfree/materials/finite_strain.hpp"

namespace mfree {

struct NeoHookean {
  Lame lame;

  template <int dim>
  [[nodiscard]] double energy(const Tensor2<dim>& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    // I_1 - 3 with the plane strain's C_zz = 1: tr C - dim in either dimension.
    return 0.5 * lame.mu * ((f.transpose() * f).trace() - double(dim)) - lame.mu * lnj +
           0.5 * lame.lambda * lnj * lnj;
  }
  template <int dim>
  [[nodiscard]] Tensor2<dim> stress(const Tensor2<dim>& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    const Tensor2<dim> finv_t = f.inverse().transpose();
    return lame.mu * (f - finv_t) + lame.lambda * lnj * finv_t;
  }
  template <int dim>
  [[nodiscard]] Tangent<dim> tangent(const Tensor2<dim>& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    const Tensor2<dim> g = f.inverse();  // g(L, i) = Finv_Li
    Tangent<dim> a;
    for (int i = 0; i < dim; ++i)
      for (int jj = 0; jj < dim; ++jj)
        for (int k = 0; k < dim; ++k)
          for (int l = 0; l < dim; ++l)
            a(tensor_index<dim>(i, jj), tensor_index<dim>(k, l)) =
                lame.mu * (i == k) * (jj == l) + (lame.mu - lame.lambda * lnj) * g(l, i) * g(jj, k) +
                lame.lambda * g(jj, i) * g(l, k);
    return a;
  }
};

}  // namespace mfree
