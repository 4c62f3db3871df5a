#pragma once
// St. Venant–Kirchhoff material, plane strain:
//
//   E = (C - I) / 2,  S = lambda tr(E) I + 2 mu E,  P = F S,  W = lambda/2 (tr E)^2 + mu E : E
//   A_iJkL = d_ik S_JL + F_iM (lambda d_MJ d_NL + mu (d_MN d_JL + d_ML d_JN)) F_kN
//
// Objective, but not for large compression (it softens and can invert). J <= 0 is a
// NumericalError.

#include "mfree/materials/finite_strain.hpp"

namespace mfree {

struct StVenantKirchhoff {
  Lame lame;

  [[nodiscard]] double energy(const Mat2& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    const Mat2 e = 0.5 * (f.transpose() * f - Mat2::Identity());
    return 0.5 * lame.lambda * e.trace() * e.trace() + lame.mu * e.cwiseProduct(e).sum();
  }
  [[nodiscard]] Mat2 second_piola(const Mat2& f) const {
    const Mat2 e = 0.5 * (f.transpose() * f - Mat2::Identity());
    return lame.lambda * e.trace() * Mat2::Identity() + 2.0 * lame.mu * e;
  }
  [[nodiscard]] Mat2 stress(const Mat2& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    return f * second_piola(f);
  }
  [[nodiscard]] Tangent tangent(const Mat2& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    const Mat2 s = second_piola(f);
    Tangent a;
    for (int i = 0; i < 2; ++i)
      for (int jj = 0; jj < 2; ++jj)
        for (int k = 0; k < 2; ++k)
          for (int l = 0; l < 2; ++l) {
            // F_iM C_MJNL F_kN with C_MJNL = lambda d_MJ d_NL + mu (d_MN d_JL + d_ML d_JN)
            const double c = lame.lambda * f(i, jj) * f(k, l) +
                             lame.mu * ((f.row(i).dot(f.row(k))) * (jj == l) + f(i, l) * f(k, jj));
            a(tensor_index(i, jj), tensor_index(k, l)) = (i == k) * s(jj, l) + c;
          }
    return a;
  }
};

}  // namespace mfree
