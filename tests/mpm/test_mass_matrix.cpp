// The two particle-to-grid mappings of seed 004 (mpm/mass_matrix.hpp), on a strip one cell
// tall with fields of x alone and CPDI weights (the seed's figures): option 1 (lumped) and
// option 2 (the pseudo-inverse of the particle-by-node matrix) for constant and linear fields
// at 1, 2 and 4 particles per cell along x, and the sign and support of their particle basis
// functions. The library's mass-matrix solve is checked against the Moore-Penrose
// pseudo-inverse formed densely here, and its partial lumping at a body's edge for symmetry
// and momentum, with and without the short-wave filter, whose effect on the modes of the
// grid is measured last.

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <cmath>
#include <random>

#include "mfree/mpm/mass_matrix.hpp"
#include "mfree/mpm/particle_basis.hpp"
#include "mfree/mpm/particles.hpp"

using namespace mfree;

namespace {

/// 8 cells of h = 1/8 along x, one cell tall; per_cell particles per cell along x, 2 along y
/// (so that y is determined and the fields depend on x alone), equal masses.
struct Strip {
  explicit Strip(int per_cell)
      : grid(Box{Vec2(0.0, 0.0), Vec2(1.0, 0.125)}, 8, 1, grid_padding(MPMMethod::cpdi)),
        basis(MPMMethod::cpdi, grid),
        mass_matrix(grid, 3) {
    const double h = 0.125;
    for (int c = 0; c < 8; ++c)
      for (int a = 0; a < per_cell; ++a)
        for (int b = 0; b < 2; ++b) {
          P.position.emplace_back(h * (c + (a + 0.5) / per_cell), h * (b + 0.5) / 2);
          P.deformation.push_back(Mat2::Identity());
          P.half_size.emplace_back(h / (2 * per_cell), h / 4);
          P.mass.push_back(1.0);
          P.volume.push_back(h * h / (2 * per_cell));
        }
    basis.resize(weights, P.size());
    for (Index p = 0; p < P.size(); ++p) basis.evaluate(P, p, weights, p);
    S = Eigen::MatrixXd::Zero(P.size(), grid.size());
    for (Index p = 0; p < P.size(); ++p) weights.for_each(p, [&](Index i, double s, const Vec2&) { S(p, i) += s; });
    const Eigen::VectorXd column_sums = S.colwise().sum().transpose();  // the lumped masses (m_p = 1)
    lumped.assign(column_sums.data(), column_sums.data() + column_sums.size());
    mass_matrix.assemble(weights, P.mass, P.volume);
  }

  /// Option 1: u_i = sum_p S_ip u_p / sum_p S_ip (zero on nodes no particle reaches).
  [[nodiscard]] Eigen::VectorXd option1(const Eigen::VectorXd& u) const {
    Eigen::VectorXd out = S.transpose() * u;
    for (Index i = 0; i < out.size(); ++i) out[i] = lumped[i] > 0.0 ? out[i] / lumped[i] : 0.0;
    return out;
  }
  /// Option 2 by definition: the Moore-Penrose pseudo-inverse of S applied to u.
  [[nodiscard]] Eigen::VectorXd option2(const Eigen::VectorXd& u) const {
    return S.completeOrthogonalDecomposition().pseudoInverse() * u;
  }
  /// Option 2 as the solver maps: M u = S^T u by the library's solve.
  [[nodiscard]] Eigen::VectorXd option2_solved(const Eigen::VectorXd& u) const {
    const Eigen::VectorXd q = S.transpose() * u;
    std::vector<Vec2> qv(static_cast<std::size_t>(grid.size()));
    for (Index i = 0; i < grid.size(); ++i) qv[i] = Vec2(q[i], 0.0);
    const std::vector<Vec2> v = mass_matrix.solve(qv, lumped, std::vector<unsigned char>(qv.size(), 0), 1e-12);
    Eigen::VectorXd out(grid.size());
    for (Index i = 0; i < grid.size(); ++i) out[i] = v[i].x();
    return out;
  }
  /// f at the particles.
  template <class F>
  [[nodiscard]] Eigen::VectorXd at_particles(F&& f) const {
    Eigen::VectorXd u(P.size());
    for (Index p = 0; p < P.size(); ++p) u[p] = f(P.position[p].x());
    return u;
  }
  /// Largest |u_i - f(x_i)| over the nodes the particles reach (interior: only those with
  /// 0 < x_i < 1).
  template <class F>
  [[nodiscard]] double nodal_error(const Eigen::VectorXd& u, F&& f, bool interior) const {
    double worst = 0.0;
    for (Index i = 0; i < grid.size(); ++i) {
      const double x = grid.node(i).x();
      if (lumped[i] <= 0.0 || (interior && (x < 1e-9 || x > 1.0 - 1e-9))) continue;
      worst = std::max(worst, std::abs(u[i] - f(x)));
    }
    return worst;
  }

