// Meshfree quadrature in three dimensions on a box solid: the background lattice's tensor
// Newton–Cotes weights, the RK weights w_K = integral of phi_K exact for the polynomials of the
// RK order on lattice, perturbed and random clouds (to round-off), and the error of a smooth
// integrand falling at the 2D rates under refinement (linear RK 2, quadratic 3 or more; a
// study: Release only, its value is the rates).
#include <fmt/format.h>

#include <array>
#include <catch2/catch.hpp>
#include <cmath>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/core/error.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/geometry/gmsh_solid.hpp"
#include "mfree/geometry/tetrahedral_mesh.hpp"
#include "mfree/quadrature/background_lattice.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"

using namespace mfree;

namespace {

using P3 = Point<3>;

const Solid& box() {
  static const Solid solid = Solid::box(P3(0.0, 0.0, 0.0), P3(1.0, 0.8, 0.6));
  return solid;
}

/// The quadrature points (a cell-centred cloud of the kind) and their RK weights.
std::pair<std::vector<P3>, std::vector<double>> rk_rule(CloudKind kind, double h, RKOrder order,
                                                        const Solid& solid = box()) {
  CloudSettings cs;
  cs.kind = kind;
  cs.spacing = h;
  cs.perturbation = 0.5;
  cs.cell_centred = true;
  cs.seed = 4;
  std::vector<P3> x = make_cloud(solid, cs);
  const double factor = order == RKOrder::linear ? 2.0 : 3.0;
  RKSettings rs;
  rs.order = order;
  rs.radius = factor * h;
  if (kind != CloudKind::lattice) rs.node_radii = nodal_support_radii(x, h, factor * 1.25);
  const RKShapeFunctions<3> rk(x, rs);
  const BackgroundLattice<3> lattice(solid, h / 2, order == RKOrder::linear ? 1 : 2);
  return {x, rk_quadrature_weights(rk, lattice)};
}

/// The monomials of degree <= 2 in x, y, z and their integrals over [0, a] x [0, b] x [0, c].
std::array<double, 10> monomials(const P3& p) {
  const double x = p[0], y = p[1], z = p[2];
  return {1.0, x, y, z, x * x, x * y, x * z, y * y, y * z, z * z};
}
std::array<double, 10> monomial_integrals() {
  const double a = 1.0, b = 0.8, c = 0.6, v = a * b * c;
  return {v,
          v * a / 2,
          v * b / 2,
          v * c / 2,
          v * a * a / 3,
          v * a * b / 4,
          v * a * c / 4,
          v * b * b / 3,
          v * b * c / 4,
          v * c * c / 3};
}

}  // namespace

TEST_CASE(
    "3D background lattice: tensor Newton-Cotes weights integrate the polynomials of their order over a box",
    "[quadrature][3d]") {
  const auto exact = monomial_integrals();
  for (int order : {1, 2}) {
    CAPTURE(order);
    const BackgroundLattice<3> lattice(box(), 0.07, order);
    std::array<double, 10> sum{};
    for (std::size_t v = 0; v < lattice.points().size(); ++v) {
      REQUIRE(box().contains(lattice.points()[v]));
      const auto m = monomials(lattice.points()[v]);
      for (int t = 0; t < 10; ++t) sum[t] += lattice.weights()[v] * m[t];
    }
    // Trapezoid: exact for 1, x, y, z and the products of distinct axes; Simpson: all ten.
    for (int t = 0; t < 10; ++t) {
      const bool square = t == 4 || t == 7 || t == 9;
      if (order == 2 || !square) CHECK(sum[t] == Approx(exact[t]).epsilon(1e-13));
    }
  }
  CHECK_THROWS_WITH(BackgroundLattice<3>(box(), 0.0, 1), Catch::Contains("spacing must be positive"));
  CHECK_THROWS_WITH(Solid::box(P3(0, 0, 0), P3(1, 0, 1)), Catch::Contains("do not span a box"));
}

