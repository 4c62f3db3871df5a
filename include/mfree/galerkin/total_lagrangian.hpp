#pragma once
// Total-Lagrangian meshfree solid mechanics (seed 003; SPEC section 5): the discrete forces
// and tangents of
//
//   int P(F) : grad_X v  +  N(u; v)  =  int rho0 b . v + int_Gt tbar . v     (statics)
//
// on the reference configuration, with F = I + grad_X u^h. At quadrature point K of the
// GalerkinQuadrature<dim> (projected, integration-consistent gradients g_I = gradbar phi_I(X_K)):
//
//   F_K = I + sum_I d_I g_I^T,   f_int,I = sum_K w_K P(F_K) t_I,
//   K_(I i)(J k) = sum_K w_K t_I,M A_iMkL(F_K) g_J,L
//
// (t_I the test gradients: g_I, or VCI's). Essential conditions by Nitsche's method on the
// reference boundary Gamma_u, for the components picked by Pi (I for `displacement`, N N^T
// for `slip`: a wall that only stops the normal component):
//
//   N(u; v) = - int Pi v . P(F) N  -  int Pi (C : grad v) N . (u - ubar)
//             + (beta M / h) int Pi v . (u - ubar),
//
// C = A(I) the reference tangent, M = C_xxxx its P-wave modulus (p_wave_modulus(), materials/),
// both of the law at the point (the penalty follows the local stiffness: a stiff inclusion
// does not stiffen the conditions on a soft matrix's boundary). The first
// term is the traction of the current state, so the form is consistent at any deformation; the second, with
// the constant C, makes it the symmetric Nitsche form of SPEC section 4 for small strain (one Newton step
// then solves a linear problem exactly). With a nonlinear material and Nitsche conditions the tangent is not
// symmetric (A(F) in one term, C in the other): symmetric() says which solver applies.
//
// Interfaces between regions (Domain::regions(); Crack::interface(); a solid's
// Solid::interfaces(), + the face of its `from` region) are tied by Nitsche's
// method (Nitsche 1971; for bonded interfaces e.g. Annavarapu, Hautefeuille, Dolbow 2012):
// with [[u]] = u+ - u- the jump from the face on the interface's left (+, normal N pointing
// into the right region) to the other, and {P} N = (P+ N + P- N) / 2 the mean traction,
//
//   T(u; v) = - int [[v]] . {P(F)} N  -  int [[u]] . {C : grad v} N  +  (beta M / h) int [[u]] . [[v]],
//
// consistent (a bonded solution makes [[u]] = 0 and the tractions equal) and, for small
// strain, symmetric; M the larger P-wave modulus of the two faces' laws. The strain may jump across
// the interface: the supports end there (the interface is a crack to them; in a solid the
// regions are separate bodies) and nodes on it are split, so each side has functions of its own. With laws
// with history each face of a tie point holds a state of its own, as a Nitsche point does.
//
// Laws with history (J2, Drucker–Prager; materials/material_state.hpp): every quadrature
// point, every Nitsche point and each face of every tie point holds a MaterialState<2>, the
// committed state_n. The forces and tangents at d are those of update(F(d), state_n) with the
// consistent tangent, so Newton iterates on one step without touching the history; commit(d)
// makes state_{n+1} the history once the step is accepted (a converged load step, a time
// step). A failed load step, cut back, leaves the history as it was. strain_energy() is the stored energy of
// the committed state, dissipated() the plastic work.
//
// Pressure p (positive into the body, SPEC section 9): with a small-strain law the dead
// traction -p N on the reference boundary; with a finite-strain law a follower load on the
// current boundary, f_I = -p int phi_I n da = -p int phi_I cof(F) N dA (Nanson's formula,
// cof F = J F^-T). In the plane cof(F) N = R F T = R x,S (x = X + u^h, S the reference arc
// length, T the tangent, R (a, b) = (b, -a) the rotation by -90 degrees), linear in the
// coefficients, with the load stiffness dF_I / dd_J = -p int phi_I (grad phi_J . T) R dS. In
// space d(cof(F) N) / dd_J = [F (grad phi_J x N)]_x (the cross-product matrix: from
// cof(F)_iM = 1/2 e_ijk e_MNL F_jN F_kL). The load stiffness makes the tangent non-symmetric.
//
// Loads: `LoadState` scales body force, tractions, pressures and prescribed displacements by
// `factor` (the load factor of a static solve) and evaluates them at `time` (dynamics).
// Units: as the material's E; in the plane forces per unit thickness.
//
// Dimension: one code for dim = 2 (a plane Domain) and dim = 3 (a Solid), instantiated in
// the .cpp.

