#pragma once
// The update shared by the plastic laws (j2_plasticity.cpp, drucker_prager.cpp), written once
// for a scalar type S: double for the stress, an automatic-differentiation scalar carrying
// d/dF (4 components) for the consistent tangent. A law supplies only its return map in the
// strain space:
//
//   1. strain: E = 1/2 ln C of the in-plane C = F^T F (E_zz = 0), or eps = sym(F) - I
//   2. elastic predictor: E_e^tr = E - E_p,n, T^tr = lambda tr(E_e^tr) 1 + 2 mu E_e^tr
//   3. the law's return: T, and alpha's increment
//   4. dE_p = D^-1 : (T^tr - T), dissipation += T : dE_p
//   5. stress: S = T : 2 dE/dC (logarithmic; below), P = F S; or P = T (small strain)
//
// Kinematics::multiplicative instead (Simo 1992; Simo & Hughes 1998, box 9.1): the state holds
// C_p^-1 - I (in-plane block and zz; the virgin state is C_p^-1 = I), and
//   1. b_e^tr = F C_p,n^-1 F^T, eps_e^tr = 1/2 ln b_e^tr (Eulerian Hencky strain)
//   2. Kirchhoff tau^tr = lambda tr(eps_e^tr) 1 + 2 mu eps_e^tr
//   3. the law's return (isotropic: tau stays coaxial with b_e^tr), alpha's increment
//   4. b_e = exp(2 D^-1 : tau), C_p^-1 = F^-1 b_e F^-T, dissipation += tau : D^-1 : (tau^tr - tau)
//   5. P = tau F^-T (sigma = tau / J)
// The yield condition then bounds the Kirchhoff stress itself at any accumulated strain. The
// additive split of the Lagrangian E = 1/2 ln C bounds T, whose push-forward loses its shear
// part under large shear: in simple shear sigma_xy / sigma_yy falls from 0.48 (gamma <= 1,
// phi = 30 degrees) to 0.25 at gamma = 3 and 0.07 at gamma = 10, so granular flows in MPM
// (unbounded shear) lose their friction.
//
// The 2 x 2 logarithm in closed form, smooth at equal eigenvalues (so that its derivatives
// exist at F = I): with m = tr C / 2, q = |C - m I|^2 / 2 (eigenvalues m +- sqrt(q)),
//   ln C = 1/2 ln(det C) I + g(q, m) (C - m I),  g = atanh(sqrt(x)) / sqrt(x) / m,  x = q / m^2,
// and T : d(ln C) gives (dq = (C - m I) : dC, dm = I : dC / 2)
//   S = 1/2 tr(T) C^-1 + (T : (C - m I)) (g_q (C - m I) + g_m / 2 I) + g (T - tr(T) / 2 I)
// (in-plane T; T_zz does not enter: C_zz = 1 and E_zz = 0).
//
// In three dimensions (dim = 3) the same steps on full symmetric tensors (Sym3), with ln and
// exp of a symmetric 3 x 3 by its eigen-decomposition A = Q diag(lambda) Q^T, and their
// derivatives (the dual numbers' parts) by the Daleckii–Krein formula
//   d f(A)[dA] = Q (G o (Q^T dA Q)) Q^T,  G_ij = (f(l_i) - f(l_j)) / (l_i - l_j), G_ii = f'(l_i)
// (Bhatia 1997, Theorem V.3.3), exact at repeated eigenvalues (F = I). Only first
// derivatives are taken through it, so the 3D laws take multiplicative and small-strain
// kinematics; the logarithmic (Lagrangian) one needs the second derivative of ln C for its
// tangent and is plane only.

#include <Eigen/Eigenvalues>
#include <array>
#include <cmath>
#include <optional>
#include <type_traits>
#include <unsupported/Eigen/AutoDiff>

#include "mfree/core/error.hpp"
#include "mfree/materials/finite_strain.hpp"
#include "mfree/materials/material_state.hpp"

