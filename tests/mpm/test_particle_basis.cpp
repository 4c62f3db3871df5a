// Partition of unity and linear completeness of every MPM basis, and gradients against
// finite differences, at random particle positions and deformed domains including next to
// the walls; the GIMPs and qCPDI against exact averages of the hats over their domains.

#include <catch2/catch.hpp>
#include <Eigen/LU>
#include <map>
#include <random>

#include "mfree/core/error.hpp"
#include "mfree/mpm/grid_transfer.hpp"
#include "mfree/mpm/particle_basis.hpp"
#include "random_domains.hpp"

using namespace mfree;

namespace {

struct Case {
  MPMMethod method;
  int degree;
};
const Case cases[] = {{MPMMethod::classic, 1},       {MPMMethod::ugimp, 1},   {MPMMethod::cpgimp, 1},
                      {MPMMethod::cpdi, 1},          {MPMMethod::qcpdi, 1},   {MPMMethod::cpdi2, 1},
                      {MPMMethod::bspline, 2},       {MPMMethod::bspline, 3}, {MPMMethod::bspline_cpgimp, 2},
                      {MPMMethod::bspline_cpgimp, 3}};

/// B-spline cpGIMP's domain, the rectangle x +- half F_ii, clipped to the grid's box b.
Box clipped_rectangle(const Vec2& x, const Mat2& F, const Vec2& half, const Box& b) {
  const Vec2 l = half.cwiseProduct(F.diagonal());
  return {(x - l).cwiseMax(b.lo), (x + l).cwiseMin(b.hi)};
}
bool is_clipped(const Vec2& x, const Mat2& F, const Vec2& half, const Box& b) {
  const Vec2 l = half.cwiseProduct(F.diagonal());
  return (x - l).x() < b.lo.x() || (x - l).y() < b.lo.y() || (x + l).x() > b.hi.x() || (x + l).y() > b.hi.y();
}

const Box domain{Vec2(0.0, 0.0), Vec2(1.0, 0.75)};

struct Weights {
  std::vector<Index> node;
  std::vector<double> S;
  std::vector<Vec2> G;
};
/// A particle: position, F and reference half sizes; CPDI2 reads its corners instead.
struct Sample {
  Vec2 x;
  Mat2 F = Mat2::Identity();
  Vec2 half = Vec2::Zero();
  DomainCorners corners{};
};
/// The sample's corners for CPDI2: the parallelogram of F.
Sample sample(const Vec2& x, const Mat2& F, const Vec2& half) { return {x, F, half, parallelogram_corners(x, F, half)}; }

void evaluate(const ParticleBasis& b, const Sample& s, WeightTable& table, Index q) {
  if (b.method() == MPMMethod::cpdi2) b.evaluate_quadrilateral(s.corners, s.x, table, q);
  else b.evaluate(s.x, s.F, s.half, table, q);
}

Weights weights_at(const ParticleBasis& b, const Sample& s) {
  WeightTable table;
  b.resize(table, 1);
  evaluate(b, s, table, 0);
  Weights w;
  table.for_each(0, [&](Index node, double S, const Vec2& G) {
    w.node.push_back(node);
    w.S.push_back(S);
    w.G.push_back(G);
  });
  REQUIRE(static_cast<int>(w.node.size()) == b.stride());
  return w;
}

}  // namespace

TEST_CASE("B-spline axis: Greville nodes reproduce x, the end functions interpolate", "[mpm]") {
  for (int p = 1; p <= 3; ++p) {
    const BSplineAxis a(0.5, 0.25, 6, p);
    CHECK(a.size() == 6 + p);
    CHECK(a.node(0) == 0.5);
    CHECK(a.node(a.size() - 1) == Approx(2.0).epsilon(1e-15));
    for (double x : {0.5, 0.51, 0.75, 1.3, 1.999, 2.0}) {
      const auto v = a.evaluate(x);
      double one = 0.0, lin = 0.0, d_one = 0.0, d_lin = 0.0;
      for (int k = 0; k <= p; ++k) {
        one += v.value[k];
        lin += a.node(v.first + k) * v.value[k];
        d_one += v.derivative[k];
        d_lin += a.node(v.first + k) * v.derivative[k];
        CHECK(v.value[k] >= 0.0);
      }
      CHECK(std::abs(one - 1.0) <= 1e-14);
      CHECK(std::abs(lin - x) <= 1e-14);
      CHECK(std::abs(d_one) <= 1e-12);
      CHECK(std::abs(d_lin - 1.0) <= 1e-12);
    }
    // Only N_0 is non-zero at the left end and only N_{n-1} at the right one.
    const auto left = a.evaluate(0.5), right = a.evaluate(2.0);
    CHECK(left.first == 0);
    CHECK(left.value[0] == 1.0);
    CHECK(right.first + p == a.size() - 1);
    CHECK(std::abs(right.value[p] - 1.0) <= 1e-15);
  }
}

