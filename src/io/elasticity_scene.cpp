#include "mfree/io/elasticity_scene.hpp"

#include <algorithm>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/io/scene_sections.hpp"

namespace mfree {

namespace {

CloudKind cloud_kind(const std::string& s) {
  return s == "lattice" ? CloudKind::lattice : s == "perturbed" ? CloudKind::perturbed : CloudKind::random;
}
RKOrder rk_order(const std::string& s) { return s == "linear" ? RKOrder::linear : RKOrder::quadratic; }
QuadratureScheme scheme(const std::string& s) {
  return s == "projected" ? QuadratureScheme::projected
                          : s == "gauss_cells" ? QuadratureScheme::gauss_cells : QuadratureScheme::nodal;
}
const std::vector<std::string> cloud_names{"lattice", "perturbed", "random"};
const std::vector<std::string> order_names{"linear", "quadratic"};
const std::vector<std::string> scheme_names{"projected", "gauss_cells", "nodal"};

}  // namespace

ElasticityScene read_elasticity_scene(const std::filesystem::path& file, bool want_study,
                                      const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  ElasticityScene out{file, Domain::rectangle(Vec2(0, 0), Vec2(1, 1)), {}, {}, 0.0, {}, {}, {}, {}, {}};
  ElasticitySettings& s = out.settings;

  {
    const SceneTable t = root.table("domain");
    if (t.has("rectangle") == t.has("mesh")) t.error("rectangle", "give exactly one of 'rectangle' and 'mesh'");
    if (t.has("rectangle")) {
      const Box b = read_box(t, "rectangle");
      if (!(b.hi.array() > b.lo.array()).all()) t.error("rectangle", "the corners must differ in x and y");
      out.domain = Domain::rectangle(b.lo, b.hi);
    } else {
      out.domain = Domain::from_file(root.folder() / t.string("mesh"));
    }
    t.finish();
  }
  {
    const SceneTable t = root.table("nodes");
    s.nodes.kind = cloud_kind(t.choice("cloud", cloud_names));
    s.nodes.spacing = t.number("spacing", 1e-12, 1e12);
    s.nodes.perturbation = t.number_or("perturbation", 0.3, 0.0, 1.0);
    s.nodes.seed = static_cast<std::uint64_t>(t.integer_or("seed", 1, 0, 1LL << 62));
    t.finish();
  }
  {
    const SceneTable t = root.table("kernel");
    s.order = rk_order(t.choice("order", order_names));
    s.window = t.choice_or("window", "cubic_bspline", {"cubic_bspline", "quadratic_spline"}) == "cubic_bspline"
                   ? Window::cubic_bspline : Window::quadratic_spline;
    s.support = t.choice_or("support", "circular", {"circular", "tensor"}) == "circular" ? SupportShape::circular
                                                                                           : SupportShape::tensor;
    s.support_factor = t.number_or("factor", s.order == RKOrder::linear ? 2.0 : 3.0, 0.5, 10.0);
    s.irregular_factor_scale = t.number_or("irregular_factor_scale", 1.25, 1.0, 5.0);
    t.finish();
  }
  {
    const SceneTable t = root.table("quadrature");
    s.scheme = scheme(t.choice("scheme", scheme_names));
    s.quadrature_ratio = t.number_or("ratio", 4.0, 1.0, 64.0);
    s.quadrature_lattice = t.choice_or("cloud", "lattice", {"lattice", "like_nodes"}) == "lattice";
    s.quadrature_order = rk_order(t.choice_or("order", "linear", order_names));
    s.quadrature_factor = t.number_or("factor", s.quadrature_order == RKOrder::linear ? 2.0 : 3.0, 0.5, 10.0);
    s.lattice_refinement = static_cast<int>(t.integer_or("lattice_refinement", 2, 1, 16));
    const std::string c = t.choice_or("consistency", "symmetric", {"symmetric", "vci", "none"});
    s.consistency = c == "symmetric" ? Consistency::symmetric : c == "vci" ? Consistency::vci : Consistency::none;
    s.gauss_points = static_cast<int>(t.integer_or("gauss_points", s.order == RKOrder::linear ? 4 : 6, 1, 12));
    t.finish();
  }
  {
    const MaterialSection m = read_material(root);
    s.problem.material = m.linear;
    out.material = m.material;
    out.density = m.density;
  }
  if (root.has("exact")) {
    const SceneTable t = root.table("exact");
    ExactSpec e;
    e.solution = t.choice("solution", {"timoshenko_beam", "linear", "quadratic", "vibration"});
    if (e.solution == "timoshenko_beam") {
      e.load = t.number("load", -1e300, 1e300);
    } else if (e.solution == "vibration") {
      e.amplitude = t.number("amplitude", 0.0, 1e300);
      if (!std::holds_alternative<NeoHookean>(out.material)) t.error("solution", "the vibration solution needs [material] model = \"neo_hookean\"");
      if (!(out.density > 0.0)) t.error("solution", "the vibration solution needs [material] density");
    } else {
      const auto a = t.numbers("offset", 2, -1e300, 1e300);
      const auto g = t.pairs("gradient", 2);
      e.offset = Vec2(a[0], a[1]);
      e.gradient << g[0][0], g[0][1], g[1][0], g[1][1];
      if (e.solution == "quadratic") {
        for (int c = 0; c < 2; ++c) {
          const std::string key = c == 0 ? "hessian_x" : "hessian_y";
          const auto h = t.pairs(key, 2);
          if (h[0][1] != h[1][0]) t.error(key, "a Hessian is symmetric: [[a, b], [b, c]]");
          e.hessians[c] << h[0][0], h[0][1], h[1][0], h[1][1];
        }
      }
    }
    t.finish();
    out.exact_spec = e;
  }
  const std::optional<ExactElasticity> exact = out.exact();
  for (const SceneTable& t : root.tables("boundary")) {
    BoundaryCondition c;
    c.name = t.string("name");
    const std::string type = t.choice("type", {"displacement", "slip", "traction"});
    c.type = type == "displacement" ? BoundaryCondition::Type::displacement
             : type == "slip"       ? BoundaryCondition::Type::slip
                                    : BoundaryCondition::Type::traction;
    c.region = read_box(t, "region");
    if (t.is_string("value")) {
      (void)t.choice("value", {"exact"});
      if (!exact) t.error("value", "'exact' needs a static [exact] solution (timoshenko_beam, linear or quadratic)");
      const ExactElasticity ex = *exact;
      if (c.type != BoundaryCondition::Type::traction)
        c.value = [ex](const Vec2& x, const Vec2&) { return ex.displacement(x); };
      else
        c.value = [ex](const Vec2& x, const Vec2& n) { return ex.traction(x, n); };
    } else {
      const auto v = t.numbers("value", 2, -1e300, 1e300);
      const Vec2 value(v[0], v[1]);
      c.value = [value](const Vec2&, const Vec2&) { return value; };
    }
    t.finish();
    s.problem.conditions.push_back(c);
  }
  if (exact) s.problem.body_force = exact->body_force;
  if (root.has("nitsche")) {
    const SceneTable t = root.table("nitsche");
    s.problem.nitsche_beta = t.number_or("beta", s.problem.nitsche_beta, 1e-6, 1e12);
    t.finish();
  }
  if (root.has("solver")) {
    const SceneTable t = root.table("solver");
    const std::string k = t.choice_or("kind", "auto", {"auto", "cholmod", "umfpack"});
    if (k != "auto") s.solver = k == "cholmod" ? SolverKind::cholmod : SolverKind::umfpack;
    t.finish();
  }
  if (root.has("newton")) {
    const SceneTable t = root.table("newton");
    NewtonSettings n;
    n.tolerance = t.number_or("tolerance", n.tolerance, 1e-16, 1.0);
    n.max_iterations = static_cast<int>(t.integer_or("max_iterations", n.max_iterations, 1, 1000));
    n.line_search = t.boolean_or("line_search", true);
    if (t.has("load_factors") && t.has("load_steps")) t.error("load_factors", "give load_steps or load_factors, not both");
    if (t.has("load_factors")) {
      n.load_factors = t.numbers("load_factors", 0, 1e-300, 1.0);
      for (std::size_t i = 1; i < n.load_factors.size(); ++i)
        if (!(n.load_factors[i] > n.load_factors[i - 1])) t.error("load_factors", "must increase");
      if (n.load_factors.back() != 1.0) t.error("load_factors", "must end at 1 (the full load)");
    }
    n.load_steps = static_cast<int>(t.integer_or("load_steps", n.load_steps, 1, 100000));
    n.max_cutbacks = static_cast<int>(t.integer_or("max_cutbacks", n.max_cutbacks, 0, 50));
    t.finish();
    out.newton = n;
  }
  if (root.has("dynamics")) {
    const SceneTable t = root.table("dynamics");
    DynamicsScene dyn;
    DynamicsSettings& d = dyn.settings;
    d.scheme = t.choice("scheme", {"central_difference", "newmark"}) == "newmark" ? TimeScheme::newmark
                                                                                 : TimeScheme::central_difference;
    d.end_time = t.number("end_time", 1e-300, 1e300);
    if (t.has("time_step")) d.time_step = t.number("time_step", 1e-300, 1e300);
    if (d.scheme == TimeScheme::newmark && !d.time_step) t.error("scheme", "newmark needs a time_step");
    d.stability_factor = t.number_or("stability_factor", d.stability_factor, 1e-6, 1.0);
    d.energy_every = static_cast<int>(t.integer_or("energy_every", 1, 0, 1 << 30));
    dyn.frames = static_cast<int>(t.integer_or("frames", 0, 0, 100000));
    dyn.error_times = t.has("error_times") ? t.numbers("error_times", 0, 0.0, 1.0) : std::vector<double>{1.0};
    if (!(out.density > 0.0)) t.error("scheme", "dynamics needs [material] density");
    d.density = out.density;
    if (out.newton) d.newton = *out.newton;
    t.finish();
    out.dynamics = dyn;
  }
  {
    const SceneTable t = root.table("output");
    out.output.folder = t.string("folder");
    // An empty list asks for nothing: no stress recovery, no files.
    if (t.has("fields") && !(t.is_array_empty("fields")))
      for (const auto& f : t.choices("fields", {"displacement", "velocity", "stress", "von_mises", "error", "weights"}))
        out.output.fields.insert(f);
    out.output.vtk = t.boolean_or("vtk", true);
    if (out.output.wants("velocity") && !out.dynamics) t.error("fields", "'velocity' needs a [dynamics] section");
    if (t.has("probe")) {
      const auto p = t.numbers("probe", 2, -1e300, 1e300);
      out.output.probe = Vec2(p[0], p[1]);
    }
    if (out.output.wants("error") && !exact && !out.vibration()) t.error("fields", "'error' needs an [exact] section");
    out.output.eigenvalues = static_cast<int>(t.integer_or("eigenvalues", 0, 0, 100));
    if (out.output.eigenvalues > 0 && out.nonlinear())
      t.error("eigenvalues", "stiffness eigenvalues are for linear statics (no [dynamics] or [newton], a small-strain material)");
    t.finish();
  }
  if (want_study || root.has("study")) {
    const SceneTable t = root.table("study");
    StudySettings st;
    st.spacings = t.numbers("spacings", 0, 1e-12, 1e12);
    // Lists left out take the scene's own value.
    st.clouds = {s.nodes.kind};
    st.orders = {s.order};
    st.schemes = {s.scheme};
    if (t.has("clouds")) {
      st.clouds.clear();
      for (const auto& c : t.choices("clouds", cloud_names)) st.clouds.push_back(cloud_kind(c));
    }
    if (t.has("orders")) {
      st.orders.clear();
      for (const auto& o : t.choices("orders", order_names)) st.orders.push_back(rk_order(o));
    }
    if (t.has("schemes")) {
      st.schemes.clear();
      for (const auto& q : t.choices("schemes", scheme_names)) st.schemes.push_back(scheme(q));
    }
    if (t.has("time_schemes")) {
      if (!out.dynamics) t.error("time_schemes", "needs a [dynamics] section");
      for (const auto& q : t.choices("time_schemes", {"central_difference", "newmark"}))
        st.time_schemes.push_back(q == "newmark" ? TimeScheme::newmark : TimeScheme::central_difference);
    } else if (out.dynamics) {
      st.time_schemes = {out.dynamics->settings.scheme};
    }
    if (t.has("time_steps")) {
      st.time_steps = t.numbers("time_steps", st.time_schemes.size(), 1e-300, 1e300);
    } else if (out.dynamics) {
      if (!out.dynamics->settings.time_step &&
          std::find(st.time_schemes.begin(), st.time_schemes.end(), TimeScheme::newmark) != st.time_schemes.end())
        t.error("time_schemes", "newmark needs a time step: give [dynamics] time_step or [study] time_steps");
      // 0: the explicit scheme's step from its stability limit.
      st.time_steps.assign(st.time_schemes.size(), out.dynamics->settings.time_step.value_or(0.0));
    }
    st.time_step_check = t.boolean_or("time_step_check", false);
    st.betas = t.has("betas") ? t.numbers("betas", 0, 1e-6, 1e12) : std::vector<double>{s.problem.nitsche_beta};
    if (t.has("probe")) {
      const auto p = t.numbers("probe", 2, -1e300, 1e300);
      st.probe = Vec2(p[0], p[1]);
    }
    if (t.has("reference")) st.reference = t.number("reference", -1e300, 1e300);
    st.quadratic_factor = t.number_or("quadratic_factor", 3.0, 0.5, 10.0);
    st.quadratic_gauss_points = static_cast<int>(t.integer_or("quadratic_gauss_points", 6, 1, 12));
    t.finish();
    out.study = st;
  }
  root.finish();
  return out;
}

std::optional<AxisAlignedVibration> ElasticityScene::vibration() const {
  if (!exact_spec || exact_spec->solution != "vibration") return std::nullopt;
  const Box b = domain.bounding_box();
  if (b.lo.norm() > 1e-12 * b.size().norm() || std::abs(b.size().x() - b.size().y()) > 1e-12 * b.size().x())
    throw InputError(fmt::format("{}: the vibration solution needs the square domain [0, L] x [0, L]", file.string()));
  const LinearElastic& m = settings.problem.material;
  return AxisAlignedVibration{exact_spec->amplitude, b.size().x(), m.youngs_modulus, m.poisson_ratio, density};
}

SolidProblem ElasticityScene::solid_problem() const {
  ElasticityProblem linear = settings.problem;
  linear.spacing = settings.nodes.spacing;
  SolidProblem p = mfree::solid_problem(linear);
  p.material = material;
  if (const auto v = vibration())
    p.body_force = [v = *v](const Vec2& x, double t) -> Vec2 { return v.density * v.body_force(x, t); };
  return p;
}

std::optional<ExactElasticity> ElasticityScene::exact() const {
  if (!exact_spec || exact_spec->solution == "vibration") return std::nullopt;
  if (exact_spec->solution == "linear") return linear_field(exact_spec->offset, exact_spec->gradient, settings.problem.material);
  if (exact_spec->solution == "quadratic")
    return quadratic_field(exact_spec->offset, exact_spec->gradient, exact_spec->hessians[0], exact_spec->hessians[1],
                           settings.problem.material);
  const Box b = domain.bounding_box();
  // The beam's axis is y = 0 from x = 0 (SPEC section 4): the domain must be [0, L] x [-D/2, D/2].
  if (std::abs(b.lo.x()) > 1e-12 * b.size().x() || std::abs(b.lo.y() + b.hi.y()) > 1e-12 * b.size().y())
    throw InputError(fmt::format("{}: the timoshenko_beam solution needs the domain [0, L] x [-D/2, D/2]", file.string()));
  return timoshenko_beam(b.size().x(), b.size().y(), exact_spec->load, settings.problem.material);
}

}  // namespace mfree
