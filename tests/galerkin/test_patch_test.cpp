#include <catch2/catch.hpp>

#include "mfree/galerkin/elasticity_solver.hpp"

using namespace mfree;

namespace {

/// Linear patch test: u = a + G x prescribed by Nitsche on the boundary part left of
/// x = x_cut, traction sigma n elsewhere. Returns max over nodes |u^h(x_I) - u(x_I)| / max |u|.
double patch_error(const Domain& domain, CloudKind kind, Consistency consistency, RKOrder order) {
  ElasticitySettings s;
  s.nodes.kind = kind;
  s.nodes.spacing = domain.bounding_box().size().minCoeff() / 8.0;
  s.nodes.perturbation = 0.4;
  s.nodes.seed = 5;
  s.order = order;
  s.support_factor = order == RKOrder::linear ? 2.0 : 3.0;
  s.consistency = consistency;
  s.problem.material = LinearElastic{2.0e5, 0.3, PlaneModel::strain};
  Mat2 g;
  g << 1e-3, 2e-3, -0.5e-3, 1.5e-3;
  const ExactElasticity exact = linear_field(Vec2(0.01, -0.02), g, s.problem.material);
  const Box box = domain.bounding_box();
  const double cut = box.lo.x() + 0.3 * box.size().x();
  const Box left{box.lo - Vec2(1, 1), Vec2(cut, box.hi.y() + 1)};
  const Box right{Vec2(cut, box.lo.y() - 1), box.hi + Vec2(1, 1)};
  s.problem.conditions = {
      {BoundaryCondition::Type::displacement, left,
       [&](const Vec2& x, const Vec2&) { return exact.displacement(x); }, "left"},
      {BoundaryCondition::Type::traction, right,
       [&](const Vec2& x, const Vec2& n) { return exact.traction(x, n); }, "right"}};
  const ElasticityResult r = solve_elasticity(domain, s, nullptr);
  const std::vector<Vec2> uh = r.displacement(r.nodes);
  double err = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < r.nodes.size(); ++i) {
    const Vec2 u = exact.displacement(r.nodes[i]);
    err = std::max(err, (uh[i] - u).norm());
    scale = std::max(scale, u.norm());
  }
  return err / scale;
}

}  // namespace

TEST_CASE("linear patch test to 1e-8 with Nitsche boundaries, consistent projected gradients",
          "[galerkin]") {
  for (const std::string name : {"rectangle.wkt", "l_shape.wkt"})
    for (CloudKind kind : {CloudKind::lattice, CloudKind::perturbed, CloudKind::random})
      for (Consistency c : {Consistency::symmetric, Consistency::vci}) {
        CAPTURE(name, to_string(kind), to_string(c));
        const Domain d = Domain::from_file(std::string(MFREE_SOURCE_DIR) + "/meshes/" + name);
        const double e = patch_error(d, kind, c, RKOrder::linear);
        INFO("patch error " << std::scientific << e);
        CHECK(e <= 1e-8);
      }
}

TEST_CASE("without a consistency correction the patch test fails (the correction matters)",
          "[galerkin]") {
  const Domain d = Domain::from_file(std::string(MFREE_SOURCE_DIR) + "/meshes/l_shape.wkt");
  CHECK(patch_error(d, CloudKind::perturbed, Consistency::none, RKOrder::linear) > 1e-6);
}
