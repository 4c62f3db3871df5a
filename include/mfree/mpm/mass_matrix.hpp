#pragma once
// The particle mass matrix of the grid and the two ways particle data reach the nodes
// (seed 004; SPEC section 11).
//
// With phi_ip = S_ip the weight of node i at particle p (particle_basis.hpp), a particle
// field u_p becomes nodal values u_i = sum_p psi_pi u_p by
//
//   lumped          psi_pi = m_p S_ip / m_i,  m_i = sum_p m_p S_ip (seed 004's option 1, what
//                   every MPM does): a local weighted mean, non-negative, compactly supported
//   pseudo_inverse  u = argmin sum_p m_p (sum_i S_ip u_i - u_p)^2, the mass-weighted
//                   pseudo-inverse of the particle-by-node matrix S (seed 004's option 2):
//                   M u = sum_p m_p S_ip u_p with the consistent mass matrix
//                   M_ij = sum_p m_p S_ip S_jp
//
// The pseudo-inverse reproduces every field the weights reproduce (constant and linear ones:
// sum_i x_i S_ip = x_p) at every node whose rows it determines, which needs at least two
// particles per cell and direction; its particle basis functions are neither non-negative nor
// compactly supported (every u_i depends on every particle of the body). Where a body covers
// a node's support only in part (a sliver of a particle domain, a body's edge between
// nodes), the rows are nearly singular: nodes whose support the particles cover by less
// than a fifth, sum_p V_p S_ip < int N_i / 5, keep their lumped values, and the others are
// solved for, each with its coupling to those lumped nodes moved onto its diagonal, as the
// lumped node's row sum carries its coupling to them (a partially lumped pseudo-inverse whose
// matrix stays symmetric with the row sums m_i; a rectangle on the node lines covers its edge
// nodes by a half and its corners by a quarter, and is solved for everywhere). With the lumped
// values taken as known in the free rows instead, the matrix was unsymmetric, and a rubber
// wedge bouncing on a floor gained 67 % of its energy in 0.6 s (1.03 with the symmetric
// matrix; verification/mpm-vibration/README.md). In the time step the
// same matrix maps momenta and forces to nodal velocities and accelerations: v = M^-1 (mv),
// a = M^-1 f, the Galerkin (consistent-mass) semi-discretisation. The rows of M sum to the
// lumped masses m_i (partition of unity), so both mappings carry the same total mass.
//
// Short-wave filter (filter = beta > 0; an addition to seed 004): the solves use
//
//   M~ = M + beta D L^-1 D,   L = diag(m_i) the lumped masses, D = L - M,
//
// in place of M, in both mappings of the time step (particle momenta to velocities, forces
// to accelerations). D has zero row sums, a non-negative diagonal and non-positive
// off-diagonal entries (the particles' couplings as a weighted graph Laplacian), so M~ is
// symmetric positive definite with the row sums m_i: momentum is carried as with M, and
// constants are reproduced. D acts on a smooth field of wave number k as O(kh) L where a
// node's particles lie to one side of it (walls, moved arrangements) and O((kh)^2) L where
// they are spread symmetrically, so D L^-1 D changes the mass of smooth modes by O((kh)^2)
// to O((kh)^4); on the grid's shortest modes (two or three cells), where M is several
// times smaller than L, it adds mass of the order of L. Linear fields are no longer
// reproduced exactly (by O(beta (kh)^2) at one-sided nodes). Why: with MLS-reconstructed
// forces, which are not the derivative of a stored energy, those short modes grow over
// several periods under the pseudo-inverse, and beta = 0.3 holds them over ten periods on 16
// cells, the one-period errors within a factor 2.5 of the unfiltered ones and their rates
// near 3 (verification/mpm-vibration/README.md). beta = 0: seed 004's
// pseudo-inverse.
//
// Storage: M as a stencil, for every node the (2r + 1)^2 entries of the nodes within r
// nodes along each axis (r = the radius of the basis: degree for B-splines, 1 for Classic,
// 3 for the methods with particle domains, whose hats reach up to 4 nodes apart). Units: kg
// per unit thickness.

#include <vector>

