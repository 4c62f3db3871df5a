// Regions tied along interfaces (Domain::from_regions, TotalLagrangian<2>'s ties): patch tests
// across the tie for one material (two parts of an assembly) and for two (a bimaterial with a
// piecewise-linear exact field, which the tie reproduces and a smooth approximation does not).

#include <Eigen/Dense>
#include <catch2/catch.hpp>
#include <initializer_list>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/newton_solver.hpp"
#include "mfree/problems/polynomial_fields.hpp"

using namespace mfree;

namespace {

const LinearElastic steel{2.0e5, 0.3, PlaneModel::strain};
const LinearElastic resin{0.5e5, 0.2, PlaneModel::strain};

/// The law everywhere, or one per region.
struct Laws {
  LinearElastic material;
  std::vector<LinearElastic> regions;
};

/// Two parts that share a kinked edge: [0, 2] x [0, 1] cut along (1, 0) - (1.2, 0.5) - (0.9, 1).
Domain two_parts(bool interfaces) {
  const std::vector<std::vector<Ring>> parts{
      {{Vec2(0, 0), Vec2(1, 0), Vec2(1.2, 0.5), Vec2(0.9, 1), Vec2(0, 1)}},
      {{Vec2(1, 0), Vec2(2, 0), Vec2(2, 1), Vec2(0.9, 1), Vec2(1.2, 0.5)}}};
  return Domain::from_regions(parts, {{"left", "right"}, interfaces}, "two parts");
}

/// A hexagonal inclusion in [0, 2] x [0, 1.25], tied round its whole boundary (an interface
/// that closes on itself); three rows of nodes of the tests' spacing 1/8 below and above it.
Domain with_inclusion() {
  const Ring inclusion{Vec2(0.45, 0.3),  Vec2(1.3, 0.32), Vec2(1.6, 0.6),
                       Vec2(1.35, 0.95), Vec2(0.6, 0.92), Vec2(0.32, 0.62)};
  const std::vector<std::vector<Ring>> parts{
      {{Vec2(0, 0), Vec2(2, 0), Vec2(2, 1.25), Vec2(0, 1.25)}, inclusion}, {inclusion}};
  return Domain::from_regions(parts, {{"matrix", "inclusion"}, true}, "inclusion");
}

/// An L of two parts: the interface x = 1 runs from the bottom to the union's re-entrant
/// corner (1, 1), where the mouth of the interface is a reflex vertex of the boundary.
Domain l_of_two_parts() {
  const std::vector<std::vector<Ring>> parts{{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(1, 2), Vec2(0, 2)}},
                                             {{Vec2(1, 0), Vec2(2, 0), Vec2(2, 1), Vec2(1, 1)}}};
  return Domain::from_regions(parts, {{"column", "foot"}, true}, "L of two parts");
}

/// Two materials side by side, the interface x = 1 straight.
Domain bimaterial(bool interfaces) {
  const std::vector<std::vector<Ring>> parts{{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 1), Vec2(0, 1)}},
                                             {{Vec2(1, 0), Vec2(2, 0), Vec2(2, 1), Vec2(1, 1)}}};
  return Domain::from_regions(parts, {{"steel", "resin"}, interfaces}, "bimaterial");
}

