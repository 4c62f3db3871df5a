#include "mfree/galerkin/exact_elasticity.hpp"

#include <Eigen/LU>
#include <cmath>

#include "mfree/core/parallel.hpp"

namespace mfree {

ElasticErrors elastic_errors(const RKShapeFunctions<2>& trial, const Eigen::VectorXd& d, const LawAt& law_at,
                             const ExactElasticity& exact, const QuadratureRule<2>& rule) {
  // Streamed over the points (fine rules have ~150 points per node): per-thread sums of
  // |u^h - u|^2, |u|^2, energy and stress norms, added in thread order.
  using Sums = Eigen::Matrix<double, 7, 1>;
  std::vector<Sums> partial(thread_count(), Sums::Zero());
  const auto tensor_norm2 = [](const Eigen::Vector3d& v) { return v[0] * v[0] + v[1] * v[1] + 2.0 * v[2] * v[2]; };
  parallel_ranges(static_cast<Index>(rule.size()), [&](int t, Index begin, Index end) {
    ShapeValues<2> v;
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
      const Eigen::Matrix3d dm = law_at(x).voigt_tangent();
      const Eigen::Matrix3d compliance = dm.inverse();
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