namespace mfree::plastic {

/// A dual number with d/dF of a dim x dim F (dim^2 components).
template <int dim>
using Dual = Eigen::AutoDiffScalar<Eigen::Matrix<double, dim * dim, 1>>;

inline double value(double x) { return x; }
template <class D>
double value(const Eigen::AutoDiffScalar<D>& x) {
  return x.value();
}

/// A symmetric plane-strain tensor: the in-plane block and the zz component.
template <class S>
struct Sym {
  using Scalar = S;
  S xx, yy, xy, zz;
  static Sym identity() { return {S(1.0), S(1.0), S(0.0), S(1.0)}; }
  friend Sym operator+(const Sym& a, const Sym& b) { return {a.xx + b.xx, a.yy + b.yy, a.xy + b.xy, a.zz + b.zz}; }
  friend Sym operator-(const Sym& a, const Sym& b) { return {a.xx - b.xx, a.yy - b.yy, a.xy - b.xy, a.zz - b.zz}; }
  friend Sym operator*(const S& c, const Sym& a) { return {c * a.xx, c * a.yy, c * a.xy, c * a.zz}; }
  [[nodiscard]] S trace() const { return xx + yy + zz; }
  [[nodiscard]] Sym deviator() const {
    const S m = trace() / 3.0;
    return {xx - m, yy - m, xy, zz - m};
  }
};

template <class S>
S dot(const Sym<S>& a, const Sym<S>& b) {
  return a.xx * b.xx + a.yy * b.yy + 2.0 * a.xy * b.xy + a.zz * b.zz;
}

/// A symmetric 3 x 3 tensor.
template <class S>
struct Sym3 {
  using Scalar = S;
  S xx, yy, zz, xy, xz, yz;
  static Sym3 identity() { return {S(1.0), S(1.0), S(1.0), S(0.0), S(0.0), S(0.0)}; }
  friend Sym3 operator+(const Sym3& a, const Sym3& b) {
    return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
  }
  friend Sym3 operator-(const Sym3& a, const Sym3& b) {
    return {a.xx - b.xx, a.yy - b.yy, a.zz - b.zz, a.xy - b.xy, a.xz - b.xz, a.yz - b.yz};
  }
  friend Sym3 operator*(const S& c, const Sym3& a) {
    return {c * a.xx, c * a.yy, c * a.zz, c * a.xy, c * a.xz, c * a.yz};
  }
  [[nodiscard]] S trace() const { return xx + yy + zz; }
  [[nodiscard]] Sym3 deviator() const {
    const S m = trace() / 3.0;
    return {xx - m, yy - m, zz - m, xy, xz, yz};
  }
  [[nodiscard]] Eigen::Matrix<S, 3, 3> matrix() const {
    Eigen::Matrix<S, 3, 3> a;
    a << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    return a;
  }
  /// The symmetric part of a 3 x 3.
  static Sym3 of(const Eigen::Matrix<S, 3, 3>& a) {
    return {a(0, 0),
            a(1, 1),
            a(2, 2),
            0.5 * (a(0, 1) + a(1, 0)),
            0.5 * (a(0, 2) + a(2, 0)),
            0.5 * (a(1, 2) + a(2, 1))};
  }
};

template <class S>
S dot(const Sym3<S>& a, const Sym3<S>& b) {
  return a.xx * b.xx + a.yy * b.yy + a.zz * b.zz + 2.0 * (a.xy * b.xy + a.xz * b.xz + a.yz * b.yz);
}

/// sqrt(x) with zero derivatives at x = 0 (a norm of a zero tensor: only compared there).
template <class S>
S safe_sqrt(const S& x) {
  using std::sqrt;
  return value(x) > 0.0 ? S(sqrt(x)) : S(0.0);
}

template <class S>
Sym<S> sym_of(const MaterialState<2>& s) {
  return {S(s.plastic_strain(0, 0)), S(s.plastic_strain(1, 1)), S(0.5 * (s.plastic_strain(0, 1) + s.plastic_strain(1, 0))),
          S(s.plastic_strain_zz)};
}
template <class S>
Sym3<S> sym_of(const MaterialState<3>& s) {
  const auto& e = s.plastic_strain;
  return {S(e(0, 0)),
          S(e(1, 1)),
          S(e(2, 2)),
          S(0.5 * (e(0, 1) + e(1, 0))),
          S(0.5 * (e(0, 2) + e(2, 0))),
          S(0.5 * (e(1, 2) + e(2, 1)))};
}

/// T = lambda tr(E) 1 + 2 mu E, and its inverse.
template <class S>
Sym<S> elastic_stress(const Lame& l, const Sym<S>& e) {
  const S volumetric = l.lambda * e.trace();
  return {volumetric + 2.0 * l.mu * e.xx, volumetric + 2.0 * l.mu * e.yy, 2.0 * l.mu * e.xy, volumetric + 2.0 * l.mu * e.zz};
}
template <class S>
Sym<S> elastic_strain(const Lame& l, const Sym<S>& t) {
  const double bulk = l.lambda + 2.0 * l.mu / 3.0;
  const S mean = t.trace() / 3.0;
  const Sym<S> dev = t.deviator();
  const S ev = mean / (3.0 * bulk);
  return {dev.xx / (2.0 * l.mu) + ev, dev.yy / (2.0 * l.mu) + ev, dev.xy / (2.0 * l.mu), dev.zz / (2.0 * l.mu) + ev};
}

template <class S>
Sym3<S> elastic_stress(const Lame& l, const Sym3<S>& e) {
  const S volumetric = l.lambda * e.trace();
  return {volumetric + 2.0 * l.mu * e.xx,
          volumetric + 2.0 * l.mu * e.yy,
          volumetric + 2.0 * l.mu * e.zz,
          2.0 * l.mu * e.xy,
          2.0 * l.mu * e.xz,
          2.0 * l.mu * e.yz};
}
template <class S>
Sym3<S> elastic_strain(const Lame& l, const Sym3<S>& t) {
  const double bulk = l.lambda + 2.0 * l.mu / 3.0;
  const S ev = t.trace() / 3.0 / (3.0 * bulk);
  const Sym3<S> dev = t.deviator();
  const S c = 1.0 / (2.0 * l.mu);
  return {c * dev.xx + ev, c * dev.yy + ev, c * dev.zz + ev, c * dev.xy, c * dev.xz, c * dev.yz};
}

/// f(A) of a symmetric 3 x 3 (above): f and its first divided difference
/// divided(l_i, l_j) = (f(l_i) - f(l_j)) / (l_i - l_j), f'(l_i) when equal.
template <class S, class F, class Divided>
Sym3<S> spectral(const Sym3<S>& a, F f, Divided divided) {
  Eigen::Matrix3d a0;
  a0 << value(a.xx), value(a.xy), value(a.xz), value(a.xy), value(a.yy), value(a.yz), value(a.xz),
      value(a.yz), value(a.zz);
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(a0);
  const Eigen::Matrix3d& q = eigen.eigenvectors();
  const Eigen::Vector3d l = eigen.eigenvalues();
  const Eigen::Matrix3d fa = q * l.unaryExpr(f).asDiagonal() * q.transpose();
  if constexpr (std::is_same_v<S, double>) {
    return Sym3<double>::of(fa);
  } else {
    Eigen::Matrix3d g;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) g(i, j) = divided(l[i], l[j]);
    const auto n = a.xx.derivatives().size();
    using Derivatives = std::decay_t<decltype(a.xx.derivatives())>;
    Derivatives dxx = a.xx.derivatives(), dyy = dxx, dzz = dxx, dxy = dxx, dxz = dxx, dyz = dxx;
    for (Eigen::Index k = 0; k < n; ++k) {
      Eigen::Matrix3d da;
      da << a.xx.derivatives()[k], a.xy.derivatives()[k], a.xz.derivatives()[k], a.xy.derivatives()[k],
          a.yy.derivatives()[k], a.yz.derivatives()[k], a.xz.derivatives()[k], a.yz.derivatives()[k],
          a.zz.derivatives()[k];
      const Eigen::Matrix3d df = q * g.cwiseProduct(q.transpose() * da * q) * q.transpose();
      dxx[k] = df(0, 0), dyy[k] = df(1, 1), dzz[k] = df(2, 2);
      dxy[k] = 0.5 * (df(0, 1) + df(1, 0)), dxz[k] = 0.5 * (df(0, 2) + df(2, 0)),
      dyz[k] = 0.5 * (df(1, 2) + df(2, 1));
    }
    return {S(fa(0, 0), dxx),
            S(fa(1, 1), dyy),
            S(fa(2, 2), dzz),
            S(0.5 * (fa(0, 1) + fa(1, 0)), dxy),
            S(0.5 * (fa(0, 2) + fa(2, 0)), dxz),
            S(0.5 * (fa(1, 2) + fa(2, 1)), dyz)};
  }
}

