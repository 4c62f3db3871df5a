#include "mfree/galerkin/elasticity_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <numbers>

#include "mfree/core/error.hpp"
#include "mfree/core/memory.hpp"
#include "mfree/galerkin/rigid_body_modes.hpp"
#include "mfree/geometry/crack_faces.hpp"
#include "mfree/geometry/interface_faces.hpp"
#include "mfree/geometry/support_obstacles.hpp"
#include "mfree/quadrature/gauss_cells.hpp"
#include "mfree/quadrature/voronoi_weights.hpp"

namespace mfree {

const NameTable<QuadratureScheme>& scheme_names() {
  static const NameTable<QuadratureScheme> table{{"projected", QuadratureScheme::projected}, {"gauss_cells", QuadratureScheme::gauss_cells}, {"nodal", QuadratureScheme::nodal}};
  return table;
}

std::string_view to_string(QuadratureScheme s) { return scheme_names().name(s); }

int default_gauss_points(RKOrder order) { return order == RKOrder::linear ? 3 : 4; }

double default_quadrature_factor(RKOrder quadrature_order, const Domain& domain) {
  return (quadrature_order == RKOrder::linear ? 2.0 : 3.0) + (domain.cracks().empty() ? 0.0 : 0.5);
}

Consistency default_consistency(QuadratureScheme s) {
  switch (s) {
    case QuadratureScheme::projected: return Consistency::symmetric;
    case QuadratureScheme::gauss_cells: return Consistency::vci;
    case QuadratureScheme::nodal: return Consistency::none;
  }
  throw Error("unknown quadrature scheme");
}

template <int dim>
std::vector<Point<dim>> Discretisation<dim>::displacement(const std::vector<Point<dim>>& points,
                                                          const Eigen::VectorXd& d) const {
  const GalerkinQuadrature<dim> at = sample_shape_functions(*trial, points, false);
  std::vector<Point<dim>> u(points.size());
  for (Index k = 0; k < at.size(); ++k) u[k] = displacement_at(at, k, d);
  return u;
}

template struct Discretisation<2>;
template struct Discretisation<3>;

namespace {

/// RK settings for a cloud of nominal spacing h: uniform radius on lattices, node radii
/// reaching across gaps on irregular clouds; on a plane domain, the supports respect its
/// cracks, slots and corners (obstacles for the largest of these radii).
template <int dim>
RKSettings rk_settings(const std::vector<Point<dim>>& points, CloudKind kind, double h, RKOrder order,
                       const ElasticitySettings& s, double factor) {
  RKSettings r;
  r.order = order;
  r.window = s.window;
  r.support = s.support;
  r.radius = factor * h;
  if (kind != CloudKind::lattice) r.node_radii = nodal_support_radii(points, h, factor * s.irregular_factor_scale);
  return r;
}
RKSettings rk_settings(const Domain& domain, const std::vector<Vec2>& points, CloudKind kind, double h,
                       RKOrder order, const ElasticitySettings& s, double factor) {
  RKSettings r = rk_settings<2>(points, kind, h, order, s, factor);
  r.rule = s.support_rule;
  const double reach =
      r.node_radii.empty() ? r.radius : *std::max_element(r.node_radii.begin(), r.node_radii.end());
  r.obstacles = std::make_shared<const SupportObstacles>(support_obstacles(domain, reach));
  return r;
}
/// In a solid the nodes of a lattice next to a surface point whose neighbours lie flat reach
/// further (clouds/point_cloud.hpp: surface_support_radii). For the trial functions, which
/// are evaluated on the surface; the quadrature cloud's functions are evaluated at the
/// lattice points inside, and widening them near the surface made a weight negative (Lamé's
/// sphere, h = 0.4).
/// In a solid, under the visibility rule, the obstacles of its surface for supports of the
/// settings' radii (a wider reach only adds triangles no segment within a support can cross
/// without leaving the solid); with tied interfaces, the regions as separate bodies (a node
/// reaches the points of its own region only).
RKSettings with_visibility(RKSettings r, const Solid& solid, const ElasticitySettings& s) {
  if (!solid.interfaces().empty() && !r.region_of)
    r.region_of = [copy = std::make_shared<const Solid>(solid)](const Point<3>& x) {
      return copy->region_at(x);
    };
  if (s.support_rule != SupportRule::visibility) return r;
  r.rule = SupportRule::visibility;
  const double largest =
      r.node_radii.empty() ? r.radius : *std::max_element(r.node_radii.begin(), r.node_radii.end());
  if (!r.surface_obstacles)
    r.surface_obstacles = std::make_shared<const SurfaceObstacles>(
        support_obstacles(solid, support_reach(r.support, largest, 3)));
  return r;
}
RKSettings rk_settings(const Solid& solid, const std::vector<Point<3>>& points, CloudKind kind, double h,
                       RKOrder order, const ElasticitySettings& s, double factor) {
  RKSettings r = rk_settings<3>(points, kind, h, order, s, factor);
  if (kind != CloudKind::lattice) return with_visibility(std::move(r), solid, s);
  // The widest radius surface_support_radii gives, and which nodes those supports reach.
  const double wide = support_reach(r.support, (factor + 0.5) * h, 3);
  std::optional<SurfaceVisibility> visibility;
  if (s.support_rule == SupportRule::visibility) {
    r.surface_obstacles = std::make_shared<const SurfaceObstacles>(support_obstacles(solid, wide));
    if (!r.surface_obstacles->empty()) visibility.emplace(*r.surface_obstacles, wide);
  }
  std::vector<int> region;
  if (!solid.interfaces().empty()) {
    region.resize(points.size());
    parallel_blocks(static_cast<Index>(points.size()), 1024, [&](Index b, Index e) {
      for (Index i = b; i < e; ++i)
        region[static_cast<std::size_t>(i)] = solid.region_at(points[static_cast<std::size_t>(i)]);
    });
  }
  std::function<void(const Point<3>&, std::vector<Index>&)> unseen;
  if (visibility || !region.empty())
    unseen = [&](const Point<3>& x, std::vector<Index>& near) {
      if (const int r_x = region.empty() ? -1 : solid.region_at(x); r_x >= 0)
        std::erase_if(near, [&](Index i) { return region[static_cast<std::size_t>(i)] != r_x; });
      VisibilityScratch scratch;
      if (!visibility || !visibility->prepare(x, scratch)) return;
      std::erase_if(near, [&](Index i) {
        return !visibility->visible(points[static_cast<std::size_t>(i)], 0.0, x, scratch);
      });
    };
  r.node_radii = surface_support_radii(solid, points, h, factor, order == RKOrder::linear ? 1 : 2, unseen);
  return with_visibility(std::move(r), solid, s);
}

/// A lower bound of the bytes a discretisation takes in dim dimensions, from the node count
/// N = |Omega| / h^dim and the supports (radius f h holds about |B_f| nodes, the ball's volume:
/// pi f^2, 4/3 pi f^3): the quadrature rows (ratio N points, |B_f| nodes each, value, gradient
/// and index: 12 + 8 dim bytes), for the projected scheme the lattice rows of the quadrature
/// cloud's functions (ratio r^dim N lattice points, r the lattice refinement, |B_fq|
/// quadrature points each), and the stiffness matrix (dim N rows, dim |B_2f| entries each, 12
/// bytes), without the factorisation's fill. In the plane, with the defaults, that is 9.5 kB a
/// node; the measured peak is 21-44 kB a node (unit square, spacings 0.01 to 0.002: 0.45 GB
/// for 10^4 nodes, 5.3 GB for 2.5 10^5).
template <int dim>
double memory_lower_bound(double measure, const ElasticitySettings& s, double quadrature_factor) {
  const double n = measure / std::pow(s.nodes.spacing, dim);
  const double f = s.support_factor, pi = std::numbers::pi;
  const auto ball = [&](double r) { return dim == 2 ? pi * r * r : 4.0 / 3.0 * pi * r * r * r; };
  const double row = 12.0 + 8.0 * dim;
  const double lattice =
      s.scheme == QuadratureScheme::projected
          ? s.quadrature_ratio * std::pow(s.lattice_refinement, dim) * ball(quadrature_factor) * row
          : 0.0;
  return n * (8.0 * dim + s.quadrature_ratio * ball(f) * row + lattice + dim * dim * ball(2.0 * f) * 12.0);
}

/// Plain supports must not join material across a gap (a slot, a thin cavity): the place,
/// and what to change, in an InputError.
void refuse_bridges(const std::vector<Vec2>& nodes, const std::vector<Vec2>& points,
                    const SupportObstacles& obstacles, double radius) {
  const std::optional<Bridge> b = find_bridge(nodes, points, obstacles, radius);
  if (!b) return;
  throw InputError(fmt::format(
      "plain supports of radius {:.4g} join material across a gap near ({:.6g}, {:.6g}): the node at "
      "({:.6g}, {:.6g}) "
      "reaches the point ({:.6g}, {:.6g}), {:.4g} away, that is {} away through the domain, so the two sides "
      "would "
      "move together; use support_rule = \"geodesic\" (the default) or \"visibility\", a smaller spacing, or "
      "allow_bridging = true to run it anyway",
      radius, 0.5 * (b->node.x() + b->point.x()), 0.5 * (b->node.y() + b->point.y()), b->node.x(),
      b->node.y(), b->point.x(), b->point.y(), b->straight,
      std::isfinite(b->in_domain) ? fmt::format("{:.4g}", b->in_domain)
                                  : std::string("more than two radii")));
}

/// Plain supports must not join material across a gap of a solid (a slot, a thin cavity,
/// a narrow hole): the place, and what to change, in an InputError.
void refuse_gaps(const Solid& solid, double radius) {
  const std::optional<SurfaceGap> g = find_gap(support_obstacles(solid, radius), radius);
  if (!g) return;
  throw InputError(fmt::format(
      "plain supports of radius {:.4g} join material across a gap near ({:.6g}): the surface at ({:.6g}) "
      "faces the surface at ({:.6g}), {:.4g} away outside the solid, so the two sides would move together; "
      "use support_rule = \"visibility\", a smaller spacing, or allow_bridging = true to run it anyway",
      radius, fmt::join((0.5 * (g->from + g->to)).eval(), ", "), fmt::join(g->from, ", "),
      fmt::join(g->to, ", "), g->width));
}

/// The boundary Gauss points (traction and Nitsche terms, and the consistency target b_I),
/// the trial functions there, and the consistency correction of the settings (or the
/// scheme's default).
template <int dim>
void add_boundary_and_consistency(const DomainOf<dim>& domain, const ElasticitySettings& s,
                                  const std::vector<BoundarySelection<dim>>& parts, Discretisation<dim>& res,
                                  StageTimer& timer) {
  const double h = s.nodes.spacing;
  res.boundary = boundary_quadrature(domain, h, s.order == RKOrder::linear ? 2 : 3, parts);
  res.at_boundary =
      timer.time("boundary functions", [&] { return boundary_functions(*res.trial, res.boundary); });
  const ConsistencyConditions<dim> conditions(res.quadrature, res.nodes, res.at_boundary, res.boundary,
                                              s.order);
  res.consistency_before = conditions.defect(res.quadrature.grad);

  res.consistency = s.consistency.value_or(default_consistency(s.scheme));
  timer.time("consistency", [&] {
    if (res.consistency == Consistency::symmetric) {
      if constexpr (dim == 2) {
        const SymmetricCorrection c = make_consistent_symmetric(
            res.quadrature, res.nodes, conditions.linear_residuals(res.quadrature.grad), s.solver);
        res.correction_residual = c.residual;
        res.correction_solver = c.solver;
        res.consistency_after = conditions.defect(res.quadrature.grad);
      }
    } else if (res.consistency == Consistency::vci) {
      res.test_gradients = conditions.vci_test_gradients();
      res.nearly_symmetric = s.order == RKOrder::linear;
      res.consistency_after = conditions.defect(res.test_gradients);
    } else {
      res.consistency_after = res.consistency_before;
    }
  });
}

}  // namespace

Discretisation<2> discretise(const Domain& domain, const ElasticitySettings& s, StageTimer& timer) {
  Discretisation<2> res;
  const double h = s.nodes.spacing;

  check_memory(
      memory_lower_bound<2>(
          domain.area(), s,
          s.quadrature_factor.value_or(default_quadrature_factor(s.quadrature_order, domain))),
      fmt::format("the discretisation of spacing {:.4g} (about {:.3g} nodes)", h, domain.area() / (h * h)));
  if (!domain.cracks().empty() && s.scheme == QuadratureScheme::nodal)
    throw InputError(
        fmt::format("the nodal scheme does not integrate cracked domains yet (its Voronoi cells do not "
                    "respect cracks): use scheme = \"projected\" or \"gauss_cells\" (domain with crack '{}')",
                    domain.cracks().front().name));
  if (!domain.cracks().empty() && s.support_rule == SupportRule::plain)
    throw InputError(
        fmt::format("crack '{}': plain supports reach across cracks and would join their faces (the crack "
                    "would not open); use support_rule = \"geodesic\" or \"visibility\"",
                    domain.cracks().front().name));
  res.nodes = timer.time("clouds", [&] { return split_on_cracks(domain, make_cloud(domain, s.nodes), h); });
  res.trial = timer.time("shape functions", [&] {
    return std::make_unique<RKShapeFunctions<2>>(
        res.nodes, rk_settings(domain, res.nodes, s.nodes.kind, h, s.order, s, s.support_factor));
  });

  // Quadrature: points, weights, and the gradients of the weak form.
  res.quadrature = timer.time("weights and projection", [&] {
    switch (s.scheme) {
      case QuadratureScheme::projected: {
        CloudSettings qc = s.nodes;
        if (s.quadrature_lattice) qc.kind = CloudKind::lattice;
        const double hq = h / std::sqrt(s.quadrature_ratio);
        const std::vector<Vec2> xq =
            split_on_cracks(domain, make_quadrature_cloud(domain, qc, s.quadrature_ratio), hq);
        const RKShapeFunctions<2> quad(
            xq,
            rk_settings(domain, xq, qc.kind, hq, s.quadrature_order, s,
                        s.quadrature_factor.value_or(default_quadrature_factor(s.quadrature_order, domain))));
        const BackgroundLattice<2> lattice(domain, hq / s.lattice_refinement,
                                           s.quadrature_order == RKOrder::linear ? 1 : 2);
        return projected_quadrature(*res.trial, quad, lattice);
      }
      case QuadratureScheme::gauss_cells:
        return direct_quadrature(
            *res.trial, gauss_cell_rule(domain, h, s.gauss_points.value_or(default_gauss_points(s.order))));
      case QuadratureScheme::nodal:
        return direct_quadrature(*res.trial,
                                 QuadratureRule<2>{res.nodes, voronoi_weights(res.nodes, domain)});
    }
    throw Error("unknown quadrature scheme");
  });

  if (s.support_rule == SupportRule::plain && !s.allow_bridging)
    refuse_bridges(res.nodes, res.quadrature.points, *res.trial->settings().obstacles,
                   res.trial->max_support_radius());

  add_boundary_and_consistency(domain, s, condition_parts(s.problem.conditions), res, timer);
  return res;
}

Discretisation<3> discretise(const Solid& solid, const ElasticitySettings& s,
                             const std::vector<BoundarySelection<3>>& parts, StageTimer& timer) {
  if (s.scheme != QuadratureScheme::projected)
    throw InputError(fmt::format("the {} scheme is plane only so far: use scheme = \"projected\" in 3D",
                                 to_string(s.scheme)));
  if (s.consistency == Consistency::symmetric)
    throw InputError(
        "the symmetric consistency correction is plane only so far: use consistency = \"vci\" in 3D");
  if (s.support_rule == SupportRule::geodesic)
    throw InputError(
        "the geodesic support rule is plane only so far: a solid takes support_rule = \"plain\" or "
        "\"visibility\"");
  const double h = s.nodes.spacing;
  const double quadrature_factor =
      s.quadrature_factor.value_or(s.quadrature_order == RKOrder::linear ? 2.0 : 3.0);
  check_memory(memory_lower_bound<3>(solid.measure(), s, quadrature_factor),
               fmt::format("the discretisation of spacing {:.4g} (about {:.3g} nodes)", h,
                           solid.measure() / (h * h * h)));
  Discretisation<3> res;
  res.nodes = timer.time("clouds", [&] { return split_on_interfaces(solid, make_cloud(solid, s.nodes), h); });
  res.trial = timer.time("shape functions", [&] {
    auto trial = std::make_unique<RKShapeFunctions<3>>(
        res.nodes, rk_settings(solid, res.nodes, s.nodes.kind, h, s.order, s, s.support_factor));
    if (s.support_rule == SupportRule::plain && !s.allow_bridging)
      refuse_gaps(solid, trial->max_support_radius());
    return trial;
  });
  res.quadrature = timer.time("weights and projection", [&] {
    CloudSettings qc = s.nodes;
    if (s.quadrature_lattice) qc.kind = CloudKind::lattice;
    const double hq = h / std::cbrt(s.quadrature_ratio);
    const std::vector<Point<3>> xq =
        split_on_interfaces(solid, make_quadrature_cloud(solid, qc, s.quadrature_ratio), hq);
    const RKShapeFunctions<3> quad(
        xq,
        with_visibility(rk_settings(xq, qc.kind, hq, s.quadrature_order, s, quadrature_factor), solid, s));
    const BackgroundLattice<3> lattice(solid, hq / s.lattice_refinement,
                                       s.quadrature_order == RKOrder::linear ? 1 : 2);
    return projected_quadrature(*res.trial, quad, lattice);
  });
  ElasticitySettings vci = s;
  vci.consistency = s.consistency.value_or(Consistency::vci);
  add_boundary_and_consistency(solid, vci, parts, res, timer);
  return res;
}

ElasticityResult solve_elasticity(const Domain& domain, const ElasticitySettings& s,
                                  const ExactElasticity* exact) {
  ElasticityResult res;
  StageTimer& timer = res.timer;
  timer.report_to(s.progress);
  static_cast<Discretisation<2>&>(res) = discretise(domain, s, timer);

  ElasticityProblem problem = s.problem;
  problem.spacing = s.nodes.spacing;
  const ElasticitySystem sys = timer.time("assembly", [&] {
    return assemble_elasticity(problem, domain, res.node_count(), res.quadrature, res.test(), res.boundary,
                               res.at_boundary);
  });
  check_rigid_body_modes(sys.stiffness, res.nodes);
  res.stiffness_nonzeros = sys.stiffness.nonZeros();
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(
      s.solver, {"stiffness", sys.symmetric, 2, res.nodes, res.nearly_symmetric}, sys.stiffness.rows());
  timer.time("factorisation", [&] {
    solver->analyze(sys.stiffness);
    solver->factorize(sys.stiffness);
  });
  res.coefficients = timer.time("solve", [&] { return solver->solve(sys.load); });
  res.solver = report(*solver);

  if (std::any_of(domain.cracks().begin(), domain.cracks().end(),
                  [](const Crack& c) { return c.tip[0] || c.tip[1]; }))
    res.tips = timer.time("stress intensity", [&] {
      // A crack whose faces carry a condition (a slip face holding a symmetry line) has no K.
      std::vector<std::string> face_conditions(domain.cracks().size());
      for (const BoundaryCondition<2>& c : s.problem.conditions)
        for (const BoundaryPiece<2>& piece : c.where)
          if (const int crack = domain.boundary()[static_cast<std::size_t>(piece.segment)].crack;
              crack >= 0 && face_conditions[static_cast<std::size_t>(crack)].empty())
            face_conditions[static_cast<std::size_t>(crack)] = c.name;
      return crack_tip_intensities(
          domain, *res.trial, res.coefficients,
          [&](const Vec2& x) -> const LinearElastic& { return s.problem.law_at(domain, x); }, s.nodes.spacing,
          face_conditions);
    });
  if (exact) {
    res.errors = timer.time("errors", [&] {
      return elastic_errors(
          *res.trial, res.coefficients,
          [&](const Vec2& x) -> const LinearElastic& { return s.problem.law_at(domain, x); }, *exact,
          gauss_cell_rule(domain, 0.5 * s.nodes.spacing, s.error_gauss_points));
    });
  }
  return res;
}

}  // namespace mfree