TEST_CASE("B-spline axis: the closed form on uniform cells is the Cox-de Boor recursion", "[mpm]") {
  // evaluate() uses the uniform B-spline's pieces on cells p - 1 .. cells - p and the recursion
  // elsewhere: on every cell, the knots included, both must give the same functions to a few
  // ulps (values, and derivatives times h, are O(1)).
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (int p = 1; p <= 3; ++p) {
    const BSplineAxis a(-0.3, 0.07, 9, p);
    std::vector<double> xs;
    for (int j = 0; j <= a.cells() + 2 * p; ++j) xs.push_back(a.knot(j));
    for (int trial = 0; trial < 2000; ++trial) xs.push_back(a.lo() + (a.hi() - a.lo()) * u(rng));
    double worst_value = 0.0, worst_derivative = 0.0;
    for (double x : xs) {
      const auto closed = a.evaluate(x), recursive = a.cox_de_boor(x);
      REQUIRE(closed.first == recursive.first);
      for (int k = 0; k <= p; ++k) {
        worst_value = std::max(worst_value, std::abs(closed.value[k] - recursive.value[k]));
        worst_derivative = std::max(worst_derivative, std::abs(closed.derivative[k] - recursive.derivative[k]) * a.spacing());
      }
    }
    INFO("degree " << p << ": values " << worst_value << ", derivatives " << worst_derivative);
    CHECK(worst_value <= 1e-15);
    CHECK(worst_derivative <= 1e-15);
  }
}

TEST_CASE("quadratic B-spline: the interior function is the uniform quadratic spline", "[mpm]") {
  // Away from the ends the open knot vector is uniform: N(x) = (1/2) s^2, 3/4 - (s - 3/2)^2, ...
  const BSplineAxis a(0.0, 1.0, 8, 2);
  for (double x : {3.1, 3.5, 3.99}) {
    const auto v = a.evaluate(x);  // cell [3, 4]: functions N_3 .. N_5, N_3 centred at 3.5 - 1
    const double s = x - 3.0;
    CHECK(v.value[0] == Approx(0.5 * (1 - s) * (1 - s)).epsilon(1e-14));
    CHECK(v.value[1] == Approx(0.75 - (s - 0.5) * (s - 0.5)).epsilon(1e-14));
    CHECK(v.value[2] == Approx(0.5 * s * s).epsilon(1e-14));
    CHECK(v.derivative[1] == Approx(-2.0 * (s - 0.5)).margin(1e-14));
  }
}