/// ln A of a symmetric positive definite 3 x 3.
template <class S>
Sym3<S> log_sym3(const Sym3<S>& a) {
  return spectral(
      a, [](double x) { return std::log(x); },
      [](double x, double y) {
        // (ln x - ln y) / (x - y) = log1p(t) / (t y), t = (x - y) / y: accurate as x -> y.
        const double t = (x - y) / y;
        return t == 0.0 ? 1.0 / y : std::log1p(t) / (t * y);
      });
}

/// exp B of a symmetric 3 x 3.
template <class S>
Sym3<S> exp_sym3(const Sym3<S>& b) {
  return spectral(
      b, [](double x) { return std::exp(x); },
      [](double x, double y) {
        const double d = x - y;
        return d == 0.0 ? std::exp(y) : std::exp(y) * std::expm1(d) / d;
      });
}

/// phi(x) = atanh(sqrt(x)) / sqrt(x) and phi'(x), 0 <= x < 1 (series below 1e-3).
template <class S>
void atanh_ratio(const S& x, S& phi, S& dphi) {
  using std::log;
  using std::sqrt;
  if (value(x) < 1e-3) {
    phi = 1.0 + x * (1.0 / 3 + x * (1.0 / 5 + x * (1.0 / 7 + x * (1.0 / 9 + x * (1.0 / 11)))));
    dphi = 1.0 / 3 + x * (2.0 / 5 + x * (3.0 / 7 + x * (4.0 / 9 + x * (5.0 / 11 + x * (6.0 / 13)))));
    return;
  }
  const S r = sqrt(x);
  phi = 0.5 * log((1.0 + r) / (1.0 - r)) / r;
  dphi = (1.0 / (1.0 - x) - phi) / (2.0 * x);
}

