#pragma once
// Matrices the linear-solver tests share.

#include <Eigen/SparseCore>
#include <vector>

#include "mfree/core/types.hpp"

namespace mfree::testing {

/// The five-point Laplacian of an n x n grid plus `shift` on the diagonal, and a
/// non-symmetric convection term of strength `convection` along x (0: symmetric).
inline Eigen::SparseMatrix<double> laplacian(int n, double shift, double convection) {
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [n](int i, int j) { return j * n + i; };
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      t.emplace_back(id(i, j), id(i, j), 4.0 + shift);
      if (i > 0) t.emplace_back(id(i, j), id(i - 1, j), -1.0 - convection);
      if (i + 1 < n) t.emplace_back(id(i, j), id(i + 1, j), -1.0 + convection);
      if (j > 0) t.emplace_back(id(i, j), id(i, j - 1), -1.0);
      if (j + 1 < n) t.emplace_back(id(i, j), id(i, j + 1), -1.0);
    }
  Eigen::SparseMatrix<double> a(n * n, n * n);
  a.setFromTriplets(t.begin(), t.end());
  return a;
}

/// Plane-strain bilinear finite elements (E = 1, nu = 0.3) on the unit square with n x n
/// cells, clamped on x = 0 by a large diagonal: a stiffness whose near-null space is the
/// rigid-body modes, 2 unknowns per node (2 I + c), and the node coordinates.
inline Eigen::SparseMatrix<double> elasticity(int n, std::vector<Vec2>& nodes) {
  const double h = 1.0 / n, lambda = 0.3 / (1.3 * 0.4), mu = 1.0 / 2.6;
  nodes.clear();
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) nodes.emplace_back(i * h, j * h);
  // Element stiffness by 2 x 2 Gauss points.
  Eigen::Matrix<double, 8, 8> ke = Eigen::Matrix<double, 8, 8>::Zero();
  const double g = 0.5 / std::sqrt(3.0);
  const double corner[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  for (double gx : {0.5 - g, 0.5 + g})
    for (double gy : {0.5 - g, 0.5 + g}) {
      Eigen::Matrix<double, 3, 8> b = Eigen::Matrix<double, 3, 8>::Zero();
      for (int a = 0; a < 4; ++a) {
        const double sx = corner[a][0], sy = corner[a][1];
        const double fx = sx > 0 ? gx : 1 - gx, fy = sy > 0 ? gy : 1 - gy;
        const double dx = sx * fy / h, dy = sy * fx / h;
        b(0, 2 * a) = dx, b(1, 2 * a + 1) = dy, b(2, 2 * a) = dy, b(2, 2 * a + 1) = dx;
      }
      Eigen::Matrix3d d;
      d << lambda + 2 * mu, lambda, 0, lambda, lambda + 2 * mu, 0, 0, 0, mu;
      ke += 0.25 * h * h * b.transpose() * d * b;
    }
  std::vector<Eigen::Triplet<double>> t;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int v[4] = {j * (n + 1) + i, j * (n + 1) + i + 1, (j + 1) * (n + 1) + i + 1, (j + 1) * (n + 1) + i};
      for (int a = 0; a < 4; ++a)
        for (int b = 0; b < 4; ++b)
          for (int r = 0; r < 2; ++r)
            for (int c = 0; c < 2; ++c) t.emplace_back(2 * v[a] + r, 2 * v[b] + c, ke(2 * a + r, 2 * b + c));
    }
  for (int j = 0; j <= n; ++j)
    for (int c = 0; c < 2; ++c) t.emplace_back(2 * j * (n + 1) + c, 2 * j * (n + 1) + c, 1e3);
  const auto size = static_cast<Eigen::Index>(2 * nodes.size());
  Eigen::SparseMatrix<double> k(size, size);
  k.setFromTriplets(t.begin(), t.end());
  k.makeCompressed();
  return k;
}

}  // namespace mfree::testing