#include <algorithm>
#include <functional>
#include <string>
#include <vector>

#include "mfree/galerkin/boundary_quadrature.hpp"
#include "mfree/galerkin/galerkin_quadrature.hpp"
#include "mfree/geometry/boundary_selection.hpp"
#include "mfree/geometry/domain_of.hpp"
#include "mfree/linalg/linear_solver.hpp"
#include "mfree/linalg/node_pattern.hpp"
#include "mfree/materials/material.hpp"

namespace mfree {

/// A boundary value at a point X of the boundary with outward unit normal N, at time t.
template <int dim>
using BoundaryValue = std::function<Point<dim>(const Point<dim>& x, const Point<dim>& n, double t)>;
/// A scalar field at reference position X and time t.
template <int dim>
using ScalarField = std::function<double(const Point<dim>& x, double t)>;
/// Body force per reference volume (rho0 b) at reference position X and time t.
template <int dim>
using BodyForce = std::function<Point<dim>(const Point<dim>& x, double t)>;

template <int dim>
struct BoundaryCondition {
  enum class Type {
    displacement,  ///< u = ubar
    slip,          ///< u . N = ubar . N, tangential traction free
    traction,      ///< P N = tbar
    pressure,      ///< P N = -p n (dead at small strain, follower at finite strain)
  };
  Type type = Type::traction;
  BoundarySelection<dim> where;  ///< the part of the boundary it holds on
  BoundaryValue<dim> value;      ///< ubar(X, N, t) or tbar(X, N, t); empty for pressure
  std::string name;              ///< for messages
  ScalarField<dim> pressure;     ///< p(X, t), positive into the body; only for pressure
};
/// The parts of the conditions, in order (the boundary quadrature is cut at their ends).
template <int dim>
std::vector<BoundarySelection<dim>> condition_parts(const std::vector<BoundaryCondition<dim>>& conditions) {
  std::vector<BoundarySelection<dim>> parts;
  for (const BoundaryCondition<dim>& c : conditions) parts.push_back(c.where);
  return parts;
}

struct LoadState {
  double factor = 1.0;  ///< multiplies every load and prescribed displacement
  double time = 0.0;    ///< time of the body force
};

/// The largest Poisson's ratio of a plane-strain law that the displacement formulation is
/// trusted with (lambda / mu = 2 nu / (1 - 2 nu) = 49). A nearly incompressible motion must be
/// represented by the trial functions themselves, and the error grows with lambda / mu
/// (volumetric locking). Measured on the Lamé cylinder at h = 0.1 (the report's stress test
/// "Near incompressibility"): at nu = 0.49 the energy error is 2.4 x (linear RK) and 1.8 x
/// (quadratic RK, VCI) its value at nu = 0.3 and the stress error 27 % and 8 %; at nu = 0.499
/// it is 5.5 x and 4.5 x, and the stress error 207 % and 73 %. Scenes beyond this value are
/// refused unless [material] allow_locking = true (studies of locking).
inline constexpr double max_poisson_ratio = 0.49;

/// The committed material states of a model's points (laws with history; empty otherwise).
template <int dim>
struct PointHistory {
  std::vector<MaterialState<dim>> domain;  ///< per quadrature point
  /// Per Nitsche point (boundary quadrature points of essential conditions), then per tie
  /// point of an interface its two faces (+, -).
  std::vector<MaterialState<dim>> boundary;
};

template <int dim>
struct SolidProblem {
  Material material = LinearElastic{};  ///< the law everywhere, unless region_materials are given
  /// For a domain of several regions (Domain::regions()), the law of each, in their order;
  /// empty: `material` in every region.
  std::vector<Material> region_materials;
  double density = 0.0;  ///< rho0 [kg/m^3] everywhere, unless region_densities are given (0: not given)
  std::vector<double> region_densities;       ///< per region, as region_materials (dynamics)
  BodyForce<dim> body_force;                  ///< empty: none
  std::vector<BoundaryCondition<dim>>
      conditions;  ///< on disjoint parts of the boundary; the rest is traction free
  /// Dimensionless beta of the penalty beta M / h, M the P-wave modulus of the law at the
  /// point (at an interface the larger of its faces' laws).
  double nitsche_beta = 100.0;
  double spacing = 1.0;                       ///< h of the penalty: nodal spacing

