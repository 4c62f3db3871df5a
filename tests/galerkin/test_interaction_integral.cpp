#include <catch2/catch.hpp>
#include <cmath>
#include <numbers>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/galerkin/interaction_integral.hpp"
#include "mfree/problems/crack_references.hpp"
#include "mfree/quadrature/quadrature_rule.hpp"

using namespace mfree;

namespace {

constexpr double pi = std::numbers::pi;

/// Samples of a field on a rule: the spans interaction_integral takes.
struct Samples {
  std::vector<Vec2> points;
  std::vector<double> weights;
  std::vector<Mat2> gradients;
  std::vector<Eigen::Vector3d> stresses;
};

/// Gauss rule in polar coordinates about `centre` (local frame of `tip`): radii split at
/// `radii` (ascending), n_r points per radial piece, n_t points on each of `arcs` equal
/// pieces of (-pi, pi). No point lies on theta = +-pi.
QuadratureRule<2> polar_rule(const CrackTipFrame& tip, const Vec2& centre, const std::vector<double>& radii,
                             int n_r, int arcs, int n_t) {
  const GaussLegendre1D gr = gauss_legendre(n_r), gt = gauss_legendre(n_t);
  const Mat2 q = tip.rotation();
  QuadratureRule<2> rule;
  for (std::size_t p = 0; p + 1 < radii.size(); ++p)
    for (int a = 0; a < arcs; ++a)
      for (int i = 0; i < n_r; ++i)
        for (int k = 0; k < n_t; ++k) {
          const double dr = radii[p + 1] - radii[p], dt = 2 * pi / arcs;
          const double rho = radii[p] + dr * gr.points[i], theta = -pi + dt * (a + gt.points[k]);
          const Vec2 local = centre + rho * Vec2(std::cos(theta), std::sin(theta));
          rule.points.push_back(tip.position + q * local);
          rule.weights.push_back(gr.weights[i] * gt.weights[k] * dr * dt * rho);
        }
  return rule;
}

/// n x n Gauss points on square cells of side h filling [-half, half]^2 of the tip's local
/// frame (half a multiple of h): the tip is a cell corner and the crack line a row of cell
/// edges, so no point lies on the crack and no cell straddles it.
QuadratureRule<2> square_rule(const CrackTipFrame& tip, double half, double h, int n) {
  const GaussLegendre1D g = gauss_legendre(n);
  const int cells = static_cast<int>(std::lround(2 * half / h));
  const Mat2 q = tip.rotation();
  QuadratureRule<2> rule;
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b)
      for (int i = 0; i < n; ++i)
        for (int k = 0; k < n; ++k) {
          const Vec2 local(-half + h * (a + g.points[i]), -half + h * (b + g.points[k]));
          rule.points.push_back(tip.position + q * local);
          rule.weights.push_back(g.weights[i] * g.weights[k] * h * h);
        }
  return rule;
}

/// The exact Williams field of (k1, k2) about `tip` sampled on `rule`.
Samples williams_samples(const CrackTipFrame& tip, double k1, double k2, const LinearElastic& m,
                         const QuadratureRule<2>& rule) {
  const ExactElasticity exact = williams_near_tip_solution(tip, k1, k2, m);
  const auto gradient = williams_near_tip_gradient(tip, k1, k2, m);
  Samples s;
  s.points = rule.points;
  s.weights = rule.weights;
  for (const Vec2& x : rule.points) {
    s.gradients.push_back(gradient(x));
    s.stresses.push_back(exact.stress(x));
  }
  return s;
}

StressIntensity integrate(const CrackTipFrame& tip, const LinearElastic& m, const DomainWeight& w,
                          const Samples& s) {
  return interaction_integral(tip, m, w, s.points, s.weights, s.gradients, s.stresses);
}

struct Errors {
  double k1, k2, j;
};