TEST_CASE("every MPM basis is a partition of unity and linearly complete, walls included", "[mpm]") {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases) {
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const double h = grid.spacing();
    const Vec2 half(h / 6.0, h / 6.0);  // 9 particles per cell
    const bool deformed = c.method == MPMMethod::cpgimp || c.method == MPMMethod::cpdi ||
                          c.method == MPMMethod::qcpdi || c.method == MPMMethod::cpdi2 ||
                          c.method == MPMMethod::bspline_cpgimp;
    double worst = 0.0;
    for (int trial = 0; trial < 400; ++trial) {
      // A quarter of the points within a particle half size of a wall.
      Vec2 x(u(rng), 0.75 * u(rng));
      if (trial % 4 == 0) x.x() = half.x() * u(rng);
      if (trial % 4 == 1) x.y() = 0.75 - half.y() * u(rng);
      Sample s = sample(x, deformed ? testing::random_deformation(rng, 0.4) : Mat2::Identity(), half);
      if (c.method == MPMMethod::cpdi2) {  // a random convex quadrilateral; x_p is its area centroid
        s.corners = testing::random_quadrilateral(rng, x, s.F, half);
        x = testing::polygon_centroid(s.corners);
      }
      if (c.method == MPMMethod::bspline_cpgimp) {  // sum_i x_i S_ip is the clipped domain's centre
        const Box r = clipped_rectangle(x, s.F, half, grid.box());
        x = 0.5 * (r.lo + r.hi);
      }
      const Weights w = weights_at(basis, s);
      double one = 0.0;
      Vec2 lin = Vec2::Zero(), d_one = Vec2::Zero();
      Mat2 d_lin = Mat2::Zero();
      for (int k = 0; k < basis.stride(); ++k) {
        const Vec2 xi = grid.node(w.node[k]);
        one += w.S[k];
        lin += w.S[k] * xi;
        d_one += w.G[k];
        d_lin += xi * w.G[k].transpose();
      }
      worst = std::max({worst, std::abs(one - 1.0), (lin - x).norm(), h * d_one.norm(),
                        (d_lin - Mat2::Identity()).norm()});
    }
    INFO(to_string(c.method) << " degree " << c.degree << ": worst " << worst);
    CHECK(worst <= 1e-12);
  }
}

TEST_CASE("MPM basis gradients are the derivatives of the weights (classic, the GIMPs, B-splines)", "[mpm]") {
  // cpGIMP at a fixed F: its rectangle translates with x_p, so G = d S / d x_p as for uGIMP.
  // The CPDIs' G is the average of grad N over the domain, not the gradient of S.
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(0.02, 0.98);
  Mat2 F;
  F << 1.3, 0.2, -0.3, 0.7;
  for (const Case& c : cases) {
    if (c.method == MPMMethod::cpdi || c.method == MPMMethod::qcpdi || c.method == MPMMethod::cpdi2) continue;
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const Vec2 half = Vec2::Constant(grid.spacing() / 6.0);
    const double eps = 1e-6;
    double worst = 0.0;
    int compared = 0;
    for (int trial = 0; trial < 100; ++trial) {
      const Vec2 x(u(rng), 0.75 * u(rng));
      // A domain clipped at a wall averages over a length that changes with x_p.
      if (c.method == MPMMethod::bspline_cpgimp && is_clipped(x, F, half, grid.box())) continue;
      const Weights w = weights_at(basis, sample(x, F, half));
      for (int d = 0; d < 2; ++d) {
        const Vec2 e = eps * Vec2::Unit(d);
        const Weights wp = weights_at(basis, sample(x + e, F, half));
        const Weights wm = weights_at(basis, sample(x - e, F, half));
        // Same cell on both sides (a kink of the hats between them spoils the difference).
        if (wp.node != w.node || wm.node != w.node) continue;
        ++compared;
        for (int k = 0; k < basis.stride(); ++k)
          worst = std::max(worst, std::abs((wp.S[k] - wm.S[k]) / (2 * eps) - w.G[k][d]) * grid.spacing());
      }
    }
    INFO(to_string(c.method) << " degree " << c.degree << ": " << compared << " derivatives compared");
    CHECK(compared >= 150);
    CHECK(worst <= 1e-7);
  }
}

