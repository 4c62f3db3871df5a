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
// The 2 x 2 logarithm in closed form, smooth at equal eigenvalues (so that its derivatives
// exist at F = I): with m = tr C / 2, q = |C - m I|^2 / 2 (eigenvalues m +- sqrt(q)),
//   ln C = 1/2 ln(det C) I + g(q, m) (C - m I),  g = atanh(sqrt(x)) / sqrt(x) / m,  x = q / m^2,
// and T : d(ln C) gives (dq = (C - m I) : dC, dm = I : dC / 2)
//   S = 1/2 tr(T) C^-1 + (T : (C - m I)) (g_q (C - m I) + g_m / 2 I) + g (T - tr(T) / 2 I)
// (in-plane T; T_zz does not enter: C_zz = 1 and E_zz = 0).

#include <unsupported/Eigen/AutoDiff>

#include <cmath>
#include <optional>

#include "mfree/materials/finite_strain.hpp"
#include "mfree/materials/material_state.hpp"

namespace mfree::plastic {

using Dual = Eigen::AutoDiffScalar<Eigen::Vector4d>;

inline double value(double x) { return x; }
inline double value(const Dual& x) { return x.value(); }

/// A symmetric plane-strain tensor: the in-plane block and the zz component.
template <class S>
struct Sym {
  S xx, yy, xy, zz;
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

/// sqrt(x) with zero derivatives at x = 0 (a norm of a zero tensor: only compared there).
template <class S>
S safe_sqrt(const S& x) {
  using std::sqrt;
  return value(x) > 0.0 ? S(sqrt(x)) : S(0.0);
}

template <class S>
Sym<S> sym_of(const MaterialState& s) {
  return {S(s.plastic_strain(0, 0)), S(s.plastic_strain(1, 1)), S(0.5 * (s.plastic_strain(0, 1) + s.plastic_strain(1, 0))),
          S(s.plastic_strain_zz)};
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

/// What an update yields in the scalar type S.
template <class S>
struct Result {
  S p[4];            // P_xx, P_xy, P_yx, P_yy (row-major, tensor_index)
  Sym<S> stress;     // T after the return
  Sym<S> plastic;    // E_p after the update
  S alpha;
  S dissipation;
  S energy;          // 1/2 E_e : D : E_e
  S jacobian;
};

/// Steps 1-5 above; `law.return_map(trial, state, lame, alpha_increment)` returns T.
template <class S, class Law>
Result<S> update(const Law& law, const Lame& lame, Kinematics kinematics, const S f[4], const MaterialState& n) {
  Result<S> r;
  r.jacobian = f[0] * f[3] - f[1] * f[2];
  std::optional<LogStrain<S>> log_strain;
  Sym<S> strain;
  if (kinematics == Kinematics::logarithmic) {
    log_strain.emplace(f);
    strain = log_strain->strain;
  } else {
    strain = {f[0] - 1.0, f[3] - 1.0, 0.5 * (f[1] + f[2]), S(0.0)};
  }
  const Sym<S> plastic_n = sym_of<S>(n);
  const Sym<S> trial = elastic_stress(lame, strain - plastic_n);
  S dalpha(0.0);
  r.stress = law.return_map(trial, n, dalpha);
  const Sym<S> dplastic = elastic_strain(lame, trial - r.stress);
  r.plastic = plastic_n + dplastic;
  r.alpha = n.alpha + dalpha;
  r.dissipation = n.dissipation + dot(r.stress, dplastic);
  r.energy = 0.5 * dot(r.stress, elastic_strain(lame, r.stress));
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

/// The stored (elastic) energy 1/2 T : E_e after the update of F from the state n.
template <class Law>
double stored_energy(const Law& law, const Lame& lame, Kinematics kinematics, const Mat2& f, const MaterialState& n) {
  const double fd[4] = {f(0, 0), f(0, 1), f(1, 0), f(1, 1)};
  return update<double>(law, lame, kinematics, fd, n).energy;
}

/// The update of a law in double precision and, with_tangent, again with dual numbers for
/// dP/dF (the same code: the consistent tangent).
template <class Law>
MaterialUpdate evaluate(const Law& law, const Lame& lame, Kinematics kinematics, const Mat2& f, const MaterialState& n,
                        bool with_tangent) {
  const double fd[4] = {f(0, 0), f(0, 1), f(1, 0), f(1, 1)};
  const Result<double> r = update<double>(law, lame, kinematics, fd, n);
  MaterialUpdate out;
  out.stress << r.p[0], r.p[1], r.p[2], r.p[3];
  out.state.plastic_strain << r.plastic.xx, r.plastic.xy, r.plastic.xy, r.plastic.yy;
  out.state.plastic_strain_zz = r.plastic.zz;
  out.state.alpha = r.alpha;
  out.state.dissipation = r.dissipation;
  // sigma_zz = T_zz / J (logarithmic: S_zz = T_zz since C_zz = 1), T_zz (small strain).
  out.stress_zz = kinematics == Kinematics::logarithmic ? r.stress.zz / r.jacobian : r.stress.zz;
  if (with_tangent) {
    Dual fx[4];
    for (int k = 0; k < 4; ++k) fx[k] = Dual(fd[k], 4, k);
    const Result<Dual> d = update<Dual>(law, lame, kinematics, fx, n);
    for (int k = 0; k < 4; ++k) out.tangent.row(k) = d.p[k].derivatives().transpose();
  }
  return out;
}

}  // namespace mfree::plastic
