#pragma once
// The functions that carry particle data to the grid and back: for particle p and grid
// node i, the weight S_ip and the gradient weight G_ip (seed 002, "Theory: Shape
// Functions"; SPEC section 7):
//
//   classic   S_ip = N_i(x_p), G_ip = grad N_i(x_p), hats N_i (degree 1)
//   ugimp     averages of the hats over the particle's undeformed square domain, which only
//             translates: S_ip = (1 / V) int_{Omega_p} N_i, G_ip = (1 / V) int grad N_i
//   cpdi      lCPDI (Sadeghirad et al. 2011): the domain is the parallelogram with half-edge
//             vectors r1 = F_p (l_x, 0), r2 = F_p (0, l_y) and corners c_k; N_i is replaced
//             by its bilinear interpolant from the corners, so S_ip = (1/4) sum_k N_i(c_k)
//             and G_ip = (1 / V) sum_k N_i(c_k) n_k, n_k = perp(c_{k+1} - c_{k-1}) / 2 the
//             corner's share of the outward edge normals (divergence theorem)
//   bspline   S_ip = N_i(x_p), G_ip = grad N_i(x_p), quadratic or cubic B-splines (seed 000
//             eqs. 4-5); the MLS-reconstructed method uses the same functions at particles
//
// Every variant is a partition of unity (sum_i S_ip = 1, sum_i G_ip = 0) and linearly
// complete (sum_i x_i S_ip = x_p, sum_i x_i G_ip^T = I) wherever its functions all exist.
//
// A particle's weights fill a fixed-size slot of a WeightTable (grid_transfer.hpp) of stride()
// entries: the two axes' functions for the tensor-product bases (all but CPDI), the entries
// for CPDI. Unused entries have S = 0 and G = 0 (CPDI's at node 0, uGIMP's at hats beside
// those its domain touches), so loops over a slot need no branch.

#include <string_view>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/mpm/grid.hpp"

namespace mfree {

enum class MPMMethod { classic, ugimp, cpdi, bspline, bspline_mls };

/// One method as a scene names it: the weights and, for B-splines, the degree.
struct MPMMethodChoice {
  MPMMethod method = MPMMethod::bspline;
  int degree = 2;  ///< 1 for the hat-function methods
  bool operator==(const MPMMethodChoice&) const = default;
};
/// classic, ugimp, cpdi, bspline (quadratic), bspline_cubic, bspline_mls.
const NameTable<MPMMethodChoice>& mpm_method_names();
/// The name of the method's first entry in mpm_method_names() (bspline for every degree).
std::string_view to_string(MPMMethod m);
/// Grid padding (cells on every side) and B-spline degree a method needs.
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
  /// Weights of a particle at x with deformation gradient F and reference domain half sizes
  /// (l_x, l_y) (F and half are read by ugimp and cpdi only), into point q of `table` (sized
  /// by resize()). Throws NumericalError naming the position when the particle (or its
  /// domain) is not on the grid.
  void evaluate(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const;

 private:
  template <int p>
  void point_weights(const Vec2& x, WeightTable& table, Index q) const;
  void gimp_weights(const Vec2& x, const Vec2& half, WeightTable& table, Index q) const;
  void cpdi_weights(const Vec2& x, const Mat2& F, const Vec2& half, WeightTable& table, Index q) const;
  void check_on_grid(const Vec2& x, const char* what) const;

  MPMMethod method_;
  const Grid& grid_;
  int stride_;
  int axis_;  ///< functions per axis of the tensor layout; 0 for CPDI's explicit entries
};

}  // namespace mfree
