#pragma once
// Small-strain linear elasticity in 2D, plane stress or plane strain, and in 3D (the law
// whose plane reduction plane strain is; plane stress has no 3D form).
//
// Voigt order (xx, yy, xy) with engineering shear strain gamma_xy = 2 eps_xy, so that
// sigma = D eps and the strain energy density is eps . D eps / 2. Units: E in stress units
// (e.g. Pa), nu dimensionless in (-1, 1/2).

#include <Eigen/Core>
#include <cmath>
#include <string_view>

#include "mfree/materials/finite_strain.hpp"

namespace mfree {

enum class PlaneModel { stress, strain };

struct LinearElastic {
  double youngs_modulus = 1.0;  ///< E > 0
  double poisson_ratio = 0.0;   ///< -1 < nu < 1/2
  PlaneModel model = PlaneModel::stress;

  /// Throws InputError (naming the value) for E <= 0 or nu outside (-1, 1/2).
  void validate() const;

  /// D (3 x 3) with sigma = D eps in Voigt form.
  [[nodiscard]] Eigen::Matrix3d voigt_tangent() const {
    const double e = youngs_modulus, nu = poisson_ratio;
    Eigen::Matrix3d d = Eigen::Matrix3d::Zero();
    if (model == PlaneModel::stress) {
      const double c = e / (1.0 - nu * nu);
      d << c, c * nu, 0.0, c * nu, c, 0.0, 0.0, 0.0, c * (1.0 - nu) / 2.0;
    } else {
      const double c = e / ((1.0 + nu) * (1.0 - 2.0 * nu));
      d << c * (1.0 - nu), c * nu, 0.0, c * nu, c * (1.0 - nu), 0.0, 0.0, 0.0, c * (1.0 - 2.0 * nu) / 2.0;
    }
    return d;
  }

  // The same law in the form every material has (finite_strain.hpp): F -> P, A = dP/dF with
  // eps = sym(F - I) and P = sigma(eps). Not objective: a rigid rotation strains it.

  /// Voigt index (xx, yy, xy) of the tensor component 2 i + J.
  static constexpr int voigt_of(int t) { return t == 0 ? 0 : t == 3 ? 1 : 2; }

  [[nodiscard]] double energy(const Mat2& f) const {
    const Eigen::Vector3d e = voigt_strain(f);
    return 0.5 * e.dot(voigt_tangent() * e);
  }
  [[nodiscard]] Mat2 stress(const Mat2& f) const {
    const Eigen::Vector3d s = voigt_tangent() * voigt_strain(f);
    Mat2 p;
    p << s[0], s[2], s[2], s[1];
    return p;
  }
  /// A(2 i + J, 2 k + L) = D(v(iJ), v(kL)): the shear strain gamma = H_xy + H_yx takes both.
  [[nodiscard]] Tangent<2> tangent(const Mat2&) const {
    const Eigen::Matrix3d d = voigt_tangent();
    Tangent<2> a;
    for (int t = 0; t < 4; ++t)
      for (int s = 0; s < 4; ++s) a(t, s) = d(voigt_of(t), voigt_of(s));
    return a;
  }
  static Eigen::Vector3d voigt_strain(const Mat2& f) {
    return {f(0, 0) - 1.0, f(1, 1) - 1.0, f(0, 1) + f(1, 0)};
  }

  /// The 3D law: sigma = lambda tr(eps) I + 2 mu eps, eps = sym(F) - I; InputError for the
  /// plane-stress model.
  [[nodiscard]] double energy(const Tensor2<3>& f) const;
  [[nodiscard]] Tensor2<3> stress(const Tensor2<3>& f) const;
  /// A_iJkL = lambda d_iJ d_kL + mu (d_ik d_JL + d_iL d_Jk).
  [[nodiscard]] Tangent<3> tangent(const Tensor2<3>& f) const;

  /// sigma_zz of an in-plane Voigt stress: nu (sigma_xx + sigma_yy) in plane strain, 0 in
  /// plane stress.
  [[nodiscard]] double out_of_plane_stress(const Eigen::Vector3d& s) const {
    return model == PlaneModel::strain ? poisson_ratio * (s[0] + s[1]) : 0.0;
  }
  /// Von Mises stress of a Voigt stress, with its sigma_zz.
  [[nodiscard]] double von_mises(const Eigen::Vector3d& s) const {
    Mat2 m;
    m << s[0], s[2], s[2], s[1];
    return mfree::von_mises(m, out_of_plane_stress(s));
  }
};

std::string_view to_string(PlaneModel model);

}  // namespace mfree
