#include "mfree/problems/timoshenko_beam.hpp"

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

}  // namespace mfree
