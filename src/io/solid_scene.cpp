#include "mfree/io/solid_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <numbers>

#include "mfree/core/error.hpp"
#include "mfree/galerkin/small_strain_errors.hpp"
#include "mfree/geometry/boundary_selection.hpp"
#include "mfree/geometry/gmsh_solid.hpp"
#include "mfree/io/elasticity_sections.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/io/scene_sections.hpp"
#include "mfree/materials/finite_strain.hpp"
#include "mfree/problems/axis_aligned_vibration.hpp"

namespace mfree {

namespace {

using ConditionType = BoundaryCondition<3>::Type;
const NameTable<ConditionType>& condition_table = condition_types<3>();

/// check_static of each component.
void check_static(const SceneTable& t, const std::string& key, const SpaceVectorFormula& f, bool dynamics) {
  for (const Formula* c : {&f.x, &f.y, &f.z}) check_static(t, key, *c, dynamics);
}

std::string box_text(const AlignedBox<3>& b) {
  return fmt::format("[[{}, {}, {}], [{}, {}, {}]]", b.min().x(), b.min().y(), b.min().z(), b.max().x(),
                     b.max().y(), b.max().z());
}

/// The Lamé constants of a linear law.
Lame lame_of(const Material& law) {
  const auto& linear = std::get<LinearElastic>(law);
  return lame_constants(linear.youngs_modulus, linear.poisson_ratio);
}

/// The region of x in `solid` (0 for a solid of one region), for values that outlive the
/// scene: a solid of several regions is kept as a copy.
std::function<std::size_t(const Point<3>&)> region_of(const Solid& solid) {
  if (solid.regions().size() < 2) return [](const Point<3>&) { return std::size_t{0}; };
  return [copy = std::make_shared<const Solid>(solid)](const Point<3>& x) {
    return static_cast<std::size_t>(std::max(0, copy->region_at(x)));
  };
}

/// The selector of a [[boundary]] table: part or region.
BoundarySelection<3> read_selection(const SceneTable& t, const Solid& solid, std::string& key,
                                    std::string& what) {
  if (t.has("part") == t.has("region")) t.error("name", "give exactly one selector: part or region");
  try {
    if (t.has("part")) {
      key = "part";
      what = fmt::format("part '{}'", t.string("part"));
      return select_part(solid, t.string("part"));
    }
    key = "region";
    const AlignedBox<3> b = read_space_box(t, "region");
    what = "region " + box_text(b);
    return select_box(solid, b);
  } catch (const InputError& e) {
    t.error(key, e.what());
  }
}

/// A region drawn round a face (thin across it) also clips strips off the faces it crosses
/// edge-on: a condition meant for the face would hold on them too (a traction along a side, a
/// clamp on a strip of it). Refused when the box, inside the solid's bounding box, is thinner
/// than 5 % of its largest side along one axis and keeps pieces of triangles turned more than
/// 10 degrees from that axis; allow_small_selection = true lifts it.
void check_slivers(const SceneTable& t, const std::string& what, const BoundarySelection<3>& selected,
                   const std::optional<AlignedBox<3>>& region, const Solid& solid) {
  if (!region) {
    if (t.has("allow_small_selection"))
      t.error("allow_small_selection", "applies to conditions selected by a region");
    return;
  }
  if (t.boolean_or("allow_small_selection", false)) return;
  const AlignedBox<3> inside = region->intersection(solid.bounding_box());
  const Point<3> extent = inside.sizes().cwiseMax(0.0);
  Index axis = 0;
  if (!(extent.minCoeff(&axis) < 0.05 * extent.maxCoeff())) return;
  const double turned = std::cos(10.0 * std::numbers::pi / 180.0);
  double area = 0.0;
  int pieces = 0;
  for (const BoundaryPiece<3>& p : selected) {
    const Point<3> n = solid.surface()[static_cast<std::size_t>(p.triangle)].area_normal().normalized();
    if (std::abs(n[axis]) >= turned) continue;
    area += selection_area(solid, {p});
    ++pieces;
  }
  if (pieces == 0) return;
  t.error("region",
          fmt::format("{} is thin across {} and clips {} piece(s) of area {:.3g} off the faces it crosses "
                      "edge-on, turned from {}: the condition would hold there too. Select the face by its "
                      "part, end the region inside the face, or set allow_small_selection = true",
                      what, "xyz"[axis], pieces, area, "xyz"[axis]));
}

/// The gradient formulas must be the derivatives of the displacement's, or every error measured
/// against them is wrong: at the points of a 6 x 6 x 6 grid over the solid's box that lie in it
/// (with their neighbours at the step), each d u_i / d x_j against a difference of u_i of step
/// 1e-5 of the box's diagonal, central, forward or backward (one of them follows a branch of a
/// formula with a kink), to 1e-3 of the largest gradient entry (or displacement per diagonal).
void check_gradient(const SceneTable& t, const SolidExact& e, const Solid& solid) {
  const AlignedBox<3>& box = solid.bounding_box();
  const double diagonal = box.diagonal().norm(), step = 1e-5 * diagonal;
  std::vector<Point<3>> samples;
  for (int i = 0; i < 6; ++i)
    for (int j = 0; j < 6; ++j)
      for (int k = 0; k < 6; ++k) {
        const Point<3> x = box.min() + box.sizes().cwiseProduct(Point<3>(i + 0.5, j + 0.5, k + 0.5) / 6.0);
        bool inside = solid.contains(x);
        for (int a = 0; a < 3 && inside; ++a)
          inside =
              solid.contains(x + step * Point<3>::Unit(a)) && solid.contains(x - step * Point<3>::Unit(a));
        if (inside) samples.push_back(x);
      }
  double scale = 0.0;
  for (const Point<3>& x : samples)
    scale = std::max(
        {scale, e.gradient_at(x).cwiseAbs().maxCoeff(), e.displacement(x).cwiseAbs().maxCoeff() / diagonal});
  for (const Point<3>& x : samples) {
    const Tensor2<3> g = e.gradient_at(x);
    const Point<3> u = e.displacement(x);
    for (int j = 0; j < 3; ++j) {
      const Point<3> ahead = e.displacement(x + step * Point<3>::Unit(j));
      const Point<3> behind = e.displacement(x - step * Point<3>::Unit(j));
      for (int i = 0; i < 3; ++i) {
        const double central = (ahead[i] - behind[i]) / (2.0 * step);
        const double off =
            std::min({std::abs(central - g(i, j)), std::abs((ahead[i] - u[i]) / step - g(i, j)),
                      std::abs((u[i] - behind[i]) / step - g(i, j))});
        if (off > 1e-3 * scale)
          t.error("gradient",
                  fmt::format("gradient[{}] is not d u_{} / d {} of the displacement's formula: at "
                              "({:.6g}) its difference is {:.6g}, the formula gives {:.6g} (the "
                              "entries run row by row: d u_x / dx, d u_x / dy, d u_x / dz, d u_y / dx, ...)",
                              3 * i + j, "xyz"[i], "xyz"[j], fmt::join(x, ", "), central, g(i, j)));
      }
    }
  }
}

SolidExact read_exact(const SceneTable& t, const Constants& constants, const SolidProblem<3>& problem,
                      const Solid& solid) {
  for (const Material& law : problem.laws())
    if (!std::holds_alternative<LinearElastic>(law))
      t.error("displacement",
              fmt::format("errors against an exact solution are those of the small-strain law: give "
                          "[material] model = \"linear_elastic\", not \"{}\"",
                          name(law)));
  SolidExact e{read_space_vector_formula(t, "displacement", constants), {}};
  check_static(t, "displacement", e.displacement, false);
  const std::vector<std::string> texts = t.expressions("gradient", 9);
  for (std::size_t i = 0; i < texts.size(); ++i) {
    e.gradient.emplace_back(texts[i], constants, t.where("gradient", static_cast<int>(i)), 3);
    check_static(t, "gradient", e.gradient.back(), false);
  }
  check_gradient(t, e, solid);
  t.finish();
  return e;
}

/// [exact] of a dynamics run: a built-in motion (solution = "vibration", amplitude), posed on
/// the cube [0, L]^3 of the scene's Neo-Hookean material and density.
ExactMotion<3> read_motion(const SceneTable& t, const Solid& solid, const MaterialSection& m,
                           std::size_t problem_laws) {
  if (t.has("displacement") || !t.has("solution"))
    t.error(
        t.has("displacement") ? "displacement" : "solution",
        "a [dynamics] run measures its errors against a built-in motion: give solution = \"vibration\" and "
        "its amplitude (formulas for u are for statics)");
  (void)t.choice("solution", {"vibration"});
  const AlignedBox<3>& b = solid.bounding_box();
  const double length = b.sizes().x();
  if (solid.mesh() || b.min().norm() > 1e-12 * length ||
      (b.sizes().array() - length).abs().maxCoeff() > 1e-12 * length)
    t.error("solution", fmt::format("the vibration solution needs the box [[0, 0, 0], [L, L, L]], not {}",
                                    solid.mesh() ? std::string("a meshed solid") : box_text(b)));
  if (problem_laws > 1)
    t.error("solution", "the vibration solution is of one material: give one [material] table");
  if (!std::holds_alternative<NeoHookean>(m.material))
    t.error(
        "solution",
        fmt::format("the vibration solution needs [material] model = \"neo_hookean\", not \"{}\"", m.model));
  if (!(m.density > 0.0)) t.error("solution", "the vibration solution needs the material's density");
  const AxisAlignedVibration a{t.number("amplitude", -1e300, 1e300), length, m.linear.youngs_modulus,
                               m.linear.poisson_ratio, m.density};
  try {
    a.check_amplitude();
  } catch (const InputError& e) {
    t.error("amplitude", e.what());
  }
  t.finish();
  return a.motion<3>();
}

/// [loads]: body_force (formulas in x, y, z), gravity (times the density of the region at x).
BodyForce<3> read_loads(const SceneTable& t, const Constants& constants, const SolidScene& scene,
                        bool dynamics) {
  std::optional<SpaceVectorFormula> force;
  Point<3> gravity = Point<3>::Zero();
  const SolidProblem<3>& problem = scene.problem;
  const double density = problem.density;
  if (t.has("body_force")) {
    force = read_space_vector_formula(t, "body_force", constants);
    check_static(t, "body_force", *force, dynamics);
  }
  if (t.has("gravity")) {
    const auto g = t.numbers("gravity", 3, -1e300, 1e300);
    if (!(density > 0.0)) t.error("gravity", "gravity needs the material's density ([material] density)");
    gravity = Point<3>(g[0], g[1], g[2]);
  }
  if (!t.has("body_force") && !t.has("gravity"))
    t.error("body_force", "give body_force or gravity (or both)");
  t.finish();
  const std::vector<double> densities =
      problem.region_densities.empty() ? std::vector<double>{density} : problem.region_densities;
  return [force, gravity, densities, region = region_of(scene.solid)](const Point<3>& x, double time) {
    const Point<3> weight = densities[region(x)] * gravity;
    return force ? Point<3>((*force)(x, time) + weight) : weight;
  };
}

/// One [[boundary]] table: the condition, its selection checked (no area, slivers, overlaps
/// with the conditions before it), recorded in out.selected.
BoundaryCondition<3> read_condition(const SceneTable& t, SolidScene& out, const Constants& constants,
                                    bool dynamics) {
  BoundaryCondition<3> c;
  c.name = t.string("name");
  c.type = read_choice(t, "type", condition_table);
  std::string key, what;
  c.where = read_selection(t, out.solid, key, what);
  check_slivers(t, what, c.where,
                key == "region" ? read_space_box(t, "region") : std::optional<AlignedBox<3>>(), out.solid);
  const double area = selection_area(out.solid, c.where);
  if (c.where.empty() || !(area > 0.0))
    t.error(key, fmt::format("{} selects no part of the surface (the solid's bounding box is {})", what,
                             box_text(out.solid.bounding_box())));
  for (const BoundaryCondition<3>& other : out.problem.conditions) {
    const double shared = overlap_area(out.solid, c.where, other.where);
    if (shared > 1e-12 * area)
      t.error(key,
              fmt::format("{} overlaps boundary '{}' over an area of {:.6g}: each part of the surface takes "
                          "one condition",
                          what, other.name, shared));
  }
  out.selected.push_back({c.name, condition_table.name(c.type), what, area});
  if (c.type == ConditionType::pressure) {
    const Formula p = read_formula(t, "value", constants, 3);
    check_static(t, "value", p, dynamics);
    c.pressure = [p](const Point<3>& x, double time) { return p(x, time); };
  } else if (t.is_string("value")) {
    (void)t.choice("value", {"exact"});
    if (!out.exact) t.error("value", "'exact' needs an [exact] section");
    const SolidExact ex = *out.exact;
    if (c.type != ConditionType::traction) {
      c.value = [ex](const Point<3>& x, const Point<3>&, double) { return ex.displacement(x); };
    } else {
      // The Lamé constants of each region's law ([exact] takes linear laws only).
      std::vector<Lame> lame;
      for (const Material& law : out.problem.laws()) lame.push_back(lame_of(law));
      c.value = [ex, lame, region = region_of(out.solid)](const Point<3>& x, const Point<3>& n, double) {
        return Point<3>(linear_stress(lame[region(x)], ex.gradient_at(x)) * n);
      };
    }
  } else {
    const SpaceVectorFormula v = read_space_vector_formula(t, "value", constants);
    check_static(t, "value", v, dynamics);
    c.value = [v](const Point<3>& x, const Point<3>&, double time) { return v(x, time); };
  }
  t.finish();
  return c;
}

/// [dynamics]: the time scheme, its step, frames and the initial fields.
SolidDynamics read_dynamics(const SceneTable& t, const Constants& constants, double density,
                            const NewtonSettings& newton, bool motion) {
  SolidDynamics dyn;
  DynamicsSettings& d = dyn.settings;
  d.scheme = read_choice(t, "scheme", time_scheme_names());
  d.end_time = t.number("end_time", 1e-300, 1e300);
  if (t.has("time_step")) d.time_step = t.number("time_step", 1e-300, 1e300);
  if (d.scheme == TimeScheme::newmark && !d.time_step) t.error("scheme", "newmark needs a time_step");
  d.stability_factor = t.number_or("stability_factor", d.stability_factor, 1e-6, 1.0);
  d.energy_every = static_cast<int>(t.integer_or("energy_every", 1, 0, 1 << 30));
  dyn.frames = static_cast<int>(t.integer_or("frames", 0, 0, 100000));
  if (t.has("error_times") && !motion)
    t.error("error_times", "errors are measured against an [exact] motion");
  if (motion) dyn.error_times = read_error_times(t);
  for (const char* key : {"initial_displacement", "initial_velocity"}) {
    if (!t.has(key)) continue;
    if (motion) t.error(key, "the [exact] motion sets the initial state");
    const SpaceVectorFormula f = read_space_vector_formula(t, key, constants);
    if (f.depends_on_time()) t.error(key, "an initial field is a function of x, y and z, not of t");
    (std::string(key) == "initial_velocity" ? dyn.initial_velocity : dyn.initial_displacement) = f;
  }
  if (!(density > 0.0)) t.error("scheme", "dynamics needs the material's density ([material] density)");
  d.newton = newton;
  t.finish();
  return dyn;
}

/// [output]: the folder, the fields, the probe, the checkpoints of a dynamic run.
SolidOutput read_output(const SceneTable& t, const SolidScene& out, bool dynamics, bool study) {
  SolidOutput o;
  o.folder = read_output_folder(t);
  if (t.has("fields") && !t.is_array_empty("fields"))
    for (const auto& f :
         t.choices("fields", {"displacement", "velocity", "stress", "von_mises", "plastic_strain", "error"}))
      o.fields.insert(f);
  if (o.wants("plastic_strain") && !out.problem.any_history())
    t.error("fields",
            fmt::format("'plastic_strain' needs a law with history (j2, drucker_prager), not {}", out.model));
  if (o.wants("error") && !out.exact)
    t.error("fields", out.motion
                          ? "'error' fields are written in statics; a [dynamics] run prints its errors at "
                            "error_times"
                          : "'error' needs an [exact] section");
  if (o.wants("velocity") && !dynamics) t.error("fields", "'velocity' needs a [dynamics] section");
  o.vtk = t.boolean_or("vtk", true);
  if (t.has("probe")) {
    const auto p = t.numbers("probe", 3, -1e300, 1e300);
    o.probe = Point<3>(p[0], p[1], p[2]);
    if (!out.solid.contains(*o.probe)) t.error("probe", "the probe lies outside the solid");
  }
  o.checkpoint_every = static_cast<int>(t.integer_or("checkpoint_every", 0, 0, 1 << 30));
  if (o.checkpoint_every > 0 && !dynamics) t.error("checkpoint_every", "checkpoints are for [dynamics] runs");
  if (o.checkpoint_every > 0 && study)
    t.error("checkpoint_every", "a study is not checkpointed: checkpoints are for one long `mfree run`");
  t.finish();
  return o;
}

/// [study] (mfree converge).
SolidStudy read_study(const SceneTable& t, const SolidScene& out) {
  SolidStudy st;
  st.spacings = t.numbers("spacings", 0, 1e-12, 1e12);
  if (out.dynamics) {
    if (!out.motion)
      t.error("spacings",
              "a study of a [dynamics] run measures errors against an exact motion: give [exact] solution = "
              "\"vibration\"");
    for (const char* key : {"orders", "probe", "quadratic_factor"})
      if (t.has(key))
        t.error(key,
                "a study of a [dynamics] run refines the spacing for each of time_schemes; this key is for "
                "statics");
    st.time = read_time_study(t, &out.dynamics->settings);
    t.finish();
    return st;
  }
  st.time = read_time_study(t, nullptr);
  st.orders =
      t.has("orders") ? read_choices(t, "orders", order_names()) : std::vector<RKOrder>{out.settings.order};
  if (t.has("probe")) {
    const auto p = t.numbers("probe", 3, -1e300, 1e300);
    st.probe = Point<3>(p[0], p[1], p[2]);
    if (!out.solid.contains(*st.probe)) t.error("probe", "the probe lies outside the solid");
  }
  st.quadratic_factor = t.number_or("quadratic_factor", 3.0, 0.5, 10.0);
  t.finish();
  return st;
}

}  // namespace

Solid read_solid_domain(const SceneTable& t) {
  if (t.has("box") == t.has("solid")) t.error("box", "give exactly one of 'box' and 'solid'");
  Solid solid = [&] {
    if (t.has("box")) {
      const AlignedBox<3> b = read_space_box(t, "box");
      if (!(b.max().array() > b.min().array()).all()) t.error("box", "the corners must differ in x, y and z");
      if (t.has("interfaces"))
        t.error("interfaces", "regions are the physical volumes of a gmsh part: a box is one region");
      return Solid::box(b.min(), b.max());
    }
    const bool tied = read_choice_or(t, "interfaces", interface_choices(), true);
    try {
      return read_gmsh_solid(t.folder() / t.string("solid"), default_gmsh_reader_limits(), tied);
    } catch (const InputError& e) {
      t.error("solid", e.what());
    }
  }();
  if (t.has("interfaces") && solid.regions().size() < 2)
    t.error("interfaces", "the solid has one region (the part has fewer than two physical volumes)");
  t.finish();
  return solid;
}

Tensor2<3> SolidExact::gradient_at(const Point<3>& x) const {
  Tensor2<3> g;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) g(i, j) = gradient[static_cast<std::size_t>(3 * i + j)](x);
  return g;
}

