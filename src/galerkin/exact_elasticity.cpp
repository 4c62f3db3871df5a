#include "mfree/galerkin/exact_elasticity.hpp"

#include <Eigen/LU>
#include <cmath>

#include "mfree/core/parallel.hpp"

namespace mfree {

ExactElasticity timoshenko_beam(double length, double depth, double load, const LinearElastic& material) {
  double e = material.youngs_modulus, nu = material.poisson_ratio;
  if (material.model == PlaneModel::strain) {
    e = e / (1.0 - nu * nu);
    nu = nu / (1.0 - nu);
  }
  const double l = length, dd = depth, p = load, inertia = dd * dd * dd / 12.0;
  ExactElasticity s;
  s.displacement = [=](const Vec2& x) {
    const double c = p / (6.0 * e * inertia);
    return Vec2(-c * x.y() * ((6.0 * l - 3.0 * x.x()) * x.x() + (2.0 + nu) * (x.y() * x.y() - dd * dd / 4.0)),
                c * (3.0 * nu * x.y() * x.y() * (l - x.x()) + (4.0 + 5.0 * nu) * dd * dd * x.x() / 4.0 +
                     (3.0 * l - x.x()) * x.x() * x.x()));
  };
  s.stress = [=](const Vec2& x) {
    return Eigen::Vector3d(-p * (l - x.x()) * x.y() / inertia, 0.0,
                           p / (2.0 * inertia) * (dd * dd / 4.0 - x.y() * x.y()));
  };
  s.body_force = [](const Vec2&) { return Vec2::Zero(); };
  return s;
}

ExactElasticity linear_field(const Vec2& a, const Mat2& g, const LinearElastic& material) {
  return quadratic_field(a, g, Mat2::Zero(), Mat2::Zero(), material);
}

ExactElasticity quadratic_field(const Vec2& a, const Mat2& g, const Mat2& h0, const Mat2& h1,
                                const LinearElastic& material) {
  const Eigen::Matrix3d d = material.voigt_tangent();
  // grad u = G + [H_0 x; H_1 x]^T row by row: d(du_c/dx_i)/dx_j = H_c(i, j).
  const auto gradient = [=](const Vec2& x) {
    Mat2 du;
    du.row(0) = (g.row(0).transpose() + h0 * x).transpose();
    du.row(1) = (g.row(1).transpose() + h1 * x).transpose();
    return du;
  };
  const auto voigt = [](const Mat2& du) { return Eigen::Vector3d(du(0, 0), du(1, 1), du(0, 1) + du(1, 0)); };
  // d sigma / dx_j = D d eps / dx_j, d eps / dx_j = (H_0(0, j), H_1(1, j), H_0(1, j) + H_1(0, j)).
  const Eigen::Vector3d ds_dx = d * Eigen::Vector3d(h0(0, 0), h1(1, 0), h0(1, 0) + h1(0, 0));
  const Eigen::Vector3d ds_dy = d * Eigen::Vector3d(h0(0, 1), h1(1, 1), h0(1, 1) + h1(0, 1));
  const Vec2 body(-(ds_dx[0] + ds_dy[2]), -(ds_dx[2] + ds_dy[1]));
  ExactElasticity s;
  s.displacement = [=](const Vec2& x) -> Vec2 {
    return a + g * x + 0.5 * Vec2(x.dot(h0 * x), x.dot(h1 * x));
  };
  s.stress = [=](const Vec2& x) -> Eigen::Vector3d { return d * voigt(gradient(x)); };
  s.body_force = [=](const Vec2&) { return body; };
  return s;
}

ElasticErrors elastic_errors(const RKShapeFunctions& trial, const Eigen::VectorXd& d,
                             const LinearElastic& material, const ExactElasticity& exact,
                             const QuadratureRule& rule) {
  const Eigen::Matrix3d dm = material.voigt_tangent();
  const Eigen::Matrix3d compliance = dm.inverse();
  // Streamed over the points (fine rules have ~150 points per node): per-thread sums of
  // |u^h - u|^2, |u|^2, energy and stress norms, added in thread order.
  using Sums = Eigen::Matrix<double, 7, 1>;
  std::vector<Sums> partial(thread_count(), Sums::Zero());
  const auto tensor_norm2 = [](const Eigen::Vector3d& v) { return v[0] * v[0] + v[1] * v[1] + 2.0 * v[2] * v[2]; };
  parallel_ranges(static_cast<Index>(rule.size()), [&](int t, Index begin, Index end) {
    ShapeValues v;
    Sums sum = Sums::Zero();
    for (Index k = begin; k < end; ++k) {
      const Vec2& x = rule.points[k];
      trial.evaluate(x, v, true);
      Vec2 uh = Vec2::Zero();
      Eigen::Vector3d epsh = Eigen::Vector3d::Zero();
      for (std::size_t a = 0; a < v.size(); ++a) {
        const Vec2 di = d.segment<2>(2 * v.nodes[a]);
        const Vec2& g = v.grad[a];
        uh += v.phi[a] * di;
        epsh += Eigen::Vector3d(g.x() * di.x(), g.y() * di.y(), g.y() * di.x() + g.x() * di.y());
      }
      const double w = rule.weights[k];
      const Vec2 u = exact.displacement(x);
      const Eigen::Vector3d s = exact.stress(x), eps = compliance * s, sh = dm * epsh;
      sum += w * (Sums() << (uh - u).squaredNorm(), u.squaredNorm(), (epsh - eps).dot(dm * (epsh - eps)),
                  eps.dot(dm * eps), tensor_norm2(sh - s), tensor_norm2(s), 0.5 * epsh.dot(sh))
                     .finished();
    }
    partial[t] = sum;
  });
  Sums total = Sums::Zero();
  for (const Sums& p : partial) total += p;
  const auto relative = [](double e, double n) { return n > 0 ? std::sqrt(e / n) : std::sqrt(e); };
  ElasticErrors r;
  r.l2_displacement = relative(total[0], total[1]);
  r.energy = relative(total[2], total[3]);
  r.l2_stress = relative(total[4], total[5]);
  r.strain_energy = total[6];
  return r;
}

}  // namespace mfree
