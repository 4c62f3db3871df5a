#include "mfree/galerkin/motion_errors.hpp"

#include <fmt/format.h>

#include <cmath>

#include "mfree/core/error.hpp"
#include "mfree/core/parallel.hpp"

namespace mfree {

template <int dim>
MotionErrorSampler<dim>::MotionErrorSampler(const RKShapeFunctions<dim>& trial,
                                            const QuadratureRule<dim>& rule, const MaterialAt<dim>& law_at)
    : at_(sample_shape_functions(trial, rule.points, true)) {
  at_.weights = rule.weights;
  for (const Point<dim>& x : rule.points) law_.push_back(law_at(x));
  for (double w : rule.weights) volume_ += w;
}

template <int dim>
MotionErrors MotionErrorSampler<dim>::operator()(const Eigen::VectorXd& d, const Eigen::VectorXd& v,
                                                 double time, const ExactMotion<dim>& exact) const {
  std::vector<Eigen::Vector3d> partial(thread_count(), Eigen::Vector3d::Zero());
  parallel_ranges(at_.size(), [&](int thread, Index begin, Index end) {
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (Index k = begin; k < end; ++k) {
      Point<dim> u = Point<dim>::Zero(), vel = Point<dim>::Zero();
      Tensor2<dim> f = Tensor2<dim>::Identity();
      for (Index s = at_.row_begin(k); s < at_.row_end(k); ++s) {
        const Index i = at_.nodes[s];
        u += at_.phi[s] * d.segment<dim>(dim * i);
        vel += at_.phi[s] * v.segment<dim>(dim * i);
        f += d.segment<dim>(dim * i) * at_.grad[s].transpose();
      }
      const Point<dim>& x = at_.points[k];
      const double w = at_.weights[k];
      sum[0] += w * (u - exact.displacement(x, time)).squaredNorm();
      sum[1] += w * (vel - exact.velocity(x, time)).squaredNorm();
      Tensor2<dim> sigma;
      try {
        sigma = cauchy_stress(law_[static_cast<std::size_t>(k)], f);
      } catch (const NumericalError& e) {  // u^h itself is inverted here: say where and when
        std::string where = fmt::format("{:.6g}", x[0]);
        for (int i = 1; i < dim; ++i) where += fmt::format(", {:.6g}", x[i]);
        throw NumericalError(fmt::format("{} in the discrete motion at error point ({}), t = {:.6g} s",
                                         e.what(), where, time));
      }
      sum[2] += w * (sigma - exact.cauchy_stress(x, time)).squaredNorm();
    }
    partial[thread] = sum;
  });
  Eigen::Vector3d total = Eigen::Vector3d::Zero();
  for (const auto& p : partial) total += p;
  return {time, std::sqrt(total[0] / volume_), std::sqrt(total[1] / volume_), std::sqrt(total[2] / volume_)};
}

template class MotionErrorSampler<2>;
template class MotionErrorSampler<3>;

}  // namespace mfree
