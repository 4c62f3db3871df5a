#include "mfree/io/scene_sections.hpp"

#include <algorithm>

namespace mfree {

MaterialSection read_material(const SceneTable& root) { return read_material_keys(root.table("material")); }

MaterialSection read_material_keys(const SceneTable& t) {
  MaterialSection m;
  m.model = t.choice("model", {"plane_stress", "plane_strain", "neo_hookean", "st_venant_kirchhoff"});
  m.linear.model = m.model == "plane_stress" ? PlaneModel::stress : PlaneModel::strain;
  m.linear.youngs_modulus = t.number("youngs_modulus", 0.0, 1e300);
  m.linear.poisson_ratio = t.number("poisson_ratio", -1.0, 0.5);
  if (!(m.linear.youngs_modulus > 0.0)) t.error("youngs_modulus", "must be positive");
  if (!(m.linear.poisson_ratio > -1.0 && m.linear.poisson_ratio < 0.5))
    t.error("poisson_ratio", "must lie strictly between -1 and 1/2");
  m.material = make_material(m.model, m.linear.youngs_modulus, m.linear.poisson_ratio);
  if (t.has("density")) {
    m.density = t.number("density", 0.0, 1e300);
    if (!(m.density > 0.0)) t.error("density", "must be positive");
  }
  t.finish();
  return m;
}

Box read_box(const SceneTable& t, const std::string& key) {
  const auto p = t.pairs(key, 2);
  return {Vec2(std::min(p[0][0], p[1][0]), std::min(p[0][1], p[1][1])),
          Vec2(std::max(p[0][0], p[1][0]), std::max(p[0][1], p[1][1]))};
}

Constants read_constants(const SceneTable& root) {
  Constants c;
  if (!root.has("constants")) return c;
  const SceneTable t = root.table("constants");
  for (const std::string& k : t.keys()) c[k] = t.number(k, -1e300, 1e300);
  // Names are checked where formulas are built; check them here too, so that a scene
  // without formulas still refuses a bad [constants] table.
  (void)Formula("0", c, t.where(c.empty() ? "" : c.begin()->first));
  t.finish();
  return c;
}

Formula read_formula(const SceneTable& t, const std::string& key, const Constants& constants) {
  return Formula(t.expression(key), constants, t.where(key));
}

VectorFormula read_vector_formula(const SceneTable& t, const std::string& key, const Constants& constants) {
  const std::vector<std::string> e = t.expressions(key, 2);
  const std::string at = t.where(key);
  return {Formula(e[0], constants, at + "[0]"), Formula(e[1], constants, at + "[1]")};
}

}  // namespace mfree