bool is_solid_scene(const std::filesystem::path& file) {
  const Scene scene = Scene::load(file);
  const SceneTable root = scene.root();
  if (!root.has("domain")) return false;
  const SceneTable domain = root.table("domain");
  return domain.has("box") || domain.has("solid");
}

/// [material], or [[material]] tables giving the solid's regions (its physical volumes) their
/// laws (tied or bonded: [domain] interfaces); the section of the first region (the one law of a solid of one
/// region) is returned.
MaterialSection read_solid_materials(const SceneTable& root, SolidScene& out) {
  SolidProblem<3>& problem = out.problem;
  const auto read = [](const SceneTable& t) { return read_material_keys(t, 3); };
  if (!root.is_array_of_tables("material")) {
    const MaterialSection m = read(root.table("material"));
    out.model = m.model;
    problem.material = m.material;
    problem.density = m.density;
    return m;
  }
  const std::vector<SceneTable> tables = root.tables("material");
  const std::vector<std::string>& regions = out.solid.regions();
  if (regions.size() < 2)
    tables.front().error("regions",
                         "[[material]] tables give the regions of a solid (the physical volumes of its gmsh "
                         "file) their laws, and this solid has one region: use one [material] table");
  const std::vector<MaterialSection> laws = read_region_materials(tables, regions, read);
  for (const MaterialSection& m : laws) {
    problem.region_materials.push_back(m.material);
    problem.region_densities.push_back(m.density);
    if (out.model.find(m.model) == std::string::npos) out.model += (out.model.empty() ? "" : " + ") + m.model;
  }
  problem.material = problem.region_materials.front();
  problem.density = problem.region_densities.front();
  return laws.front();
}

