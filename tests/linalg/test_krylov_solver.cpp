#include <array>
#include <catch2/catch.hpp>
#include <vector>

#include "../test_support.hpp"
#include "mfree/core/error.hpp"
#include "mfree/linalg/krylov_solver.hpp"
#include "mfree/linalg/sparse_solver.hpp"
#include "model_matrices.hpp"

using namespace mfree;

namespace {

/// |b - A x| / |b|.
double relative_residual(const SparseMatrix& a, const Eigen::VectorXd& x, const Eigen::VectorXd& b) {
  return (b - a * x).norm() / b.norm();
}

SolverSettings krylov(SolverKind kind, Preconditioner p, double tolerance = 1e-10) {
  SolverSettings s;
  s.kind = kind;
  s.preconditioner = p;
  s.tolerance = tolerance;
  return s;
}

}  // namespace

TEST_CASE("PETSc CG and GMRES reach their tolerance on the true residual with every preconditioner, and refactorise in place",
          "[linalg][krylov]") {
  for (SolverKind kind : {SolverKind::cg, SolverKind::gmres})
    for (Preconditioner p : {Preconditioner::gamg, Preconditioner::boomeramg, Preconditioner::jacobi}) {
      CAPTURE(to_string(kind), to_string(p));
      const double conv = kind == SolverKind::gmres ? 0.3 : 0.0;
      const SparseMatrix a = testing::laplacian(40, 0.0, conv);
      const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(a.rows(), -1.0, 2.0);
      KrylovSolver solver(kind, krylov(kind, p, 1e-9), {"test", conv == 0.0, 1, {}});
      solver.analyze(a);
      solver.factorize(a);
      const Eigen::VectorXd b = a * x;
      const Eigen::VectorXd y = solver.solve(b);
      CHECK(relative_residual(a, y, b) <= 1e-9);
      CHECK(relative_residual(a, y, b) > 1e-16);  // an iterative answer, not a factorisation's
      CHECK(solver.statistics().iterations > 0);
      CHECK(solver.statistics().worst_residual <= 1e-9);
      // New values on the same pattern: factorize() again, no new analysis.
      const SparseMatrix a2 = testing::laplacian(40, 0.5, conv);
      solver.factorize(a2);
      const Eigen::VectorXd b2 = a2 * x;
      CHECK(relative_residual(a2, solver.solve(b2), b2) <= 1e-9);
      CHECK(solver.statistics().solves == 2);
    }
}

TEST_CASE("PETSc algebraic multigrid: CG iterations hardly grow with the grid, Jacobi's double", "[linalg][krylov]") {
  const auto iterations = [](int n, Preconditioner p) {
    const SparseMatrix a = testing::laplacian(n, 0.0, 0.0);
    KrylovSolver solver(SolverKind::cg, krylov(SolverKind::cg, p, 1e-8), {"test", true, 1, {}});
    solver.analyze(a);
    solver.factorize(a);
    (void)solver.solve(Eigen::VectorXd::Ones(a.rows()));
    return solver.statistics().iterations;
  };
  for (Preconditioner p : {Preconditioner::gamg, Preconditioner::boomeramg}) {
    CAPTURE(to_string(p));
    CHECK(iterations(128, p) <= 1.5 * iterations(32, p));
  }
  CHECK(iterations(128, Preconditioner::jacobi) >= 3.0 * iterations(32, Preconditioner::jacobi));
}

TEST_CASE("PETSc GAMG with the rigid-body modes of the nodes: elasticity solved to tolerance, fewer iterations than without",
          "[linalg][krylov]") {
  std::vector<Vec2> nodes;
  const SparseMatrix k = testing::elasticity(48, nodes);
  Eigen::VectorXd f = Eigen::VectorXd::Zero(k.rows());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    if (nodes[i].x() == 1.0) f[2 * i + 1] = -1.0;  // a shear load on x = 1
  const auto solve = [&](std::span<const Vec2> near_null) {
    KrylovSolver solver(SolverKind::cg, krylov(SolverKind::cg, Preconditioner::gamg), {"stiffness", true, 2, near_null});
    solver.analyze(k);
    solver.factorize(k);
    const Eigen::VectorXd u = solver.solve(f);
    return std::pair{u, solver.statistics().iterations};
  };
  const auto [u, with_modes] = solve(nodes);
  const auto [v, constants_only] = solve({});
  SparseSolver direct(SolverKind::cholmod);
  direct.analyze(k);
  direct.factorize(k);
  const Eigen::VectorXd exact = direct.solve(f);
  CHECK((u - exact).norm() <= 1e-7 * exact.norm());
  CHECK((v - exact).norm() <= 1e-7 * exact.norm());
  CHECK(with_modes < constants_only);
}

TEST_CASE("A PETSc Krylov solve that does not converge is an error naming the method, the system, the iterations and the "
          "residual",
          "[linalg][krylov]") {
  const SparseMatrix a = testing::laplacian(40, 0.0, 0.0);
  SolverSettings s = krylov(SolverKind::cg, Preconditioner::jacobi);
  s.max_iterations = 3;
  KrylovSolver solver(SolverKind::cg, s, {"test system", true, 1, {}});
  solver.analyze(a);
  solver.factorize(a);
  const std::string m = testing::message_of<NumericalError>([&] { (void)solver.solve(Eigen::VectorXd::Ones(a.rows())); });
  CHECK_THAT(m, Catch::Contains("cg + jacobi") && Catch::Contains("test system") &&
                    Catch::Contains("no convergence after 3 iterations") && Catch::Contains("|b - A x| / |b| = "));
  // A zero right-hand side has the zero solution, without iterations.
  CHECK(solver.solve(Eigen::VectorXd::Zero(a.rows())).norm() == 0.0);
}