TEST_CASE("particle to grid conserves mass and momentum to round-off", "[mpm]") {
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  for (const Case& c : cases) {
    const Grid grid(domain, 8, c.degree, grid_padding(c.method));
    const ParticleBasis basis(c.method, grid);
    const Vec2 half = Vec2::Constant(grid.spacing() / 6.0);
    const Index n = 2000;
    WeightTable table;
    basis.resize(table, n);
    std::vector<double> mass(n);
    std::vector<Vec2> momentum(n);
    double total_mass = 0.0;
    Vec2 total_momentum = Vec2::Zero();
    for (Index p = 0; p < n; ++p) {
      const Vec2 x(u(rng), 0.75 * u(rng));
      evaluate(basis, sample(x, Mat2::Identity(), half), table, p);
      mass[p] = 0.5 + u(rng);
      momentum[p] = mass[p] * Vec2(u(rng) - 0.5, u(rng) - 0.5);
      total_mass += mass[p];
      total_momentum += momentum[p];
    }
    std::vector<Eigen::Vector3d> g;
    ScatterBuffers<Eigen::Vector3d> partial;
    scatter<Eigen::Vector3d>(table, grid.size(), g, partial, [&](Index q) {
      return [&, q](double S, const Vec2&) { return Eigen::Vector3d(S * mass[q], S * momentum[q].x(), S * momentum[q].y()); };
    });
    Eigen::Vector3d sum = Eigen::Vector3d::Zero();
    for (const auto& v : g) sum += v;
    INFO(to_string(c.method) << " degree " << c.degree);
    CHECK(std::abs(sum[0] - total_mass) <= 1e-13 * total_mass);
    CHECK((sum.tail<2>() - total_momentum).norm() <= 1e-13 * total_mass);
  }
}

namespace {

/// The exact average over [a, b] of the hat of node xi and spacing h, and of its derivative:
/// the trapezoid rule on the pieces between the hat's kinks, exact for a piecewise linear
/// function (and the midpoint rule on its piecewise constant derivative).
std::pair<double, double> hat_average(double xi, double h, double a, double b) {
  const auto N = [&](double x) { return std::max(0.0, 1.0 - std::abs(x - xi) / h); };
  const auto dN = [&](double x) { return std::abs(x - xi) >= h ? 0.0 : (x < xi ? 1.0 / h : -1.0 / h); };
  std::vector<double> cuts{a};
  for (double k : {xi - h, xi, xi + h})
    if (k > a && k < b) cuts.push_back(k);
  cuts.push_back(b);
  double value = 0.0, slope = 0.0;
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double l = cuts[k + 1] - cuts[k];
    value += 0.5 * l * (N(cuts[k]) + N(cuts[k + 1]));
    slope += l * dN(0.5 * (cuts[k] + cuts[k + 1]));
  }
  return {value / (b - a), slope / (b - a)};
}

std::map<Index, std::pair<double, Vec2>> by_node(const Weights& w) {
  std::map<Index, std::pair<double, Vec2>> out;
  for (std::size_t k = 0; k < w.node.size(); ++k) {
    out.try_emplace(w.node[k], 0.0, Vec2::Zero());  // Eigen's vectors start uninitialised
    out[w.node[k]].first += w.S[k];
    out[w.node[k]].second += w.G[k];
  }
  return out;
}

}  // namespace

TEST_CASE("cpGIMP: the exact averages over the rectangle stretched by F_ii, wider than a cell too", "[mpm]") {
  const Grid grid(domain, 8, 1, 1);
  const ParticleBasis basis(MPMMethod::cpgimp, grid);
  const double h = grid.spacing();
  const Vec2 half(h / 2, h / 2);  // one particle per cell
  Mat2 F;
  F << 1.9, 0.4, -0.3, 0.6;  // the domain spans 1.9 cells in x; the shear is not seen
  double worst = 0.0;
  std::mt19937_64 rng(23);
  std::uniform_real_distribution<double> u(0.1, 0.9);
  for (int trial = 0; trial < 50; ++trial) {
    const Vec2 x(u(rng), 0.75 * u(rng));
    const Vec2 l = half.cwiseProduct(F.diagonal());
    const auto exact = by_node(weights_at(basis, sample(x, F, half)));
    double total = 0.0;
    for (Index n = 0; n < grid.size(); ++n) {
      const Vec2 xi = grid.node(n);
      const auto [sx, dx] = hat_average(xi.x(), h, x.x() - l.x(), x.x() + l.x());
      const auto [sy, dy] = hat_average(xi.y(), h, x.y() - l.y(), x.y() + l.y());
      const auto it = exact.find(n);
      const double S = it == exact.end() ? 0.0 : it->second.first;
      const Vec2 G = it == exact.end() ? Vec2::Zero() : it->second.second;
      worst = std::max({worst, std::abs(S - sx * sy), h * (G - Vec2(dx * sy, sx * dy)).norm()});
      total += sx * sy;
    }
    REQUIRE(std::abs(total - 1.0) <= 1e-12);  // every hat the rectangle touches was compared
  }
  INFO("worst " << worst);
  CHECK(worst <= 1e-14);
}