#include "mfree/core/name_table.hpp"
#include "mfree/core/types.hpp"
#include "mfree/mpm/grid.hpp"
#include "mfree/mpm/grid_transfer.hpp"

namespace mfree {

enum class GridMapping { lumped, pseudo_inverse };
/// The mappings by name: lumped, pseudo_inverse.
const NameTable<GridMapping>& grid_mapping_names();

class GridMassMatrix {
 public:
  /// radius: the largest node distance (per axis) of two nodes one particle reaches;
  /// filter: beta of the short-wave filter (>= 0; 0: the pseudo-inverse itself).
  GridMassMatrix(const Grid& grid, int radius, double filter = 0.0);

  /// M_ij = sum_q mass[q] S_qi S_qj over the points q of the table, and the nodes' cover
  /// sum_q volume[q] S_qi / int N_i. NumericalError naming the point when two of its nodes
  /// lie farther apart than the radius.
  void assemble(const WeightTable& weights, const std::vector<double>& mass, const std::vector<double>& volume);

  /// M~ u = q (the filtered matrix; M itself when beta = 0) for u, node by node and component by component,
  /// with the lumped masses m_i (the row sums, as scattered): u = 0 on the nodes whose lumped mass is at most
  /// `floor` and on the components `held` holds (bit 0: x, bit 1: y; the walls' zero velocities), u_i = q_i /
  /// m_i on the nodes covered by less than a fifth, M~ u = q in the rows of the others with their couplings
  /// to those nodes summed on the diagonal (a symmetric matrix with the row sums m_i: sum_i m_i u_i = sum_i
  /// q_i on the components not held). Conjugate gradients with the diagonal of M~ as preconditioner, started
  /// from the lumped values q_i / m_i, to a residual of 1e-13 |q|. NumericalError naming the place when M is
  /// (nearly) singular on the free nodes, which shows as a nodal value over 100 times the
  /// largest lumped one (too few particles to determine it), or the iteration does not
  /// converge.
  [[nodiscard]] std::vector<Vec2> solve(const std::vector<Vec2>& q, const std::vector<double>& lumped,
                                        const std::vector<unsigned char>& held, double floor) const;

  /// M~ x over every node (no walls, no lumped nodes): the matrix the solves invert.
  [[nodiscard]] std::vector<Vec2> filtered_product(const std::vector<Vec2>& x) const;
  /// M_ij (0 beyond the radius).
  [[nodiscard]] double entry(Index i, Index j) const;
  /// sum_j M_ij, the lumped mass m_i.
  [[nodiscard]] double row_sum(Index i) const;
  /// sum_p V_p S_ip / int N_i: how much of node i's support the particles cover.
  [[nodiscard]] double cover(Index i) const { return cover_[static_cast<std::size_t>(i)]; }

 private:
  /// Stencil position of node j in node i's row, or -1 beyond the radius.
  [[nodiscard]] int offset(Index i, Index j) const;
  /// f(j, o) for every node j of the grid within node i's stencil, o its stencil position.
  template <class F>
  void for_each_in_stencil(Index i, F&& f) const;
  /// y = M x.
  void multiply(const std::vector<Vec2>& x, std::vector<Vec2>& y) const;
  /// y = M~ x; d and f: work vectors of the nodes' size.
  void multiply_filtered(const std::vector<Vec2>& x, std::vector<Vec2>& y, std::vector<Vec2>& d,
                         std::vector<Vec2>& f) const;

  const Grid& grid_;
  Index nodes_, nx_;
  int radius_, width_;                 ///< width = 2 radius + 1
  double filter_;                      ///< beta
  std::vector<double> values_;         ///< node i's row: width^2 entries, (dx, dy) at (dx + r) + width (dy + r)
  std::vector<double> lumped_;         ///< per node: m_i, the row sum of M
  std::vector<double> diagonal_;       ///< per node: M~_ii
  ScatterBuffers<double> partial_;     ///< per-thread rows of the assembly
  std::vector<double> cover_;          ///< per node: sum_p V_p S_ip / int N_i
  ScatterBuffers<double> partial_cover_;
};

}  // namespace mfree