/// The exact field prescribed by Nitsche on x < 0.3, its traction elsewhere; max over the
/// nodes of |u^h - u| / max |u|. The projected scheme takes VCI for quadratic RK (its
/// symmetric correction is linear).
double tied_patch_error(const Domain& domain, const Laws& laws, const ExactElasticity& exact, CloudKind kind,
                        RKOrder order, SupportRule rule,
                        QuadratureScheme scheme = QuadratureScheme::gauss_cells) {
  ElasticitySettings s;
  s.scheme = scheme;
  if (scheme == QuadratureScheme::projected && order == RKOrder::quadratic) s.consistency = Consistency::vci;
  s.support_rule = rule;
  s.nodes.kind = kind;
  s.nodes.spacing = 1.0 / 8.0;
  s.nodes.perturbation = 0.4;
  s.nodes.seed = 7;
  s.order = order;
  s.support_factor = order == RKOrder::linear ? 2.0 : 3.0;
  s.problem.material = laws.material;
  s.problem.region_materials = laws.regions;
  s.problem.body_force = exact.body_force;
  const Box box = domain.bounding_box();
  const Box left{box.lo - Vec2(1, 1), Vec2(0.3, box.hi.y() + 1)};
  const Box right{Vec2(0.3, box.lo.y() - 1), box.hi + Vec2(1, 1)};
  s.problem.conditions = {
      {BoundaryCondition<2>::Type::displacement, select_box(domain, left),
       [&](const Vec2& x, const Vec2&, double) { return exact.displacement(x); }, "left"},
      {BoundaryCondition<2>::Type::traction, select_box(domain, right),
       [&](const Vec2& x, const Vec2& n, double) { return exact.traction(x, n); }, "right"}};
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

/// The linear and quadratic fields of one part (steel everywhere) across the domain's ties:
/// both schemes, the given clouds and rules, each to 1e-10.
void check_one_part_fields(const Domain& tied, std::initializer_list<CloudKind> kinds,
                           std::initializer_list<SupportRule> rules) {
  Mat2 g, h0, h1;
  g << 1e-3, 2e-3, -0.5e-3, 1.5e-3;
  h0 << 0.8e-3, -0.3e-3, -0.3e-3, 0.5e-3;
  h1 << -0.4e-3, 0.6e-3, 0.6e-3, 1.1e-3;
  for (const QuadratureScheme scheme : {QuadratureScheme::gauss_cells, QuadratureScheme::projected})
    for (const CloudKind kind : kinds)
      for (const SupportRule rule : rules) {
        const double linear = tied_patch_error(tied, {steel, {}}, linear_field(Vec2(0.01, -0.02), g, steel),
                                               kind, RKOrder::linear, rule, scheme);
        const double quadratic =
            tied_patch_error(tied, {steel, {}}, quadratic_field(Vec2(0.01, -0.02), g, h0, h1, steel), kind,
                             RKOrder::quadratic, rule, scheme);
        CAPTURE(to_string(scheme), to_string(kind), to_string(rule), linear, quadratic);
        CHECK(linear < 1e-10);
        CHECK(quadratic < 1e-10);
      }
}

/// The default discretisation of a domain at spacing h.
Discretisation<2> discretised(const Domain& domain, double h) {
  ElasticitySettings es;
  es.nodes.spacing = h;
  StageTimer timer;
  return discretise(domain, es, timer);
}

/// The model of p on it, with the discretisation's test gradients (VCI with Gauss cells).
TotalLagrangian<2> model_on(const SolidProblem<2>& p, const Domain& domain, const Discretisation<2>& disc) {
  return TotalLagrangian<2>(p, domain, disc.node_count(), disc.quadrature, disc.test(), disc.boundary,
                            disc.at_boundary);
}

}  // namespace

TEST_CASE("two parts tied along a kinked edge reproduce linear and quadratic fields of one part",
          "[galerkin][regions][heavy]") {
  const Domain tied = two_parts(true);
  REQUIRE(tied.cracks().size() == 1);
  CHECK(tied.cracks()[0].name == "left/right");
  check_one_part_fields(tied, {CloudKind::lattice, CloudKind::perturbed, CloudKind::random},
                        {SupportRule::geodesic, SupportRule::visibility});
}

TEST_CASE("an inclusion tied round its closed interface reproduces linear and quadratic fields of one part",
          "[galerkin][regions][heavy]") {
  const Domain tied = with_inclusion();
  REQUIRE(tied.cracks().size() == 1);
  const Crack& loop = tied.cracks()[0];
  CHECK(loop.name == "matrix/inclusion");
  CHECK(loop.closed());
  CHECK(loop.points.size() == 7);
  CHECK(!loop.tip[0]);
  CHECK(!loop.tip[1]);
  check_one_part_fields(tied, {CloudKind::lattice, CloudKind::perturbed, CloudKind::random},
                        {SupportRule::geodesic, SupportRule::visibility});
}

