#include "mfree/io/mpm_scene.hpp"

#include <cmath>
#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/io/scene_sections.hpp"

namespace mfree {

namespace {

const std::vector<std::string> method_names{"classic", "ugimp", "cpdi", "bspline", "bspline_cubic", "bspline_mls"};
const std::vector<std::string> update_names{"usf", "usl", "szs", "usavg"};

MPMMethodChoice method_of(const std::string& s) {
  if (s == "classic") return {MPMMethod::classic, 1};
  if (s == "ugimp") return {MPMMethod::ugimp, 1};
  if (s == "cpdi") return {MPMMethod::cpdi, 1};
  if (s == "bspline_cubic") return {MPMMethod::bspline, 3};
  if (s == "bspline_mls") return {MPMMethod::bspline_mls, 2};
  return {MPMMethod::bspline, 2};
}
UpdateScheme update_of(const std::string& s) {
  return s == "usf" ? UpdateScheme::usf : s == "usl" ? UpdateScheme::usl : s == "szs" ? UpdateScheme::szs : UpdateScheme::usavg;
}
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

}  // namespace

std::string method_name(const MPMMethodChoice& m) {
  if (m.method == MPMMethod::bspline && m.degree == 3) return "bspline_cubic";
  return std::string(to_string(m.method));
}

bool is_mpm_scene(const std::filesystem::path& file) { return Scene::load(file).root().has("mpm"); }

MPMScene read_mpm_scene(const std::filesystem::path& file, bool want_study, const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  MPMScene out;
  out.file = file;
  MPMProblem& pr = out.problem;
  MPMSettings& s = out.settings;
  {
    const SceneTable t = root.table("domain");
    pr.domain = read_box(t, "rectangle");
    if (!(pr.domain.hi.array() > pr.domain.lo.array()).all()) t.error("rectangle", "the corners must differ in x and y");
    t.finish();
  }
  const MaterialSection material = read_material(root);
  pr.material = material.material;
  pr.density = material.density;
  if (!(pr.density > 0.0)) root.error("material", "an MPM scene needs [material] density");
  if (root.has("exact")) {
    const SceneTable t = root.table("exact");
    (void)t.choice("solution", {"vibration"});
    const double amplitude = t.number("amplitude", 0.0, 1e300);
    if (!std::holds_alternative<NeoHookean>(pr.material))
      t.error("solution", "the vibration solution needs [material] model = \"neo_hookean\"");
    const Box& d = pr.domain;
    if (d.lo.norm() > 1e-12 * d.size().norm() || std::abs(d.size().x() - d.size().y()) > 1e-12 * d.size().x())
      t.error("solution", "the vibration solution needs the square domain [0, L] x [0, L]");
    const AxisAlignedVibration v{amplitude, d.size().x(), material.linear.youngs_modulus, material.linear.poisson_ratio,
                                 pr.density};
    out.vibration = v;
    pr.body_force = [v](const Vec2& X, double t) { return v.body_force(X, t); };
    pr.initial_velocity = [v](const Vec2& X) { return v.velocity(X, 0.0); };
    t.finish();
  }
  {
    const SceneTable t = root.table("mpm");
    const MPMMethodChoice m = method_of(t.choice("method", method_names));
    s.method = m.method;
    s.degree = m.degree == 1 ? 2 : m.degree;
    s.update = update_of(t.choice_or("update", "usf", update_names));
    s.cells = static_cast<int>(t.integer("cells", 1, 100000));
    s.particles_per_side = per_side(t, "particles_per_cell", t.integer_or("particles_per_cell", 4, 1, 25));
    s.mls_support = t.number_or("mls_support", s.mls_support, 1.0, 10.0);
    if (t.has("mls_support") && s.method != MPMMethod::bspline_mls) t.error("mls_support", "only bspline_mls reconstructs");
    s.deformation_terms = static_cast<int>(t.integer_or("deformation_terms", 2, 1, 10));
    if (t.has("slip_walls") && !t.is_array_empty("slip_walls"))
      for (const auto& w : t.choices("slip_walls", {"left", "right", "bottom", "top"}))
        s.walls.push_back(w == "left" ? Wall::left : w == "right" ? Wall::right : w == "bottom" ? Wall::bottom : Wall::top);
    if (t.has("gravity")) {
      if (out.vibration) t.error("gravity", "the [exact] solution sets the body force");
      const Vec2 g = pair_of(t, "gravity");
      pr.body_force = [g](const Vec2&, double) { return g; };
    }
    if (t.has("initial_velocity")) {
      if (out.vibration) t.error("initial_velocity", "the [exact] solution sets the initial velocity");
      const Vec2 v = pair_of(t, "initial_velocity");
      pr.initial_velocity = [v](const Vec2&) { return v; };
    }
    const double h = pr.domain.size().x() / s.cells;
    const double rows = pr.domain.size().y() / h;
    if (std::abs(rows - std::round(rows)) > 1e-9 * rows)
      t.error("cells", fmt::format("the domain height {} is not a whole number of cells of size {}", pr.domain.size().y(), h));
    t.finish();
  }
  {
    const SceneTable t = root.table("dynamics");
    s.end_time = t.number("end_time", 1e-300, 1e300);
    if (t.has("time_step")) s.time_step = t.number("time_step", 1e-300, 1e300);
    s.allow_unstable_time_step = t.boolean_or("allow_unstable_time_step", false);
    s.courant = t.number_or("courant", 0.5, 1e-6, s.allow_unstable_time_step ? 100.0 : 1.0);
    out.frames = static_cast<int>(t.integer_or("frames", 0, 0, 100000));
    out.energy_every = static_cast<int>(t.integer_or("energy_every", 0, 0, 1 << 30));
    if (t.has("error_times")) {
      if (!out.vibration) t.error("error_times", "errors need an [exact] solution");
      out.error_times = t.numbers("error_times", 0, 0.0, 1.0);
    } else if (out.vibration) {
      out.error_times = {1.0};
    }
    t.finish();
  }
  {
    const SceneTable t = root.table("output");
    out.folder = t.string("folder");
    if (t.has("fields") && !t.is_array_empty("fields"))
      for (const auto& f : t.choices("fields", {"displacement", "velocity", "stress", "von_mises", "error", "grid"})) {
        if (f == "displacement") out.fields.displacement = true;
        if (f == "velocity") out.fields.velocity = true;
        if (f == "stress") out.fields.stress = true;
        if (f == "von_mises") out.fields.von_mises = true;
        if (f == "error") out.fields.error = true;
        if (f == "grid") out.fields.grid = true;
      }
    if (out.fields.error && !out.vibration) t.error("fields", "'error' needs an [exact] section");
    out.vtk = t.boolean_or("vtk", true);
    t.finish();
  }
  if (want_study || root.has("study")) {
    const SceneTable t = root.table("study");
    MPMStudy st;
    for (const double c : t.numbers("cells", 0, 1, 100000)) {
      if (c != std::round(c)) t.error("cells", "must be whole numbers");
      st.cells.push_back(static_cast<int>(c));
    }
    st.methods = {MPMMethodChoice{s.method, s.method == MPMMethod::bspline ? s.degree : (is_bspline(s.method) ? 2 : 1)}};
    if (t.has("methods")) {
      st.methods.clear();
      for (const auto& m : t.choices("methods", method_names)) st.methods.push_back(method_of(m));
    }
    st.updates = {s.update};
    if (t.has("updates")) {
      st.updates.clear();
      for (const auto& u : t.choices("updates", update_names)) st.updates.push_back(update_of(u));
    }
    st.particles_per_side = {s.particles_per_side};
    if (t.has("particles_per_cell")) {
      st.particles_per_side.clear();
      for (const double n : t.numbers("particles_per_cell", 0, 1, 25)) st.particles_per_side.push_back(per_side(t, "particles_per_cell", std::lround(n)));
    }
    if (!out.vibration) t.error("cells", "a study needs an [exact] solution to measure errors against");
    t.finish();
    out.study = st;
  }
  root.finish();
  return out;
}

}  // namespace mfree