TEST_CASE("The solver factory (PETSc above the limit): auto is direct up to direct_limit, Krylov above, and symmetric-only methods refuse others",
          "[linalg]") {
  SolverSettings s;
  s.direct_limit = 100;
  const SystemDescription sym{"s", true, 1, {}}, unsym{"u", false, 1, {}};
  CHECK(choose_solver(s, sym, 100) == SolverKind::cholmod);
  CHECK(choose_solver(s, unsym, 100) == SolverKind::umfpack);
  CHECK(choose_solver(s, sym, 101) == SolverKind::cg);
  CHECK(choose_solver(s, unsym, 101) == SolverKind::gmres);
  for (SolverKind k : {SolverKind::cholmod, SolverKind::cg}) {
    s.kind = k;
    CHECK_THROWS_AS(choose_solver(s, unsym, 10), InputError);
    CHECK(choose_solver(s, sym, 1000) == k);
  }
  s.kind = SolverKind::gmres;
  CHECK(choose_solver(s, sym, 10) == SolverKind::gmres);
  // Both kinds of solver through the one interface give the same answer.
  const SparseMatrix a = testing::laplacian(20, 0.1, 0.0);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(a.rows());
  s.kind.reset();
  s.direct_limit = 0;
  const std::unique_ptr<LinearSolver> iterative = make_linear_solver(s, sym, a.rows());
  s.direct_limit = a.rows();
  const std::unique_ptr<LinearSolver> direct = make_linear_solver(s, sym, a.rows());
  for (LinearSolver* solver : {iterative.get(), direct.get()}) {
    solver->analyze(a);
    solver->factorize(a);
  }
  CHECK(iterative->kind() == SolverKind::cg);
  CHECK(direct->kind() == SolverKind::cholmod);
  const Eigen::VectorXd x = direct->solve(b);
  CHECK((iterative->solve(b) - x).norm() <= 1e-8 * x.norm());
  CHECK_THAT(report(*iterative).text(), Catch::Contains("cg + gamg (tolerance 1e-10), 1 solves"));
  // The default preconditioner: GAMG for (nearly) symmetric systems, BoomerAMG for the others;
  // a scene's choice overrides it.
  SystemDescription nearly = unsym;
  nearly.nearly_symmetric = true;
  s.direct_limit = 0;
  CHECK_THAT(make_linear_solver(s, unsym, 10)->description(), Catch::StartsWith("gmres + boomeramg"));
  CHECK_THAT(make_linear_solver(s, nearly, 10)->description(), Catch::StartsWith("gmres + gamg"));
  s.preconditioner = Preconditioner::boomeramg;
  CHECK_THAT(make_linear_solver(s, nearly, 10)->description(), Catch::StartsWith("gmres + boomeramg"));
}

TEST_CASE(
    "In space auto turns iterative above 3000 unknowns (20 000 far from symmetric), and PETSc's GAMG with "
    "its SOR "
    "smoothers solves a vector Laplacian",
    "[linalg]") {
  // Nodes of a 12^3 grid, three unknowns each: -Laplace u = 1 per component, u = 0 outside.
  const int n = 12;
  std::vector<Point<3>> nodes;
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) nodes.emplace_back(i, j, k);
  const Index size = 3 * static_cast<Index>(nodes.size());
  std::vector<Eigen::Triplet<double>> t;
  const auto id = [&](int i, int j, int k) { return (k * n + j) * n + i; };
  for (int k = 0; k < n; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i)
        for (int c = 0; c < 3; ++c) {
          const Index row = 3 * id(i, j, k) + c;
          t.emplace_back(row, row, 6.0);
          for (const auto& [di, dj, dk] :
               {std::array{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}})
            if (i + di >= 0 && i + di < n && j + dj >= 0 && j + dj < n && k + dk >= 0 && k + dk < n)
              t.emplace_back(row, 3 * id(i + di, j + dj, k + dk) + c, -1.0);
        }
  SparseMatrix a(size, size);
  a.setFromTriplets(t.begin(), t.end());
  a.makeCompressed();
  const SystemDescription space{"vector laplacian", true, 3, std::span<const Point<3>>(nodes)};
  const SystemDescription plane{"vector laplacian", true, 3, std::span<const Point<2>>{}};
  SolverSettings s;
  CHECK(choose_solver(s, space, 3000) == SolverKind::cholmod);
  CHECK(choose_solver(s, space, 3001) == SolverKind::cg);
  CHECK(choose_solver(s, plane, 200000) == SolverKind::cholmod);
  CHECK(choose_solver(s, plane, 200001) == SolverKind::cg);
  // Far from symmetric in space: direct to 20 000.
  SystemDescription skew = space;
  skew.symmetric = false;
  CHECK(choose_solver(s, skew, 20000) == SolverKind::umfpack);
  CHECK(choose_solver(s, skew, 20001) == SolverKind::gmres);
  skew.nearly_symmetric = true;
  CHECK(choose_solver(s, skew, 3001) == SolverKind::gmres);
  const std::unique_ptr<LinearSolver> solver = make_linear_solver(s, space, size);
  REQUIRE(solver->kind() == SolverKind::cg);
  solver->analyze(a);
  solver->factorize(a);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(size);
  const Eigen::VectorXd x = solver->solve(b);
  CHECK((b - a * x).norm() <= 1e-10 * b.norm());
  CHECK(solver->statistics().most_iterations < 30);
}
