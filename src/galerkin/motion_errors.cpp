#include "mfree/galerkin/motion_errors.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

MotionErrorSampler::MotionErrorSampler(const RKShapeFunctions<2>& trial, const QuadratureRule<2>& rule,
                                       const MaterialAt& law_at)
    : at_(sample_shape_functions(trial, rule.points, true)) {
  at_.weights = rule.weights;
  for (const Vec2& x : rule.points) law_.push_back(law_at(x));
  for (double w : rule.weights) volume_ += w;
}

MotionErrors MotionErrorSampler::operator()(const Eigen::VectorXd& d, const Eigen::VectorXd& v, double time,
                                            const ExactMotion& exact) const {
  std::vector<Eigen::Vector3d> partial(thread_count(), Eigen::Vector3d::Zero());
  parallel_ranges(at_.size(), [&](int thread, Index begin, Index end) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Index k = begin; k < end; ++k) {
      Vec2 u = Vec2::Zero(), vel = Vec2::Zero();
      Mat2 f = Mat2::Identity();
      for (Index s = at_.row_begin(k); s < at_.row_end(k); ++s) {
        const Index i = at_.nodes[s];
        u += at_.phi[s] * d.segment<2>(2 * i);
        vel += at_.phi[s] * v.segment<2>(2 * i);
        f += d.segment<2>(2 * i) * at_.grad[s].transpose();
      }
      const Vec2& x = at_.points[k];
      const double w = at_.weights[k];
      sum[0] += w * (u - exact.displacement(x, time)).squaredNorm();
      sum[1] += w * (vel - exact.velocity(x, time)).squaredNorm();
      Mat2 sigma;
      try {
        sigma = cauchy_stress(law_[static_cast<std::size_t>(k)], f);
      } catch (const NumericalError& e) {  // u^h itself is inverted here: say where and when
        throw NumericalError(fmt::format("{} in the discrete motion at error point ({:.6g}, {:.6g}), t = {:.6g} s",
                                         e.what(), x.x(), x.y(), time));
      }
      sum[2] += w * (sigma - exact.cauchy_stress(x, time)).squaredNorm();
    }
    partial[thread] = sum;
  });
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (const auto& p : partial) total += p;
  return {time, std::sqrt(total[0] / volume_), std::sqrt(total[1] / volume_), std::sqrt(total[2] / volume_)};
}

}  // namespace mfree