namespace {

/// The averages over [a, b] of every function of a B-spline axis and of their derivatives:
/// three-point Gauss–Legendre (exact to degree 5) on the pieces between the knots, the
/// functions by the Cox–de Boor recursion.
std::pair<std::vector<double>, std::vector<double>> spline_averages(const BSplineAxis& ax, double a,
                                                                    double b) {
  std::vector<double> value(ax.size(), 0.0), slope(ax.size(), 0.0);
  std::vector<double> cuts{a};
  for (int k = 1; k < ax.cells(); ++k)
    if (const double knot = ax.lo() + k * ax.spacing(); knot > a && knot < b) cuts.push_back(knot);
  cuts.push_back(b);
  const double g = std::sqrt(0.6);
  for (std::size_t k = 0; k + 1 < cuts.size(); ++k) {
    const double mid = 0.5 * (cuts[k] + cuts[k + 1]), r = 0.5 * (cuts[k + 1] - cuts[k]);
    for (const auto& [t, w] :
         {std::pair{-g, 5.0 / 9.0}, std::pair{0.0, 8.0 / 9.0}, std::pair{g, 5.0 / 9.0}}) {
      const BSplineAxis::Values v = ax.cox_de_boor(mid + r * t);
      for (int m = 0; m <= ax.degree(); ++m) value[v.first + m] += w * r * v.value[m] / (b - a);
    }
  }
  for (const auto& [x, sign] : {std::pair{a, -1.0}, std::pair{b, 1.0}}) {
    const BSplineAxis::Values v = ax.cox_de_boor(x);
    for (int m = 0; m <= ax.degree(); ++m) slope[v.first + m] += sign * v.value[m] / (b - a);
  }
  return {value, slope};
}

}  // namespace

TEST_CASE(
    "B-spline cpGIMP: the exact averages of quadratic and cubic B-splines over the stretched rectangle, "
    "clipped at the walls",
    "[mpm]") {
  Mat2 F;
  F << 1.7, 0.4, -0.3, 0.6;  // 0.85 cells wide in x; the shear is not seen
  for (const int degree : {2, 3}) {
    const Grid grid(domain, 8, degree, 0);
    const ParticleBasis basis(MPMMethod::bspline_cpgimp, grid);
    const double h = grid.spacing();
    const Vec2 half(h / 4, h / 4);  // four particles per cell
    std::mt19937_64 rng(29);
    std::uniform_real_distribution<double> u(0.0, 1.0);
    double worst = 0.0;
    int clipped = 0;
    for (int trial = 0; trial < 200; ++trial) {
      Vec2 x(u(rng), 0.75 * u(rng));
      if (trial % 4 == 0) x.x() = h * 0.4 * u(rng);  // within the half width of the left wall
      if (trial % 4 == 1) x.y() = 0.75 - h * 0.1 * u(rng);
      const Box r = clipped_rectangle(x, F, half, grid.box());
      clipped += is_clipped(x, F, half, grid.box());
      const auto [sx, dx] = spline_averages(grid.x_axis(), r.lo.x(), r.hi.x());
      const auto [sy, dy] = spline_averages(grid.y_axis(), r.lo.y(), r.hi.y());
      const auto weights = by_node(weights_at(basis, sample(x, F, half)));
      for (Index n = 0; n < grid.size(); ++n) {
        const int i = static_cast<int>(n % grid.nx()), j = static_cast<int>(n / grid.nx());
        const auto it = weights.find(n);
        const double S = it == weights.end() ? 0.0 : it->second.first;
        const Vec2 G = it == weights.end() ? Vec2::Zero() : it->second.second;
        worst = std::max(
            {worst, std::abs(S - sx[i] * sy[j]), h * (G - Vec2(dx[i] * sy[j], sx[i] * dy[j])).norm()});
      }
    }
    INFO("degree " << degree << ": worst " << worst << ", " << clipped << " clipped domains");
    CHECK(clipped >= 80);
    CHECK(worst <= 1e-14);
  }
}