/// The in-plane logarithmic strain E = 1/2 ln C and the coefficients of its stress map.
template <class S>
struct LogStrain {
  S cxx, cyy, cxy;  // C
  S m, g, gq, gm, det;
  Sym<S> strain;

  explicit LogStrain(const S f[4]) {
    using std::log;
    cxx = f[0] * f[0] + f[2] * f[2];
    cyy = f[1] * f[1] + f[3] * f[3];
    cxy = f[0] * f[1] + f[2] * f[3];
    m = 0.5 * (cxx + cyy);
    const S a = 0.5 * (cxx - cyy);
    const S q = a * a + cxy * cxy;
    det = cxx * cyy - cxy * cxy;
    S phi, dphi;
    atanh_ratio(S(q / (m * m)), phi, dphi);
    g = phi / m;
    gq = dphi / (m * m * m);
    gm = -(phi + 2.0 * (q / (m * m)) * dphi) / (m * m);
    const S half_ln_det = 0.25 * log(det);
    strain = {half_ln_det + 0.5 * g * a, half_ln_det - 0.5 * g * a, 0.5 * g * cxy, S(0.0)};
  }
  /// S = T : 2 dE/dC (above), as (S_xx, S_yy, S_xy).
  void second_piola(const Sym<S>& t, S& sxx, S& syy, S& sxy) const {
    const S a = 0.5 * (cxx - cyy);
    const S tr = t.xx + t.yy;
    const S t_d = (t.xx - t.yy) * a + 2.0 * t.xy * cxy;  // T : (C - m I)
    const S k = 0.5 * tr / det;                          // 1/2 tr(T) C^-1 = k [cyy, -cxy; -cxy, cxx]
    const S c = t_d * gq, iso = 0.5 * t_d * gm;
    sxx = k * cyy + c * a + iso + g * (t.xx - 0.5 * tr);
    syy = k * cxx - c * a + iso + g * (t.yy - 0.5 * tr);
    sxy = -k * cxy + c * cxy + g * t.xy;
  }
};

/// ln A of a symmetric positive definite 2 x 2 (a_xx, a_yy, a_xy) in closed form (as LogStrain).
template <class S>
void log_sym2(const S& axx, const S& ayy, const S& axy, S& lxx, S& lyy, S& lxy) {
  using std::log;
  const S m = 0.5 * (axx + ayy), a = 0.5 * (axx - ayy);
  const S q = a * a + axy * axy;
  S phi, dphi;
  atanh_ratio(S(q / (m * m)), phi, dphi);
  const S g = phi / m, half_ln_det = 0.5 * log(axx * ayy - axy * axy);
  lxx = half_ln_det + g * a;
  lyy = half_ln_det - g * a;
  lxy = g * axy;
}