SolidScene read_solid_scene(const std::filesystem::path& file, bool want_study,
                            const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  const bool dynamics = root.has("dynamics");
  SolidScene out{file, read_solid_domain(root.table("domain")), {}, {}, {}, {}, {}, {}, {}, {}, {}, {}};
  ElasticitySettings& s = out.settings;
  SolidProblem<3>& problem = out.problem;
  read_nodes_section(root.table("nodes"), s);
  read_kernel_section(root.table("kernel"), s, 3);
  read_quadrature_section(root.optional_table("quadrature"), s, 3);
  problem.spacing = s.nodes.spacing;
  const MaterialSection m = read_solid_materials(root, out);
  const Constants constants = read_constants(root);

  if (root.has("exact") && dynamics) {
    out.motion = read_motion(root.table("exact"), out.solid, m, problem.laws().size());
    if (root.has("loads"))
      root.table("loads").error("body_force", "the [exact] motion sets the body force: remove [loads]");
    const ExactMotion<3>& motion = *out.motion;
    problem.body_force = [b = motion.body_force, rho = m.density](const Point<3>& x, double time) {
      return Point<3>(rho * b(x, time));
    };
  } else if (root.has("exact")) {
    out.exact = read_exact(root.table("exact"), constants, problem, out.solid);
  }
  if (root.has("loads")) problem.body_force = read_loads(root.table("loads"), constants, out, dynamics);

  for (const SceneTable& t : root.tables("boundary"))
    problem.conditions.push_back(read_condition(t, out, constants, dynamics));
  if (root.has("nitsche"))
    problem.nitsche_beta = read_nitsche_section(root.table("nitsche"), problem.nitsche_beta);
  if (root.has("solver")) read_solver_section(root.table("solver"), s);
  if (root.has("newton")) {
    out.newton = read_newton_section(root.table("newton"), s.solver);
  } else {
    out.newton.load_steps = 1;
    out.newton.solver = s.solver;
  }
  if (dynamics)
    out.dynamics =
        read_dynamics(root.table("dynamics"), constants, m.density, out.newton, out.motion.has_value());
  out.output = read_output(root.table("output"), out, dynamics, want_study);
  if (want_study || root.has("study")) out.study = read_study(root.table("study"), out);
  root.finish();
  return out;
}

Lame SolidScene::lame_at(const Point<3>& x) const { return lame_of(problem.law_at(solid, x)); }

std::string SolidScene::describe_conditions() const {
  std::string text;
  for (const SelectedSurface& c : selected)
    text += fmt::format("  boundary '{}': {} on {} (area {:.6g})\n", c.name, c.type, c.selector, c.area);
  return text;
}

}  // namespace mfree