  /// The laws: one per region, or the one law.
  [[nodiscard]] std::vector<Material> laws() const {
    return region_materials.empty() ? std::vector<Material>{material} : region_materials;
  }
  /// Whether a law has history (J2, Drucker–Prager).
  [[nodiscard]] bool any_history() const {
    const std::vector<Material> all = laws();
    return std::any_of(all.begin(), all.end(), [](const Material& m) { return has_history(m); });
  }
  /// The law of region r.
  [[nodiscard]] const Material& law(int region) const {
    return region_materials.empty() ? material : region_materials[static_cast<std::size_t>(region)];
  }
  /// rho0 of region r.
  [[nodiscard]] double density_of(int region) const {
    return region_densities.empty() ? density : region_densities[static_cast<std::size_t>(region)];
  }
  /// The law at X of the domain (its region's; on the boundary, the nearest region's).
  [[nodiscard]] const Material& law_at(const Domain& domain, const Vec2& x) const requires(dim == 2) {
    return region_materials.empty() ? material : law(domain.nearest_region(x).first);
  }
  /// The law at X of the solid (its region's; X in the closed solid).
  [[nodiscard]] const Material& law_at(const Solid& solid, const Point<3>& x) const requires(dim == 3) {
    return region_materials.empty() ? material : law(std::max(0, solid.region_at(x)));
  }
};

template <int dim>
class TotalLagrangian {
 public:
  /// Views q, test gradients (same layout as q.grad; null: q.grad), bq and at_boundary (the
  /// trial functions with gradients at bq's points): they must outlive this object. A
  /// boundary point takes the first condition whose part holds it; bq cut at the conditions'
  /// parts (boundary_quadrature(..., condition_parts(conditions)), as discretise() does)
  /// integrates each condition over exactly its part.
  TotalLagrangian(SolidProblem<dim> problem, const DomainOf<dim>& domain, Index nodes,
                  const GalerkinQuadrature<dim>& q, const std::vector<Point<dim>>* test_gradients,
                  const BoundaryQuadrature<dim>& bq, const GalerkinQuadrature<dim>& at_boundary);

  [[nodiscard]] Index nodes() const { return nodes_; }
  [[nodiscard]] Eigen::Index dofs() const { return dim * Eigen::Index{nodes_}; }
  [[nodiscard]] const SolidProblem<dim>& problem() const { return problem_; }
  [[nodiscard]] const GalerkinQuadrature<dim>& quadrature() const { return q_; }
  /// True when the tangent is symmetric at every state (CHOLMOD applies).
  [[nodiscard]] bool symmetric() const { return symmetric_; }
  /// A dim N x dim N matrix with the tangent's sparsity, values zero: tangent(), mass() and
  /// their sums share it.
  [[nodiscard]] SparseMatrix zero_matrix() const { return block_matrix(pattern_, dim); }

  /// F_K = I + sum_I d_I g_I^T at quadrature point k.
  [[nodiscard]] Tensor2<dim> deformation_gradient(Index k, const Eigen::VectorXd& d) const;
  /// sum_K w_K P(F_K) t_I: the domain term. Throws NumericalError when J <= 0 somewhere.
  [[nodiscard]] Eigen::VectorXd internal_force(const Eigen::VectorXd& d) const;
  /// The boundary terms that depend on the state: Nitsche's terms N(u; phi_I e_i) of the
  /// essential conditions, minus the follower pressure loads (finite strain).
  [[nodiscard]] Eigen::VectorXd boundary_force(const Eigen::VectorXd& d, const LoadState& load) const;
  /// Body force, tractions and dead pressures against phi_I.
  [[nodiscard]] Eigen::VectorXd external_force(const LoadState& load) const;
  /// Overwrites k's values (k from zero_matrix()) with the tangent of internal_force +
  /// boundary_force at d.
  void tangent(const Eigen::VectorXd& d, const LoadState& load, SparseMatrix& k) const;
  /// sum_K w_K W(F_K, state_K): the stored energy (with history: of the committed state,
  /// so call it after commit(d)).
  [[nodiscard]] double strain_energy(const Eigen::VectorXd& d) const;