TEST_CASE(
    "3D background lattice on a meshed solid: cut cells integrate Omega_h's volume and first moments to "
    "round-off",
    "[quadrature][3d]") {
  // The thick sphere's octant of tetrahedra (curved faces as flat triangles): the exact
  // moments of Omega_h are sums over its tetrahedra (closed forms).
  const Solid solid = testing::thick_sphere_octant(0.15);
  const TetrahedralMesh& mesh = *solid.mesh();
  double volume = 0.0;
  P3 first = P3::Zero();
  Tensor2<3> second = Tensor2<3>::Zero();
  for (Index t = 0; t < mesh.size(); ++t) {
    const Tetrahedron tet = mesh.tetrahedron(t);
    volume += tetrahedron_volume(tet);
    first += tetrahedron_volume(tet) * tetrahedron_centroid(tet);
    second += tetrahedron_second_moments(tet);
  }
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const BackgroundLattice<3> lattice(solid, 0.06, order);
    CHECK(lattice.cut_cells() > 0);
    double w = 0.0;
    P3 wx = P3::Zero();
    Tensor2<3> wxx = Tensor2<3>::Zero();
    for (std::size_t k = 0; k < lattice.points().size(); ++k) {
      const P3& x = lattice.points()[k];
      REQUIRE(solid.contains(x));
      w += lattice.weights()[k];
      wx += lattice.weights()[k] * x;
      wxx += lattice.weights()[k] * x * x.transpose();
    }
    CHECK(w == Approx(volume).epsilon(1e-13));
    CHECK((wx - first).norm() <= 1e-12 * first.norm());
    // Second moments: Simpson's rule exact on the whole cells and the cut cells' weights fitted
    // to them where their points allow; the trapezoid's error is O(h^2).
    CAPTURE((wxx - second).norm() / second.norm());
    CHECK((wxx - second).norm() <= (order == 2 ? 1e-6 : 1e-2) * second.norm());
  }
  // The RK weights of quadrature clouds in the solid carry these moments over: sum w_K = |Omega_h|
  // and sum w_K x_K = its first moment, to round-off (partition of unity, linear reproduction).
  for (const CloudKind kind : {CloudKind::lattice, CloudKind::random}) {
    CAPTURE(to_string(kind));
    const auto [x, w] = rk_rule(kind, 0.15, RKOrder::linear, solid);
    double sum = 0.0;
    P3 sum_x = P3::Zero();
    for (std::size_t k = 0; k < x.size(); ++k) {
      sum += w[k];
      sum_x += w[k] * x[k];
    }
    CHECK(sum == Approx(volume).epsilon(1e-12));
    CHECK((sum_x - first).norm() <= 1e-12 * first.norm());
  }
}

TEST_CASE(
    "3D background lattice at tied interfaces: each region's volume and first moments to round-off, by "
    "points inside it",
    "[quadrature][3d]") {
  // The two-layer sphere's octant: the cells that touch the interface r = 1.5 are cut and
  // integrated region by region, so the lattice's points of each region integrate that
  // region's part of Omega_h, and the quadrature-cloud functions, which end at the interface,
  // are integrated on their side only.
  const Solid solid = read_gmsh_solid(testing::source_dir() + "/meshes/two_layer_sphere_octant.geo");
  const Solid bonded = read_gmsh_solid(testing::source_dir() + "/meshes/two_layer_sphere_octant.geo",
                                       default_gmsh_reader_limits(), false);
  const TetrahedralMesh& mesh = *solid.mesh();
  std::array<double, 2> volume{};
  std::array<P3, 2> first{P3::Zero(), P3::Zero()};
  for (Index t = 0; t < mesh.size(); ++t) {
    const Tetrahedron tet = mesh.tetrahedron(t);
    volume[mesh.region(t)] += tetrahedron_volume(tet);
    first[mesh.region(t)] += tetrahedron_volume(tet) * tetrahedron_centroid(tet);
  }
  for (const int order : {1, 2}) {
    CAPTURE(order);
    const BackgroundLattice<3> lattice(solid, 0.1, order);
    CHECK(lattice.cut_cells() > BackgroundLattice<3>(bonded, 0.1, order).cut_cells());
    std::array<double, 2> w{};
    std::array<P3, 2> wx{P3::Zero(), P3::Zero()};
    for (std::size_t k = 0; k < lattice.points().size(); ++k) {
      const P3& x = lattice.points()[k];
      const int r = solid.region_at(x);
      REQUIRE(r >= 0);
      w[r] += lattice.weights()[k];
      wx[r] += lattice.weights()[k] * x;
    }
    for (int r = 0; r < 2; ++r) {
      CAPTURE(r);
      INFO(fmt::format("relative {:.3e}, first moments {:.3e}", w[r] / volume[r] - 1.0,
                       (wx[r] - first[r]).norm() / first[r].norm()));
      // 1.3e-13 with Simpson's rule (the weights fitted in many small cut parts).
      CHECK(w[r] == Approx(volume[r]).epsilon(1e-12));
      CHECK((wx[r] - first[r]).norm() <= 1e-12 * first[r].norm());
    }
  }
}

TEST_CASE("3D RK quadrature weights integrate the polynomials of the RK order to round-off on every cloud",
          "[quadrature][3d]") {
  const auto exact = monomial_integrals();
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed, CloudKind::random})
    for (RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
      CAPTURE(to_string(kind), to_string(order));
      const auto [x, w] = rk_rule(kind, 0.1, order);
      std::array<double, 10> sum{};
      for (std::size_t k = 0; k < x.size(); ++k) {
        const auto m = monomials(x[k]);
        for (int t = 0; t < 10; ++t) sum[t] += w[k] * m[t];
      }
      const int terms = order == RKOrder::linear ? 4 : 10;
      for (int t = 0; t < terms; ++t) CHECK(sum[t] == Approx(exact[t]).epsilon(1e-12));
    }
}

