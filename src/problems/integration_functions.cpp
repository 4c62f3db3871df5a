#include "mfree/problems/integration_functions.hpp"

#include <cmath>
#include <numbers>

namespace mfree {

namespace {

constexpr double pi = std::numbers::pi;

// The integrals as 2^dim prod L_i / c^dim: in the plane 4 Lx Ly / c^2, to the bit.

template <int dim>
IntegrandOf<dim> f1(const Point<dim>& lo, const Point<dim>& hi) {
  const Point<dim> size = hi - lo;
  double integral = std::pow(2.0, dim);
  for (int i = 0; i < dim; ++i) integral *= size[i];
  integral /= std::pow(pi, dim);
  return {[=](const Point<dim>& x) {
            double f = 1.0;
            for (int i = 0; i < dim; ++i) f *= std::sin(pi * (x[i] - lo[i]) / size[i]);
            return f;
          },
          integral};
}

template <int dim>
IntegrandOf<dim> f2(const Point<dim>& lo, const Point<dim>& hi) {
  const Point<dim> size = hi - lo, centre = 0.5 * (lo + hi);
  double integral = std::pow(2.0, dim);
  for (int i = 0; i < dim; ++i) integral *= size[i];
  integral /= std::pow(3.0, dim);
  return {[=](const Point<dim>& x) {
            double f = 1.0;
            for (int i = 0; i < dim; ++i) {
              const double u = 2.0 * (x[i] - centre[i]) / size[i];
              f *= 1.0 - u * u;
            }
            return f;
          },
          integral};
}

}  // namespace

template <int dim>
const NameTable<IntegrandOn<dim>>& integration_functions() {
  static const NameTable<IntegrandOn<dim>> table{{"f1", f1<dim>}, {"f2", f2<dim>}};
  return table;
}

template const NameTable<IntegrandOn<2>>& integration_functions<2>();
template const NameTable<IntegrandOn<3>>& integration_functions<3>();

}  // namespace mfree