TEST_CASE("an interface ending at the union's re-entrant corner: tied parts reproduce fields of one part",
          "[galerkin][regions]") {
  const Domain tied = l_of_two_parts();
  REQUIRE(tied.cracks().size() == 1);
  CHECK(!tied.cracks()[0].tip[0]);
  CHECK(!tied.cracks()[0].tip[1]);
  check_one_part_fields(tied, {CloudKind::lattice, CloudKind::perturbed}, {SupportRule::geodesic});
}

TEST_CASE(
    "a bimaterial tied at its interface reproduces the piecewise-linear field; a smooth approximation does "
    "not",
    "[galerkin][regions]") {
  // Left (steel) gradient G1; right (resin) gradient G2 with the same du/dy (continuity along
  // x = 1) and the same traction sigma e_x: two equations for dux/dx, duy/dx of G2.
  Mat2 g1;
  g1 << 1e-3, 0.4e-3, -0.3e-3, -0.2e-3;
  const auto voigt = [](const Mat2& g) { return Eigen::Vector3d(g(0, 0), g(1, 1), g(0, 1) + g(1, 0)); };
  const Eigen::Vector3d s1 = steel.voigt_tangent() * voigt(g1);
  const Eigen::Matrix3d d2 = resin.voigt_tangent();
  // sigma_xx = d2(0,0) a + d2(0,1) g1(1,1) + d2(0,2) (g1(0,1) + c), sigma_xy likewise, with
  // a = dux/dx and c = duy/dx on the right.
  Eigen::Matrix2d m;
  m << d2(0, 0), d2(0, 2), d2(2, 0), d2(2, 2);
  const Eigen::Vector2d rhs(s1[0] - d2(0, 1) * g1(1, 1) - d2(0, 2) * g1(0, 1),
                            s1[2] - d2(2, 1) * g1(1, 1) - d2(2, 2) * g1(0, 1));
  const Eigen::Vector2d ac = m.lu().solve(rhs);
  Mat2 g2 = g1;
  g2(0, 0) = ac[0];
  g2(1, 0) = ac[1];
  const Vec2 a(0.01, -0.02);
  ExactElasticity exact;
  exact.displacement = [=](const Vec2& x) -> Vec2 {
    const Vec2 at_interface = a + g1 * Vec2(1.0, x.y());
    return x.x() <= 1.0 ? Vec2(a + g1 * x) : Vec2(at_interface + g2 * Vec2(x.x() - 1.0, 0.0));
  };
  exact.stress = [=](const Vec2& x) -> Eigen::Vector3d {
    return x.x() <= 1.0 ? s1 : Eigen::Vector3d(resin.voigt_tangent() * voigt(g2));
  };
  exact.body_force = [](const Vec2&) { return Vec2::Zero(); };
  REQUIRE((g2 - g1).norm() > 0.5 * g1.norm());  // the strain jumps

  const Domain tied = bimaterial(true), smooth = bimaterial(false);
  for (const QuadratureScheme scheme : {QuadratureScheme::gauss_cells, QuadratureScheme::projected})
    for (const CloudKind kind : {CloudKind::lattice, CloudKind::perturbed}) {
      CAPTURE(to_string(scheme), to_string(kind));
      CHECK(tied_patch_error(tied, {steel, {steel, resin}}, exact, kind, RKOrder::linear, SupportRule::geodesic,
                             scheme) < 1e-10);
      CHECK(tied_patch_error(smooth, {steel, {steel, resin}}, exact, kind, RKOrder::linear, SupportRule::geodesic,
                             scheme) > 1e-4);
    }
}

