#include "mfree/problems/integration_functions.hpp"

#include <cmath>
#include <numbers>

namespace mfree {

namespace {

constexpr double pi = std::numbers::pi;

Integrand f1(const Box& r) {
  const double lx = r.size().x(), ly = r.size().y();
  const Vec2 lo = r.lo;
  return {[=](const Vec2& x) {
            return std::sin(pi * (x.x() - lo.x()) / lx) * std::sin(pi * (x.y() - lo.y()) / ly);
          },
          4.0 * lx * ly / (pi * pi)};
}

Integrand f2(const Box& r) {
  const double lx = r.size().x(), ly = r.size().y();
  const Vec2 centre = 0.5 * (r.lo + r.hi);
  return {[=](const Vec2& x) {
            const double u = 2.0 * (x.x() - centre.x()) / lx, v = 2.0 * (x.y() - centre.y()) / ly;
            return (1.0 - u * u) * (1.0 - v * v);
          },
          4.0 * lx * ly / 9.0};
}

}  // namespace

const NameTable<IntegrandOn>& integration_functions() {
  static const NameTable<IntegrandOn> table{{"f1", f1}, {"f2", f2}};
  return table;
}

}  // namespace mfree
