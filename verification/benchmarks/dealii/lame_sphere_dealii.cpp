// The peer of mfree's Lamé sphere (verification/lame-sphere): the same problem solved by
// deal.II's Q1 or Q2 elements, for the side-by-side work-precision comparison of
// verification/benchmarks/dealii/README.md. Built only by that folder's run.sh, never by
// mfree's CMake: deal.II is a peer, not a dependency.
//
// Problem: one eighth of the thick sphere a = 1 <= r <= b = 2, pressure p = 1 on r = a,
// r = b free, slip on x = 0, y = 0, z = 0; linear elasticity E = 1000, nu = 0.3. Exact:
//   u = (F1 + F2 / r^3) x,  F1 = C (1 - 2 nu),  F2 = C (1 + nu) b^3 / 2,  C = p a^3 / (E (b^3 - a^3)),
//   du_i/dx_j = (F1 + F2 / r^3) delta_ij - 3 F2 x_i x_j / r^5.
// Discretisation: GridGenerator::quarter_hyper_shell (its 3D form is the octant) refined
// globally, spherical manifold, Q_k elements with a degree-k mapping (the curved faces
// represented to the element's order), Gauss rules of k + 1 points per direction.
// Solver: conjugate gradients to |b - A x| <= 1e-10 |b| (mfree's default tolerance), preconditioned by
// Trilinos ML's smoothed-aggregation AMG given the six rigid-body modes of the support
// points as its null space. One thread (deal.II's task threads limited to 1; run with
// OMP_NUM_THREADS=1).
//
// Usage: lame_sphere_dealii DEGREE REFINEMENTS
// Prints one CSV row: degree,refinements,cells,dofs,nonzeros,setup_s,assembly_s,amg_s,solve_s,
// solution_s,iterations,l2,energy,errors_s,peak_rss_mb — solution_s = mesh + DoF set-up +
// assembly + AMG set-up + solve (everything up to u^h), errors_s the error measurement alone
// (Gauss rules of k + 3 points per direction), the errors relative: ||u - u_h|| / ||u|| in L2
// and sqrt(∫ (e - e_h) : C : (e - e_h)) / sqrt(∫ e : C : e) in energy.

#include <deal.II/base/function.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/multithread_info.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>
#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q.h>
#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/manifold_lib.h>
#include <deal.II/grid/tria.h>
#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/solver_cg.h>
#include <deal.II/lac/solver_control.h>
#include <deal.II/lac/trilinos_precondition.h>
#include <deal.II/lac/trilinos_sparse_matrix.h>
#include <deal.II/lac/vector.h>
#include <deal.II/numerics/vector_tools.h>
#include <sys/resource.h>

#include <Teuchos_ParameterList.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <string>
#include <vector>