  Grid grid;
  ParticleBasis basis;
  Particles P;
  WeightTable weights;
  Eigen::MatrixXd S;  ///< particles x nodes
  std::vector<double> lumped;
  GridMassMatrix mass_matrix;
};

const auto one = [](double) { return 1.0; };
const auto line = [](double x) { return x; };

}  // namespace

TEST_CASE("the stencil mass matrix is S^T S of the particle weights, its rows summing to the lumped masses",
          "[mpm][mapping]") {
  for (int per_cell : {1, 2, 4}) {
    const Strip s(per_cell);
    const Eigen::MatrixXd dense = s.S.transpose() * s.S;  // m_p = 1
    double entries = 0.0, rows = 0.0;
    for (Index i = 0; i < s.grid.size(); ++i) {
      rows = std::max(rows, std::abs(s.mass_matrix.row_sum(i) - s.lumped[i]));
      for (Index j = 0; j < s.grid.size(); ++j) entries = std::max(entries, std::abs(s.mass_matrix.entry(i, j) - dense(i, j)));
    }
    INFO(per_cell << " particles per cell along x");
    CHECK(dense.maxCoeff() > 0.1);
    CHECK(entries <= 1e-14);
    CHECK(rows <= 1e-13);
  }
}

TEST_CASE("seed 004's mappings: constant and linear fields at 1, 2 and 4 particles per cell", "[mpm][mapping]") {
  for (int per_cell : {1, 2, 4}) {
    const Strip s(per_cell);
    INFO(per_cell << " particles per cell along x");
    // Option 1 carries a constant exactly at any density, and a linear field at every node
    // the particles surround symmetrically, but not at the ends (the nodal value there is the
    // mean over the particles on one side).
    CHECK(s.nodal_error(s.option1(s.at_particles(one)), one, false) <= 1e-14);
    CHECK(s.nodal_error(s.option1(s.at_particles(line)), line, true) <= 1e-14);
    CHECK(s.nodal_error(s.option1(s.at_particles(line)), line, false) >= 0.01);
    const Eigen::VectorXd constant = s.option2(s.at_particles(one)), linear = s.option2(s.at_particles(line));
    if (per_cell == 1) {
      // One particle per cell: fewer particles than nodes, the fit interpolates the particle
      // values but the nodes wiggle about both fields (the null space of S).
      CHECK((s.S * linear - s.at_particles(line)).cwiseAbs().maxCoeff() <= 1e-12);
      CHECK(s.nodal_error(constant, one, false) >= 0.01);
      CHECK(s.nodal_error(linear, line, false) >= 0.01);
    } else {
      // Two or more: both fields exactly, the ends included.
      CHECK(s.nodal_error(constant, one, false) <= 1e-12);
      CHECK(s.nodal_error(linear, line, false) <= 1e-12);
      // The solver's mass-matrix solve is that pseudo-inverse.
      CHECK((s.option2_solved(s.at_particles(line)) - linear).cwiseAbs().maxCoeff() <= 1e-11);
      const Eigen::VectorXd wave = s.at_particles([](double x) { return std::sin(5.0 * x) + x * x; });
      CHECK((s.option2_solved(wave) - s.option2(wave)).cwiseAbs().maxCoeff() <= 1e-11);
    }
  }
}

