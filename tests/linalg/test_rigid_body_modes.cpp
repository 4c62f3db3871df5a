// The rigid-body modes of a cloud in 2D and 3D: every rigid motion a + omega x (x - o) of the
// nodes lies in their span (to round-off), they are independent (3 and 6), the scalar modes
// are the linear functions; and the well-posedness check of galerkin/rigid_body_modes.hpp
// names the one motion a 3D stiffness leaves free.
#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/rigid_body_modes.hpp"
#include "mfree/linalg/rigid_body_modes.hpp"

using namespace mfree;

namespace {

template <int dim>
std::vector<Point<dim>> random_cloud(int n) {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 2.0);
  std::vector<Point<dim>> x(n);
  for (auto& p : x)
    for (int c = 0; c < dim; ++c) p[c] = u(rng);
  return x;
}

/// |u - R (R^+ u)| / |u| of the least-squares fit of u by the columns of R.
double outside_span(const Eigen::MatrixXd& r, const Eigen::VectorXd& u) {
  const Eigen::VectorXd fit = r * r.colPivHouseholderQr().solve(u);
  return (u - fit).norm() / u.norm();
}

}  // namespace

TEST_CASE("rigid-body modes span the rigid motions of a 3D cloud (6) and of a plane one (3)",
          "[linalg][3d]") {
  const auto x3 = random_cloud<3>(40);
  const Point<3> o(0.3, -0.2, 0.5);
  const Eigen::MatrixXd r3 = rigid_body_modes<3>(x3, 3, o);
  REQUIRE(r3.cols() == 6);
  CHECK(r3.colPivHouseholderQr().rank() == 6);
  // u_I = a + omega x (x_I - p) about any point p.
  const Eigen::Vector3d a(0.4, -1.1, 0.7), omega(-0.3, 0.8, 0.25), p(1.0, 2.0, -3.0);
  Eigen::VectorXd u(3 * x3.size());
  for (std::size_t i = 0; i < x3.size(); ++i) u.segment<3>(3 * i) = a + omega.cross(x3[i] - p);
  CHECK(outside_span(r3, u) < 1e-13);
  // A stretch is no rigid motion.
  Eigen::VectorXd stretch = Eigen::VectorXd::Zero(3 * x3.size());
  for (std::size_t i = 0; i < x3.size(); ++i) stretch[3 * i] = x3[i].x();
  CHECK(outside_span(r3, stretch) > 0.1);
  // Column 5 is the rotation about z through o.
  CHECK(r3(3 * 7, 5) == -(x3[7].y() - o.y()));
  CHECK(r3(3 * 7 + 1, 5) == x3[7].x() - o.x());
  CHECK(rigid_body_mode_name<3>(5) == "rotation about z");

  const auto x2 = random_cloud<2>(30);
  const Eigen::MatrixXd r2 = rigid_body_modes<2>(x2, 2, Vec2::Zero());
  REQUIRE(r2.cols() == 3);
  Eigen::VectorXd u2(2 * x2.size());
  for (std::size_t i = 0; i < x2.size(); ++i)
    u2.segment<2>(2 * i) = Vec2(0.5 - 0.2 * x2[i].y(), -0.3 + 0.2 * x2[i].x());
  CHECK(outside_span(r2, u2) < 1e-13);
  // Scalar fields: 1, x, y, z.
  const Eigen::MatrixXd s3 = rigid_body_modes<3>(x3, 1, o);
  REQUIRE(s3.cols() == 4);
  CHECK(s3(7, 3) == x3[7].z() - o.z());
}

TEST_CASE("the well-posedness check of a 3D stiffness names the rigid motion it leaves free",
          "[galerkin][3d]") {
  const auto x = random_cloud<3>(25);
  const Eigen::Index n = 3 * static_cast<Eigen::Index>(x.size());
  SparseMatrix identity(n, n);
  identity.setIdentity();
  CHECK_NOTHROW(check_rigid_body_modes(identity, x));
  // K = I - q q^T, q the rotation about z through the centroid: that motion alone is free.
  Point<3> c = Point<3>::Zero();
  for (const auto& p : x) c += p;
  c /= static_cast<double>(x.size());
  const Eigen::VectorXd q = rigid_body_modes<3>(x, 3, c).col(5).normalized();
  const Eigen::MatrixXd dense = Eigen::MatrixXd::Identity(n, n) - q * q.transpose();
  const SparseMatrix k = dense.sparseView();
  const RigidBodyEnergy<3> e = rigid_body_energy(k, x);
  CHECK(std::abs(e.eigenvalues[0]) < 1e-12);
  CHECK(e.eigenvalues[1] > 0.1);
  CHECK_THROWS_WITH(check_rigid_body_modes(k, x),
                    Catch::Contains("1.00 rotation about z") || Catch::Contains("-1.00 rotation about z"));
}