TEST_CASE(
    "3D RK quadrature: the error of a smooth integrand falls at rate 2 (linear) and 3 or more (quadratic)",
    "[quadrature][3d][study]") {
  // f = e^x cos(2 y) e^-z over [0, 1] x [0, 0.8] x [0, 0.6].
  const auto f = [](const P3& p) { return std::exp(p[0]) * std::cos(2.0 * p[1]) * std::exp(-p[2]); };
  const double exact = (std::exp(1.0) - 1.0) * (std::sin(1.6) / 2.0) * (1.0 - std::exp(-0.6));
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed})
    for (RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
      CAPTURE(to_string(kind), to_string(order));
      std::vector<double> errors, spacings;
      // Linear RK is pre-asymptotic above h = 0.05 (rate 1.4 from 0.2 to 0.1).
      const std::array<double, 3> levels =
          order == RKOrder::linear ? std::array{0.1, 0.05, 0.025} : std::array{0.2, 0.1, 0.05};
      for (double h : levels) {
        const auto [x, w] = rk_rule(kind, h, order);
        double integral = 0.0;
        for (std::size_t k = 0; k < x.size(); ++k) integral += w[k] * f(x[k]);
        errors.push_back(std::abs(integral - exact) / std::abs(exact));
        spacings.push_back(std::cbrt(box().measure() / static_cast<double>(x.size())));
      }
      const double rate = std::log(errors[1] / errors[2]) / std::log(spacings[1] / spacings[2]);
      CAPTURE(errors[0], errors[1], errors[2], rate);
      CHECK(rate >= (order == RKOrder::linear ? 1.8 : 2.8));
    }
}

TEST_CASE(
    "3D projected quadrature: the projected gradients reproduce the gradients of the RK order's fields at "
    "the "
    "centroids, and the weights sum to the volume",
    "[quadrature][3d]") {
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed})
    for (RKOrder order : {RKOrder::linear, RKOrder::quadratic}) {
      CAPTURE(to_string(kind), to_string(order));
      const double h = 0.125;
      CloudSettings cs;
      cs.kind = kind;
      cs.spacing = h;
      cs.perturbation = 0.5;
      cs.seed = 2;
      const std::vector<P3> nodes = make_cloud(box(), cs);
      const std::vector<P3> points = make_quadrature_cloud(box(), cs, 1.0);
      const double factor = order == RKOrder::linear ? 2.0 : 3.0;
      RKSettings rs;
      rs.order = order;
      rs.radius = factor * h;
      RKSettings qs = rs;
      if (kind != CloudKind::lattice) {
        rs.node_radii = nodal_support_radii(nodes, h, factor * 1.25);
        qs.node_radii = nodal_support_radii(points, h, factor * 1.25);
      }
      const RKShapeFunctions<3> trial(nodes, rs), functions(points, qs);
      const BackgroundLattice<3> lattice(box(), h / 2, order == RKOrder::linear ? 1 : 2);
      const GalerkinQuadrature<3> q = projected_quadrature(trial, functions, lattice);
      double volume = 0.0, worst = 0.0;
      const int terms = order == RKOrder::linear ? 4 : 10;
      for (Index k = 0; k < q.size(); ++k) {
        volume += q.weights[k];
        // sum_I gradbar phi_I(x_K) p(x_I) = grad p(c_K) for every monomial p of the order.
        std::array<P3, 10> sum;
        sum.fill(P3::Zero());
        for (Index s = q.row_begin(k); s < q.row_end(k); ++s) {
          const auto m = monomials(nodes[q.nodes[s]]);
          for (int t = 0; t < terms; ++t) sum[t] += m[t] * q.grad[s];
        }
        const P3& c = q.centroids[k];
        const std::array<P3, 10> exact = {
            P3::Zero(),        P3(1, 0, 0),       P3(0, 1, 0),        P3(0, 0, 1),       P3(2 * c[0], 0, 0),
            P3(c[1], c[0], 0), P3(c[2], 0, c[0]), P3(0, 2 * c[1], 0), P3(0, c[2], c[1]), P3(0, 0, 2 * c[2])};
        for (int t = 0; t < terms; ++t) worst = std::max(worst, (sum[t] - exact[t]).norm());
      }
      CHECK(volume == Approx(box().measure()).epsilon(1e-12));
      CHECK(worst < 1e-10);
    }
}