TEST_CASE("two layers under their weight: quadratic RK tied at the interface reproduces the kinked field",
          "[galerkin][regions]") {
  // sigma_yy = rho g (1 - y), sigma_xx = sigma_xy = 0 in both layers (plane stress, lateral
  // edges free); with nu / E equal in the layers the field is continuous:
  //   u_x = -(nu / E) sigma_yy x,  u_y = int_0^y sigma_yy / E - (nu rho g / (2 E)) x^2,
  // quadratic in each layer, its strain eps_yy jumping at y = 1/2 (E differs 4 x).
  const LinearElastic lower{1000.0, 0.3, PlaneModel::stress}, upper{250.0, 0.075, PlaneModel::stress};
  const double rho_g = 2.0;
  const auto law = [&](double y) -> const LinearElastic& { return y <= 0.5 ? lower : upper; };
  const auto uy_axis = [&](double y) {  // int_0^y rho g (1 - s) / E(s) ds
    const auto part = [&](double a, double b, double e) {
      return rho_g * ((b - a) - 0.5 * (b * b - a * a)) / e;
    };
    return y <= 0.5 ? part(0, y, 1000.0) : part(0, 0.5, 1000.0) + part(0.5, y, 250.0);
  };
  ExactElasticity exact;
  exact.displacement = [&](const Vec2& x) -> Vec2 {
    const LinearElastic& m = law(x.y());
    const double s = rho_g * (1 - x.y()), k = m.poisson_ratio / m.youngs_modulus;
    return {-k * s * x.x(), uy_axis(x.y()) - 0.5 * k * rho_g * x.x() * x.x()};
  };
  exact.stress = [&](const Vec2& x) -> Eigen::Vector3d { return {0.0, rho_g * (1 - x.y()), 0.0}; };
  exact.body_force = [&](const Vec2&) { return Vec2(0.0, rho_g); };  // div sigma + b = 0
  const std::vector<std::vector<Ring>> layers{{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 0.5), Vec2(0, 0.5)}},
                                              {{Vec2(0, 0.5), Vec2(1, 0.5), Vec2(1, 1), Vec2(0, 1)}}};
  for (const bool tied : {true, false}) {
    const Domain d = Domain::from_regions(layers, {{"lower", "upper"}, tied}, "layers");
    const double e = tied_patch_error(d, {lower, {lower, upper}}, exact, CloudKind::lattice,
                                      RKOrder::quadratic, SupportRule::geodesic);
    INFO((tied ? "tied " : "smooth ") << e);
    CHECK((tied ? e < 1e-10 : e > 1e-4));
  }
}

TEST_CASE("supports end at a curved interface: no function of one layer is nonzero in the other",
          "[galerkin][regions][heavy]") {
  // The two-layer cylinder's interface, r = 1.5 in 768 pieces: a path bending at one of its
  // vertices itself (not on its reflex face) passed from one layer to the other.
  const Domain d = Domain::from_file(testing::source_dir() +
                                     "/verification/two-material-cylinder/two_layer_cylinder_768.geo");
  REQUIRE(d.regions().size() == 2);
  // Geodesic supports (the rule that bends paths at corners), linear RK at h = 0.05, where
  // 1444 of 3622 values leaked before.
  ElasticitySettings s;
  s.nodes.kind = CloudKind::lattice;
  s.nodes.spacing = 0.05;
  s.support_factor = 2.5;
  StageTimer timer;
  const Discretisation<2> disc = discretise(d, s, timer);
  int leaks = 0, checked = 0;
  for (double t = 0.005; t < 1.57; t += 0.02)
    for (double r : {1.45, 1.49, 1.4999, 1.5001, 1.51, 1.55}) {
      const Vec2 x(r * std::cos(t), r * std::sin(t));
      const GalerkinQuadrature<2> at = sample_shape_functions(*disc.trial, {x}, false);
      for (Index k = at.row_begin(0); k < at.row_end(0); ++k, ++checked)
        if (at.phi[k] != 0.0 && d.region_at(disc.nodes[at.nodes[k]]) != d.region_at(x)) ++leaks;
    }
  CAPTURE(checked);
  CHECK(checked > 2000);
  CHECK(leaks == 0);
}

