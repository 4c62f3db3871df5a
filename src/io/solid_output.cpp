#include "mfree/io/solid_output.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "mfree/geometry/domain_triangulation.hpp"
#include "mfree/io/vtk_output.hpp"

namespace mfree {

namespace {

std::string frame_file(int frame) { return fmt::format("field_{:04d}.vtu", frame); }
std::string point_file(int frame) { return fmt::format("points_{:04d}.vtu", frame); }

}  // namespace

void SolidFrames::save(CheckpointState& state) const {
  std::vector<double> times;
  for (const auto& step : steps_) times.push_back(step.first);
  state.put("frames.time", std::move(times));
}

void SolidFrames::restore(const CheckpointState& state, double time, std::size_t most) {
  const std::vector<double>& times = state.times("frames.time", time, most);
  steps_.clear();
  point_steps_.clear();
  for (const double t : times) {
    steps_.emplace_back(t, frame_file(frames()));
    if (model_) point_steps_.emplace_back(t, point_file(frames() - 1));
  }
}

SolidFrames::SolidFrames(const ElasticityScene& scene, const Discretisation<2>& disc,
                         const ExactMotion<2>* exact, const TotalLagrangian<2>* model)
    : output_(scene.output),
      exact_(exact),
      model_(scene.law_with(has_history) ? model : nullptr),
      folder_(scene.output.folder) {
  if (scene.law_with(has_history) && !model_)
    throw std::logic_error("SolidFrames: a law with history needs the model that holds it");
  Triangulation tri = triangulate_domain(scene.domain, disc.nodes);
  points_ = std::move(tri.points);
  samples_ = std::move(tri.samples);
  // Each sample lies in its face's region: its law there.
  for (const Vec2& x : samples_) law_.push_back(scene.law_at(x));
  triangles_ = std::move(tri.triangles);
  const bool gradients = !model_ && (output_.wants("stress") || output_.wants("von_mises") || output_.wants("error"));
  at_ = sample_shape_functions(*disc.trial, samples_, gradients);
}

void SolidFrames::write_points(double time, const Eigen::VectorXd& d) {
  const GalerkinQuadrature<2>& q = model_->quadrature();
  const bool want_response = output_.wants("stress") || output_.wants("von_mises") || output_.wants("plastic_strain");
  std::vector<double> u, sigma, vm, alpha;
  for (Index k = 0; k < q.size(); ++k) {
    if (output_.wants("displacement")) {
      const Vec2 uk = displacement_at(q, k, d);
      u.insert(u.end(), {uk.x(), uk.y()});
    }
    if (!want_response) continue;
    const TotalLagrangian<2>::PointResponse r = model_->response(k, d);
    if (output_.wants("stress")) sigma.insert(sigma.end(), {r.cauchy(0, 0), r.cauchy(1, 1), r.cauchy(0, 1)});
    if (output_.wants("von_mises")) vm.push_back(von_mises(r.cauchy, r.cauchy_zz));
    if (output_.wants("plastic_strain")) alpha.push_back(r.state.alpha);
  }
  std::vector<PointField> fields;
  if (output_.wants("displacement")) fields.push_back({"displacement", 2, std::move(u)});
  if (output_.wants("stress")) fields.push_back({"cauchy_stress_xx_yy_xy", 3, std::move(sigma)});
  if (output_.wants("von_mises")) fields.push_back({"von_mises", 1, std::move(vm)});
  if (output_.wants("plastic_strain")) fields.push_back({"plastic_strain", 1, std::move(alpha)});
  const std::string name = point_file(frames());
  write_point_cloud_vtu(folder_ / name, q.points, fields);
  point_steps_.emplace_back(time, name);
  write_pvd(point_series(), point_steps_);
}

void SolidFrames::write(double time, const Eigen::VectorXd& d, const Eigen::VectorXd* v) {
  if (model_) write_points(time, d);
  const bool want_error = output_.wants("error") && exact_;
  const bool want_u = output_.wants("displacement") || want_error;
  const bool want_v = v && output_.wants("velocity");
  const bool want_stress = !model_ && (output_.wants("stress") || output_.wants("von_mises") || want_error);
  std::vector<double> u, vel, sigma, vm, ue, se;
  for (Index k = 0; k < at_.size(); ++k) {
    Vec2 uk = Vec2::Zero(), vk = Vec2::Zero();
    Mat2 f = Mat2::Identity();
    for (Index s = at_.row_begin(k); s < at_.row_end(k); ++s) {
      const auto di = d.segment<2>(2 * at_.nodes[s]);
      if (want_u) uk += at_.phi[s] * di;
      if (want_v) vk += at_.phi[s] * v->segment<2>(2 * at_.nodes[s]);
      if (want_stress) f += di * at_.grad[s].transpose();
    }
    if (output_.wants("displacement")) u.insert(u.end(), {uk.x(), uk.y()});
    if (want_v) vel.insert(vel.end(), {vk.x(), vk.y()});
    if (want_stress) {
      const Material& law = law_[static_cast<std::size_t>(k)];
      const Mat2 s = cauchy_stress(law, f);
      if (output_.wants("stress")) sigma.insert(sigma.end(), {s(0, 0), s(1, 1), s(0, 1)});
      if (output_.wants("von_mises")) vm.push_back(von_mises(s, out_of_plane_stress(law, f)));
      if (want_error) {
        const Vec2 eu = uk - exact_->displacement(samples_[k], time);
        const Mat2 es = s - exact_->cauchy_stress(samples_[k], time);
        ue.insert(ue.end(), {eu.x(), eu.y()});
        se.insert(se.end(), {es(0, 0), es(1, 1), es(0, 1)});
      }
    }
  }
  std::vector<PointField> fields;
  if (output_.wants("displacement")) fields.push_back({"displacement", 2, std::move(u)});
  if (want_v) fields.push_back({"velocity", 2, std::move(vel)});
  if (want_stress && output_.wants("stress")) fields.push_back({"cauchy_stress_xx_yy_xy", 3, std::move(sigma)});
  if (want_stress && output_.wants("von_mises")) fields.push_back({"von_mises", 1, std::move(vm)});
  if (want_error) {
    fields.push_back({"displacement_error", 2, std::move(ue)});
    fields.push_back({"stress_error_xx_yy_xy", 3, std::move(se)});
  }
  const std::string name = frame_file(frames());
  write_triangles_vtu(folder_ / name, points_, triangles_, fields);
  steps_.emplace_back(time, name);
  write_pvd(series(), steps_);
}

}  // namespace mfree
