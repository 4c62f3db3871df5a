#include "mfree/problems/polynomial_fields.hpp"

namespace mfree {

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

}  // namespace mfree