  /// True when the law has history (the points hold states, commit() updates them).
  [[nodiscard]] bool has_history() const { return history_laws_; }
  /// Makes the states of the update at d the committed history (an accepted step). No-op
  /// for laws without history.
  void commit(const Eigen::VectorXd& d);
  /// internal_force(d) and commit(d) in one pass over the points (one update per point, not
  /// two): for explicit steps, whose every state is accepted.
  [[nodiscard]] Eigen::VectorXd internal_force_committed(const Eigen::VectorXd& d);
  [[nodiscard]] const PointHistory<dim>& history() const { return history_; }

  // The boundary terms point by point, for the reactions (galerkin/reactions.hpp): the same
  // values boundary_force() and external_force() integrate.
  [[nodiscard]] const BoundaryQuadrature<dim>& boundary() const { return bq_; }
  [[nodiscard]] const GalerkinQuadrature<dim>& at_boundary() const { return at_boundary_; }
  /// The two parts of Nitsche's flux at one Nitsche point: traction = Pi P(F) N of the
  /// committed state [Pa], gap = Pi (u^h - factor ubar) [m].
  struct NitscheValues {
    Index point = 0;  ///< index into boundary() / at_boundary()
    const BoundaryCondition<dim>* condition = nullptr;
    Point<dim> traction = Point<dim>::Zero();
    Point<dim> gap = Point<dim>::Zero();
    double penalty = 0.0;  ///< beta M / h of the point's law [Pa / m]
  };
  /// The Nitsche points: the boundary points of the essential conditions, in boundary order.
  [[nodiscard]] std::size_t nitsche_points() const { return nitsche_.size(); }
  [[nodiscard]] NitscheValues nitsche_values(std::size_t b, const Eigen::VectorXd& d,
                                             const LoadState& load) const;
  /// The applied traction at boundary point p per unit reference length (area) [Pa]: tbar or
  /// -p N of a natural condition (dead), -p cof(F) N of a follower pressure; zero elsewhere.
  [[nodiscard]] Point<dim> boundary_load(Index p, const Eigen::VectorXd& d, const LoadState& load) const;
  /// Replaces the history (a resumed run); InputError when the sizes do not fit.
  void set_history(PointHistory<dim> history);
  /// sum_K w_K D_K: the plastic work done so far (committed) [J/m per unit thickness in the
  /// plane, J in 3D].
  [[nodiscard]] double dissipated() const;
  /// sum_K w_K over the points that have yielded (committed alpha > 0): the area of the
  /// plastic zone [m^2; m^3 in 3D].
  [[nodiscard]] double plastic_area() const;
  /// The update at quadrature point k from its committed state: Cauchy stress, sigma_zz and
  /// the state (for output: the stress where it lives).
  struct PointResponse {
    Tensor2<dim> cauchy = Tensor2<dim>::Zero();
    double cauchy_zz = 0.0;
    MaterialState<dim> state;
  };
  [[nodiscard]] PointResponse response(Index k, const Eigen::VectorXd& d) const;

  /// rho0 per quadrature point, its region's; InputError when a region has no density.
  [[nodiscard]] std::vector<double> point_densities() const;
  /// Consistent mass sum_K w_K rho0_K phi_I phi_J (times I_dim), rho0_K the density of point K's
  /// region, on the tangent's pattern (so M and K add value by value). InputError when a
  /// region has no density.
  [[nodiscard]] SparseMatrix mass_matrix() const;
  /// Row-sum lumped mass m_I = sum_K w_K rho0_K phi_I(X_K) (per DOF: m_I dim times). Throws
  /// NumericalError naming the node when one is not positive.
  [[nodiscard]] Eigen::VectorXd lumped_mass(const std::vector<Point<dim>>& node_positions) const;

