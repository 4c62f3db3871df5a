#include "mfree/io/scene_sections.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <map>
#include <numbers>
#include <optional>

#include "mfree/core/error.hpp"
#include "mfree/io/read_choice.hpp"

namespace mfree {

MaterialSection read_material(const SceneTable& root) { return read_material_keys(root.table("material")); }

MaterialSection read_material_keys(const SceneTable& t, int dimension) {
  MaterialSection m;
  if (dimension == 3) {
    // A solid's small-strain law is the 3D one (the plane-strain law's parent), named as such;
    // the plane laws are no choice.
    std::vector<std::string> models{"linear_elastic"};
    for (const std::string& name : material_models().names())
      if (name != "plane_stress" && name != "plane_strain") models.push_back(name);
    m.model = t.choice("model", models);
  } else {
    m.model = t.choice("model", material_models().names());
  }
  m.linear.model = m.model == "plane_stress" ? PlaneModel::stress : PlaneModel::strain;
  m.linear.youngs_modulus = t.number("youngs_modulus", 0.0, 1e300);
  m.linear.poisson_ratio = t.number("poisson_ratio", -1.0, 0.5);
  if (!(m.linear.youngs_modulus > 0.0)) t.error("youngs_modulus", "must be positive");
  if (!(m.linear.poisson_ratio > -1.0 && m.linear.poisson_ratio < 0.5))
    t.error("poisson_ratio", "must lie strictly between -1 and 1/2");
  MaterialParameters p;
  p.youngs_modulus = m.linear.youngs_modulus;
  p.poisson_ratio = m.linear.poisson_ratio;
  // The plastic models' constants; only they take these keys (finish() refuses them elsewhere).
  const double degrees = std::numbers::pi / 180.0;
  if (m.model == "j2" || m.model == "drucker_prager")
    p.kinematics = read_choice_or(t, "kinematics", kinematics_names(), Kinematics::multiplicative);
  if (dimension == 3 && p.kinematics == Kinematics::logarithmic)
    t.error("kinematics",
            "the logarithmic kinematics is plane only; a solid takes \"multiplicative\" or "
            "\"small_strain\"");
  if (m.model == "j2") {
    p.yield_stress = t.number("yield_stress", 0.0, 1e300);
    p.isotropic_modulus = t.number_or("isotropic_modulus", 0.0, 0.0, 1e300);
    p.kinematic_modulus = t.number_or("kinematic_modulus", 0.0, 0.0, 1e300);
    if (p.kinematic_modulus > 0.0 && p.kinematics == Kinematics::multiplicative)
      t.error("kinematic_modulus", "kinematic hardening needs kinematics = \"logarithmic\" or \"small_strain\" (the "
                                   "multiplicative law, the default, hardens isotropically only)");
    if (t.has("saturation_stress")) {
      p.saturation_stress = t.number("saturation_stress", p.yield_stress, 1e300);
      p.saturation_rate = t.number("saturation_rate", 0.0, 1e300);
    }
  }
  if (m.model == "drucker_prager") {
    p.friction_angle = t.number("friction_angle", 0.0, 89.9) * degrees;
    p.dilatancy_angle = t.number_or("dilatancy_angle", 0.0, 0.0, 89.9) * degrees;
    if (p.dilatancy_angle > p.friction_angle) t.error("dilatancy_angle", "must not exceed the friction angle");
    p.cohesion = t.number_or("cohesion", 0.0, 0.0, 1e300);
    if (t.has("tension_cutoff")) p.tension_cutoff = t.number("tension_cutoff", -1e300, 1e300);
    if (p.friction_angle == 0.0 && !(p.cohesion > 0.0)) t.error("cohesion", "must be positive with a zero friction angle");
  }
  m.material = make_material(m.model == "linear_elastic" ? "plane_strain" : m.model, p);
  if (t.has("density")) {
    m.density = t.number("density", 0.0, 1e300);
    if (!(m.density > 0.0)) t.error("density", "must be positive");
  }
  t.finish();
  return m;
}

std::vector<MaterialSection> read_region_materials(
    const std::vector<SceneTable>& tables, const std::vector<std::string>& region_names,
    const std::function<MaterialSection(const SceneTable&)>& read) {
  std::vector<int> law_of(region_names.size(), -1);
  std::vector<std::string> names;
  std::vector<MaterialSection> sections;
  for (const SceneTable& t : tables) {
    const std::string name = t.string("name");
    if (std::find(names.begin(), names.end(), name) != names.end())
      t.error("name", fmt::format("a second [[material]] named '{}'", name));
    names.push_back(name);
    for (const std::string& r : t.choices("regions", region_names)) {
      const auto at = static_cast<std::size_t>(std::find(region_names.begin(), region_names.end(), r) -
                                               region_names.begin());
      if (law_of[at] >= 0)
        t.error("regions",
                fmt::format("region '{}' has a law already ([[material]] '{}')", r, names[law_of[at]]));
      law_of[at] = static_cast<int>(names.size() - 1);
    }
    sections.push_back(read(t));
  }
  for (std::size_t r = 0; r < region_names.size(); ++r)
    if (law_of[r] < 0)
      tables.back().error(
          "regions",
          fmt::format("region '{}' has no law: name it in the regions of a [[material]]", region_names[r]));
  // A density in some tables and not in others is a slip, whatever the run needs.
  for (std::size_t l = 0; l < tables.size(); ++l)
    if (tables[l].has("density") != tables.front().has("density"))
      tables[l].error("density",
                      fmt::format("[[material]] '{}' gives a density and '{}' does not: give one in "
                                  "every [[material]], or in none",
                                  names[tables.front().has("density") ? 0 : l],
                                  names[tables.front().has("density") ? l : 0]));
  std::vector<MaterialSection> by_region;
  for (int l : law_of) by_region.push_back(sections[static_cast<std::size_t>(l)]);
  return by_region;
}

Box read_box(const SceneTable& t, const std::string& key) {
  const auto p = t.pairs(key, 2);
  return {Vec2(std::min(p[0][0], p[1][0]), std::min(p[0][1], p[1][1])),
          Vec2(std::max(p[0][0], p[1][0]), std::max(p[0][1], p[1][1]))};
}

AlignedBox<3> read_space_box(const SceneTable& t, const std::string& key) {
  const auto p = t.triples(key, 2);
  const Vec3 a(p[0][0], p[0][1], p[0][2]), b(p[1][0], p[1][1], p[1][2]);
  return {a.cwiseMin(b), a.cwiseMax(b)};
}

Constants read_constants(const SceneTable& root) {
  Constants c;
  if (!root.has("constants")) return c;
  const SceneTable t = root.table("constants");
  // A constant is a number or a formula of other constants (no x, y, t): resolved in as many
  // passes as the chain of references is long.
  std::map<std::string, std::string> pending;
  for (const std::string& k : t.keys()) pending[k] = t.expression(k);
  for (const auto& [name, text] : pending) (void)Formula("0", Constants{{name, 0.0}}, t.where(name));  // valid names
  while (!pending.empty()) {
    std::size_t resolved = 0;
    for (auto it = pending.begin(); it != pending.end();) {
      bool ready = true;
      std::optional<Formula> f;
      try {
        f.emplace(it->second, c, t.where(it->first));
      } catch (const InputError&) {
        ready = false;  // names a constant not resolved yet, or is wrong: the last pass says which
      }
      if (ready && !f->is_constant())
        t.error(it->first, fmt::format("a constant may use other constants, not x, y, X, Y or t: '{}'", it->second));
      if (!ready) {
        ++it;
        continue;
      }
      c[it->first] = (*f)(Vec2(0.0, 0.0));
      it = pending.erase(it);
      ++resolved;
    }
    if (resolved == 0) {
      // No progress: a formula that is wrong, names an unknown constant, or a cycle. The
      // parser's message for the first of them says which.
      const auto& [name, text] = *pending.begin();
      Constants all = c;
      for (const auto& [n, v] : pending) all[n] = 0.0;
      (void)Formula(text, all, t.where(name));
      t.error(name, fmt::format("'{}' refers to itself through other constants", text));
    }
  }
  t.finish();
  return c;
}

Formula read_formula(const SceneTable& t, const std::string& key, const Constants& constants, int dimension) {
  return Formula(t.expression(key), constants, t.where(key), dimension);
}

VectorFormula read_vector_formula(const SceneTable& t, const std::string& key, const Constants& constants) {
  const std::vector<std::string> e = t.expressions(key, 2);
  return {Formula(e[0], constants, t.where(key, 0)), Formula(e[1], constants, t.where(key, 1))};
}

SpaceVectorFormula read_space_vector_formula(const SceneTable& t, const std::string& key,
                                             const Constants& constants) {
  const std::vector<std::string> e = t.expressions(key, 3);
  return {Formula(e[0], constants, t.where(key, 0), 3), Formula(e[1], constants, t.where(key, 1), 3),
          Formula(e[2], constants, t.where(key, 2), 3)};
}

std::filesystem::path read_output_folder(const SceneTable& t) {
  const std::filesystem::path folder = t.string("folder");
  std::filesystem::path normal = folder.lexically_normal();
  if (!normal.has_filename()) normal = normal.parent_path();  // "results/run/"
  const std::filesystem::path name = normal.filename();
  if (folder.empty() || name.empty() || name == "." || name == "..")
    t.error("folder", fmt::format("'{}' is not a folder of its own: give one the run may create and replace "
                                  "(e.g. \"results/NAME\")",
                                  folder.string()));
  return folder;
}

BuiltinChoice read_builtin_solution(const SceneTable& t, const SolutionSetting& setting, bool motion) {
  BuiltinChoice c;
  c.name = t.choice("solution", builtin_solutions().names());
  const BuiltinSolution& s = c.solution();
  for (const SolutionParameter& p : s.parameters) {
    switch (p.kind) {
      case ParameterKind::number:
        c.values.numbers[p.name] = t.number(p.name, -1e300, 1e300);
        break;
      case ParameterKind::vector: {
        const auto a = t.numbers(p.name, 2, -1e300, 1e300);
        c.values.vectors[p.name] = Vec2(a[0], a[1]);
        break;
      }
      case ParameterKind::matrix:
      case ParameterKind::symmetric_matrix: {
        const auto m = t.pairs(p.name, 2);
        if (p.kind == ParameterKind::symmetric_matrix && m[0][1] != m[1][0])
          t.error(p.name, "a symmetric matrix: [[a, b], [b, c]]");
        c.values.matrices[p.name] << m[0][0], m[0][1], m[1][0], m[1][1];
        break;
      }
    }
  }
  if (motion && !s.motion)
    t.error("solution", fmt::format("the {} solution is static; a motion is needed here", c.name));
  if (!motion && !s.statics)
    t.error("solution", fmt::format("the {} solution is a motion; it needs a dynamic run", c.name));
  try {
    if (motion)
      (void)s.motion(c.values, setting);
    else
      (void)s.statics(c.values, setting);
  } catch (const InputError& e) {
    t.error("solution", e.what());
  }
  return c;
}

}  // namespace mfree
