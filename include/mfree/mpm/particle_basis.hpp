#pragma once
// The functions that carry particle data to the grid and back: for particle p and grid
// node i, the weight S_ip and the gradient weight G_ip (seed 002, "Theory: Shape
// Functions"; SPEC sections 7 and 11). The GIMP methods average the grid's hats N_i over the
// particle domain Omega_p of area V: S_ip = (1 / V) int N_i, G_ip = (1 / V) int grad N_i.
//
//   classic   S_ip = N_i(x_p), G_ip = grad N_i(x_p), hats N_i (degree 1)
//   ugimp     the exact averages over the undeformed square domain x_p +- (l_x, l_y), which
//             only translates
//   cpgimp    the exact averages over the axis-aligned rectangle x_p +- (l_x F_xx, l_y F_yy).
//             The stretch is F_ii, the projection of the deformed edge F (l_i e_i) onto its
//             own axis: for the motions without shear that cpGIMP is made for (F diagonal) the
//             rectangle is the deformed domain itself and its area J V_0, so in 1D cpGIMP is
//             finite GIMP (seed 002). The column norm |F e_i| would keep a rotated domain's
//             size but grow it under shear; with F_ii a rotation shrinks the domain and
//             F_ii <= 0 is refused (NumericalError).
//   cpdi      lCPDI (Sadeghirad, Brannon, Burghardt 2011): the parallelogram with corners
//             x_p + F_p (+-l_x, +-l_y), mapped by the bilinear element
//   qcpdi     qCPDI (the same paper): that parallelogram mapped by the 8-node serendipity
//             element (corners and edge midpoints)
//   cpdi2     CPDI2 (Sadeghirad, Brannon, Guilkey 2013): the quadrilateral of the particle's own
//             tracked corners (Particles::corners), mapped by the bilinear element
//             The CPDIs replace N_i by its interpolant on the element's nodes y_k:
//             S_ip = sum_k w_k N_i(y_k), G_ip = (1 / V) sum_k N_i(y_k) int grad M_k, with the
//             weights and gradient integrals of domain_nodes.hpp
//   bspline   S_ip = N_i(x_p), G_ip = grad N_i(x_p), quadratic or cubic B-splines (seed 000
//             eqs. 4-5); the MLS-reconstructed method uses the same functions at particles
//   bspline_cpgimp
//             the exact averages of the quadratic or cubic B-splines over cpGIMP's rectangle,
//             clipped to the grid (whose ends are the walls of the open knot vectors). Point
//             values of the B-splines make the particles a quadrature of the internal force
//             whose error stops the convergence once particles have crossed knot lines; the
//             averages integrate the functions exactly over domains that tile the body, so
//             only the stress, constant on each domain, is approximated (Steffen, Kirby,
//             Berzins 2008 trace the stall to that quadrature). In 1D, and in 2D without shear,
//             the rectangles are the deformed domains themselves.
//
// Corners are counter-clockwise, c_0 at (-l_x, -l_y) of the reference domain, and
// perp(d) = (d_y, -d_x) turns a counter-clockwise edge into its outward normal (times length).
//
// Every variant is a partition of unity (sum_i S_ip = 1, sum_i G_ip = 0) and linearly
// complete (sum_i x_i S_ip = x_p, and sum_i x_i G_ip^T = I) wherever its functions all exist.
// For CPDI2, sum_i x_i S_ip is the area centroid of the tracked quadrilateral, which x_p
// (moved with sum_i S_ip v_i like every particle) need not stay exactly.
//
// A particle's weights fill a fixed-size slot of a WeightTable (grid_transfer.hpp) of stride()
// entries: the two axes' functions for the tensor-product bases (classic, the GIMPs,
// B-splines), explicit entries for the CPDIs (4 hats at each of 4 or 8 points: 16 or 32, so
// they always fit). uGIMP's domain is at most a cell wide (3 hats per axis); cpGIMP's slot
// holds 4 hats per axis, a domain of up to two cells, and B-spline cpGIMP's p + 2 functions
// per axis, a domain that meets at most two cells (always when it is at most a cell wide);
// one that outgrows its slot is a NumericalError naming the particle. Unused entries have S = 0 and G = 0 (the CPDIs' at
// node 0, the GIMPs' at hats beside those the domain touches), so loops need no branch.