/// Relative errors of K_I, K_II (by the larger |K|) and J of the exact field on a rule.
Errors errors_on(const CrackTipFrame& tip, const LinearElastic& m, const DomainWeight& w,
                 const QuadratureRule<2>& rule, double k1, double k2) {
  const StressIntensity r = integrate(tip, m, w, williams_samples(tip, k1, k2, m, rule));
  const double scale = std::max(std::abs(k1), std::abs(k2));
  const double j = (k1 * k1 + k2 * k2) / near_tip_constants(m).effective_modulus;
  CHECK(r.coverage == Approx(1.0).epsilon(1e-6));
  return {std::abs(r.k1 - k1) / scale, std::abs(r.k2 - k2) / scale, std::abs(r.j - j) / j};
}

const std::vector<DomainWeight> radii_sets(WeightProfile p) {
  return {{0.1, 0.3, p}, {0.2, 0.5, p}, {0.4, 1.0, p}, {0.05, 1.5, p}};
}

const std::vector<CrackTipFrame> tips{{Vec2(0, 0), Vec2(1, 0)},
                                      {Vec2(0.3, -0.2), Vec2(std::cos(0.7), std::sin(0.7))},
                                      {Vec2(-1.0, 2.0), Vec2(-0.6, -0.8)}};

}  // namespace

// (a), (b): the exact field of K_I = 1.3, K_II = -0.4 on a polar Gauss rule (radial pieces
// split at r0, r1, so both weights integrate without a kink in a piece): K and J to 1e-12
// (measured 1.4e-15 at most),
// for four domains (domain independence), three tip frames, both plane models and weights.
TEST_CASE("interaction integral: exact Williams field on a polar rule", "[interaction_integral]") {
  for (const PlaneModel model : {PlaneModel::strain, PlaneModel::stress})
    for (const WeightProfile profile : {WeightProfile::linear, WeightProfile::smooth})
      for (const CrackTipFrame& tip : tips)
        for (const DomainWeight& w : radii_sets(profile)) {
          const LinearElastic m{70.0, 0.33, model};
          const QuadratureRule<2> rule =
              polar_rule(tip, Vec2::Zero(), {0.5 * w.inner_radius, w.inner_radius, w.outer_radius}, 4, 4, 12);
          const Errors e = errors_on(tip, m, w, rule, 1.3, -0.4);
          INFO(to_string(model) << ", r0 = " << w.inner_radius << ", r1 = " << w.outer_radius
                                << ", tip direction " << tip.direction.transpose());
          CHECK(e.k1 <= 1e-12);
          CHECK(e.k2 <= 1e-12);
          CHECK(e.j <= 1e-12);
        }
}

// (a), (b) on background cells the circles cut: the smooth weight, 4 x 4 Gauss points on
// cells of side h around the tip: K and J to 1e-6 for h = r1 / 40 (measured 5e-8 at most;
// 1.5e-6 at h = r1 / 20; the linear weight, whose gradient jumps inside cut cells, stays
// at 1e-4 to 1e-3 on the same cells).
TEST_CASE("interaction integral: exact Williams field on square Gauss cells", "[interaction_integral]") {
  const LinearElastic m{1.0, 0.3, PlaneModel::strain};
  for (const CrackTipFrame& tip : tips)
    for (const DomainWeight& w : radii_sets(WeightProfile::smooth)) {
      const double h = w.outer_radius / 40.0;
      const QuadratureRule<2> rule = square_rule(tip, 42 * h, h, 4);
      const Errors e = errors_on(tip, m, w, rule, 1.3, -0.4);
      INFO("r0 = " << w.inner_radius << ", r1 = " << w.outer_radius << ", tip direction "
                   << tip.direction.transpose());
      CHECK(e.k1 <= 1e-6);
      CHECK(e.k2 <= 1e-6);
      CHECK(e.j <= 1e-6);
    }
}

