#include "mfree/io/elasticity_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <type_traits>

#include "mfree/core/error.hpp"
#include "mfree/io/elasticity_sections.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/io/scene_sections.hpp"

namespace mfree {

namespace {

using ConditionType = BoundaryCondition<2>::Type;
const NameTable<ConditionType>& condition_table = condition_types<2>();

/// The selector keys of a [[boundary]] table: exactly one of part, ring (alone or with
/// edges), edges (of the outer ring) and region.
BoundarySelection<2> read_selection(const SceneTable& t, const Domain& domain, std::string& key,
                                    std::string& what) {
  const int given = t.has("part") + (t.has("ring") || t.has("edges")) + t.has("region");
  if (given != 1) t.error("name", "give exactly one selector: part, ring (with or without edges), edges or region");
  try {
    if (t.has("part")) {
      key = "part";
      what = fmt::format("part '{}'", t.string("part"));
      return select_part(domain, t.string("part"));
    }
    if (t.has("region")) {
      key = "region";
      const Box b = read_box(t, "region");
      what = fmt::format("region [[{}, {}], [{}, {}]]", b.lo.x(), b.lo.y(), b.hi.x(), b.hi.y());
      return select_box(domain, b);
    }
    key = t.has("edges") ? "edges" : "ring";
    const int ring = static_cast<int>(t.integer_or("ring", 0, 0, 1 << 30));
    if (!t.has("edges")) {
      what = ring == 0 ? std::string("the outer ring") : fmt::format("hole {}", ring);
      return select_ring(domain, ring);
    }
    std::vector<int> edges;
    for (const double e : t.numbers("edges", 0, 0, 1 << 30)) {
      if (e != std::floor(e)) t.error("edges", "edge numbers are whole numbers");
      edges.push_back(static_cast<int>(e));
    }
    what = fmt::format("{} edge(s) of ring {}", edges.size(), ring);
    return select_edges(domain, ring, edges);
  } catch (const InputError& e) {
    t.error(key, e.what());
  }
}

/// A region meant for an edge but placed beside it clips slivers of the edges it crosses: a
/// displacement or slip condition there holds the body by almost nothing, and the run solves
/// a problem with a near-free rigid mode without a word. Refused when the selected length is
/// below 1% of the region's longer side inside the domain's bounding box. A region drawn round
/// an edge clips the edges it crosses at its corners (corner_slivers): the condition then acts
/// there too (a slip condition meant for the bottom holds u_x on a stretch of a side), refused
/// for every type of condition. allow_small_selection = true lifts both.
void check_sliver(const SceneTable& t, BoundaryCondition<2>::Type type, const std::string& what,
                  const BoundarySelection<2>& selected, const std::optional<Box>& region,
                  const Domain& domain) {
  constexpr double sliver = 0.01;
  if (!region) {
    if (t.has("allow_small_selection"))
      t.error("allow_small_selection", "applies to conditions selected by a region");
    return;
  }
  if (t.boolean_or("allow_small_selection", false)) return;
  const Box domain_box = domain.bounding_box();
  const std::vector<CornerSliver> corners = corner_slivers(domain, selected);
  if (!corners.empty()) {
    const CornerSliver& c = corners.front();
    const BoundarySegment& g = domain.boundary()[static_cast<std::size_t>(c.piece.segment)];
    t.error("region",
            fmt::format("{} clips {} sliver(s) off the edges it crosses: one of length {:.3g} off the edge "
                        "({:.6g}, {:.6g}) - ({:.6g}, {:.6g}) at the corner ({:.6g}, {:.6g}), where the "
                        "selection turns by {:.0f} degrees; the {} condition would hold there too. End the "
                        "region inside the edge it is meant for, or set allow_small_selection = true",
                        what, corners.size(), c.length, g.a.x(), g.a.y(), g.b.x(), g.b.y(), c.corner.x(),
                        c.corner.y(), c.turn, condition_table.name(type)));
  }
  if (type != ConditionType::displacement && type != ConditionType::slip) return;
  const Vec2 lo = region->lo.cwiseMax(domain_box.lo), hi = region->hi.cwiseMin(domain_box.hi);
  const double extent = (hi - lo).cwiseMax(0.0).maxCoeff();
  const double length = selection_length(domain, selected);
  if (length >= sliver * extent) return;
  t.error("region",
          fmt::format("{} selects a boundary length of {:.3g}, {:.2g}% of the region's extent {:.6g} inside "
                      "the domain's bounding box [[{}, {}], [{}, {}]]: it clips slivers of the edges it "
                      "crosses, and a {} condition on them holds the body by almost nothing; move the region "
                      "onto the edge it is meant for, or set allow_small_selection = true",
                      what, length, 100.0 * length / extent, extent, domain_box.lo.x(), domain_box.lo.y(),
                      domain_box.hi.x(), domain_box.hi.y(), condition_table.name(type)));
}

/// No formula of a static run may use t: it would be evaluated at t = 0 only.
/// [material] or one [[material]]: the law's keys, with the plane-strain bound on Poisson's
/// ratio (allow_locking lifts it).
MaterialSection read_plane_material(const SceneTable& t) {
  const bool allow_locking = t.boolean_or("allow_locking", false);
  const MaterialSection m = read_material_keys(t);
  if (m.linear.model == PlaneModel::strain && m.linear.poisson_ratio > max_poisson_ratio && !allow_locking)
    t.error("poisson_ratio",
            fmt::format(
                "{} is above {}, the largest Poisson's ratio of a plane-strain law this displacement "
                "formulation is trusted with: near incompressibility (lambda / mu = {:.3g}) locks it, and "
                "its stress error grows without bound (the report's stress test 'Near incompressibility'); "
                "use nu <= {} or plane stress (allow_locking = true runs it anyway, for studies of locking)",
                m.linear.poisson_ratio, max_poisson_ratio,
                2 * m.linear.poisson_ratio / (1 - 2 * m.linear.poisson_ratio), max_poisson_ratio));
  return m;
}

/// A [quadrature] key that no scheme of the scene (its own, or its study's) reads is an
/// error, not a setting silently ignored.
void check_scheme_keys(const SceneTable& t, QuadratureScheme scheme, const std::optional<StudySettings>& study) {
  std::vector<QuadratureScheme> used{scheme};
  if (study) used.insert(used.end(), study->schemes.begin(), study->schemes.end());
  const auto uses = [&](QuadratureScheme q) { return std::find(used.begin(), used.end(), q) != used.end(); };
  std::string names;
  for (QuadratureScheme q : used)
    if (names.find(to_string(q)) == std::string::npos) names += (names.empty() ? "" : ", ") + std::string(to_string(q));
  const auto refuse = [&](std::string_view key, QuadratureScheme reader) {
    if (t.has(key) && !uses(reader))
      t.error(key, fmt::format("is read by the {} scheme only, and this scene solves with {}: remove it or choose "
                               "that scheme", to_string(reader), names));
  };
  for (std::string_view key : {"ratio", "cloud", "order", "factor", "lattice_refinement"})
    refuse(key, QuadratureScheme::projected);
  refuse("gauss_points", QuadratureScheme::gauss_cells);
}

/// [domain]: a rectangle, or a WKT or gmsh file (its regions and interfaces).
void read_plane_domain(const SceneTable& root, ElasticityScene& out) {
  const SceneTable t = root.table("domain");
  if (t.has("rectangle") == t.has("mesh")) t.error("rectangle", "give exactly one of 'rectangle' and 'mesh'");
  if (t.has("rectangle")) {
    const Box b = read_box(t, "rectangle");
    if (!(b.hi.array() > b.lo.array()).all()) t.error("rectangle", "the corners must differ in x and y");
    out.domain = Domain::rectangle(b.lo, b.hi);
    for (const char* key : {"regions", "interfaces"})
      if (t.has(key))
        t.error(key, "regions are polygons of a mesh file (WKT or gmsh): a rectangle is one region");
  } else {
    RegionOptions regions;
    if (t.has("regions")) regions.names = t.names("regions");
    regions.interfaces = read_choice_or(t, "interfaces", interface_choices(), true);
    try {
      out.domain = Domain::from_file(root.folder() / t.string("mesh"), regions);
    } catch (const InputError& e) {
      t.error("mesh", e.what());
    }
    if (t.has("interfaces") && out.domain.regions().empty())
      t.error("interfaces", "the domain has one region (the file holds one polygon or one physical surface)");
  }
  t.finish();
}

/// [material], or [[material]] tables giving the regions their laws.
void read_plane_materials(const SceneTable& root, ElasticityScene& out) {
  ElasticitySettings& s = out.settings;
  if (root.is_array_of_tables("material")) {
    // One law per region, each [[material]] naming the regions it fills.
    const std::vector<Region>& regions = out.domain.regions();
    std::vector<std::string> region_names;
    for (const Region& r : regions) region_names.push_back(r.name);
    const std::vector<SceneTable> tables = root.tables("material");
    if (regions.empty())
      tables.front().error("regions",
                           "[[material]] tables give the regions of a domain their laws, and this domain "
                           "has one region: use one [material] table");
    for (const MaterialSection& m : read_region_materials(tables, region_names, read_plane_material)) {
      out.region_materials.push_back(m.material);
      out.region_densities.push_back(m.density);
      s.problem.region_materials.push_back(m.linear);
    }
    s.problem.material = s.problem.region_materials.front();
    out.material = out.region_materials.front();
    out.density = out.region_densities.front();
  } else {
    const MaterialSection m = read_plane_material(root.table("material"));
    s.problem.material = m.linear;
    out.material = m.material;
    out.density = m.density;
  }
}

/// [loads]: body_force (formulas in x, y), gravity (times the density).
void read_loads(const SceneTable& root, ElasticityScene& out) {
  const bool dynamics = root.has("dynamics");
  if (root.has("loads")) {
    const SceneTable t = root.table("loads");
    if (t.has("body_force")) {
      out.body_force = read_vector_formula(t, "body_force", out.constants);
      check_static(t, "body_force", out.body_force->x, dynamics);
      check_static(t, "body_force", out.body_force->y, dynamics);
    }
    if (t.has("gravity")) {
      const auto g = t.numbers("gravity", 2, -1e300, 1e300);
      if (!(out.density > 0.0))
        t.error("gravity",
                "gravity needs the material's density ([material] density, or one in every [[material]])");
      out.gravity = Vec2(g[0], g[1]);
    }
    if (!t.has("body_force") && !t.has("gravity")) t.error("body_force", "give body_force or gravity (or both)");
    t.finish();
  }
}

/// [exact]: a built-in solution, or u with sigma or grad u as formulas.
void read_exact(const SceneTable& root, ElasticityScene& out) {
  const ElasticitySettings& s = out.settings;
  const bool dynamics = root.has("dynamics");
  if (root.has("exact")) {
    const SceneTable t = root.table("exact");
    ExactSpec e;
    if (t.has("solution") == t.has("displacement"))
      t.error("solution", "give a built-in solution, or the exact displacement as formulas (displacement = [ux, uy])");
    if (t.has("displacement")) {
      ExactFormulas f{read_vector_formula(t, "displacement", out.constants), {}, {}};
      if (t.has("stress") == t.has("gradient"))
        t.error("displacement", "give the exact stress = [sxx, syy, sxy] or the displacement gradient = "
                                "[dux/dx, dux/dy, duy/dx, duy/dy] as formulas (one of them)");
      const std::string key = t.has("stress") ? "stress" : "gradient";
      const std::vector<std::string> texts = t.expressions(key, key == "stress" ? 3 : 4);
      std::vector<Formula> parts;
      for (std::size_t i = 0; i < texts.size(); ++i)
        parts.emplace_back(texts[i], out.constants, t.where(key, static_cast<int>(i)));
      (key == "stress" ? f.stress : f.gradient) = std::move(parts);
      if (!dynamics) {
        check_static(t, "displacement", f.displacement.x, false);
        check_static(t, "displacement", f.displacement.y, false);
        for (const Formula& g : key == "stress" ? f.stress : f.gradient) check_static(t, key, g, false);
      } else {
        t.error("displacement", "exact solutions given as formulas are for statics; dynamics measures errors against a "
                                "built-in motion (solution = \"...\")");
      }
      e.formulas = std::move(f);
    } else {
      if (!s.problem.region_materials.empty())
        t.error("solution",
                "built-in solutions are posed on one material; give the exact solution of a domain of "
                "several materials as formulas");
      e.builtin = read_builtin_solution(t, out.solution_setting(), dynamics);
    }
    // Errors are measured from the stress of F at their own points, which hold no history.
    if (const Material* m = out.law_with(has_history))
      t.error(e.builtin ? "solution" : "displacement",
              fmt::format("errors against an exact solution need elastic laws; '{}' has history (its stress "
                          "lives at the quadrature points: ask [output] fields for it)",
                          name(*m)));
    // A built-in solution comes with the body force that makes it exact; another one would not.
    if (e.builtin && (out.body_force || out.gravity))
      t.error("solution", fmt::format("the {} solution sets the body force: remove [loads]", e.builtin->name));
    t.finish();
    out.exact_spec = std::move(e);
  }
}

/// [[boundary]] tables: each condition, its selection checked against slivers and overlaps.
void read_boundaries(const SceneTable& root, ElasticityScene& out) {
  ElasticitySettings& s = out.settings;
  const bool dynamics = root.has("dynamics");
  const std::optional<ExactElasticity> exact = out.exact();
  const std::vector<SceneTable> boundaries = root.tables("boundary");
  for (const SceneTable& t : boundaries) {
    BoundaryCondition<2> c;
    c.name = t.string("name");
    c.type = read_choice(t, "type", condition_table);
    std::string key, what;
    c.where = read_selection(t, out.domain, key, what);
    const double length = selection_length(out.domain, c.where);
    if (c.where.empty() || !(length > 0.0))
      t.error(key, fmt::format("{} selects no part of the boundary (the domain's bounding box is [[{}, {}], [{}, {}]])",
                               what, out.domain.bounding_box().lo.x(), out.domain.bounding_box().lo.y(),
                               out.domain.bounding_box().hi.x(), out.domain.bounding_box().hi.y()));
    check_sliver(t, c.type, what, c.where, key == "region" ? read_box(t, "region") : std::optional<Box>(),
                 out.domain);
    for (std::size_t k = 0; k < s.problem.conditions.size(); ++k) {
      const double shared = overlap_length(out.domain, c.where, s.problem.conditions[k].where);
      if (shared > 1e-12 * length)
        t.error(key, fmt::format("{} overlaps boundary '{}' over a length of {:.6g}: each part of the boundary takes "
                                 "one condition",
                                 what, s.problem.conditions[k].name, shared));
    }
    out.selected.push_back({c.name, condition_table.name(c.type), what, length});
    if (c.type == ConditionType::pressure) {
      const Formula p = read_formula(t, "value", out.constants);
      check_static(t, "value", p, dynamics);
      c.pressure = [p](const Vec2& x, double time) { return p(x, time); };
    } else if (t.is_string("value")) {
      (void)t.choice("value", {"exact"});
      if (!exact) t.error("value", "'exact' needs a static [exact] solution (built-in or formulas)");
      const ExactElasticity ex = *exact;
      if (c.type != ConditionType::traction)
        c.value = [ex](const Vec2& x, const Vec2&, double) { return ex.displacement(x); };
      else
        c.value = [ex](const Vec2& x, const Vec2& n, double) { return ex.traction(x, n); };
    } else {
      const VectorFormula v = read_vector_formula(t, "value", out.constants);
      check_static(t, "value", v.x, dynamics);
      check_static(t, "value", v.y, dynamics);
      c.value = [v](const Vec2& x, const Vec2&, double time) { return v(x, time); };
    }
    t.finish();
    s.problem.conditions.push_back(c);
  }
}

/// [dynamics]: the time scheme, its steps, frames, error times and initial fields.
void read_dynamics(const SceneTable& root, ElasticityScene& out) {
  const ElasticitySettings& s = out.settings;
  if (root.has("dynamics")) {
    const SceneTable t = root.table("dynamics");
    DynamicsScene dyn;
    DynamicsSettings& d = dyn.settings;
    d.scheme = read_choice(t, "scheme", time_scheme_names());
    d.end_time = t.number("end_time", 1e-300, 1e300);
    if (t.has("time_step")) d.time_step = t.number("time_step", 1e-300, 1e300);
    if (d.scheme == TimeScheme::newmark && !d.time_step) t.error("scheme", "newmark needs a time_step");
    d.stability_factor = t.number_or("stability_factor", d.stability_factor, 1e-6, 1.0);
    d.energy_every = static_cast<int>(t.integer_or("energy_every", 1, 0, 1 << 30));
    dyn.frames = static_cast<int>(t.integer_or("frames", 0, 0, 100000));
    dyn.error_times = read_error_times(t);
    for (const char* key : {"initial_displacement", "initial_velocity"}) {
      if (!t.has(key)) continue;
      if (out.motion()) t.error(key, "the [exact] motion sets the initial state");
      const VectorFormula f = read_vector_formula(t, key, out.constants);
      if (f.depends_on_time()) t.error(key, "an initial field is a function of X and Y, not of t");
      (std::string(key) == "initial_velocity" ? dyn.initial_velocity : dyn.initial_displacement) = f;
    }
    if (!(out.density > 0.0))
      t.error("scheme",
              "dynamics needs the material's density ([material] density, or one in every [[material]])");
    if (out.newton) d.newton = *out.newton;
    d.newton.solver = s.solver;
    t.finish();
    out.dynamics = dyn;
  }
}

/// [output]: the folder, the fields, the probe, eigenvalues and checkpoints.
void read_output(const SceneTable& root, ElasticityScene& out, bool want_study) {
  const std::optional<ExactElasticity> exact = out.exact();
  const SceneTable t = root.table("output");
  out.output.folder = read_output_folder(t);
  // An empty list asks for nothing: no stress recovery, no files.
  if (t.has("fields") && !(t.is_array_empty("fields")))
    for (const auto& f : t.choices("fields", {"displacement", "velocity", "stress", "von_mises",
                                              "plastic_strain", "error", "weights"}))
      out.output.fields.insert(f);
  if (out.output.wants("plastic_strain") && !out.law_with(has_history))
    t.error("fields",
            fmt::format("'plastic_strain' needs a law with history (j2, drucker_prager), not the {}",
                        out.law_names()));
  out.output.vtk = t.boolean_or("vtk", true);
  if (out.output.wants("velocity") && !out.dynamics)
    t.error("fields", "'velocity' needs a [dynamics] section");
  if (t.has("probe")) {
    const auto p = t.numbers("probe", 2, -1e300, 1e300);
    out.output.probe = Vec2(p[0], p[1]);
    if (!out.domain.contains(*out.output.probe)) t.error("probe", "the probe lies outside the domain");
  }
  if (out.output.wants("error") && !exact && !out.motion())
    t.error("fields", "'error' needs an [exact] section");
  out.output.eigenvalues = static_cast<int>(t.integer_or("eigenvalues", 0, 0, 100));
  if (out.output.eigenvalues > 0 && out.nonlinear())
    t.error(
        "eigenvalues",
        "stiffness eigenvalues are for linear statics (no [dynamics] or [newton], a small-strain material)");
  out.output.checkpoint_every = static_cast<int>(t.integer_or("checkpoint_every", 0, 0, 1 << 30));
  if (out.output.checkpoint_every > 0 && !out.dynamics)
    t.error("checkpoint_every", "checkpoints are for [dynamics] runs (and MPM runs)");
  if (out.output.checkpoint_every > 0 && want_study)
    t.error("checkpoint_every", "a study is not checkpointed: checkpoints are for one long `mfree run`");
  t.finish();
}

/// [study] (mfree converge; required when `want_study`).
void read_study(const SceneTable& root, ElasticityScene& out, bool want_study) {
  const ElasticitySettings& s = out.settings;
  if (want_study && !out.dynamics && out.nonlinear())
    root.error("study", "mfree converge runs linear statics and dynamics; this scene is solved by Newton (a "
                        "finite-strain material or [newton]): run it with mfree run");
  if (want_study || root.has("study")) {
    const SceneTable t = root.table("study");
    StudySettings st;
    st.spacings = t.numbers("spacings", 0, 1e-12, 1e12);
    // Lists left out take the scene's own value.
    st.clouds = {s.nodes.kind};
    st.orders = {s.order};
    st.schemes = {s.scheme};
    if (t.has("clouds")) st.clouds = read_choices(t, "clouds", cloud_kind_names());
    if (t.has("orders")) st.orders = read_choices(t, "orders", order_names());
    if (t.has("schemes")) st.schemes = read_choices(t, "schemes", scheme_names());
    st.time = read_time_study(t, out.dynamics ? &out.dynamics->settings : nullptr);
    st.betas = t.has("betas") ? t.numbers("betas", 0, 1e-6, 1e12) : std::vector<double>{s.problem.nitsche_beta};
    if (t.has("probe")) {
      const auto p = t.numbers("probe", 2, -1e300, 1e300);
      st.probe = Vec2(p[0], p[1]);
      if (!out.domain.contains(*st.probe)) t.error("probe", "the probe lies outside the domain");
    }
    if (t.has("reference")) st.reference = t.number("reference", -1e300, 1e300);
    st.quadratic_factor = t.number_or("quadratic_factor", 3.0, 0.5, 10.0);
    st.quadratic_gauss_points = s.gauss_points;
    if (t.has("quadratic_gauss_points"))
      st.quadratic_gauss_points = static_cast<int>(t.integer("quadratic_gauss_points", 1, 12));
    t.finish();
    out.study = st;
  }
}

}  // namespace

ElasticityScene read_elasticity_scene(const std::filesystem::path& file, bool want_study,
                                      const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  ElasticityScene out{file, {}, {}, {}, {}, Domain::rectangle(Vec2(0, 0), Vec2(1, 1)), {}, {}, 0.0, {}, {},
                      {},   {}, {}, {}, {}};
  ElasticitySettings& s = out.settings;

  read_plane_domain(root, out);
  read_nodes_section(root.table("nodes"), s);
  read_kernel_section(root.table("kernel"), s, 2);
  const SceneTable quadrature = root.optional_table("quadrature");
  read_quadrature_section(quadrature, s, 2);
  read_plane_materials(root, out);
  out.constants = read_constants(root);
  read_loads(root, out);
  read_exact(root, out);
  read_boundaries(root, out);
  s.problem.body_force = out.static_body_force();
  if (root.has("nitsche"))
    s.problem.nitsche_beta = read_nitsche_section(root.table("nitsche"), s.problem.nitsche_beta);
  if (root.has("solver")) read_solver_section(root.table("solver"), s);
  if (root.has("newton")) out.newton = read_newton_section(root.table("newton"), s.solver);
  read_dynamics(root, out);
  read_output(root, out, want_study);
  read_study(root, out, want_study);
  check_scheme_keys(quadrature, s.scheme, out.study);
  root.finish();
  return out;
}

SolutionSetting ElasticityScene::solution_setting() const {
  return {domain.bounding_box(), settings.problem.material, std::holds_alternative<NeoHookean>(material), density};
}

std::optional<ExactMotion<2>> ElasticityScene::motion() const {
  if (!exact_spec || !exact_spec->builtin || !exact_spec->builtin->solution().motion) return std::nullopt;
  return exact_spec->builtin->solution().motion(exact_spec->builtin->values, solution_setting());
}

SolidProblem<2> ElasticityScene::solid_problem() const {
  ElasticityProblem linear = settings.problem;
  linear.spacing = settings.nodes.spacing;
  SolidProblem<2> p = mfree::solid_problem(linear);
  p.material = material;
  p.region_materials = region_materials;
  p.density = density;
  p.region_densities = region_densities;
  if (const auto m = motion())
    p.body_force = [b = m->body_force, rho = density](const Vec2& x, double t) -> Vec2 { return rho * b(x, t); };
  else if (body_force || gravity)
    p.body_force = loads_body_force();
  return p;
}

BodyForce<2> ElasticityScene::loads_body_force() const {
  // Gravity in a region of its own density: the nearest region's at X.
  std::function<double(const Vec2&)> rho = [rho = density](const Vec2&) { return rho; };
  if (gravity && !region_densities.empty())
    rho = [at = std::make_shared<const Domain>(domain), d = region_densities](const Vec2& x) {
      return d[static_cast<std::size_t>(at->nearest_region(x).first)];
    };
  return [f = body_force, g = gravity, rho](const Vec2& x, double t) -> Vec2 {
    Vec2 b = Vec2::Zero();
    if (f) b += (*f)(x, t);
    if (g) b += rho(x) * *g;
    return b;
  };
}

VectorField ElasticityScene::static_body_force() const {
  if (body_force || gravity) return [b = loads_body_force()](const Vec2& x) { return b(x, 0.0); };
  if (exact_spec && exact_spec->formulas) return {};  // the loads are the scene's: none
  const std::optional<ExactElasticity> e = exact();
  return e ? e->body_force : VectorField{};
}

const Material& ElasticityScene::law_at(const Vec2& x) const {
  return region_materials.empty()
             ? material
             : region_materials[static_cast<std::size_t>(domain.nearest_region(x).first)];
}

const Material* ElasticityScene::law_with(bool (*property)(const Material&)) const {
  if (region_materials.empty()) return property(material) ? &material : nullptr;
  for (const Material& m : region_materials)
    if (property(m)) return &m;
  return nullptr;
}

std::string ElasticityScene::law_names() const {
  if (region_materials.empty()) return fmt::format("{} material", name(material));
  std::string out = "materials ";
  for (std::size_t r = 0; r < region_materials.size(); ++r)
    out += fmt::format("{}{} in '{}'", r ? ", " : "", name(region_materials[r]), domain.regions()[r].name);
  return out;
}

std::string ElasticityScene::describe_conditions() const {
  std::string out;
  for (const SelectedPart& p : selected)
    out += fmt::format("  boundary '{}' ({}): {}, length {:.6g}\n", p.name, p.type, p.selector, p.length);
  return out;
}

std::optional<ExactElasticity> ElasticityScene::exact() const {
  if (!exact_spec) return std::nullopt;
  if (const auto& f = exact_spec->formulas) {
    // Strain from the gradient, or from the stress by the compliance of the small-strain law.
    ExactElasticity e;
    e.displacement = [u = f->displacement](const Vec2& x) { return u(x); };
    if (!f->stress.empty())
      e.stress = [sg = f->stress](const Vec2& x) { return Eigen::Vector3d(sg[0](x), sg[1](x), sg[2](x)); };
    else
      e.stress = [g = f->gradient, p = settings.problem,
                  at = std::make_shared<const Domain>(domain)](const Vec2& x) {
        const double a = g[0](x), b = g[1](x), c = g[2](x), dd = g[3](x);
        return Eigen::Vector3d(p.law_at(*at, x).voigt_tangent() * Eigen::Vector3d(a, dd, b + c));
      };
    e.body_force = static_body_force();
    if (!e.body_force) e.body_force = [](const Vec2&) { return Vec2::Zero(); };
    return e;
  }
  const BuiltinSolution& b = exact_spec->builtin->solution();
  if (!b.statics) return std::nullopt;
  return b.statics(exact_spec->builtin->values, solution_setting());
}

}  // namespace mfree
