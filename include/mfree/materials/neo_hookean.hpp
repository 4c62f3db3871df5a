#pragma once
// Compressible Neo-Hookean material (SPEC section 5; the model of seed 000), plane strain:
//
//   W = mu/2 (tr C - 2) - mu ln J + lambda/2 (ln J)^2,     C = F^T F, J = det F
//   P = mu (F - F^-T) + lambda ln J F^-T
//   A_iJkL = mu d_ik d_JL + (mu - lambda ln J) Finv_Li Finv_Jk + lambda Finv_Ji Finv_Lk
//
// (seed 000 eq. (40) prints the transpose of P.) J <= 0 is a NumericalError.

#include "mfree/materials/finite_strain.hpp"

namespace mfree {

struct NeoHookean {
  Lame lame;

  [[nodiscard]] double energy(const Mat2& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    return 0.5 * lame.mu * ((f.transpose() * f).trace() - 2.0) - lame.mu * lnj + 0.5 * lame.lambda * lnj * lnj;
  }
  [[nodiscard]] Mat2 stress(const Mat2& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    const Mat2 finv_t = f.inverse().transpose();
    return lame.mu * (f - finv_t) + lame.lambda * lnj * finv_t;
  }
  [[nodiscard]] Tangent tangent(const Mat2& f) const {
    const double lnj = std::log(checked_jacobian(f, "Neo-Hookean"));
    const Mat2 g = f.inverse();  // g(L, i) = Finv_Li
    Tangent a;
    for (int i = 0; i < 2; ++i)
      for (int jj = 0; jj < 2; ++jj)
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l)
            a(tensor_index(i, jj), tensor_index(k, l)) =
                lame.mu * (i == k) * (jj == l) + (lame.mu - lame.lambda * lnj) * g(l, i) * g(jj, k) +
                lame.lambda * g(jj, i) * g(l, k);
    return a;
  }
};

}  // namespace mfree