namespace {

using namespace dealii;
constexpr int dim = 3;

constexpr double pressure = 1.0, inner = 1.0, outer = 2.0, youngs = 1000.0, poisson = 0.3;
constexpr double lambda = youngs * poisson / ((1 + poisson) * (1 - 2 * poisson));
constexpr double mu = youngs / (2 * (1 + poisson));
const double big_c =
    pressure * inner * inner * inner / (youngs * (outer * outer * outer - inner * inner * inner));
const double f1 = big_c * (1 - 2 * poisson);
const double f2 = big_c * (1 + poisson) * outer * outer * outer / 2;

Tensor<1, dim> exact_u(const Point<dim>& x) {
  const double r = x.norm();
  return (f1 + f2 / (r * r * r)) * Tensor<1, dim>(x);
}

Tensor<2, dim> exact_grad(const Point<dim>& x) {
  const double r = x.norm(), r3 = r * r * r, r5 = r3 * r * r;
  Tensor<2, dim> g;
  for (unsigned i = 0; i < dim; ++i)
    for (unsigned j = 0; j < dim; ++j) g[i][j] = (i == j ? f1 + f2 / r3 : 0.0) - 3 * f2 * x[i] * x[j] / r5;
  return g;
}

/// sigma : eps for the strain eps (symmetric): 2 mu eps:eps + lambda tr(eps)^2.
double energy_density(const SymmetricTensor<2, dim>& eps) {
  return 2 * mu * (eps * eps) + lambda * trace(eps) * trace(eps);
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

int main(int argc, char** argv) {
  Utilities::MPI::MPI_InitFinalize mpi(argc, argv, 1);
  if (argc != 3) {
    std::fprintf(stderr, "usage: %s DEGREE REFINEMENTS\n", argv[0]);
    return 2;
  }
  const unsigned degree = static_cast<unsigned>(std::atoi(argv[1]));
  const unsigned refinements = static_cast<unsigned>(std::atoi(argv[2]));
  if (degree < 1 || degree > 4 || refinements > 8) {
    std::fprintf(stderr, "degree 1..4, refinements 0..8\n");
    return 2;
  }
  MultithreadInfo::set_thread_limit(1);

  // Mesh, elements, constraints (slip: the normal component of u zero on the three planes).
  const auto t_setup = std::chrono::steady_clock::now();
  Triangulation<dim> tria;
  GridGenerator::quarter_hyper_shell(tria, Point<dim>(), inner, outer, 0,
                                     true);  // ids 0 inner, 1 outer, 2..4 x, y, z = 0
  tria.refine_global(refinements);
  const MappingQ<dim> mapping(degree);
  const FESystem<dim> fe(FE_Q<dim>(degree), dim);
  DoFHandler<dim> dofs(tria);
  dofs.distribute_dofs(fe);
  AffineConstraints<double> constraints;
  for (unsigned c = 0; c < dim; ++c)
    VectorTools::interpolate_boundary_values(mapping, dofs, 2 + c, Functions::ZeroFunction<dim>(dim),
                                             constraints, fe.component_mask(FEValuesExtractors::Scalar(c)));
  constraints.close();
  DynamicSparsityPattern dsp(dofs.n_dofs());
  DoFTools::make_sparsity_pattern(dofs, dsp, constraints, false);
  TrilinosWrappers::SparseMatrix matrix;
  matrix.reinit(dsp);
  Vector<double> rhs(dofs.n_dofs()), u(dofs.n_dofs());
  const double setup_s = seconds_since(t_setup);

  // Assembly: K_ij = ∫ 2 mu eps(phi_i) : eps(phi_j) + lambda div phi_i div phi_j, and the
  // pressure on the bore as the traction -p n (n the solid's outward normal).
  const auto t_assembly = std::chrono::steady_clock::now();
  {
    const QGauss<dim> cell_rule(degree + 1);
    const QGauss<dim - 1> face_rule(degree + 1);
    FEValues<dim> fv(mapping, fe, cell_rule, update_gradients | update_JxW_values);
    FEFaceValues<dim> ffv(mapping, fe, face_rule, update_values | update_normal_vectors | update_JxW_values);
    const FEValuesExtractors::Vector disp(0);
    const unsigned n = fe.n_dofs_per_cell();
    FullMatrix<double> ke(n, n);
    Vector<double> fe_rhs(n);
    std::vector<types::global_dof_index> index(n);
    std::vector<SymmetricTensor<2, dim>> eps(n);
    std::vector<double> div(n);
    for (const auto& cell : dofs.active_cell_iterators()) {
      fv.reinit(cell);
      ke = 0;
      fe_rhs = 0;
      for (unsigned q = 0; q < cell_rule.size(); ++q) {
        for (unsigned i = 0; i < n; ++i) {
          eps[i] = fv[disp].symmetric_gradient(i, q);
          div[i] = fv[disp].divergence(i, q);
        }
        const double dx = fv.JxW(q);
        for (unsigned i = 0; i < n; ++i)
          for (unsigned j = 0; j <= i; ++j)
            ke(i, j) += (2 * mu * (eps[i] * eps[j]) + lambda * div[i] * div[j]) * dx;
      }
      for (unsigned i = 0; i < n; ++i)
        for (unsigned j = i + 1; j < n; ++j) ke(i, j) = ke(j, i);
      for (const auto f : cell->face_indices())
        if (cell->face(f)->at_boundary() && cell->face(f)->boundary_id() == 0) {
          ffv.reinit(cell, f);
          for (unsigned q = 0; q < face_rule.size(); ++q)
            for (unsigned i = 0; i < n; ++i)
              fe_rhs(i) -= pressure * (ffv[disp].value(i, q) * ffv.normal_vector(q)) * ffv.JxW(q);
        }
      cell->get_dof_indices(index);
      constraints.distribute_local_to_global(ke, fe_rhs, index, matrix, rhs);
    }
    matrix.compress(VectorOperation::add);
  }
  const double assembly_s = seconds_since(t_assembly);

  // AMG with the rigid-body modes of the support points as ML's null space.
  const auto t_amg = std::chrono::steady_clock::now();
  std::vector<Point<dim>> support(dofs.n_dofs());
  DoFTools::map_dofs_to_support_points(mapping, dofs, support);
  std::vector<unsigned> component(dofs.n_dofs());
  {
    std::vector<types::global_dof_index> index(fe.n_dofs_per_cell());
    for (const auto& cell : dofs.active_cell_iterators()) {
      cell->get_dof_indices(index);
      for (unsigned i = 0; i < index.size(); ++i) component[index[i]] = fe.system_to_component_index(i).first;
    }
  }
  const std::size_t nd = dofs.n_dofs();
  std::vector<double> modes(6 * nd, 0.0);  // column-major: mode m at [m nd, (m + 1) nd)
  for (std::size_t k = 0; k < nd; ++k) {
    const unsigned c = component[k];
    const Point<dim>& x = support[k];
    modes[c * nd + k] = 1.0;                                   // translation e_c
    modes[3 * nd + k] = c == 1 ? -x[2] : c == 2 ? x[1] : 0.0;  // rotation about x
    modes[4 * nd + k] = c == 0 ? x[2] : c == 2 ? -x[0] : 0.0;  // rotation about y
    modes[5 * nd + k] = c == 0 ? -x[1] : c == 1 ? x[0] : 0.0;  // rotation about z
  }
  TrilinosWrappers::PreconditionAMG amg;
  {
    TrilinosWrappers::PreconditionAMG::AdditionalData data;
    data.elliptic = true;
    data.higher_order_elements = degree > 1;
    data.smoother_sweeps = 2;
    data.aggregation_threshold = 0.02;
    Teuchos::ParameterList list;
    std::unique_ptr<Epetra_MultiVector> unused;
    data.set_parameters(list, unused, matrix);
    list.set("null space: type", "pre-computed");
    list.set("null space: dimension", 6);
    list.set("null space: vectors", modes.data());
    amg.initialize(matrix, list);
  }
  const double amg_s = seconds_since(t_amg);

  const auto t_solve = std::chrono::steady_clock::now();
  SolverControl control(10000, 1e-10 * rhs.l2_norm());
  SolverCG<Vector<double>> cg(control);
  cg.solve(matrix, u, rhs, amg);
  constraints.distribute(u);
  const double solve_s = seconds_since(t_solve);
  const double solution_s = seconds_since(t_setup);

  // Errors over the mapped cells, Gauss rules of k + 3 points per direction.
  const auto t_errors = std::chrono::steady_clock::now();
  double e_l2 = 0, u_l2 = 0, e_energy = 0, u_energy = 0;
  {
    const QGauss<dim> rule(degree + 3);
    FEValues<dim> fv(mapping, fe, rule,
                     update_values | update_gradients | update_quadrature_points | update_JxW_values);
    const FEValuesExtractors::Vector disp(0);
    std::vector<Tensor<1, dim>> uh(rule.size());
    std::vector<Tensor<2, dim>> gh(rule.size());
    for (const auto& cell : dofs.active_cell_iterators()) {
      fv.reinit(cell);
      fv[disp].get_function_values(u, uh);
      fv[disp].get_function_gradients(u, gh);
      for (unsigned q = 0; q < rule.size(); ++q) {
        const Point<dim>& x = fv.quadrature_point(q);
        const Tensor<1, dim> ue = exact_u(x);
        const Tensor<2, dim> ge = exact_grad(x);
        const double dx = fv.JxW(q);
        e_l2 += (ue - uh[q]).norm_square() * dx;
        u_l2 += ue.norm_square() * dx;
        e_energy += energy_density(symmetrize(ge - gh[q])) * dx;
        u_energy += energy_density(symmetrize(ge)) * dx;
      }
    }
  }
  const double errors_s = seconds_since(t_errors);

  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  std::printf("%u,%u,%u,%zu,%zu,%.4f,%.4f,%.4f,%.4f,%.4f,%u,%.6e,%.6e,%.4f,%.1f\n", degree, refinements,
              tria.n_active_cells(), static_cast<std::size_t>(nd),
              static_cast<std::size_t>(matrix.n_nonzero_elements()), setup_s, assembly_s, amg_s, solve_s,
              solution_s, control.last_step(), std::sqrt(e_l2 / u_l2), std::sqrt(e_energy / u_energy),
              errors_s, usage.ru_maxrss / 1024.0);
  return 0;
}