#include <array>
#include <string_view>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/mpm/domain_nodes.hpp"
#include "mfree/mpm/grid.hpp"
#include "mfree/mpm/particles.hpp"

namespace mfree {

enum class MPMMethod { classic, ugimp, cpgimp, cpdi, qcpdi, cpdi2, bspline, bspline_cpgimp, bspline_mls };

/// One method as a scene names it: the weights and, for B-splines, the degree.
struct MPMMethodChoice {
  MPMMethod method = MPMMethod::bspline;
  int degree = 2;  ///< 1 for the hat-function methods
  bool operator==(const MPMMethodChoice&) const = default;
};
/// classic, ugimp, cpgimp, cpdi, qcpdi, cpdi2, bspline (quadratic), bspline_cubic,
/// bspline_cpgimp (quadratic), bspline_cpgimp_cubic, bspline_mls.
const NameTable<MPMMethodChoice>& mpm_method_names();
/// The name of the method's first entry in mpm_method_names() (bspline for every degree).
std::string_view to_string(MPMMethod m);
/// Whether the method's weights need particle domains (Particles::half_size, and for CPDI2
/// Particles::corners): the GIMPs (B-spline cpGIMP too) and the CPDIs.
bool uses_domains(MPMMethod m);
/// Grid padding (cells on every side) a method needs: one for the hat-function methods with
/// domains (B-spline cpGIMP clips its domains at the walls instead).
int grid_padding(MPMMethod m);
bool is_bspline(MPMMethod m);

struct WeightTable;

class ParticleBasis {
 public:
  ParticleBasis(MPMMethod method, const Grid& grid);

  [[nodiscard]] MPMMethod method() const { return method_; }
  [[nodiscard]] int stride() const { return stride_; }
  /// Sizes `table` for `points` points in this basis' layout.
  void resize(WeightTable& table, Index points) const;
  /// Weights of particle p of P (its position, F, half size and, for CPDI2, corners) into
  /// point q of `table` (sized by resize()).
  void evaluate(const Particles& P, Index p, WeightTable& table, Index q) const;
  /// Weights of a particle at x with deformation gradient F and reference domain half sizes
  /// (l_x, l_y) (F is read by the cpGIMPs, cpdi and qcpdi, half by the methods with domains), into
  /// point q of `table`. Every method but cpdi2 (std::logic_error: its domain is its corners).
  /// Throws NumericalError naming the position when the particle (or a point of its domain)
  /// is not on the grid or its domain is degenerate or outgrows the slot.
  void evaluate(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const;
  /// CPDI2's weights for the quadrilateral with counter-clockwise corners c of the particle at
  /// x (x names it in messages); for cpdi2 (and the parallelogram of cpdi) only.
  void evaluate_quadrilateral(const DomainCorners& c, const Vec2& x, WeightTable& table, Index q) const;
  /// The particle domain as the method sees it (ugimp: the reference square; the cpGIMPs: the
  /// stretched rectangle, not clipped; cpdi, qcpdi: the parallelogram; cpdi2: the tracked corners),
  /// counter-clockwise; for the methods with domains only (std::logic_error otherwise).
  [[nodiscard]] DomainCorners domain_corners(const Particles& P, Index p) const;
  /// sum_i N_i(x) v_i with the grid's hats N_i (degree 1), x on the grid: the grid velocity
  /// that moves CPDI2's corners.
  [[nodiscard]] Vec2 hat_interpolate(const Vec2& x, const std::vector<Vec2>& nodal) const;

 private:
  template <int p>
  void point_weights(const Vec2& x, WeightTable& table, Index q) const;
  template <int n>
  void gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const;
  template <int p>
  void bspline_gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const;
  template <int n>
  void node_sum(const DomainNodes<n>& nodes, const Vec2& x, const char* what, WeightTable& table, Index q) const;
  [[nodiscard]] Vec2 stretched_half(const Vec2& x, const Mat2& F, const Vec2& half) const;
  void check_on_grid(const Vec2& y, const char* what, const Vec2& particle) const;

  MPMMethod method_;
  const Grid& grid_;
  int stride_;
  int axis_;  ///< functions per axis of the tensor layout; 0 for the CPDIs' explicit entries
};

}  // namespace mfree
