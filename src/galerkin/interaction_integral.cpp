#include "mfree/galerkin/interaction_integral.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>

#include "mfree/core/error.hpp"

namespace mfree {

void DomainWeight::validate() const {
  if (!(inner_radius > 0.0 && outer_radius > inner_radius && std::isfinite(outer_radius)))
    throw InputError(
        fmt::format("interaction integral: the domain radii must satisfy 0 < inner < outer "
                    "(finite), got inner = {}, outer = {}; the weight q is 1 inside the inner "
                    "radius and 0 beyond the outer one",
                    inner_radius, outer_radius));
}

namespace {

/// s = (rho - r0) / (r1 - r0) clamped to [0, 1].
double annulus_fraction(const DomainWeight& w, double rho) {
  const double s = (rho - w.inner_radius) / (w.outer_radius - w.inner_radius);
  return s < 0.0 ? 0.0 : s > 1.0 ? 1.0 : s;
}

}  // namespace

double DomainWeight::value(double rho) const {
  const double s = annulus_fraction(*this, rho);
  if (profile == WeightProfile::linear) return 1.0 - s;
  return 1.0 - s * s * s * (10.0 - 15.0 * s + 6.0 * s * s);
}

double DomainWeight::slope(double rho) const {
  if (!(rho > inner_radius && rho < outer_radius)) return 0.0;
  const double width = outer_radius - inner_radius, s = (rho - inner_radius) / width;
  if (profile == WeightProfile::linear) return -1.0 / width;
  return -30.0 * s * s * (1.0 - s) * (1.0 - s) / width;
}

double DomainWeight::slope_integral() const { return std::numbers::pi * (inner_radius + outer_radius); }

namespace {

/// The bilinear form of the domain integrand of two fields a, b (each a displacement
/// gradient H(i, j) = u_i,j and a stress) with weight gradient g, all in crack-tip
/// coordinates: sigma^a_ij u^b_i,1 g_j + sigma^b_ij u^a_i,1 g_j - sigma^a_ij eps^b_ij g_1.
/// Twice the J integrand for a = b; the interaction integrand of Yau et al. otherwise.
double bilinear_integrand(const Mat2& grad_a, const Mat2& stress_a, const Mat2& grad_b, const Mat2& stress_b,
                          const Vec2& g) {
  const Mat2 strain_b = 0.5 * (grad_b + grad_b.transpose());
  return (stress_a * g).dot(grad_b.col(0)) + (stress_b * g).dot(grad_a.col(0)) -
         stress_a.cwiseProduct(strain_b).sum() * g.x();
}

}  // namespace

InteractionIntegrand interaction_integrand(const Mat2& grad_u, const Mat2& stress, double r, double theta,
                                           const Vec2& grad_q, const NearTipConstants& constants) {
  const NearTipState one = williams_field(1.0, 0.0, r, theta, constants);
  const NearTipState two = williams_field(0.0, 1.0, r, theta, constants);
  InteractionIntegrand v;
  v.mode_one = bilinear_integrand(grad_u, stress, one.gradient, one.stress, grad_q);
  v.mode_two = bilinear_integrand(grad_u, stress, two.gradient, two.stress, grad_q);
  v.j = 0.5 * bilinear_integrand(grad_u, stress, grad_u, stress, grad_q);
  return v;
}

namespace {

void check_sizes(std::size_t points, std::size_t weights, std::size_t gradients, std::size_t stresses) {
  if (weights != points || gradients != points || stresses != points)
    throw InputError(
        fmt::format("interaction integral: the samples must have one weight, gradient and stress "
                    "per point; got {} points, {} weights, {} gradients, {} stresses",
                    points, weights, gradients, stresses));
}

Mat2 tensor_of(const Eigen::Vector3d& voigt) {
  Mat2 m;
  m << voigt[0], voigt[2], voigt[2], voigt[1];
  return m;
}

}  // namespace

StressIntensity interaction_integral(const CrackTipFrame& tip, const LinearElastic& material,
                                     const DomainWeight& weight, std::span<const Vec2> points,
                                     std::span<const double> weights,
                                     std::span<const Mat2> displacement_gradients,
                                     std::span<const Eigen::Vector3d> stresses, double coverage_tolerance) {
  tip.validate();
  material.validate();
  weight.validate();
  check_sizes(points.size(), weights.size(), displacement_gradients.size(), stresses.size());
  const NearTipConstants constants = near_tip_constants(material);
  const Mat2 q = tip.rotation();  // global = Q local
  double mode_one = 0.0, mode_two = 0.0, j = 0.0, slope_sum = 0.0;
  Index used = 0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const Vec2 x = q.transpose() * (points[k] - tip.position);
    const double rho = x.norm(), slope = weight.slope(rho);
    if (slope == 0.0) continue;  // q is constant here: no contribution
    const Mat2 h = q.transpose() * displacement_gradients[k] * q;
    const Mat2 s = q.transpose() * tensor_of(stresses[k]) * q;
    if (!std::isfinite(weights[k]) || !h.allFinite() || !s.allFinite())
      throw NumericalError(
          fmt::format("interaction integral: sample {} at ({}, {}) inside the domain of the tip "
                      "at ({}, {}) has a non-finite weight, gradient or stress",
                      k, points[k].x(), points[k].y(), tip.position.x(), tip.position.y()));
    const InteractionIntegrand v =
        interaction_integrand(h, s, rho, std::atan2(x.y(), x.x()), slope * x / rho, constants);
    mode_one += weights[k] * v.mode_one;
    mode_two += weights[k] * v.mode_two;
    j += weights[k] * v.j;
    slope_sum += weights[k] * std::abs(slope);
    ++used;
  }
  StressIntensity result;
  result.k1 = constants.effective_modulus * mode_one / 2.0;
  result.k2 = constants.effective_modulus * mode_two / 2.0;
  result.j = j;
  result.coverage = slope_sum / weight.slope_integral();
  result.points_used = used;
  if (!(std::abs(result.coverage - 1.0) <= coverage_tolerance))
    throw InputError(
        fmt::format("interaction integral: the samples cover {:.4g} of the domain {} < |x - tip| < {} "
                    "about the tip at ({}, {}) (tolerance {}; {} points inside); the annulus must "
                    "lie inside the body and the rule must fill it: use a smaller outer radius or "
                    "a finer rule",
                    result.coverage, weight.inner_radius, weight.outer_radius, tip.position.x(),
                    tip.position.y(), coverage_tolerance, used));
  return result;
}

}  // namespace mfree