TEST_CASE(
    "a J2 layer tied to an elastic one: uniaxial strain follows the material point at every point, ties "
    "included",
    "[galerkin][regions][plasticity]") {
  // Plane-strain uniaxial compression of two layers (J2 below y = 0.5, a stiffer elastic law
  // above), slip on the left, right and bottom, the top pressed down by f delta. Each layer
  // strains uniformly, u_y = -eps_1 y below and -(eps_1 / 2 + eps_2 (y - 1/2)) above, with
  // eps_1 / 2 + eps_2 / 2 = f delta and P_yy equal across the tie: piecewise linear, so the
  // tie (split nodes) holds it exactly, and every quadrature, Nitsche and tie point of the
  // J2 layer must follow the material point's path through the load factors, which it does
  // only if the tie's faces carry their committed states.
  const std::vector<std::vector<Ring>> parts{{{Vec2(0, 0), Vec2(1, 0), Vec2(1, 0.5), Vec2(0, 0.5)}},
                                             {{Vec2(0, 0.5), Vec2(1, 0.5), Vec2(1, 1), Vec2(0, 1)}}};
  const Domain domain = Domain::from_regions(parts, {{"soft", "stiff"}, true}, "layers");
  const Discretisation<2> disc = discretised(domain, 0.125);
  J2Plasticity j2;
  j2.lame = lame_constants(1000.0, 0.3);
  j2.yield_stress = 5.0;
  j2.isotropic_modulus = 100.0;
  const LinearElastic stiff{4000.0, 0.25, PlaneModel::strain};
  const double delta = 0.04;  // the J2 layer strains about 14 times its yield strain
  SolidProblem<2> p;
  p.region_materials = {j2, stiff};
  p.spacing = 0.125;
  const auto zero = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); };
  const auto edge = [&](Vec2 lo, Vec2 hi) { return select_box(domain, Box{lo, hi}); };
  p.conditions = {{BoundaryCondition<2>::Type::displacement, edge(Vec2(-0.1, 0.99), Vec2(1.1, 1.1)),
                   [delta](const Vec2&, const Vec2&, double) { return Vec2(0.0, -delta); }, "top"},
                  {BoundaryCondition<2>::Type::slip, edge(Vec2(-0.1, -0.1), Vec2(1.1, 0.01)), zero, "bottom"},
                  {BoundaryCondition<2>::Type::slip, edge(Vec2(-0.1, 0.01), Vec2(0.01, 0.99)), zero, "left"},
                  {BoundaryCondition<2>::Type::slip, edge(Vec2(0.99, 0.01), Vec2(1.1, 0.99)), zero, "right"}};
  TotalLagrangian<2> model(p, domain, disc.node_count(), disc.quadrature, disc.test(), disc.boundary,
                           disc.at_boundary);
  REQUIRE(model.has_history());
  NewtonSettings s;
  s.load_factors = {0.1, 0.25, 0.5, 0.75, 1.0};
  s.tolerance = 1e-12;
  StageTimer timer;
  const StaticSolution sol = solve_static(model, {}, s, timer);

  // The exact path: at each factor the strain split that balances P_yy (bisection), the
  // J2 point committed after each.
  const auto uniaxial = [](double eps) { return Mat2(Eigen::Vector2d(1.0, 1.0 - eps).asDiagonal()); };
  MaterialState<2> point;
  MaterialUpdate<2> last;
  double eps1 = 0.0;
  for (const double f : s.load_factors) {
    double lo = 0.0, hi = 2.0 * f * delta;
    for (int it = 0; it < 200; ++it) {
      eps1 = 0.5 * (lo + hi);
      const double gap = update(Material(j2), uniaxial(eps1), point, false).stress(1, 1) -
                         stress(Material(stiff), uniaxial(2.0 * f * delta - eps1))(1, 1);
      (gap > 0.0 ? lo : hi) = eps1;
    }
    last = update(Material(j2), uniaxial(eps1), point, false);
    point = last.state;
  }
  REQUIRE(point.alpha > 0.02);
  const double eps2 = 2.0 * delta - eps1;
  double worst_u = 0.0;
  for (std::size_t i = 0; i < disc.nodes.size(); ++i) {
    const double y = disc.nodes[i].y();
    const double uy = y <= 0.5 ? -eps1 * y : -(0.5 * eps1 + eps2 * (y - 0.5));
    worst_u =
        std::max(worst_u, (disc.displacement({disc.nodes[i]}, sol.coefficients)[0] - Vec2(0.0, uy)).norm());
  }
  double worst_alpha = 0.0;
  int soft_points = 0;
  for (Index k = 0; k < disc.quadrature.size(); ++k) {
    if (disc.quadrature.points[k].y() > 0.5) continue;
    ++soft_points;
    worst_alpha =
        std::max(worst_alpha, std::abs(model.response(k, sol.coefficients).state.alpha - point.alpha));
  }
  // Boundary states: the Nitsche points', then two faces per tie point, one of each layer.
  const std::vector<MaterialState<2>>& faces = model.history().boundary;
  const std::size_t ties = (faces.size() - model.nitsche_points()) / 2;
  std::size_t plastic_faces = 0;
  for (std::size_t b = 0; b < faces.size(); ++b) {
    if (faces[b].alpha == 0.0) continue;
    plastic_faces += b >= model.nitsche_points();
    worst_alpha = std::max(worst_alpha, std::abs(faces[b].alpha - point.alpha));
  }
  CAPTURE(eps1, eps2, point.alpha, soft_points, ties, plastic_faces);
  CHECK(worst_u <= 1e-10 * delta);
  CHECK(worst_alpha <= 1e-8 * point.alpha);
  CHECK(ties >= 8);
  CHECK(plastic_faces == ties);
}