TEST_CASE("cpGIMP: a domain outgrowing its slot or with F_ii <= 0 is refused, naming the particle", "[mpm]") {
  // B-spline cpGIMP's slot of 4 quadratics per axis holds a domain within two cells: one 2.2
  // cells tall meets three wherever it lies.
  const Grid splines(domain, 8, 2, 0);
  const ParticleBasis averaged(MPMMethod::bspline_cpgimp, splines);
  WeightTable averaged_table;
  averaged.resize(averaged_table, 1);
  CHECK_THROWS_WITH(averaged.evaluate(Vec2(0.5, 0.4), Mat2(Vec2(1.0, 2.2).asDiagonal()),
                                      Vec2::Constant(splines.spacing() / 2), averaged_table, 0),
                    Catch::Contains("B-spline cpGIMP: the particle domain at (0.5, 0.4)") &&
                        Catch::Contains("more than the 4 functions per axis"));
  CHECK_THROWS_AS(ParticleBasis(MPMMethod::bspline_cpgimp, Grid(domain, 1, 2, 0)), InputError);  // one cell

  const Grid grid(domain, 8, 1, 1);
  const ParticleBasis basis(MPMMethod::cpgimp, grid);
  const Vec2 half = Vec2::Constant(grid.spacing() / 2);
  WeightTable table;
  basis.resize(table, 1);
  Mat2 F = Mat2::Identity();
  F(0, 0) = 2.3;  // 2.3 cells wide: 4 hats at most in a slot, this touches 4 or 5
  CHECK_THROWS_WITH(basis.evaluate(Vec2(0.5, 0.4), F, half, table, 0),
                    Catch::Contains("cpGIMP: the particle domain at (0.5, 0.4)") &&
                        Catch::Contains("more than the 4 functions per axis"));
  F(0, 0) = 0.2;
  F(1, 1) = -0.1;
  CHECK_THROWS_WITH(basis.evaluate(Vec2(0.5, 0.4), F, half, table, 0),
                    Catch::Contains("cpGIMP: the particle domain at (0.5, 0.4) has stretches F_xx = 0.2, F_yy = -0.1"));
  // A uGIMP domain of more than a cell is refused the same way.
  const ParticleBasis ugimp(MPMMethod::ugimp, grid);
  ugimp.resize(table, 1);
  CHECK_THROWS_WITH(ugimp.evaluate(Vec2(0.44, 0.4), Mat2::Identity(), 1.2 * half, table, 0),
                    Catch::Contains("uGIMP: the particle domain at (0.44, 0.4)") &&
                        Catch::Contains("more than the 3 functions per axis"));
}

