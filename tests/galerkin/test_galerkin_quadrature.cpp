// The projected Galerkin quadrature (SPEC sections 2 and 3): weights and centroids integrate
// 1 and x, projected gradients of a quadratic field are exact at the row centroids, and the
// lattice sums come out the same bit for bit on every run and thread count.

#include <omp.h>

#include <catch2/catch.hpp>

#include "../test_support.hpp"
#include "mfree/clouds/point_cloud.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/quadrature/rk_quadrature.hpp"

using namespace mfree;

namespace {

/// The projected quadrature (no consistency correction) of the domain, `levels` node spacings
/// across its smaller side.
Discretisation<2> projected(const Domain& domain, CloudKind kind, RKOrder order, double levels = 8.0) {
  ElasticitySettings s;
  s.scheme = QuadratureScheme::projected;
  s.nodes.kind = kind;
  s.nodes.spacing = domain.bounding_box().size().minCoeff() / levels;
  s.nodes.perturbation = 0.4;
  s.nodes.seed = 3;
  s.order = order;
  s.support_factor = order == RKOrder::linear ? 2.0 : 3.0;
  s.quadrature_order = order;
  s.quadrature_factor = s.support_factor;
  s.consistency = Consistency::none;
  StageTimer timer;
  return discretise(domain, s, timer);
}

Domain l_shape() { return Domain::from_file(mfree::testing::source_dir() + "/meshes/l_shape.wkt"); }

}  // namespace

TEST_CASE("projected quadrature: weights and centroids integrate 1 and x; quadratic gradients exact at the centroids",
          "[galerkin]") {
  const Domain domain = l_shape();
  for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed}) {
    CAPTURE(to_string(kind));
    const Discretisation<2> d = projected(domain, kind, RKOrder::quadratic);
    const GalerkinQuadrature<2>& q = d.quadrature;
    double area = 0.0;
    Vec2 moment = Vec2::Zero();
    for (Index k = 0; k < q.size(); ++k) {
      area += q.weights[k];
      moment += q.weights[k] * q.centroids[k];
    }
    CHECK(std::abs(area - domain.area()) <= 1e-12 * domain.area());
    CHECK((moment - domain.first_moment()).norm() <= 1e-12 * domain.first_moment().norm());
    // u = x^2 - 3 x y + 2 y^2 + x: grad u = (2 x - 3 y + 1, -3 x + 4 y), a linear field that
    // the projection (1 / w_K) integral of phi_K grad u^h gives exactly at c_K, not at x_K.
    const auto u = [](const Vec2& x) { return x.x() * x.x() - 3.0 * x.x() * x.y() + 2.0 * x.y() * x.y() + x.x(); };
    const auto grad = [](const Vec2& x) { return Vec2(2.0 * x.x() - 3.0 * x.y() + 1.0, -3.0 * x.x() + 4.0 * x.y()); };
    double at_centroid = 0.0, at_point = 0.0, scale = 0.0;
    for (Index k = 0; k < q.size(); ++k) {
      Vec2 g = Vec2::Zero();
      for (Index s = q.row_begin(k); s < q.row_end(k); ++s) g += u(d.nodes[q.nodes[s]]) * q.grad[s];
      at_centroid = std::max(at_centroid, (g - grad(q.centroids[k])).norm());
      at_point = std::max(at_point, (g - grad(q.points[k])).norm());
      scale = std::max(scale, grad(q.centroids[k]).norm());
    }
    INFO("largest gradient error at c_K " << at_centroid << ", at x_K " << at_point << ", scale " << scale);
    CHECK(at_centroid <= 1e-10 * scale);
    CHECK(at_point >= 1e-4 * scale);  // near the boundary c_K and x_K differ
  }
}

TEST_CASE("projected quadrature: the same numbers bit for bit on every run and thread count", "[galerkin]") {
  const Domain domain = l_shape();
  // About 10^4 lattice points: many blocks of work for the threads to share.
  const int threads = omp_get_max_threads();
  omp_set_num_threads(1);
  const Discretisation<2> one = projected(domain, CloudKind::perturbed, RKOrder::linear, 32.0);
  omp_set_num_threads(std::max(2, threads));
  const Discretisation<2> first = projected(domain, CloudKind::perturbed, RKOrder::linear, 32.0);
  const Discretisation<2> second = projected(domain, CloudKind::perturbed, RKOrder::linear, 32.0);
  omp_set_num_threads(threads);
  const auto identical = [](const GalerkinQuadrature<2>& a, const GalerkinQuadrature<2>& b) {
    if (a.size() != b.size() || a.grad.size() != b.grad.size()) return false;
    for (Index k = 0; k < a.size(); ++k)
      if (!testing::same_bits(a.weights[k], b.weights[k]) || !testing::same_bits(a.centroids[k].x(), b.centroids[k].x()) ||
          !testing::same_bits(a.centroids[k].y(), b.centroids[k].y()))
        return false;
    for (std::size_t s = 0; s < a.grad.size(); ++s)
      if (!testing::same_bits(a.grad[s].x(), b.grad[s].x()) || !testing::same_bits(a.grad[s].y(), b.grad[s].y()))
        return false;
    return true;
  };
  CHECK(identical(first.quadrature, second.quadrature));
  CHECK(identical(one.quadrature, first.quadrature));
}

TEST_CASE("projected quadrature: its weights are the integration study's rk_quadrature_weights, bit for bit",
          "[galerkin]") {
  // One computation of w_K = integral of phi_K (quadrature/rk_quadrature.hpp): the integration
  // study measures the weights the solver uses, on every cloud, with 1 and 2 threads.
  const Domain domain = l_shape();
  CloudSettings cs;
  cs.kind = CloudKind::perturbed;
  cs.spacing = 1.0 / 16;
  cs.perturbation = 0.4;
  cs.seed = 5;
  const std::vector<Vec2> nodes = make_cloud(domain, cs);
  cs.cell_centred = true;
  const std::vector<Vec2> points = make_cloud(domain, cs);
  RKSettings rs;
  rs.radius = 2.0 * cs.spacing;
  rs.node_radii = nodal_support_radii(nodes, cs.spacing, 2.5);
  const RKShapeFunctions<2> trial(nodes, rs);
  rs.node_radii = nodal_support_radii(points, cs.spacing, 2.5);
  const RKShapeFunctions<2> quadrature_functions(points, rs);
  const BackgroundLattice<2> lattice(domain, cs.spacing / 2, 1);
  const int threads = omp_get_max_threads();
  for (const int t : {1, std::max(2, threads)}) {
    omp_set_num_threads(t);
    const std::vector<double> study = rk_quadrature_weights(quadrature_functions, lattice);
    const GalerkinQuadrature<2> solver = projected_quadrature(trial, quadrature_functions, lattice);
    REQUIRE(study.size() == solver.weights.size());
    std::size_t differ = 0;
    for (std::size_t k = 0; k < study.size(); ++k) differ += !testing::same_bits(study[k], solver.weights[k]);
    CAPTURE(t);
    CHECK(differ == 0);
  }
  omp_set_num_threads(threads);
}