 private:
  struct NitschePoint {
    Index point;            ///< index into bq / at_boundary
    Tensor2<dim> projection;  ///< Pi
    const BoundaryCondition<dim>* condition;
    double penalty;  ///< beta M / h of the point's law [Pa / m]
  };
  /// A point of an interface: the same point on its two faces.
  struct TiePoint {
    Index plus;   ///< on the face whose material is on the interface's left (normal into the right)
    Index minus;  ///< on the other face
    double penalty;  ///< beta M / h, M the larger of the faces' laws [Pa / m]
  };
  /// One side of a tie point's row: the functions there, with the sign of their jump.
  struct TieSide {
    Index point;
    double sign;
  };

  /// The update at quadrature point k (or Nitsche point b) from its committed state.
  [[nodiscard]] MaterialUpdate<dim> domain_update(Index k, const Tensor2<dim>& f, bool with_tangent) const;
  [[nodiscard]] MaterialUpdate<dim> boundary_update(std::size_t b, const Tensor2<dim>& f,
                                                    bool with_tangent) const;
  /// sum_K w_K P(F_K) t_I from the committed states; with `commit`, each point's new state
  /// written into it after its update.
  [[nodiscard]] Eigen::VectorXd domain_force(const Eigen::VectorXd& d,
                                             std::vector<MaterialState<dim>>* commit) const;
  /// cof(F) N at follower point p: the current boundary's area normal n da / dA (plane:
  /// R x,S, the current tangent per reference length turned outward).
  [[nodiscard]] Point<dim> follower_normal(Index p, const Eigen::VectorXd& d) const;
  /// F at Nitsche point p (the trial functions of at_boundary).
  [[nodiscard]] Tensor2<dim> boundary_deformation_gradient(Index point, const Eigen::VectorXd& d) const;
  /// The tie's terms at its points: forces added to f, and with k the tangent added to k's values.
  void add_tie_force(const Eigen::VectorXd& d, Eigen::VectorXd& f) const;
  void add_tie_tangent(const Eigen::VectorXd& d, double* values) const;
  /// The update at face `face` (0: +, 1: -) of tie point `tie` with its law, from its committed state.
  [[nodiscard]] MaterialUpdate<dim> tie_update(std::size_t tie, int face, const Eigen::VectorXd& d,
                                               bool with_tangent) const;
  /// Where the state of a tie point's face lives in history_.boundary.
  [[nodiscard]] std::size_t tie_state(std::size_t tie, int face) const {
    return nitsche_.size() + 2 * tie + static_cast<std::size_t>(face);
  }
  /// Commits the states of the Nitsche and tie points at d.
  void commit_boundary(const Eigen::VectorXd& d);

  SolidProblem<dim> problem_;
  bool history_laws_ = false;
  PointHistory<dim> history_;
  Index nodes_;
  const GalerkinQuadrature<dim>& q_;
  const std::vector<Point<dim>>& test_;
  const BoundaryQuadrature<dim>& bq_;
  const GalerkinQuadrature<dim>& at_boundary_;
  std::vector<const BoundaryCondition<dim>*> traction_of_point_;  ///< per boundary point; null if none
  std::vector<NitschePoint> nitsche_;
  std::vector<TiePoint> ties_;
  std::vector<int> law_of_point_;            ///< per quadrature point, its region's law
  std::vector<int> law_of_boundary_;         ///< per boundary point
  std::vector<Tangent<dim>> reference_tangents_;  ///< per law, C = A(I)
  std::vector<double> penalty_of_law_;       ///< per law, beta M / h
  bool linear_ = true;                       ///< every law linear
  std::vector<std::pair<Index, const BoundaryCondition<dim>*>> follower_;  ///< points of follower pressures
  std::vector<const BoundaryCondition<dim>*> follower_of_point_;  ///< per boundary point; null if none
  std::vector<Index> boundary_offsets_{0}, boundary_nodes_;
  RowIncidence domain_rows_;
  RowIncidence boundary_rows_;
  NodePattern pattern_;
  /// Per slot of a Nitsche point's row in at_boundary: (C : grad(phi_I e_i)) N as the columns
  /// i of a dim x dim matrix, the traction of a test function in the symmetrising term.
  std::vector<Tensor2<dim>> reference_traction_;
  bool domain_symmetric_ = true;  ///< test = trial gradients and a tangent with major symmetry
  bool symmetric_ = true;
};

}  // namespace mfree