TEST_CASE("Nitsche's penalty is beta M / h with M the P-wave modulus of the law at the point",
          "[galerkin][regions]") {
  // M = lambda + 2 mu in plane strain, E / (1 - nu^2) in plane stress: the stiffness of the
  // tractions the penalty must dominate, of the point's own law (near incompressibility
  // lambda / mu = 4999 on the left: scaled by E the penalty would fall below them).
  const double e = 3e7, nu = 0.4999;
  const LinearElastic rubber{e, nu, PlaneModel::strain};
  const LinearElastic sheet{2e5, 0.3, PlaneModel::stress};
  const Domain domain = bimaterial(true);
  const Discretisation<2> disc = discretised(domain, 0.25);
  SolidProblem<2> p;
  p.region_materials = {rubber, sheet};
  p.spacing = 0.25;
  p.nitsche_beta = 50.0;
  const auto zero = [](const Vec2&, const Vec2&, double) { return Vec2(0.0, 0.0); };
  p.conditions = {
      {BoundaryCondition<2>::Type::displacement, select_box(domain, Box{Vec2(-1, -1), Vec2(0.01, 2)}), zero,
       "left"},
      {BoundaryCondition<2>::Type::slip, select_box(domain, Box{Vec2(1.99, -1), Vec2(3, 2)}), zero, "right"}};
  const TotalLagrangian<2> model = model_on(p, domain, disc);
  const double lambda = e * nu / ((1 + nu) * (1 - nu * 2)), mu = e / (2 * (1 + nu));
  const Eigen::VectorXd d = Eigen::VectorXd::Zero(model.dofs());
  REQUIRE(model.nitsche_points() > 4);
  for (std::size_t b = 0; b < model.nitsche_points(); ++b) {
    const TotalLagrangian<2>::NitscheValues v = model.nitsche_values(b, d, {});
    const bool left = v.condition->name == "left";
    const double m = left ? lambda + 2 * mu : 2e5 / (1 - 0.3 * 0.3);
    CHECK(v.penalty == Approx(50.0 * m / 0.25).epsilon(1e-12));
  }
}

TEST_CASE("the mass of two regions: rho0 of each region, summed over the nodes to rho1 A1 + rho2 A2",
          "[galerkin][regions][dynamics]") {
  const Domain domain = bimaterial(true);  // two unit squares
  const Discretisation<2> disc = discretised(domain, 0.125);
  SolidProblem<2> p;
  p.region_materials = {steel, resin};
  p.region_densities = {7800.0, 1200.0};
  p.spacing = 0.125;
  const TotalLagrangian<2> model = model_on(p, domain, disc);
  const Eigen::VectorXd lumped = model.lumped_mass(disc.nodes);
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(model.dofs());
  // Per direction: sum_I m_I = sum_K w_K rho0_K (the functions sum to one).
  CHECK(lumped.sum() == Approx(2.0 * (7800.0 + 1200.0)).epsilon(1e-12));
  CHECK(ones.dot(model.mass_matrix() * ones) == Approx(2.0 * (7800.0 + 1200.0)).epsilon(1e-12));
  p.region_densities = {7800.0, 0.0};
  const TotalLagrangian<2> without = model_on(p, domain, disc);
  CHECK_THAT(mfree::testing::message_of<InputError>([&] { (void)without.mass_matrix(); }),
             Catch::Contains("region 1 has 0"));
}
