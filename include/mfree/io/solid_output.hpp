#pragma once
// VTK frames of a total-Lagrangian run, for ParaView: one field_NNNN.vtu per frame on a
// constrained Delaunay triangulation of the nodes (holes respected), and series.pvd listing
// the frames with their time (dynamics) or load factor (statics), so ParaView plays them as
// a time series. Only the fields the scene asks for ([output] fields) are computed:
//
//   displacement  u^h = sum phi_I d_I (never the coefficients)
//   velocity      v^h = sum phi_I v_I (dynamics)
//   stress        Cauchy stress (xx, yy, xy) of F^h = I + grad u^h
//   von_mises     of the Cauchy stress with the law's sigma_zz
//   error         u^h - u and sigma^h - sigma against the exact motion, when there is one
//
// A law with history (J2, Drucker–Prager) has its stress at the quadrature points, where its
// state lives: stress, von_mises and plastic_strain (the equivalent plastic strain alpha) are
// then written on those points instead, as points_NNNN.vtu in points.pvd, with u^h there;
// the triangulation keeps the displacement and velocity.
//
// Files are written atomically; the .pvd is rewritten after every frame, so a run stopped
// early leaves a valid series of the frames written so far.

#include <filesystem>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/galerkin/total_lagrangian.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_scene.hpp"

namespace mfree {

class SolidFrames {
 public:
  /// exact: the motion errors are measured against (may be null). model: the solver whose
  /// quadrature points hold the history (needed for a law with history, else unused); it
  /// must outlive the frames.
  SolidFrames(const ElasticityScene& scene, const Discretisation<2>& disc, const ExactMotion<2>* exact,
              const TotalLagrangian<2>* model = nullptr);
  /// Writes frame number frames() at `time`; v may be null (statics).
  void write(double time, const Eigen::VectorXd& d, const Eigen::VectorXd* v);
  [[nodiscard]] int frames() const { return static_cast<int>(steps_.size()); }
  /// Checkpoints: the series written so far ("frames.time"), and continuing it. restore()
  /// takes at most `most` frames at times in [0, time] (the run's so far), in order
  /// (InputError otherwise, io/checkpoint.hpp).
  void save(CheckpointState& state) const;
  void restore(const CheckpointState& state, double time, std::size_t most);
  [[nodiscard]] std::filesystem::path series() const { return folder_ / "series.pvd"; }
  /// The series of the quadrature points (a law with history).
  [[nodiscard]] std::filesystem::path point_series() const { return folder_ / "points.pvd"; }

 private:
  const OutputSettings& output_;
  std::vector<Material> law_;  ///< per sample
  const ExactMotion<2>* exact_;
  const TotalLagrangian<2>* model_;  ///< set for a law with history
  std::filesystem::path folder_;
  std::vector<Vec2> points_, samples_;  ///< the plot's vertices, where their fields are sampled
  std::vector<std::array<Index, 3>> triangles_;
  GalerkinQuadrature<2> at_;
  std::vector<std::pair<double, std::string>> steps_, point_steps_;

  /// The quadrature-point fields of a law with history.
  void write_points(double time, const Eigen::VectorXd& d);
};

}  // namespace mfree