TEST_CASE("seed 004's particle basis: option 1 non-negative and compact, option 2 neither", "[mpm][mapping]") {
  // The particle basis function of particle p: the nodal values of the field that is 1 at p
  // and 0 at every other particle. Particle p sits in the middle cell.
  for (int per_cell : {2, 4}) {
    const Strip s(per_cell);
    const Index p = 2 * per_cell * 4;  // the first particle of cell 4
    Eigen::VectorXd u = Eigen::VectorXd::Zero(s.P.size());
    u[p] = 1.0;
    const Eigen::VectorXd psi1 = s.option1(u), psi2 = s.option2(u);
    double far1 = 0.0, far2 = 0.0;  // largest |psi| at nodes two cells or more from p's domain
    for (Index i = 0; i < s.grid.size(); ++i) {
      if (std::abs(s.grid.node(i).x() - s.P.position[p].x()) < 2.0 * 0.125) continue;
      far1 = std::max(far1, std::abs(psi1[i]));
      far2 = std::max(far2, std::abs(psi2[i]));
    }
    INFO(per_cell << " particles per cell along x: option 2's largest far value " << far2 << ", smallest "
                  << psi2.minCoeff());
    CHECK(psi1.minCoeff() >= 0.0);
    CHECK(far1 == 0.0);
    CHECK(psi2.minCoeff() < -0.01 * psi2.maxCoeff());
    CHECK(far2 > 1e-4 * psi2.maxCoeff());
  }
}

TEST_CASE("the partially lumped pseudo-inverse is symmetric and conserves momentum at a body's edge",
          "[mpm][mapping]") {
  const double filter = GENERATE(0.0, 0.3);
  INFO("short-wave filter beta = " << filter);
  // A disk of 3 x 3 particles per cell on quadratic B-splines: its edge covers some nodes by
  // less than a fifth (lumped) next to others solved for. u = A^-1 q with A symmetric and its
  // rows summing to the lumped masses: q1 . u2 = q2 . u1 and sum_i m_i u_i = sum_i q_i.
  const double h = 1.0 / 16;
  const Grid grid(Box{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}, 16, 2, 0);
  const ParticleBasis basis(MPMMethod::bspline, grid);
  const Particles box = fill_box(Box{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}, h, 3, 1000.0, false);
  Particles P;
  for (Index p = 0; p < box.size(); ++p)
    if ((box.position[p] - Vec2(0.47, 0.52)).norm() < 0.3) {
      P.position.push_back(box.position[p]);
      P.deformation.push_back(Mat2::Identity());
      P.mass.push_back(box.mass[p]);
      P.volume.push_back(box.volume[p]);
    }
  WeightTable weights;
  basis.resize(weights, P.size());
  for (Index p = 0; p < P.size(); ++p) basis.evaluate(P, p, weights, p);
  GridMassMatrix M(grid, 2, filter);
  M.assemble(weights, P.mass, P.volume);
  std::vector<double> lumped(static_cast<std::size_t>(grid.size()), 0.0);
  for (Index p = 0; p < P.size(); ++p)
    weights.for_each(p, [&](Index i, double S, const Vec2&) { lumped[i] += P.mass[p] * S; });
  int edge = 0, solved = 0;
  for (Index i = 0; i < grid.size(); ++i) {
    if (lumped[i] <= 0.0) continue;
    (M.cover(i) < 0.2 ? edge : solved) += 1;
  }
  REQUIRE(edge >= 8);
  REQUIRE(solved >= 60);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  const auto random_q = [&] {
    std::vector<Vec2> q(lumped.size(), Vec2::Zero());
    for (std::size_t i = 0; i < q.size(); ++i)
      if (lumped[i] > 0.0) q[i] = lumped[i] * Vec2(value(rng), value(rng));
    return q;
  };
  const std::vector<unsigned char> none(lumped.size(), 0);
  const std::vector<Vec2> q1 = random_q(), q2 = random_q();
  const std::vector<Vec2> u1 = M.solve(q1, lumped, none, 1e-12), u2 = M.solve(q2, lumped, none, 1e-12);
  double q1u2 = 0.0, q2u1 = 0.0, scale = 0.0;
  Vec2 momentum = Vec2::Zero(), data = Vec2::Zero();
  for (std::size_t i = 0; i < lumped.size(); ++i) {
    q1u2 += q1[i].dot(u2[i]);
    q2u1 += q2[i].dot(u1[i]);
    scale += q1[i].norm() * u2[i].norm();
    momentum += lumped[i] * u1[i];
    data += q1[i];
  }
  CHECK(std::abs(q1u2 - q2u1) <= 1e-10 * scale);
  double total = 0.0;
  for (std::size_t i = 0; i < lumped.size(); ++i) total += q1[i].norm();
  CHECK((momentum - data).norm() <= 1e-10 * total);
}