TEST_CASE("qCPDI: a parallelogram in one cell gets the exact averages of the hats; lCPDI misses their quadratic part",
          "[mpm]") {
  // In one cell a hat is bilinear in (x, y), so quadratic in the parallelogram's (xi, eta):
  // the serendipity element holds every quadratic, its interpolant is the hat itself, and S and
  // G are exact. The bilinear element lacks xi^2 and eta^2: with N_i = (a + b dx)(c + d dy)
  // about the centre, lCPDI's S exceeds the average by b d (r1x r1y + r2x r2y) (1 - 1/3),
  // the corners' mean of xi^2 being 1 and its average 1/3.
  const Grid grid(domain, 8, 1, 1);
  const double h = grid.spacing();
  const ParticleBasis qcpdi(MPMMethod::qcpdi, grid), lcpdi(MPMMethod::cpdi, grid);
  const Vec2 x(0.31, 0.32), half(0.02, 0.02);  // the cell [0.25, 0.375]^2
  const Vec2 r1(0.03, 0.01), r2(-0.012, 0.02);
  Mat2 F;
  F << r1 / half.x(), r2 / half.y();
  for (const Vec2& c : parallelogram_corners(x, F, half)) REQUIRE(((c.array() > 0.25) && (c.array() < 0.375)).all());
  const auto q = by_node(weights_at(qcpdi, sample(x, F, half)));
  const auto l = by_node(weights_at(lcpdi, sample(x, F, half)));
  const double gp = std::sqrt(0.6), p[3] = {-gp, 0.0, gp}, gw[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double worst_q = 0.0, worst_l = 0.0, largest_l = 0.0;
  int nodes = 0;
  for (Index n = 0; n < grid.size(); ++n) {
    const Vec2 xi = grid.node(n);
    if ((xi - x).cwiseAbs().maxCoeff() >= h) continue;  // the cell's 4 nodes
    ++nodes;
    double S = 0.0;
    Vec2 G = Vec2::Zero();
    for (int i = 0; i < 3; ++i)  // 3 x 3 Gauss points of the affine map: exact for quadratics
      for (int j = 0; j < 3; ++j) {
        const Vec2 y = x + r1 * p[i] + r2 * p[j], d = y - xi;
        const double nx = 1 - std::abs(d.x()) / h, ny = 1 - std::abs(d.y()) / h;
        const double w = gw[i] * gw[j] / 4;
        S += w * nx * ny;
        G += w * Vec2(-(d.x() > 0 ? 1 : -1) / h * ny, -(d.y() > 0 ? 1 : -1) / h * nx);
      }
    worst_q = std::max({worst_q, std::abs(q.at(n).first - S), h * (q.at(n).second - G).norm()});
    const double b = -((x - xi).x() > 0 ? 1 : -1) / h, d = -((x - xi).y() > 0 ? 1 : -1) / h;
    const double excess = b * d * (r1.x() * r1.y() + r2.x() * r2.y()) * 2.0 / 3.0;
    worst_l = std::max(worst_l, std::abs(l.at(n).first - S - excess));
    largest_l = std::max(largest_l, std::abs(l.at(n).first - S));
  }
  INFO("qCPDI " << worst_q << ", lCPDI against its predicted excess " << worst_l << ", lCPDI's excess " << largest_l);
  CHECK(nodes == 4);
  CHECK(worst_q <= 1e-14);
  CHECK(worst_l <= 1e-15);
  CHECK(largest_l >= 1e-3);
}

TEST_CASE("CPDI2 on a parallelogram's corners is lCPDI", "[mpm]") {
  const Grid grid(domain, 8, 1, 1);
  const ParticleBasis cpdi(MPMMethod::cpdi, grid), cpdi2(MPMMethod::cpdi2, grid);
  Mat2 F;
  F << 1.4, 0.5, -0.2, 0.9;
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(0.05, 0.95);
  double worst = 0.0;
  for (int trial = 0; trial < 100; ++trial) {
    const Sample s = sample(Vec2(u(rng), 0.75 * u(rng)), F, Vec2::Constant(grid.spacing() / 4));
    const auto a = by_node(weights_at(cpdi, s)), b = by_node(weights_at(cpdi2, s));
    REQUIRE(a.size() == b.size());
    for (const auto& [n, sg] : a)
      worst = std::max({worst, std::abs(sg.first - b.at(n).first), grid.spacing() * (sg.second - b.at(n).second).norm()});
  }
  CHECK(worst <= 1e-15);
}

TEST_CASE("a CPDI2 corner or qCPDI midside off the grid is refused, naming it and the particle", "[mpm]") {
  const Grid grid(domain, 8, 1, 1);  // extent [-0.125, 1.125] x [-0.125, 0.875]
  const ParticleBasis cpdi2(MPMMethod::cpdi2, grid), qcpdi(MPMMethod::qcpdi, grid);
  WeightTable table;
  cpdi2.resize(table, 1);
  const DomainCorners c{Vec2(0.9, 0.5), Vec2(1.2, 0.5), Vec2(1.0, 0.6), Vec2(0.9, 0.6)};
  CHECK_THROWS_WITH(cpdi2.evaluate_quadrilateral(c, Vec2(0.95, 0.55), table, 0),
                    Catch::Contains("a CPDI2 particle corner at (1.2, 0.5) (of the particle at (0.95, 0.55)) left the grid"));
  qcpdi.resize(table, 1);
  CHECK_THROWS_WITH(qcpdi.evaluate(Vec2(1.05, 0.5), Mat2::Identity(), Vec2(0.1, 0.01), table, 0),
                    Catch::Contains("a qCPDI particle node at (1.15, 0.49) (of the particle at (1.05, 0.5)) left the grid"));
}
