#include "mfree/problems/crack_references.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"

namespace mfree {

namespace {

constexpr double pi = std::numbers::pi;

void require_crack_length(double a, const char* what) {
  if (!(a > 0.0) || !std::isfinite(a))
    throw InputError(fmt::format("{}: the crack half-length must be positive and finite, got {}", what, a));
}

}  // namespace

StressIntensityPair griffith_inclined_crack(double stress, double half_length, double beta) {
  require_crack_length(half_length, "Griffith inclined crack");
  const double root = std::sqrt(pi * half_length), s = std::sin(beta), c = std::cos(beta);
  return {stress * s * s * root, stress * s * c * root};
}

double centre_crack_strip_factor(double a_over_w) {
  if (!(a_over_w >= 0.0 && a_over_w < 1.0))
    throw InputError(
        fmt::format("centre crack in a strip: a/w must lie in [0, 1) (a the half-length, w the "
                    "half-width), got {}",
                    a_over_w));
  const double r2 = a_over_w * a_over_w;
  return (1.0 - 0.025 * r2 + 0.06 * r2 * r2) * std::sqrt(1.0 / std::cos(pi * a_over_w / 2.0));
}

double edge_crack_strip_factor(double a_over_w) {
  if (!(a_over_w >= 0.0 && a_over_w <= 0.6))
    throw InputError(
        fmt::format("edge crack in a strip: a/w must lie in [0, 0.6], the range of the "
                    "handbook fit (a the depth, w the width), got {}",
                    a_over_w));
  const double r = a_over_w;
  return 1.12 + r * (-0.231 + r * (10.55 + r * (-21.72 + r * 30.39)));
}

double griffith_crack_opening(double normal_stress, double half_length, double s,
                              const LinearElastic& material) {
  require_crack_length(half_length, "Griffith crack opening");
  material.validate();
  if (!(std::abs(s) < half_length)) return 0.0;
  const double effective = near_tip_constants(material).effective_modulus;
  return 4.0 * normal_stress * std::sqrt(half_length * half_length - s * s) / effective;
}

namespace {

/// Williams' field of (k1, k2) about `tip` at a global point, in the tip's local frame, with
/// the rotation Q that takes local tensors to global ones (Q T Q^T).
struct WilliamsAbout {
  Mat2 q;
  Vec2 origin;
  double k1, k2;
  NearTipConstants c;
  [[nodiscard]] NearTipState at(const Vec2& x) const {
    const Vec2 local = q.transpose() * (x - origin);
    return williams_field(k1, k2, local.norm(), std::atan2(local.y(), local.x()), c);
  }
};

WilliamsAbout williams_about(const CrackTipFrame& tip, double k1, double k2, const LinearElastic& material) {
  tip.validate();
  material.validate();
  return {tip.rotation(), tip.position, k1, k2, near_tip_constants(material)};
}

}  // namespace

ExactElasticity williams_near_tip_solution(const CrackTipFrame& tip, double k1, double k2,
                                           const LinearElastic& material) {
  const WilliamsAbout w = williams_about(tip, k1, k2, material);
  ExactElasticity e;
  e.displacement = [=](const Vec2& x) -> Vec2 {
    if (x == w.origin) return Vec2::Zero();  // u vanishes at the tip
    return w.q * w.at(x).displacement;
  };
  e.stress = [=](const Vec2& x) {
    const Mat2 s = w.q * w.at(x).stress * w.q.transpose();
    return Eigen::Vector3d(s(0, 0), s(1, 1), s(0, 1));
  };
  e.body_force = [](const Vec2&) { return Vec2::Zero(); };
  return e;
}

std::function<Mat2(const Vec2&)> williams_near_tip_gradient(const CrackTipFrame& tip, double k1, double k2,
                                                            const LinearElastic& material) {
  const WilliamsAbout w = williams_about(tip, k1, k2, material);
  return [=](const Vec2& x) -> Mat2 { return w.q * w.at(x).gradient * w.q.transpose(); };
}

}  // namespace mfree
