#pragma once
// Moving-least-squares reconstruction of particle fields at Gauss points (seed 000 eqs.
// 6-21): with the particles at x_p as the data points,
//
//   f_g = sum_p phi_gp f_p,   phi_gp = phi_p(x_g),
//
// phi the MLS functions of a linear (basis [1, x, y], seed 000 eq. 15) or quadratic basis
// with the quadratic spline kernel on a square support (eqs. 16-17) of half width a =
// support x h (seed 000: linear, a = 3 h, where its r_x = (x - x_p) / (2 l_x) reaches 3/2).
// The mfree default is the linear basis on a = 1.5 h (half the seed's support: more accurate
// at every grid); the quadratic basis on a = 1.5 h, with the pseudo-inverse mapping and the
// Verlet update, converges at 2.3-3.5 on the vibration problem (verification/mpm-vibration/
// README.md; ten periods at A = 0.1 on 16 cells complete with the lumped mapping, not with the
// pseudo-inverse, whose wall nodes run away after nine), but needs 6 particles not on one
// conic around every Gauss point: a body's edge
// with 2 particles per cell and direction leaves Gauss points that see two rows (a conic),
// and the run stops there (NumericalError).
// These are the RK functions of kernels/ with the particles as nodes (the moment matrix of
// kernels/rk_moment.hpp, which the Galerkin solver's functions use too), evaluated cell by
// cell: the particles are binned by half cells, and one pass over those around a cell sums
// the four moment matrices of its Gauss points side by side (one SIMD lane each) and
// stores phi_gp of the four points per particle, so that a reconstruction reads each
// particle's value once per cell. Cost at 64^2 cells, 9 particles per cell and the default
// kernel: the whole MLS step about 2.5 plain B-spline steps (verification/benchmarks).
// Limit: a body with free surfaces inside the grid gains energy once it presses against a
// wall (the Gauss points of a partly filled cell carry the whole cell; verification/
// mpm-vibration/README.md, "Bodies that do not fill the grid").
//
// The Gauss points are the 2 x 2 Gauss-Legendre points of every grid cell that holds a
// particle (cells the bodies leave empty have none), each with weight h^2 / 4 (omega_g),
// and carry the grid functions' weights (N_i, grad N_i) there. The reconstruction reproduces
// 1, x and y but does not conserve mass (SPEC section 7): the solver scales the reconstructed
// densities to the particles' mass each step and reports the defect it removed.

#include <array>
#include <vector>

#include "mfree/kernels/rk_shape_functions.hpp"
#include "mfree/mpm/grid_transfer.hpp"
#include "mfree/mpm/particle_basis.hpp"

namespace mfree {

class MLSReconstruction {
 public:
  /// order: of the basis; support: kernel half width in cells (seed 000: linear, 3).
  MLSReconstruction(const Grid& grid, const ParticleBasis& basis, RKOrder order, double support);

  [[nodiscard]] Index points() const { return static_cast<Index>(points_.size()); }
  [[nodiscard]] const std::vector<Vec2>& gauss_points() const { return points_; }
  [[nodiscard]] double gauss_weight() const { return omega_; }
  /// N_i and grad N_i at the Gauss points.
  [[nodiscard]] const WeightTable& grid_weights() const { return weights_; }

  /// Gauss points of the cells holding particles and phi_gp for the particles at
  /// `positions` (once per step, reused by every field). Throws NumericalError naming the
  /// Gauss point when too few particles surround it.
  void update(const std::vector<Vec2>& positions);

  /// at_gauss[g] = sum_p phi_gp value(p) (eqs. 18-21). Fields needed at the same time are
  /// best reconstructed together (T stacking them): every call streams all phi_gp.
  template <class T, class Value>
  void reconstruct(std::vector<T>& at_gauss, Value&& value) const {
    at_gauss.resize(points_.size());
    parallel_blocks(static_cast<Index>(rows_.size()), 64, [&](Index begin, Index end) {
      for (Index c = begin; c < end; ++c) {
        const Row& row = rows_[c];
        // Column j of sum: component j of T at the four points (a lane each).
        Eigen::Array<double, 4, T::SizeAtCompileTime> sum;
        sum.setZero();
        for (std::size_t k = 0; k < row.particle.size(); ++k) {
          const T v = value(row.particle[k]);
          for (int j = 0; j < T::SizeAtCompileTime; ++j) sum.col(j) += row.phi[k] * v.data()[j];
        }
        for (int q = 0; q < 4; ++q)
          for (int j = 0; j < T::SizeAtCompileTime; ++j) at_gauss[4 * c + q].data()[j] = sum(q, j);
      }
    });
  }

 private:
  template <int Order>
  void update_rows(const std::vector<Vec2>& positions);

  const Grid& grid_;
  const ParticleBasis& basis_;
  std::vector<unsigned char> active_;  ///< per cell of the grid box: holds a particle
  std::vector<Vec2> points_;           ///< 4 per cell holding particles: (-,-), (+,-), (-,+), (+,+) about its centre
  double omega_ = 0.0;
  WeightTable weights_;
  RKSettings settings_;
  /// The particles of the grid box by half cells (bins of h / 2): those of bin b are
  /// bin_particle_[bin_start_[b] .. bin_start_[b + 1]), at bin_position_[same range].
  std::vector<Index> bin_start_, bin_particle_, bin_cell_;
  std::vector<Vec2> bin_position_;
  /// phi_gp of the four Gauss points of one active cell: the particles p the functions of
  /// any of them reach, and the four values (zero for the points out of p's reach).
  struct Row {
    std::vector<Index> particle;
    std::vector<Eigen::Array4d> phi;
  };
  std::vector<Row> rows_;
};

}  // namespace mfree