// (c): pure mode I gives K_II = 0 to 1e-8 K_I, and pure mode II K_I = 0.
TEST_CASE("interaction integral: pure modes do not mix", "[interaction_integral]") {
  const LinearElastic m{200.0, 0.25, PlaneModel::stress};
  for (const CrackTipFrame& tip : tips) {
    const DomainWeight w{0.2, 0.6, WeightProfile::smooth};
    for (const QuadratureRule<2>& rule :
         {polar_rule(tip, Vec2::Zero(), {0.2, 0.6}, 4, 4, 12), square_rule(tip, 0.63, 0.015, 4)}) {
      const StressIntensity one = integrate(tip, m, w, williams_samples(tip, 2.5, 0.0, m, rule));
      CHECK(one.k1 == Approx(2.5).epsilon(1e-6));
      CHECK(std::abs(one.k2) <= 1e-8 * 2.5);
      const StressIntensity two = integrate(tip, m, w, williams_samples(tip, 0.0, 0.7, m, rule));
      CHECK(two.k2 == Approx(0.7).epsilon(1e-6));
      CHECK(std::abs(two.k1) <= 1e-8 * 0.7);
    }
  }
}

// (d): away from the tip the integrands are divergence free, so with a weight about a point
// c whose disc holds neither the tip nor the crack, int (...) q_,j dA = 0 (to 1e-11 of the
// integral of their absolute values), for discs ahead of the tip (across theta = 0) and
// above and below the crack.
TEST_CASE("interaction integral: zero over a domain without the tip", "[interaction_integral]") {
  const LinearElastic m{1.0, 0.3, PlaneModel::strain};
  const NearTipConstants c = near_tip_constants(m);
  const CrackTipFrame tip{Vec2(0.3, -0.2), Vec2(std::cos(0.7), std::sin(0.7))};
  const Samples s = [&] {
    Samples all;
    for (const Vec2 centre : {Vec2(1.0, 0.0), Vec2(-1.0, 0.8), Vec2(-0.6, -0.7)}) {
      const QuadratureRule<2> rule = polar_rule(tip, centre, {0.0, 0.1, 0.45}, 6, 4, 16);
      const Samples part = williams_samples(tip, 1.3, -0.4, m, rule);
      all.points.insert(all.points.end(), part.points.begin(), part.points.end());
      all.weights.insert(all.weights.end(), part.weights.begin(), part.weights.end());
      all.gradients.insert(all.gradients.end(), part.gradients.begin(), part.gradients.end());
      all.stresses.insert(all.stresses.end(), part.stresses.begin(), part.stresses.end());
    }
    return all;
  }();
  const DomainWeight w{0.1, 0.45, WeightProfile::smooth};
  const Mat2 q = tip.rotation();
  for (const Vec2 centre : {Vec2(1.0, 0.0), Vec2(-1.0, 0.8), Vec2(-0.6, -0.7)}) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero(), size = Eigen::Vector3d::Zero();
    for (std::size_t k = 0; k < s.points.size(); ++k) {
      const Vec2 x = tip.to_local(s.points[k]), d = x - centre;
      if (d.norm() >= w.outer_radius) continue;  // another disc's point
      const Mat2 h = q.transpose() * s.gradients[k] * q;
      Mat2 sigma;
      sigma << s.stresses[k][0], s.stresses[k][2], s.stresses[k][2], s.stresses[k][1];
      sigma = q.transpose() * sigma * q;
      const Vec2 grad_q = d.norm() > 0 ? Vec2(w.slope(d.norm()) * d / d.norm()) : Vec2::Zero();
      const InteractionIntegrand v =
          interaction_integrand(h, sigma, x.norm(), std::atan2(x.y(), x.x()), grad_q, c);
      const Eigen::Vector3d values(v.mode_one, v.mode_two, v.j);
      sum += s.weights[k] * values;
      size += s.weights[k] * values.cwiseAbs();
    }
    INFO("disc centre " << centre.transpose() << ": sums " << sum.transpose() << ", sizes "
                        << size.transpose());
    CHECK(size.minCoeff() > 1e-3);  // the integrands are not zero themselves
    CHECK(std::abs(sum[0]) <= 1e-11 * size[0]);
    CHECK(std::abs(sum[1]) <= 1e-11 * size[1]);
    CHECK(std::abs(sum[2]) <= 1e-11 * size[2]);
  }
}

