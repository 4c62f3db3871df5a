#include "mfree/linalg/linear_solver.hpp"

#include <fmt/format.h>

#include "mfree/core/error.hpp"
#include "mfree/linalg/krylov_solver.hpp"
#include "mfree/linalg/sparse_solver.hpp"

namespace mfree {

const NameTable<SolverKind>& solver_kind_names() {
  static const NameTable<SolverKind> table{{"cholmod", SolverKind::cholmod},
                                           {"umfpack", SolverKind::umfpack},
                                           {"cg", SolverKind::cg},
                                           {"gmres", SolverKind::gmres}};
  return table;
}

std::string_view to_string(SolverKind kind) { return solver_kind_names().name(kind); }

const NameTable<Preconditioner>& preconditioner_names() {
  static const NameTable<Preconditioner> table{{"gamg", Preconditioner::gamg},
                                               {"boomeramg", Preconditioner::boomeramg},
                                               {"jacobi", Preconditioner::jacobi}};
  return table;
}

std::string_view to_string(Preconditioner p) { return preconditioner_names().name(p); }

Index default_direct_limit(const SystemDescription& system) {
  if (!std::holds_alternative<std::span<const Point<3>>>(system.nodes)) return 200000;
  return (system.symmetric || system.nearly_symmetric) && !system.favours_direct ? 3000 : 20000;
}

SolverKind choose_solver(const SolverSettings& settings, const SystemDescription& system, Index size) {
  if (!settings.kind) {
    if (size <= settings.direct_limit.value_or(default_direct_limit(system)))
      return system.symmetric ? SolverKind::cholmod : SolverKind::umfpack;
    return system.symmetric ? SolverKind::cg : SolverKind::gmres;
  }
  const SolverKind k = *settings.kind;
  if (!system.symmetric && (k == SolverKind::cholmod || k == SolverKind::cg))
    throw InputError(fmt::format(
        "[solver] kind = \"{}\" needs a symmetric positive definite system, and the {} system is not symmetric "
        "(use {} or auto)",
        to_string(k), system.name, k == SolverKind::cholmod ? "umfpack" : "gmres"));
  return k;
}

std::unique_ptr<LinearSolver> make_linear_solver(const SolverSettings& settings, const SystemDescription& system,
                                                 Index size) {
  const SolverKind k = choose_solver(settings, system, size);
  if (is_direct(k)) return std::make_unique<SparseSolver>(k);
  return std::make_unique<KrylovSolver>(k, settings, system);
}

std::string SolverReport::text() const {
  const SolveStatistics& s = statistics;
  if (is_direct(kind)) return fmt::format("{}, {} solves", method, s.solves);
  return fmt::format("{}, {} solves, {} iterations (at most {} in one), |b - A x| / |b| <= {:.1e}", method, s.solves,
                     s.iterations, s.most_iterations, s.worst_residual);
}

SolverReport report(const LinearSolver& solver) { return {solver.kind(), solver.description(), solver.statistics()}; }

}  // namespace mfree