/// exp B of a symmetric 2 x 2 in closed form: e^m (cosh r I + sinh r / r (B - m I)),
/// r^2 = ((b_xx - b_yy) / 2)^2 + b_xy^2; by series in r^2 for small r (smooth derivatives).
template <class S>
void exp_sym2(const S& bxx, const S& byy, const S& bxy, S& exx, S& eyy, S& exy) {
  using std::cosh;
  using std::exp;
  using std::sinh;
  using std::sqrt;
  const S m = 0.5 * (bxx + byy), a = 0.5 * (bxx - byy);
  const S r2 = a * a + bxy * bxy;
  S ch, sh;  // cosh r and sinh r / r
  if (value(r2) < 1e-4) {
    ch = 1.0 + r2 * (1.0 / 2 + r2 * (1.0 / 24 + r2 * (1.0 / 720 + r2 * (1.0 / 40320))));
    sh = 1.0 + r2 * (1.0 / 6 + r2 * (1.0 / 120 + r2 * (1.0 / 5040 + r2 * (1.0 / 362880))));
  } else {
    const S r = sqrt(r2);
    ch = cosh(r);
    sh = sinh(r) / r;
  }
  const S em = exp(m);
  exx = em * (ch + sh * a);
  eyy = em * (ch - sh * a);
  exy = em * sh * bxy;
}

/// What an update yields in the scalar type S.
template <class S, int dim>
struct Result {
  using Tensor = std::conditional_t<dim == 2, Sym<S>, Sym3<S>>;
  S p[dim * dim];  // P row-major (tensor_index): P_xx, P_xy, P_yx, P_yy in 2D
  Tensor stress;   // T after the return
  Tensor plastic;  // E_p after the update
  S alpha;
  S dissipation;
  S energy;          // 1/2 E_e : D : E_e
  S jacobian;
};

/// Steps 2-4 on an additive split of the strain (small strain, logarithmic): the trial stress
/// of E - E_p,n, the law's return, and E_p, alpha, the plastic work and the stored energy
/// after it. T: the plane Sym or the 3D Sym3 of the scalar S. Always inlined, as the code it
/// replaced was written in each update: the compiler then fuses the same multiply-adds, and
/// the plane results stay what they were bit for bit (not inlined, the logarithmic J2 update
/// moved in its last bits).
template <class S, int dim, class Law, class T>
[[gnu::always_inline]] inline void additive_return(const Law& law, const Lame& lame, const T& strain,
                                                   const MaterialState<dim>& n, Result<S, dim>& r) {
  const T plastic_n = sym_of<S>(n);
  const T trial = elastic_stress(lame, strain - plastic_n);
  S dalpha(0.0);
  r.stress = law.return_map(trial, n, dalpha);
  const T dplastic = elastic_strain(lame, trial - r.stress);
  r.plastic = plastic_n + dplastic;
  r.alpha = n.alpha + dalpha;
  r.dissipation = n.dissipation + dot(r.stress, dplastic);
  r.energy = 0.5 * dot(r.stress, elastic_strain(lame, r.stress));
}

