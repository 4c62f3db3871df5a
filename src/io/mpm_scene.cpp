#include "mfree/io/mpm_scene.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "mfree/core/error.hpp"
#include "mfree/core/name_table.hpp"
#include "mfree/geometry/domain.hpp"
#include "mfree/io/read_choice.hpp"
#include "mfree/io/scene_sections.hpp"

namespace mfree {

namespace {

/// Particles per cell (a square number) -> per side.
int per_side(const SceneTable& t, const std::string& key, long long n) {
  const int side = static_cast<int>(std::lround(std::sqrt(static_cast<double>(n))));
  if (side * side != n || side < 1 || side > 5) t.error(key, "must be 1, 4, 9, 16 or 25 (a square number of particles)");
  return side;
}
Vec2 pair_of(const SceneTable& t, const std::string& key) {
  const auto v = t.numbers(key, 2, -1e300, 1e300);
  return {v[0], v[1]};
}
/// A vector formula that is constant becomes its value: no parser runs per particle.
template <class... Args>
std::function<Vec2(const Vec2&, Args...)> vector_field(const VectorFormula& f) {
  if (f.x.is_constant() && f.y.is_constant()) {
    const Vec2 c = f(Vec2::Zero());
    return [c](const Vec2&, Args...) { return c; };
  }
  return [f](const Vec2& X, Args... t) { return f(X, t...); };
}

/// Walls per side of the grid box from [mpm] walls = {side = kind, ...}; open where unlisted.
Walls read_walls(const SceneTable& mpm) {
  Walls walls{Wall::open, Wall::open, Wall::open, Wall::open};
  if (!mpm.has("walls")) return walls;
  const SceneTable t = mpm.table("walls");
  for (const std::string& side : side_names().names())
    walls[static_cast<std::size_t>(side_names().value(side))] =
        wall_names().value(t.choice_or(side, "open", wall_names().names()));
  t.finish();
  return walls;
}

/// [[material]] tables, in order; names distinct.
std::vector<MPMMaterial> read_materials(const std::vector<SceneTable>& tables, std::vector<MaterialSection>& sections) {
  std::vector<MPMMaterial> out;
  for (const SceneTable& t : tables) {
    const std::string name = t.string("name");
    for (const MPMMaterial& m : out)
      if (m.name == name) t.error("name", fmt::format("a second material named '{}'", name));
    const MaterialSection s = read_material_keys(t);
    if (!(s.density > 0.0)) t.error("model", "an MPM material needs a density");
    out.push_back({name, s.material, s.density});
    sections.push_back(s);
  }
  return out;
}

/// One [[body]] table: name, shape and its keys, material (index into `materials`),
/// velocity, particles per cell.
MPMBody read_body(const SceneTable& t, const std::vector<MPMMaterial>& materials, const Constants& constants) {
  MPMBody b;
  b.name = t.string("name");
  b.shape = read_choice(t, "shape", shape_names());
  std::string key;  // the key of the shape's geometry, named by messages about the body
  switch (b.shape) {
    case Shape::rectangle: {
      key = "box";
      const Box box = read_box(t, key);
      if (!(box.hi.array() > box.lo.array()).all()) t.error(key, "the corners must differ in x and y");
      const MPMBody r = rectangle_body(b.name, box);
      b.bounds = r.bounds;
      b.contains = r.contains;
      break;
    }
    case Shape::circle: {
      key = "centre";
      const Vec2 c = pair_of(t, key);
      const double r = t.number("radius", 0.0, 1e300);
      if (!(r > 0.0)) t.error("radius", "must be positive");
      b.bounds = {c - Vec2(r, r), c + Vec2(r, r)};
      b.contains = [c, r](const Vec2& x) { return (x - c).squaredNorm() <= r * r; };
      break;
    }
    case Shape::polygon: {
      key = "wkt";
      const std::filesystem::path file = t.folder() / t.string(key);
      std::shared_ptr<const Domain> domain;
      try {
        domain = std::make_shared<const Domain>(Domain::from_file(file));
      } catch (const InputError& e) {
        t.error(key, e.what());
      }
      b.bounds = domain->bounding_box();
      b.contains = [domain](const Vec2& x) { return domain->contains(x); };
      break;
    }
  }
  b.where = t.where(key);
  const std::string material = t.string("material");
  std::string defined;
  for (std::size_t k = 0; k < materials.size(); ++k) {
    if (materials[k].name == material) b.material = static_cast<int>(k);
    defined += fmt::format("{}'{}'", k ? ", " : "", materials[k].name);
  }
  if (materials.empty() || materials[b.material].name != material)
    t.error("material", fmt::format("no [[material]] is named '{}' (defined: {})", material,
                                    materials.empty() ? "none" : defined));
  if (t.has("velocity")) {
    const VectorFormula v = read_vector_formula(t, "velocity", constants);
    if (v.depends_on_time()) t.error("velocity", "an initial velocity is a field in X and Y, not t");
    b.initial_velocity = vector_field<>(v);
    b.velocity_where = t.where("velocity");
  }
  if (t.has("particles_per_cell"))
    b.particles_per_side = per_side(t, "particles_per_cell", t.integer("particles_per_cell", 1, 25));
  t.finish();
  return b;
}

}  // namespace

std::string method_name(const MPMMethodChoice& m) { return mpm_method_names().name(m); }

MPMMethodChoice method_of(const MPMSettings& s) {
  return {s.method, s.method == MPMMethod::bspline_mls ? 2 : is_bspline(s.method) ? s.degree : 1};
}

bool is_mpm_scene(const std::filesystem::path& file) { return Scene::load(file).root().has("mpm"); }

MPMScene read_mpm_scene(const std::filesystem::path& file, bool want_study, const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  MPMScene out;
  out.file = file;
  MPMProblem& pr = out.problem;
  MPMSettings& s = out.settings;
  const Constants constants = read_constants(root);
  const SceneTable mpm = root.table("mpm");
  pr.box = read_box(mpm, "box");
  if (!(pr.box.hi.array() > pr.box.lo.array()).all()) mpm.error("box", "the corners must differ in x and y");

  std::vector<MaterialSection> sections;
  const std::vector<SceneTable> material_tables = root.tables("material");
  if (material_tables.empty()) root.error("mpm", "an MPM scene needs [[material]] tables (name, model, ..., density)");
  pr.materials = read_materials(material_tables, sections);
  const std::vector<SceneTable> body_tables = root.tables("body");
  if (body_tables.empty()) root.error("mpm", "an MPM scene needs at least one [[body]]");
  for (const SceneTable& t : body_tables) {
    pr.bodies.push_back(read_body(t, pr.materials, constants));
    for (std::size_t k = 0; k + 1 < pr.bodies.size(); ++k)
      if (pr.bodies[k].name == pr.bodies.back().name)
        t.error("name", fmt::format("a second body named '{}'", pr.bodies.back().name));
  }
  for (std::size_t k = 0; k < pr.materials.size(); ++k) {
    bool used = false;
    for (const MPMBody& b : pr.bodies) used = used || b.material == static_cast<int>(k);
    if (!used) material_tables[k].error("name", fmt::format("material '{}' is used by no [[body]]", pr.materials[k].name));
  }

  if (root.has("exact")) {
    const SceneTable t = root.table("exact");
    if (pr.bodies.size() != 1) t.error("solution", "an exact motion needs a single [[body]]");
    const MPMBody& body = pr.bodies.front();
    const Box& d = pr.box;
    if (body.shape != Shape::rectangle || (body.bounds.lo - d.lo).norm() > 1e-12 * d.size().norm() ||
        (body.bounds.hi - d.hi).norm() > 1e-12 * d.size().norm())
      t.error("solution", "an exact motion needs the body to be the rectangle filling the grid box");
    if (body.initial_velocity) body_tables.front().error("velocity", "the [exact] solution sets the initial velocity");
    const MaterialSection& material = sections[static_cast<std::size_t>(body.material)];
    const SolutionSetting on{d, material.linear, std::holds_alternative<NeoHookean>(material.material), material.density};
    const BuiltinChoice c = read_builtin_solution(t, on, true);
    const ExactMotion<2> m = c.solution().motion(c.values, on);
    out.exact = m;
    pr.body_force = m.body_force;
    pr.body_force_where = t.where("solution");
    pr.bodies.front().initial_velocity = [v = m.velocity](const Vec2& X) { return v(X, 0.0); };
    pr.bodies.front().velocity_where = t.where("solution");
    t.finish();
  }
  {
    const SceneTable& t = mpm;
    const MPMMethodChoice m = read_choice(t, "method", mpm_method_names());
    s.method = m.method;
    s.degree = m.degree == 1 ? 2 : m.degree;
    s.update = read_choice_or(t, "update", update_names(), UpdateScheme::usf);
    s.mapping = read_choice_or(t, "mapping", grid_mapping_names(), GridMapping::lumped);
    s.cells = static_cast<int>(t.integer("cells", 1, 100000));
    s.particles_per_side = per_side(t, "particles_per_cell", t.integer_or("particles_per_cell", 4, 1, 25));
    s.mass_filter = t.number_or("mass_filter", 0.0, 0.0, 1.0);
    if (s.mass_filter > 0.0 && s.mapping != GridMapping::pseudo_inverse)
      t.error("mass_filter",
              "only the pseudo_inverse mapping has a mass matrix to filter (0 turns the filter off)");
    s.mls_support = t.number_or("mls_support", s.mls_support, 1.0, 10.0);
    if (t.has("mls_support") && s.method != MPMMethod::bspline_mls) t.error("mls_support", "only bspline_mls reconstructs");
    s.mls_basis = read_choice_or(t, "mls_basis", order_names(), s.mls_basis);
    if (t.has("mls_basis") && s.method != MPMMethod::bspline_mls) t.error("mls_basis", "only bspline_mls reconstructs");
    s.deformation_terms = static_cast<int>(t.integer_or("deformation_terms", 2, 1, 10));
    s.walls = read_walls(t);
    s.damping = t.number_or("damping", 0.0, 0.0, 1e300);
    if (s.damping > 0.0 && s.update == UpdateScheme::verlet)
      t.error("damping", "the verlet update takes no damping; use usf, usl, szs or usavg with damping");
    if (t.has("gravity")) {
      if (out.exact) t.error("gravity", "the [exact] solution sets the body force");
      pr.body_force = vector_field<double>(read_vector_formula(t, "gravity", constants));
      pr.body_force_where = t.where("gravity");
    }
    const double h = pr.box.size().x() / s.cells;
    // Particle volumes (h / n)^2, n = 1 to 5 per side, must be doubles of their own.
    if (!(std::isfinite(h * h) && (h / 5.0) * (h / 5.0) >= std::numeric_limits<double>::min()))
      t.error(
          "box",
          fmt::format("a grid box {:.4g} x {:.4g} m of cells h = {:.4g} m gives particle volumes (h / n)^2 "
                      "outside what a double holds; give the box in units that make its size of order one",
                      pr.box.size().x(), pr.box.size().y(), h));
    const double rows = pr.box.size().y() / h;
    if (std::abs(rows - std::round(rows)) > 1e-9 * rows)
      t.error("cells", fmt::format("the grid box height {} is not a whole number of cells of size {}", pr.box.size().y(), h));
    t.finish();
  }
  {
    const SceneTable t = root.table("dynamics");
    s.end_time = t.number("end_time", 1e-300, 1e300);
    if (t.has("time_step")) s.time_step = t.number("time_step", 1e-300, 1e300);
    s.allow_unstable_time_step = t.boolean_or("allow_unstable_time_step", false);
    s.courant = t.number_or("courant", 0.5, 1e-6, s.allow_unstable_time_step ? 100.0 : 1.0);
    out.frames = static_cast<int>(t.integer_or("frames", 0, 0, 100000));
    if (t.has("energy_every")) out.energy_every = static_cast<int>(t.integer_or("energy_every", 0, 0, 1 << 30));
    if (t.has("error_times")) {
      if (!out.exact) t.error("error_times", "errors need an [exact] solution");
      out.error_times = t.numbers("error_times", 0, 0.0, 1.0);
    } else if (out.exact) {
      out.error_times = {1.0};
    }
    t.finish();
  }
  {
    const SceneTable t = root.table("output");
    out.folder = read_output_folder(t);
    if (t.has("fields") && !t.is_array_empty("fields"))
      for (const auto& f : t.choices("fields", {"displacement", "velocity", "stress", "von_mises", "plastic_strain", "body",
                                                "error", "grid", "domains"})) {
        if (f == "displacement") out.fields.displacement = true;
        if (f == "velocity") out.fields.velocity = true;
        if (f == "stress") out.fields.stress = true;
        if (f == "von_mises") out.fields.von_mises = true;
        if (f == "plastic_strain") out.fields.plastic_strain = true;
        if (f == "body") out.fields.body = true;
        if (f == "error") out.fields.error = true;
        if (f == "grid") out.fields.grid = true;
        if (f == "domains") out.fields.domains = true;
      }
    if (out.fields.error && !out.exact) t.error("fields", "'error' needs an [exact] section");
    if (out.fields.domains && !uses_domains(s.method))
      t.error(
          "fields",
          fmt::format("'domains' needs a method with particle domains (ugimp, cpgimp, cpdi, qcpdi, cpdi2, "
                      "bspline_cpgimp, bspline_cpgimp_cubic), "
                      "not {}",
                      method_name(method_of(s))));
    out.vtk = t.boolean_or("vtk", true);
    out.particles_csv = t.boolean_or("particles_csv", false);
    out.checkpoint_every = static_cast<int>(t.integer_or("checkpoint_every", 0, 0, 1 << 30));
    if (t.has("probe")) {
      const auto p = t.numbers("probe", 2, -1e300, 1e300);
      out.probe = Vec2(p[0], p[1]);
      if (std::none_of(pr.bodies.begin(), pr.bodies.end(), [&](const MPMBody& b) { return b.contains(*out.probe); }))
        t.error("probe", "the probe lies in no body (it is a material point: a reference position inside one)");
    }
    if (out.checkpoint_every > 0 && want_study)
      t.error("checkpoint_every", "a study is not checkpointed: checkpoints are for one long `mfree run`");
    t.finish();
  }
  if (want_study || root.has("study")) {
    const SceneTable t = root.table("study");
    MPMStudy st;
    for (const double c : t.numbers("cells", 0, 1, 100000)) {
      if (c != std::round(c)) t.error("cells", "must be whole numbers");
      st.cells.push_back(static_cast<int>(c));
    }
    st.methods = {method_of(s)};
    if (t.has("methods")) st.methods = read_choices(t, "methods", mpm_method_names());
    st.updates = {s.update};
    if (t.has("updates")) st.updates = read_choices(t, "updates", update_names());
    if (s.damping > 0.0 && std::count(st.updates.begin(), st.updates.end(), UpdateScheme::verlet) > 0)
      t.error("updates", "the verlet update takes no damping, and [mpm] sets damping");
    st.mappings = {s.mapping};
    if (t.has("mappings")) st.mappings = read_choices(t, "mappings", grid_mapping_names());
    if (s.mass_filter > 0.0 && std::count(st.mappings.begin(), st.mappings.end(), GridMapping::lumped) > 0)
      t.error("mappings", "[mpm] sets mass_filter, which the lumped mapping has no mass matrix for");
    st.particles_per_side = {s.particles_per_side};
    if (t.has("particles_per_cell")) {
      for (const MPMBody& b : pr.bodies)
        if (b.particles_per_side > 0)
          t.error("particles_per_cell", fmt::format("body '{}' sets its own particles_per_cell", b.name));
      st.particles_per_side.clear();
      for (const double n : t.numbers("particles_per_cell", 0, 1, 25)) st.particles_per_side.push_back(per_side(t, "particles_per_cell", std::lround(n)));
    }
    if (!out.exact && !out.probe)
      t.error("cells", "a study without an [exact] solution compares the displacement at a probe between grids: give "
                       "[output] probe = [X, Y]");
    t.finish();
    out.study = st;
  }
  root.finish();
  return out;
}

}  // namespace mfree
