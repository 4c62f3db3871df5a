#include "mfree/galerkin/exact_elasticity.hpp"

#include <Eigen/LU>
#include <cmath>

#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"

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
  const Eigen::Vector3d strain(g(0, 0), g(1, 1), g(0, 1) + g(1, 0));
  const Eigen::Vector3d stress = material.voigt_tangent() * strain;
  ExactElasticity s;
  s.displacement = [=](const Vec2& x) { return Vec2(a + g * x); };
  s.stress = [=](const Vec2&) { return stress; };
  s.body_force = [](const Vec2&) { return Vec2::Zero(); };
  return s;
}

ElasticErrors elastic_errors(const RKShapeFunctions& trial, const Eigen::VectorXd& d,
                             const LinearElastic& material, const ExactElasticity& exact,
                             const QuadratureRule& rule) {
  const Eigen::Matrix3d dm = material.voigt_tangent();
  const Eigen::Matrix3d compliance = dm.inverse();
  const GalerkinQuadrature at = sample_shape_functions(trial, rule.points, true);
  double eu = 0, nu = 0, ee = 0, ne = 0, es = 0, ns = 0, energy = 0;
  for (Index k = 0; k < at.size(); ++k) {
    const double w = rule.weights[k];
    const Vec2 u = exact.displacement(rule.points[k]);
    const Eigen::Vector3d s = exact.stress(rule.points[k]);
    const Eigen::Vector3d eps = compliance * s;
    const Vec2 uh = displacement_at(at, k, d);
    const Eigen::Vector3d epsh = strain_at(at, k, d);
    const Eigen::Vector3d sh = dm * epsh;
    eu += w * (uh - u).squaredNorm();
    nu += w * u.squaredNorm();
    ee += w * (epsh - eps).dot(dm * (epsh - eps));
    ne += w * eps.dot(dm * eps);
    // Stress norm with the tensor inner product (the shear counts twice).
    const auto tensor_norm2 = [](const Eigen::Vector3d& v) { return v[0] * v[0] + v[1] * v[1] + 2.0 * v[2] * v[2]; };
    es += w * tensor_norm2(sh - s);
    ns += w * tensor_norm2(s);
    energy += 0.5 * w * epsh.dot(sh);
  }
  ElasticErrors r;
  r.l2_displacement = nu > 0 ? std::sqrt(eu / nu) : std::sqrt(eu);
  r.energy = ne > 0 ? std::sqrt(ee / ne) : std::sqrt(ee);
  r.l2_stress = ns > 0 ? std::sqrt(es / ns) : std::sqrt(es);
  r.strain_energy = energy;
  return r;
}

}  // namespace mfree
