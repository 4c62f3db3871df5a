#include "mfree/io/elasticity_sections.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "mfree/io/read_choice.hpp"

namespace mfree {

namespace {

const NameTable<bool> quadrature_cloud_table{{"lattice", true}, {"like_nodes", false}};

/// auto (the solver the system's symmetry picks), then every solver by name.
const NameTable<std::optional<SolverKind>>& solver_choices() {
  static const NameTable<std::optional<SolverKind>> table = [] {
    std::vector<std::pair<std::string, std::optional<SolverKind>>> e{{"auto", std::nullopt}};
    for (const auto& [name, kind] : solver_kind_names().entries()) e.emplace_back(name, kind);
    return NameTable<std::optional<SolverKind>>(std::move(e));
  }();
  return table;
}

}  // namespace

const NameTable<bool>& interface_choices() {
  static const NameTable<bool> table{{"tied", true}, {"smooth", false}};
  return table;
}

template <int dim>
const NameTable<typename BoundaryCondition<dim>::Type>& condition_types() {
  using Type = typename BoundaryCondition<dim>::Type;
  static const NameTable<Type> table{{"displacement", Type::displacement},
                                     {"slip", Type::slip},
                                     {"traction", Type::traction},
                                     {"pressure", Type::pressure}};
  return table;
}
template const NameTable<BoundaryCondition<2>::Type>& condition_types<2>();
template const NameTable<BoundaryCondition<3>::Type>& condition_types<3>();

void check_static(const SceneTable& t, const std::string& key, const Formula& f, bool dynamics) {
  if (f.depends_on_time() && !dynamics)
    t.error(
        key,
        fmt::format("formula '{}' uses t, but only [dynamics] runs have a time (a static run scales loads by "
                    "its load factor)",
                    f.expression()));
}

void read_nodes_section(const SceneTable& t, ElasticitySettings& s) {
  s.nodes.kind = read_choice(t, "cloud", cloud_kind_names());
  s.nodes.spacing = t.number("spacing", 1e-12, 1e12);
  s.nodes.perturbation = t.number_or("perturbation", 0.3, 0.0, 1.0);
  s.nodes.seed = static_cast<std::uint64_t>(t.integer_or("seed", 1, 0, 1LL << 62));
  t.finish();
}

void read_kernel_section(const SceneTable& t, ElasticitySettings& s, int dimension) {
  s.order = read_choice(t, "order", order_names());
  s.window = read_choice_or(t, "window", window_names(), Window::cubic_bspline);
  s.support = read_choice_or(t, "support", support_names(), SupportShape::circular);
  s.support_factor = t.number_or("factor", s.order == RKOrder::linear ? 2.0 : 3.0, 0.5, 10.0);
  s.irregular_factor_scale = t.number_or("irregular_factor_scale", 1.25, 1.0, 5.0);
  const bool circular = s.support == SupportShape::circular;
  // In a solid the supports are plain unless asked (visibility changes the functions beside
  // every re-entrant edge and hole); plain ones are refused across gaps. Geodesic ones are
  // plane only so far.
  static const NameTable<SupportRule> solid_rules{{"plain", SupportRule::plain},
                                                  {"visibility", SupportRule::visibility}};
  if (dimension == 3 && t.has("support_rule") && t.string("support_rule") == "geodesic")
    t.error("support_rule",
            "geodesic supports are plane only so far: a solid takes \"plain\" or \"visibility\"");
  s.support_rule = dimension == 3
                       ? read_choice_or(t, "support_rule", solid_rules, SupportRule::plain)
                       : read_choice_or(t, "support_rule", support_rule_names(),
                                        circular ? SupportRule::geodesic : SupportRule::visibility);
  s.allow_bridging = t.boolean_or("allow_bridging", false);
  if (s.allow_bridging && s.support_rule != SupportRule::plain)
    t.error("allow_bridging", "applies to support_rule = \"plain\" only: the other rules do not bridge gaps");
  if (s.support_rule == SupportRule::geodesic && !circular)
    t.error("support_rule",
            "geodesic distances need circular supports; tensor supports take \"visibility\" or "
            "\"plain\"");
  t.finish();
}

void read_quadrature_section(const SceneTable& t, ElasticitySettings& s, int dimension) {
  const bool solid = dimension == 3;
  s.scheme = read_choice_or(t, "scheme", scheme_names(),
                            solid ? QuadratureScheme::projected : QuadratureScheme::gauss_cells);
  if (solid && s.scheme != QuadratureScheme::projected)
    t.error("scheme", fmt::format("the {} scheme is plane only so far: a solid takes \"projected\"",
                                  to_string(s.scheme)));
  s.quadrature_ratio = t.number_or("ratio", solid ? 8.0 : 4.0, 1.0, 64.0);
  s.quadrature_lattice = read_choice_or(t, "cloud", quadrature_cloud_table, true);
  // In 3D quadratic RK needs quadrature-cloud functions of its order (with linear ones the
  // cube's L2 error stalls at rate 0.24): the order follows the RK order there.
  s.quadrature_order = read_choice_or(t, "order", order_names(), solid ? s.order : RKOrder::linear);
  if (t.has("factor")) s.quadrature_factor = t.number("factor", 0.5, 10.0);
  s.lattice_refinement = static_cast<int>(t.integer_or("lattice_refinement", 2, 1, 16));
  if (t.has("consistency")) s.consistency = read_choice(t, "consistency", consistency_names());
  if (solid && s.consistency == Consistency::symmetric)
    t.error("consistency",
            "the symmetric correction is plane only so far: a solid takes \"vci\" or \"none\"");
  if (solid && t.has("gauss_points"))
    t.error("gauss_points", "is read by the gauss_cells scheme, which is plane only so far");
  if (t.has("gauss_points")) s.gauss_points = static_cast<int>(t.integer("gauss_points", 1, 12));
  t.finish();
}

double read_nitsche_section(const SceneTable& t, double beta) {
  beta = t.number_or("beta", beta, 1e-6, 1e12);
  t.finish();
  return beta;
}

void read_solver_section(const SceneTable& t, ElasticitySettings& s) {
  SolverSettings& v = s.solver;
  v.kind = read_choice_or(t, "kind", solver_choices(), std::optional<SolverKind>{});
  // Keys the chosen solver would not read are errors, not silently dropped: the Krylov
  // settings with a direct kind, the crossing size with a kind that is fixed.
  if (v.kind && is_direct(*v.kind))
    for (const char* key : {"preconditioner", "tolerance", "max_iterations"})
      if (t.has(key))
        t.error(key, fmt::format("is a setting of the Krylov solvers (cg, gmres, auto), not of kind = \"{}\"",
                                 to_string(*v.kind)));
  // VCI's test gradients differ from the trial ones: its stiffness is not symmetric.
  if (v.kind && (*v.kind == SolverKind::cholmod || *v.kind == SolverKind::cg) &&
      s.consistency.value_or(default_consistency(s.scheme)) == Consistency::vci)
    t.error("kind", fmt::format("\"{}\" needs a symmetric positive definite system; the stiffness of "
                                "consistency = \"vci\" is not symmetric (use {} or auto)",
                                to_string(*v.kind), *v.kind == SolverKind::cg ? "gmres" : "umfpack"));
  if (v.kind && t.has("direct_limit"))
    t.error("direct_limit", "is the size at which kind = \"auto\" turns iterative; kind is not auto");
  if (t.has("preconditioner")) v.preconditioner = read_choice(t, "preconditioner", preconditioner_names());
  v.tolerance = t.number_or("tolerance", v.tolerance, 1e-15, 0.1);
  v.max_iterations = static_cast<int>(t.integer_or("max_iterations", v.max_iterations, 1, 1000000));
  if (t.has("direct_limit")) v.direct_limit = static_cast<Index>(t.integer("direct_limit", 0, 2000000000));
  t.finish();
}

NewtonSettings read_newton_section(const SceneTable& t, const SolverSettings& solver) {
  NewtonSettings n;
  n.tolerance = t.number_or("tolerance", n.tolerance, 1e-16, 1.0);
  n.absolute_tolerance = t.number_or("absolute_tolerance", 0.0, 0.0, 1e300);
  n.max_iterations = static_cast<int>(t.integer_or("max_iterations", n.max_iterations, 1, 1000));
  n.line_search = t.boolean_or("line_search", true);
  if (t.has("load_factors") && t.has("load_steps"))
    t.error("load_factors", "give load_steps or load_factors, not both");
  if (t.has("load_factors")) {
    n.load_factors = t.numbers("load_factors", 0, 1e-300, 1.0);
    for (std::size_t i = 1; i < n.load_factors.size(); ++i)
      if (!(n.load_factors[i] > n.load_factors[i - 1])) t.error("load_factors", "must increase");
    if (n.load_factors.back() != 1.0) t.error("load_factors", "must end at 1 (the full load)");
  }
  n.load_steps = static_cast<int>(t.integer_or("load_steps", n.load_steps, 1, 100000));
  n.max_cutbacks = static_cast<int>(t.integer_or("max_cutbacks", n.max_cutbacks, 0, 50));
  n.solver = solver;
  t.finish();
  return n;
}

TimeStudy read_time_study(const SceneTable& t, const DynamicsSettings* dynamics) {
  TimeStudy time;
  if (t.has("time_schemes")) {
    if (!dynamics) t.error("time_schemes", "needs a [dynamics] section");
    time.schemes = read_choices(t, "time_schemes", time_scheme_names());
  } else if (dynamics) {
    time.schemes = {dynamics->scheme};
  }
  if (t.has("time_steps")) {
    if (!dynamics) t.error("time_steps", "needs a [dynamics] section");
    time.steps = t.numbers("time_steps", time.schemes.size(), 1e-300, 1e300);
  } else if (dynamics) {
    if (!dynamics->time_step &&
        std::find(time.schemes.begin(), time.schemes.end(), TimeScheme::newmark) != time.schemes.end())
      t.error("time_schemes", "newmark needs a time step: give [dynamics] time_step or [study] time_steps");
    time.steps.assign(time.schemes.size(), dynamics->time_step.value_or(0.0));
  }
  if (t.has("time_step_check") && !dynamics) t.error("time_step_check", "needs a [dynamics] section");
  time.step_check = t.boolean_or("time_step_check", false);
  return time;
}

std::vector<double> read_error_times(const SceneTable& t) {
  return t.has("error_times") ? t.numbers("error_times", 0, 0.0, 1.0) : std::vector<double>{1.0};
}

}  // namespace mfree
