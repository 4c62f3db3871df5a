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
// README.md; over ten periods at A = 0.1 on 16 cells every MLS configuration gains energy,
// the pseudo-inverse's most), but needs 6 particles not on one conic around every Gauss
// point (the linear basis 3 not on a line).
// These are the RK functions of kernels/ with the particles as nodes (the moment matrix of
// kernels/rk_moment.hpp, which the Galerkin solver's functions use too), evaluated cell by
// cell: the particles are binned by half cells, and one pass over those around a cell sums
// the four moment matrices of its Gauss points side by side (one SIMD lane each) and
// stores phi_gp of the four points per particle, so that a reconstruction reads each
// particle's value once per cell. Cost at 64^2 cells, 9 particles per cell and the default
// kernel: the whole MLS step 2.5-2.8 plain B-spline steps (verification/benchmarks).
//
// Quadrature (the mixed integration of Al-Kafaji, PhD thesis, Stuttgart 2013: Gauss points
// where the material fills the cells, the particles themselves elsewhere). The Gauss points
// are the 2 x 2 Gauss-Legendre points, weight omega_g = h^2 / 4, of every interior cell: one
// the bodies fill, with every neighbour on the grid filled too. Filled: the cell's corners,
// edge midpoints and centre all lie in particle domains, the square of the particle's
// reference volume (sqrt(V_p0) wide) mapped by F_p about x_p (lCPDI's domain, seed 002),
// widened by a quarter against the gaps neighbouring domains leave under a varying F. The
// particles of interior cells are the data of the reconstruction; every other particle (a
// band one to two cells deep along free surfaces and gaps to walls) is its own quadrature
// point, weight V_p, as in plain B-spline MPM, and no Gauss point sees it. So each particle's
// mass and stress enter one quadrature, and no Gauss point extrapolates over an edge. An
// interior cell with a Gauss point whose moment matrix is singular (the particles drew
// apart, or lie on a line or conic) is integrated by its particles too; they stay data for
// the other cells' Gauss points. With
// Gauss points in every cell holding particles, a rubber wedge dropped on a floor had 1.9-4.8
// times the energy put in 0.12 s after impact (verification/mpm-vibration/README.md, "Bodies
// that do not fill the grid"). A body that fills the grid (the vibration problem) has Gauss
// points in every cell. The grid weights (N_i, grad N_i) are tabulated at all quadrature
// points, Gauss points first. The reconstruction reproduces 1, x and y but does not conserve
// mass (SPEC section 7): the solver scales the densities at the Gauss points to the mass of
// the interior cells' particles each step and reports the defect it removed.
// Limit: the work of the Gauss-point forces is not the particles' stress power, and a body
// that deforms strongly gains energy (the wedge: a third of the energy put in, 0.6 s after
// impact; plain B-splines 0.7 %).

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

  /// Quadrature points: the Gauss points, then the particles outside the interior cells.
  [[nodiscard]] Index points() const { return gauss_count() + static_cast<Index>(own_.size()); }
  [[nodiscard]] Index gauss_count() const { return static_cast<Index>(points_.size()); }
  [[nodiscard]] const std::vector<Vec2>& gauss_points() const { return points_; }
  [[nodiscard]] double gauss_weight() const { return omega_; }
  /// The particles that are their own quadrature points: point gauss_count() + k is
  /// particle own_particles()[k].
  [[nodiscard]] const std::vector<Index>& own_particles() const { return own_; }
  /// Interior cells the last update() returned to particle quadrature.
  [[nodiscard]] Index demoted_cells() const { return demoted_; }
  /// N_i and grad N_i at the quadrature points.
  [[nodiscard]] const WeightTable& grid_weights() const { return weights_; }

  /// The interior cells, Gauss points and phi_gp for the particles at `positions` with
  /// deformation gradients F_p and reference volumes V_p0 (once per step, reused by every
  /// field). An interior cell with a Gauss point whose moment matrix is singular (too few
  /// data around it, or all on a line or conic) gets no Gauss points: its particles are
  /// their own quadrature points (demoted_cells()).
  void update(const std::vector<Vec2>& positions, const std::vector<Mat2>& deformation,
              const std::vector<double>& volume0);

  /// at[g] = sum_p phi_gp value(p) at the Gauss points (eqs. 18-21), value(p) at a particle
  /// of its own. Fields needed at the same time are best reconstructed together (T stacking
  /// them): every call streams all phi_gp.
  template <class T, class Value>
  void reconstruct(std::vector<T>& at, Value&& value) const {
    at.resize(static_cast<std::size_t>(points()));
    const std::size_t gauss = points_.size();
    for (std::size_t k = 0; k < own_.size(); ++k) at[gauss + k] = value(own_[k]);
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
          for (int j = 0; j < T::SizeAtCompileTime; ++j) at[4 * c + q].data()[j] = sum(q, j);
      }
    });
  }

 private:
  /// The rows of the cells with Gauss points; 1 for a cell where a moment matrix is singular.
  template <int Order>
  std::vector<unsigned char> update_rows(const std::vector<Vec2>& positions);
  void place_gauss_points(const std::vector<unsigned char>& cells);
  void interior_cells(const std::vector<Vec2>& positions, const std::vector<Mat2>& deformation,
                      const std::vector<double>& volume0, std::vector<unsigned char>& interior) const;

  const Grid& grid_;
  const ParticleBasis& basis_;
  std::vector<unsigned char> gauss_cells_;  ///< per cell of the grid box: interior, not demoted
  std::vector<Vec2> points_;                ///< 4 per Gauss cell: (-,-), (+,-), (-,+), (+,+) about its centre
  std::vector<Index> own_;                  ///< the particles of the other cells
  std::vector<unsigned char> is_data_;      ///< per particle: in an interior cell (demoted or not)
  Index demoted_ = 0;
  double omega_ = 0.0;
  WeightTable weights_;
  RKSettings settings_;
  /// The particles of the grid box by half cells (bins of h / 2): those of bin b are
  /// bin_particle_[bin_start_[b] .. bin_start_[b + 1]), at bin_position_[same range].
  std::vector<Index> bin_start_, bin_particle_, bin_cell_;
  std::vector<Vec2> bin_position_;
  /// phi_gp of the four Gauss points of one interior cell: the particles p the functions of
  /// any of them reach, and the four values (zero for the points out of p's reach).
  struct Row {
    std::vector<Index> particle;
    std::vector<Eigen::Array4d> phi;
  };
  std::vector<Row> rows_;
};

}  // namespace mfree
