#pragma once
// St. Venant–Kirchhoff material, in 3D and in plane strain (dim = 2, E_zz = 0):
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

  template <int dim>
  [[nodiscard]] double energy(const Tensor2<dim>& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    const Tensor2<dim> e = 0.5 * (f.transpose() * f - Tensor2<dim>::Identity());
    return 0.5 * lame.lambda * e.trace() * e.trace() + lame.mu * e.cwiseProduct(e).sum();
  }
  template <int dim>
  [[nodiscard]] Tensor2<dim> second_piola(const Tensor2<dim>& f) const {
    const Tensor2<dim> e = 0.5 * (f.transpose() * f - Tensor2<dim>::Identity());
    return lame.lambda * e.trace() * Tensor2<dim>::Identity() + 2.0 * lame.mu * e;
  }
  template <int dim>
  [[nodiscard]] Tensor2<dim> stress(const Tensor2<dim>& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    return f * second_piola(f);
  }
  template <int dim>
  [[nodiscard]] Tangent<dim> tangent(const Tensor2<dim>& f) const {
    (void)checked_jacobian(f, "St. Venant-Kirchhoff");
    const Tensor2<dim> s = second_piola(f);
    Tangent<dim> a;
    for (int i = 0; i < dim; ++i)
      for (int jj = 0; jj < dim; ++jj)
        for (int k = 0; k < dim; ++k)
          for (int l = 0; l < dim; ++l) {
            // F_iM C_MJNL F_kN with C_MJNL = lambda d_MJ d_NL + mu (d_MN d_JL + d_ML d_JN)
            const double c = lame.lambda * f(i, jj) * f(k, l) +
                             lame.mu * ((f.row(i).dot(f.row(k))) * (jj == l) + f(i, l) * f(k, jj));
            a(tensor_index<dim>(i, jj), tensor_index<dim>(k, l)) = (i == k) * s(jj, l) + c;
          }
    return a;
  }
};

}  // namespace mfree