/// Steps 1-5 above; `law.return_map(trial, state, lame, alpha_increment)` returns T.
template <class S, class Law>
Result<S, 2> update(const Law& law, const Lame& lame, Kinematics kinematics, const S f[4],
                    const MaterialState<2>& n) {
  Result<S, 2> r;
  r.jacobian = f[0] * f[3] - f[1] * f[2];
  if (kinematics == Kinematics::multiplicative) {
    using std::exp;
    using std::log;
    const Sym<S> cp = sym_of<S>(n);  // C_p^-1 - I
    const S axx = 1.0 + cp.xx, ayy = 1.0 + cp.yy, axy = cp.xy;
    // b_e^tr = F C_p^-1 F^T (f row-major: F_xx, F_xy, F_yx, F_yy)
    const S ux = axx * f[0] + axy * f[1], uy = axy * f[0] + ayy * f[1];  // (C_p^-1 F^T) column x
    const S vx = axx * f[2] + axy * f[3], vy = axy * f[2] + ayy * f[3];  // column y
    const S bxx = f[0] * ux + f[1] * uy, byy = f[2] * vx + f[3] * vy, bxy = f[0] * vx + f[1] * vy;
    Sym<S> strain;
    log_sym2(bxx, byy, bxy, strain.xx, strain.yy, strain.xy);
    strain.xx *= 0.5;
    strain.yy *= 0.5;
    strain.xy *= 0.5;
    strain.zz = 0.5 * log(S(1.0 + cp.zz));
    const Sym<S> trial = elastic_stress(lame, strain);  // Kirchhoff
    S dalpha(0.0);
    r.stress = law.return_map(trial, n, dalpha);
    const Sym<S> elastic = elastic_strain(lame, r.stress);
    S exx, eyy, exy;
    exp_sym2(S(2.0 * elastic.xx), S(2.0 * elastic.yy), S(2.0 * elastic.xy), exx, eyy, exy);  // b_e
    // C_p^-1 = F^-1 b_e F^-T, F^-1 = [f3, -f1; -f2, f0] / J
    const S ij = 1.0 / r.jacobian;
    const S gxx = f[3] * ij, gxy = -f[1] * ij, gyx = -f[2] * ij, gyy = f[0] * ij;
    const S wx = exx * gxx + exy * gxy, wy = exy * gxx + eyy * gxy;  // (b_e F^-T) column x
    const S zx = exx * gyx + exy * gyy, zy = exy * gyx + eyy * gyy;  // column y
    r.plastic = {gxx * wx + gxy * wy - 1.0, gyx * zx + gyy * zy - 1.0, gxx * zx + gxy * zy,
                 exp(S(2.0 * elastic.zz)) - 1.0};
    r.alpha = n.alpha + dalpha;
    r.dissipation = n.dissipation + dot(r.stress, elastic_strain(lame, trial - r.stress));
    r.energy = 0.5 * dot(r.stress, elastic);
    // P = tau F^-T, F^-T = [f3, -f2; -f1, f0] / J
    const Sym<S>& t = r.stress;
    r.p[0] = (t.xx * f[3] - t.xy * f[1]) * ij;
    r.p[1] = (t.xy * f[0] - t.xx * f[2]) * ij;
    r.p[2] = (t.xy * f[3] - t.yy * f[1]) * ij;
    r.p[3] = (t.yy * f[0] - t.xy * f[2]) * ij;
    return r;
  }
  std::optional<LogStrain<S>> log_strain;
  Sym<S> strain;
  if (kinematics == Kinematics::logarithmic) {
    log_strain.emplace(f);
    strain = log_strain->strain;
  } else {
    strain = {f[0] - 1.0, f[3] - 1.0, 0.5 * (f[1] + f[2]), S(0.0)};
  }
  additive_return(law, lame, strain, n, r);
  if (log_strain) {
    S sxx, syy, sxy;
    log_strain->second_piola(r.stress, sxx, syy, sxy);
    r.p[0] = f[0] * sxx + f[1] * sxy;
    r.p[1] = f[0] * sxy + f[1] * syy;
    r.p[2] = f[2] * sxx + f[3] * sxy;
    r.p[3] = f[2] * sxy + f[3] * syy;
  } else {
    r.p[0] = r.stress.xx;
    r.p[1] = r.stress.xy;
    r.p[2] = r.stress.xy;
    r.p[3] = r.stress.yy;
  }
  return r;
}

