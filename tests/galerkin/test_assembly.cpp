#include <catch2/catch.hpp>
#include <memory>

#include "mfree/clouds/point_cloud.hpp"
#include "mfree/galerkin/consistency.hpp"
#include "mfree/galerkin/small_strain_elasticity.hpp"
#include "mfree/quadrature/gauss_cells.hpp"

using namespace mfree;

namespace {

/// Strain-displacement matrix of all quadrature points: rows 3K..3K+2 hold the Voigt strain
/// (eps_xx, eps_yy, gamma_xy) at point K, columns 2I, 2I+1 the coefficients of node I.
SparseMatrix strain_matrix(const GalerkinQuadrature<2>& q, const std::vector<Vec2>& grad, Index nodes) {
  std::vector<Eigen::Triplet<double>> t;
  for (Index k = 0; k < q.size(); ++k)
    for (Index s = q.row_begin(k); s < q.row_end(k); ++s) {
      const Index i = q.nodes[s];
      t.emplace_back(3 * k, 2 * i, grad[s].x());
      t.emplace_back(3 * k + 1, 2 * i + 1, grad[s].y());
      t.emplace_back(3 * k + 2, 2 * i, grad[s].y());
      t.emplace_back(3 * k + 2, 2 * i + 1, grad[s].x());
    }
  SparseMatrix b(3 * q.size(), 2 * nodes);
  b.setFromTriplets(t.begin(), t.end());
  return b;
}

/// The domain stiffness by global sparse products: K = B_test^T (W D) B_trial, W = diag(w_K).
SparseMatrix reference_stiffness(const GalerkinQuadrature<2>& q, const std::vector<Vec2>& test,
                                 const Eigen::Matrix3d& d, Index nodes) {
  std::vector<Eigen::Triplet<double>> t;
  for (Index k = 0; k < q.size(); ++k)
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) t.emplace_back(3 * k + r, 3 * k + c, q.weights[k] * d(r, c));
  SparseMatrix wd(3 * q.size(), 3 * q.size());
  wd.setFromTriplets(t.begin(), t.end());
  const SparseMatrix bt = strain_matrix(q, test, nodes);
  return SparseMatrix(bt.transpose()) * (wd * strain_matrix(q, q.grad, nodes));
}

/// Cantilever [0, 48] x [-6, 6] on a lattice of spacing 3 with 3 x 3 Gauss points per cell.
struct Cantilever {
  Domain domain = Domain::rectangle(Vec2(0.0, -6.0), Vec2(48.0, 6.0));
  double h = 3.0;
  std::vector<Vec2> nodes;
  std::unique_ptr<RKShapeFunctions<2>> trial;
  GalerkinQuadrature<2> q;
  BoundaryQuadrature<2> bq;
  GalerkinQuadrature<2> at_boundary;
  ElasticityProblem problem;

  Cantilever() {
    CloudSettings c;
    c.spacing = h;
    nodes = make_cloud(domain, c);
    RKSettings rk;
    rk.radius = 2.0 * h;
    trial = std::make_unique<RKShapeFunctions<2>>(nodes, rk);
    q = direct_quadrature(*trial, gauss_cell_rule(domain, h, 3));
    bq = boundary_quadrature(domain, h, 2);
    at_boundary = boundary_functions(*trial, bq);
    problem.material = LinearElastic{3.0e7, 0.3, PlaneModel::stress};
    problem.spacing = h;
  }
  [[nodiscard]] Index size() const { return static_cast<Index>(nodes.size()); }
  [[nodiscard]] ElasticitySystem assemble(const GalerkinQuadrature<2>& quadrature,
                                          const std::vector<Vec2>* test) const {
    return assemble_elasticity(problem, domain, size(), quadrature, test, bq, at_boundary);
  }
};

double relative_difference(const SparseMatrix& a, const SparseMatrix& b) {
  return SparseMatrix(a - b).norm() / b.norm();
}

}  // namespace

TEST_CASE("domain stiffness equals B_test^T W D B_trial, symmetric gradients", "[galerkin]") {
  const Cantilever c;
  const ElasticitySystem sys = c.assemble(c.q, nullptr);
  const SparseMatrix ref = reference_stiffness(c.q, c.q.grad, c.problem.material.voigt_tangent(), c.size());
  REQUIRE(sys.symmetric);
  REQUIRE(sys.stiffness.rows() == 2 * c.size());
  REQUIRE(sys.stiffness.isCompressed());
  CHECK(relative_difference(sys.stiffness, ref) <= 1e-13);
  // The upper blocks are copies of the lower ones.
  CHECK(SparseMatrix(SparseMatrix(sys.stiffness.transpose()) - sys.stiffness).norm() == 0.0);
}

TEST_CASE("domain stiffness equals B_test^T W D B_trial, VCI test gradients", "[galerkin]") {
  const Cantilever c;
  const std::vector<Vec2> test =
      ConsistencyConditions(c.q, c.nodes, c.at_boundary, c.bq, RKOrder::linear).vci_test_gradients();
  const ElasticitySystem sys = c.assemble(c.q, &test);
  const SparseMatrix ref = reference_stiffness(c.q, test, c.problem.material.voigt_tangent(), c.size());
  REQUIRE_FALSE(sys.symmetric);
  CHECK(relative_difference(sys.stiffness, ref) <= 1e-13);
  // VCI makes the matrix non-symmetric: the comparison above must see the test gradients.
  CHECK(relative_difference(SparseMatrix(sys.stiffness.transpose()), sys.stiffness) > 1e-6);
}

TEST_CASE("Nitsche boundary terms add to the domain stiffness", "[galerkin]") {
  Cantilever c;
  const Vec2 ubar(1e-3, -2e-3);
  c.problem.conditions = {{BoundaryCondition<2>::Type::displacement, select_part(c.domain, "left"),
                           [ubar](const Vec2&, const Vec2&, double) { return ubar; }, "left end"}};
  // With no quadrature points the system holds the boundary terms alone.
  GalerkinQuadrature<2> none;
  none.offsets = {0};
  const ElasticitySystem boundary = c.assemble(none, nullptr);
  const ElasticitySystem sys = c.assemble(c.q, nullptr);
  const SparseMatrix ref = reference_stiffness(c.q, c.q.grad, c.problem.material.voigt_tangent(), c.size());
  REQUIRE(boundary.stiffness.nonZeros() > 0);
  CHECK(relative_difference(sys.stiffness, SparseMatrix(ref + boundary.stiffness)) <= 1e-13);
  CHECK((sys.load - boundary.load).norm() == 0.0);
  CHECK(relative_difference(SparseMatrix(sys.stiffness.transpose()), sys.stiffness) <= 1e-14);
}
