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
// Files are written atomically; the .pvd is rewritten after every frame, so a run stopped
// early leaves a valid series of the frames written so far.

#include <filesystem>
#include <vector>

#include "mfree/galerkin/elasticity_solver.hpp"
#include "mfree/galerkin/motion_errors.hpp"
#include "mfree/io/checkpoint.hpp"
#include "mfree/io/elasticity_scene.hpp"

namespace mfree {

class SolidFrames {
 public:
  /// exact: the motion errors are measured against (may be null).
  SolidFrames(const ElasticityScene& scene, const Discretisation& disc, const ExactMotion* exact);
  /// Writes frame number frames() at `time`; v may be null (statics).
  void write(double time, const Eigen::VectorXd& d, const Eigen::VectorXd* v);
  [[nodiscard]] int frames() const { return static_cast<int>(steps_.size()); }
  /// Checkpoints: the series written so far ("frames.time"), and continuing it.
  void save(CheckpointState& state) const;
  void restore(const CheckpointState& state);
  [[nodiscard]] std::filesystem::path series() const { return folder_ / "series.pvd"; }

 private:
  const OutputSettings& output_;
  Material material_;
  const ExactMotion* exact_;
  std::filesystem::path folder_;
  std::vector<Vec2> points_;
  std::vector<std::array<Index, 3>> triangles_;
  GalerkinQuadrature at_;
  std::vector<std::pair<double, std::string>> steps_;
};

}  // namespace mfree