/// Steps 1-5 in 3D (multiplicative or small strain; above).
template <class S, class Law>
Result<S, 3> update(const Law& law, const Lame& lame, Kinematics kinematics, const S f[9],
                    const MaterialState<3>& n) {
  using M3 = Eigen::Matrix<S, 3, 3>;
  M3 fm;
  for (int k = 0; k < 9; ++k) fm(k / 3, k % 3) = f[k];
  Result<S, 3> r;
  r.jacobian = fm.determinant();
  if (kinematics == Kinematics::multiplicative) {
    const Sym3<S> plastic_n = sym_of<S>(n);  // C_p^-1 - I
    // b_e^tr = F C_p^-1 F^T, eps_e^tr = 1/2 ln b_e^tr
    const M3 be_trial = fm * (Sym3<S>::identity() + plastic_n).matrix() * fm.transpose();
    const Sym3<S> strain = S(0.5) * log_sym3(Sym3<S>::of(be_trial));
    const Sym3<S> trial = elastic_stress(lame, strain);  // Kirchhoff
    S dalpha(0.0);
    r.stress = law.return_map(trial, n, dalpha);
    const Sym3<S> elastic = elastic_strain(lame, r.stress);
    const M3 be = exp_sym3(S(2.0) * elastic).matrix();
    // F^-1 by cofactors: the adjugate over J.
    M3 finv;
    finv(0, 0) = fm(1, 1) * fm(2, 2) - fm(1, 2) * fm(2, 1);
    finv(0, 1) = fm(0, 2) * fm(2, 1) - fm(0, 1) * fm(2, 2);
    finv(0, 2) = fm(0, 1) * fm(1, 2) - fm(0, 2) * fm(1, 1);
    finv(1, 0) = fm(1, 2) * fm(2, 0) - fm(1, 0) * fm(2, 2);
    finv(1, 1) = fm(0, 0) * fm(2, 2) - fm(0, 2) * fm(2, 0);
    finv(1, 2) = fm(0, 2) * fm(1, 0) - fm(0, 0) * fm(1, 2);
    finv(2, 0) = fm(1, 0) * fm(2, 1) - fm(1, 1) * fm(2, 0);
    finv(2, 1) = fm(0, 1) * fm(2, 0) - fm(0, 0) * fm(2, 1);
    finv(2, 2) = fm(0, 0) * fm(1, 1) - fm(0, 1) * fm(1, 0);
    finv *= S(1.0) / r.jacobian;
    r.plastic = Sym3<S>::of(M3(finv * be * finv.transpose())) - Sym3<S>::identity();  // C_p^-1 - I
    r.alpha = n.alpha + dalpha;
    r.dissipation = n.dissipation + dot(r.stress, elastic_strain(lame, trial - r.stress));
    r.energy = 0.5 * dot(r.stress, elastic);
    const M3 p = r.stress.matrix() * finv.transpose();  // P = tau F^-T
    for (int k = 0; k < 9; ++k) r.p[k] = p(k / 3, k % 3);
    return r;
  }
  if (kinematics != Kinematics::small_strain)
    throw InputError(
        "the logarithmic (Lagrangian) kinematics of the plastic laws is plane only; a solid takes "
        "multiplicative (the default) or small_strain");
  additive_return(law, lame, Sym3<S>(Sym3<S>::of(fm) - Sym3<S>::identity()), n, r);
  const M3 p = r.stress.matrix();
  for (int k = 0; k < 9; ++k) r.p[k] = p(k / 3, k % 3);
  return r;
}

/// F row-major, as the updates take it.
template <int dim>
std::array<double, dim * dim> components(const Tensor2<dim>& f) {
  std::array<double, dim * dim> c;
  for (int k = 0; k < dim * dim; ++k) c[k] = f(k / dim, k % dim);
  return c;
}

/// The stored (elastic) energy 1/2 T : E_e after the update of F from the state n.
template <class Law, int dim>
double stored_energy(const Law& law, const Lame& lame, Kinematics kinematics, const Tensor2<dim>& f,
                     const MaterialState<dim>& n) {
  return update<double>(law, lame, kinematics, components(f).data(), n).energy;
}

/// The update of a law in double precision and, with_tangent, again with dual numbers for
/// dP/dF (the same code: the consistent tangent).
template <class Law, int dim>
MaterialUpdate<dim> evaluate(const Law& law, const Lame& lame, Kinematics kinematics, const Tensor2<dim>& f,
                             const MaterialState<dim>& n, bool with_tangent) {
  constexpr int nf = dim * dim;
  const std::array<double, nf> fd = components(f);
  const Result<double, dim> r = update<double>(law, lame, kinematics, fd.data(), n);
  MaterialUpdate<dim> out;
  for (int k = 0; k < nf; ++k) out.stress(k / dim, k % dim) = r.p[k];
  if constexpr (dim == 2) {
    out.state.plastic_strain << r.plastic.xx, r.plastic.xy, r.plastic.xy, r.plastic.yy;
    out.state.plastic_strain_zz = r.plastic.zz;
    // sigma_zz = T_zz / J (logarithmic: S_zz = T_zz since C_zz = 1), T_zz (small strain).
    // multiplicative: tau_zz / J.
    out.stress_zz = kinematics != Kinematics::small_strain ? r.stress.zz / r.jacobian : r.stress.zz;
  } else {
    out.state.plastic_strain = r.plastic.matrix();
  }
  out.state.alpha = r.alpha;
  out.state.dissipation = r.dissipation;
  if (with_tangent) {
    Dual<dim> fx[nf];
    for (int k = 0; k < nf; ++k) fx[k] = Dual<dim>(fd[k], nf, k);
    const Result<Dual<dim>, dim> d = update<Dual<dim>>(law, lame, kinematics, fx, n);
    for (int k = 0; k < nf; ++k) out.tangent.row(k) = d.p[k].derivatives().transpose();
  }
  return out;
}

}  // namespace mfree::plastic