// The weights: q(r0) = 1, q(r1) = 0, dq/drho = the central difference of q, and
// int |grad q| dA = pi (r0 + r1) by a fine 1D rule.
TEST_CASE("interaction integral: domain weights", "[interaction_integral]") {
  for (const WeightProfile p : {WeightProfile::linear, WeightProfile::smooth}) {
    const DomainWeight w{0.3, 1.1, p};
    CHECK(w.value(0.1) == 1.0);
    CHECK(w.value(0.3) == 1.0);
    CHECK(w.value(1.1) == 0.0);
    CHECK(w.value(2.0) == 0.0);
    CHECK(w.slope(0.2) == 0.0);
    CHECK(w.slope(1.2) == 0.0);
    for (const double rho : {0.35, 0.6, 0.9, 1.05})
      CHECK(w.slope(rho) == Approx((w.value(rho + 1e-6) - w.value(rho - 1e-6)) / 2e-6).epsilon(1e-8));
    const GaussLegendre1D g = gauss_legendre(8);
    double integral = 0.0;
    for (int i = 0; i < 8; ++i) {
      const double rho = 0.3 + 0.8 * g.points[i];
      integral += g.weights[i] * 0.8 * 2 * pi * rho * std::abs(w.slope(rho));
    }
    CHECK(integral == Approx(w.slope_integral()).epsilon(1e-13));
  }
}

TEST_CASE("interaction integral: bad input", "[interaction_integral]") {
  using testing::message_of;
  const LinearElastic m{1.0, 0.3, PlaneModel::strain};
  const CrackTipFrame tip{Vec2(0.5, 0.5), Vec2(1, 0)};
  const DomainWeight w{0.1, 0.4};
  Samples s = williams_samples(tip, 1.0, 0.0, m, polar_rule(tip, Vec2::Zero(), {0.1, 0.4}, 3, 4, 8));
  CHECK_NOTHROW(integrate(tip, m, w, s));
  // Spans of different sizes.
  Samples short_weights = s;
  short_weights.weights.pop_back();
  CHECK_THAT(message_of<InputError>([&] { integrate(tip, m, w, short_weights); }),
             Catch::Contains("got 96 points, 95 weights, 96 gradients, 96 stresses"));
  // Radii.
  CHECK_THAT(message_of<InputError>([&] {
               integrate(tip, m, DomainWeight{0.0, 0.4}, s);
             }),
             Catch::Contains("0 < inner < outer") && Catch::Contains("inner = 0, outer = 0.4"));
  CHECK_THAT(message_of<InputError>([&] {
               integrate(tip, m, DomainWeight{0.5, 0.4}, s);
             }),
             Catch::Contains("inner = 0.5, outer = 0.4"));
  // A tip without a direction.
  CHECK_THAT(message_of<InputError>([&] {
               integrate(CrackTipFrame{tip.position, Vec2::Zero()}, m, w, s);
             }),
             Catch::Contains("crack tip at (0.5, 0.5)"));
  // Half the annulus (as when it leaves the body): coverage 1/2.
  Samples half;
  for (std::size_t k = 0; k < s.points.size(); ++k)
    if (s.points[k].y() > 0.5) {
      half.points.push_back(s.points[k]);
      half.weights.push_back(s.weights[k]);
      half.gradients.push_back(s.gradients[k]);
      half.stresses.push_back(s.stresses[k]);
    }
  CHECK_THAT(message_of<InputError>([&] { integrate(tip, m, w, half); }),
             Catch::Contains(
                 "the samples cover 0.5 of the domain 0.1 < |x - tip| < 0.4 about the tip at (0.5, 0.5)") &&
                 Catch::Contains("use a smaller outer radius"));
  // A non-finite stress inside the annulus names its sample.
  s.stresses[7][1] = std::nan("");
  CHECK_THAT(message_of<NumericalError>([&] { integrate(tip, m, w, s); }),
             Catch::Contains("sample 7 at (") && Catch::Contains("non-finite"));
}
