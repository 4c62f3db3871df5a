#include "mfree/io/path_scene.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/core/step_count.hpp"

namespace mfree {

namespace {

/// The four formulas in the order of [path] deformation_gradient (row-major, as F(i, J)).
Mat2 evaluate(const std::vector<Formula>& f, double t) {
  const Vec2 origin = Vec2::Zero();  // never read: the formulas use no x, y (checked)
  // Each value before the matrix is filled: a formula that throws (NaN) must not leave an
  // Eigen comma initializer half done (it asserts on that in its destructor).
  const double xx = f[0](origin, t), xy = f[1](origin, t), yx = f[2](origin, t), yy = f[3](origin, t);
  Mat2 out;
  out << xx, xy, yx, yy;
  return out;
}

}  // namespace

Mat2 PathScene::deformation(double t) const { return evaluate(deformation_gradient, t); }

DeformationPath PathScene::deformation_path() const {
  return [f = deformation_gradient](double t) { return evaluate(f, t); };
}

bool is_path_scene(const std::filesystem::path& file) { return Scene::load(file).root().has("path"); }

PathScene read_path_scene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  const Scene scene = Scene::load(file, overrides);
  const SceneTable root = scene.root();
  PathScene out;
  out.file = file;
  const Constants constants = read_constants(root);
  {
    const SceneTable t = root.table("material");
    if (t.has("density")) t.error("density", "a material-point path has no mass: remove density");
    out.material = read_material_keys(t);  // finishes t
  }
  {
    const SceneTable t = root.table("path");
    const std::string key = "deformation_gradient";
    const std::vector<std::string> text = t.expressions(key, 4);
    const char* component[4] = {"F_xx", "F_xy", "F_yx", "F_yy"};
    for (int k = 0; k < 4; ++k) {
      Formula f(text[static_cast<std::size_t>(k)], constants, t.where(key, k));
      if (f.depends_on_space())
        throw InputError(fmt::format("{}: {} = '{}' uses x, y, X or Y; a material point has no position: F is a "
                                     "function of t and the [constants] only",
                                     t.where(key, k), component[k], f.expression()));
      out.deformation_gradient.push_back(std::move(f));
    }
    out.path.end_time = t.number("end_time", 0.0, 1e300);
    if (!(out.path.end_time > 0.0)) t.error("end_time", "must be positive");
    const auto most = static_cast<long long>(max_time_steps);
    out.path.increments = static_cast<int>(t.integer("increments", 1, most));
    out.path.record_every = static_cast<int>(t.integer_or("record_every", 1, 1, most));
    t.finish();
  }
  {
    const SceneTable t = root.table("output");
    out.folder = read_output_folder(t);
    t.finish();
  }
  root.finish();
  // The formulas at both ends: one that is NaN or infinite there is an error now, naming its
  // key, not after part of the path has run.
  (void)out.deformation(0.0);
  (void)out.deformation(out.path.end_time);
  return out;
}

}  // namespace mfree