namespace {

/// The unit box filled with 3 x 3 particles per cell of quadratic B-splines on n cells.
struct FilledBox {
  explicit FilledBox(int n)
      : grid(Box{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}, n, 2, 0),
        P(fill_box(Box{Vec2(0.0, 0.0), Vec2(1.0, 1.0)}, 1.0 / n, 3, 1000.0, false)) {
    const ParticleBasis basis(MPMMethod::bspline, grid);
    basis.resize(weights, P.size());
    for (Index p = 0; p < P.size(); ++p) basis.evaluate(P, p, weights, p);
  }
  /// u^T A u / u^T M u for the x components u_i = f(i), A = M~ (beta) and M = M~ (0).
  template <class F>
  [[nodiscard]] double mass_ratio(double beta, F&& f) const {
    GridMassMatrix plain(grid, 2), filtered(grid, 2, beta);
    plain.assemble(weights, P.mass, P.volume);
    filtered.assemble(weights, P.mass, P.volume);
    std::vector<Vec2> u(static_cast<std::size_t>(grid.size()));
    for (Index i = 0; i < grid.size(); ++i) u[i] = Vec2(f(i), 0.0);
    const std::vector<Vec2> a = filtered.filtered_product(u), m = plain.filtered_product(u);
    double ua = 0.0, um = 0.0;
    for (std::size_t i = 0; i < u.size(); ++i) {
      ua += u[i].dot(a[i]);
      um += u[i].dot(m[i]);
    }
    return ua / um;
  }
  Grid grid;
  Particles P;
  WeightTable weights;
};

}  // namespace

TEST_CASE("the short-wave filter adds mass to the grid's shortest modes, not to smooth ones",
          "[mpm][mapping]") {
  // The checkerboard (-1)^(i + j), the grid's shortest mode, is 18 times heavier with
  // beta = 0.3; sin(pi x) sin(pi y) + 1/2 by 1.2e-4 on 16 cells and 1.4e-5 on 32 (rate 3.1:
  // h^4 where the particles surround a node symmetrically, h^2 at the walls).
  const double beta = 0.3;
  std::vector<double> smooth_change;
  for (int n : {16, 32}) {
    const FilledBox box(n);
    const Index nx = box.grid.nx();
    const auto checkerboard = [nx](Index i) { return (i % nx + i / nx) % 2 == 0 ? 1.0 : -1.0; };
    const auto smooth = [&box](Index i) {
      const Vec2 x = box.grid.node(i);
      return std::sin(3.14159265358979 * x.x()) * std::sin(3.14159265358979 * x.y()) + 0.5;
    };
    const double shortest = box.mass_ratio(beta, checkerboard), change = box.mass_ratio(beta, smooth) - 1.0;
    INFO(n << " cells: the checkerboard's mass grows by " << shortest << ", a smooth mode's by " << change);
    CHECK(shortest >= 10.0);
    CHECK(change >= 0.0);
    CHECK(change <= 3e-4);
    smooth_change.push_back(change);
  }
  const double rate = std::log2(smooth_change[0] / smooth_change[1]);
  INFO("rate " << rate);
  CHECK(rate >= 2.5);
}

TEST_CASE("the solve inverts the filtered matrix", "[mpm][mapping]") {
  const FilledBox box(8);
  GridMassMatrix M(box.grid, 2, 0.3);
  M.assemble(box.weights, box.P.mass, box.P.volume);
  std::vector<double> lumped(static_cast<std::size_t>(box.grid.size()));
  for (Index i = 0; i < box.grid.size(); ++i) lumped[i] = M.row_sum(i);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Vec2> u(lumped.size());
  for (Vec2& v : u) v = Vec2(value(rng), value(rng));
  const std::vector<Vec2> back =
      M.solve(M.filtered_product(u), lumped, std::vector<unsigned char>(u.size(), 0), 1e-12);
  double worst = 0.0;
  for (std::size_t i = 0; i < u.size(); ++i) worst = std::max(worst, (back[i] - u[i]).cwiseAbs().maxCoeff());
  CHECK(worst <= 1e-10);
}
