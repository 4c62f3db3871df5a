#include <catch2/catch.hpp>

#include "mfree/core/error.hpp"
#include "mfree/linalg/sparse_solver.hpp"
#include "model_matrices.hpp"

using namespace mfree;

using testing::laplacian;

TEST_CASE("CHOLMOD and UMFPACK solve to round-off and reuse the symbolic analysis", "[linalg]") {
  for (SolverKind kind : {SolverKind::cholmod, SolverKind::umfpack}) {
    CAPTURE(to_string(kind));
    const double conv = kind == SolverKind::umfpack ? 0.3 : 0.0;
    const SparseMatrix a = laplacian(30, 0.0, conv);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
    SparseSolver solver(kind);
    solver.analyze(a);
    solver.factorize(a);
    CHECK((solver.solve(a * x) - x).norm() <= 1e-12 * x.norm());
    // Same pattern, new values: factorize again without a new analysis.
    const SparseMatrix b = laplacian(30, 0.5, conv);
    solver.factorize(b);
    CHECK((solver.solve(b * x) - x).norm() <= 1e-12 * x.norm());
  }
}

TEST_CASE("CHOLMOD refuses an indefinite matrix with a clear error", "[linalg]") {
  const SparseMatrix a = laplacian(10, -6.0, 0.0);  // eigenvalues down to -6 + small: indefinite
  SparseSolver solver(SolverKind::cholmod);
  solver.analyze(a);
  CHECK_THROWS_AS(solver.factorize(a), NumericalError);
  CHECK_THROWS_WITH(solver.factorize(a), Catch::Contains("not positive definite"));
}
