// The implicit steps' sparse LU (mpm/implicit/linear_solver.hpp): each solver the build has solves a small
// unsymmetric system to round-off and refuses a singular one, and UMFPACK's shared library is
// loaded by the first UMFPACK factorisation, not before: an explicit run does not carry it (nor
// the BLAS, LAPACK and Fortran run-time it pulls in, 3.6 MB resident).
#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "mpm/implicit/linear_solver.hpp"
#include "mpm/explicit/solver.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

bool umfpackLoaded() {
  std::ifstream maps("/proc/self/maps");
  std::string line;
  while (std::getline(maps, line))
    if (line.find("libumfpack") != std::string::npos) return true;
  return false;
}

// A tridiagonal, unsymmetric, diagonally dominant n x n matrix.
Eigen::SparseMatrix<double> tridiagonal(int n, double diagonal) {
  Eigen::SparseMatrix<double> k(n, n);
  for (int i = 0; i < n; ++i) {
    k.insert(i, i) = diagonal + i;
    if (i > 0) k.insert(i, i - 1) = -1.0;
    if (i + 1 < n) k.insert(i, i + 1) = -2.0;
  }
  k.makeCompressed();
  return k;
}

TEST(LinearSolver, EachSolverSolvesASmallUnsymmetricSystemAndRefusesASingularOne) {
  for (const LinearSolverKind kind : {LinearSolverKind::SparseLU, LinearSolverKind::Umfpack}) {
    if (!available(kind)) continue;
    LinearSolver lu(kind);
    const Eigen::SparseMatrix<double> k = tridiagonal(12, 5.0);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(12, -1.0, 2.0);
    ASSERT_TRUE(lu.factorize(k)) << toString(kind);
    EXPECT_LT((lu.solve(k * x) - x).norm(), 1e-13 * x.norm()) << toString(kind);
    // The same pattern again, other values (the analysis is kept).
    const Eigen::SparseMatrix<double> k2 = tridiagonal(12, 9.0);
    ASSERT_TRUE(lu.factorize(k2)) << toString(kind);
    EXPECT_LT((lu.solve(k2 * x) - x).norm(), 1e-13 * x.norm()) << toString(kind);
    Eigen::SparseMatrix<double> singular = k;  // a zero row and column
    for (int j = 0; j < 12; ++j)
      for (Eigen::SparseMatrix<double>::InnerIterator it(singular, j); it; ++it)
        if (it.row() == 4 || it.col() == 4) it.valueRef() = 0.0;
    LinearSolver fresh(kind);
    EXPECT_FALSE(fresh.factorize(singular)) << toString(kind);
  }
}

// GMRES with BoomerAMG (docs/implicit.md, "The AMG solver"): the same small system to its
// tolerance (1e-8 relative residual; this matrix's condition number is below 10, so the error is
// below 1e-7), with and without the unknowns' components, and again after new values (the
// hierarchy kept). It has no factorisation to fail: a singular K shows as GMRES not converging.
TEST(LinearSolver, AmgSolvesASmallUnsymmetricSystemToItsTolerance) {
  if (!available(LinearSolverKind::Amg)) GTEST_SKIP() << "this build has no hypre (libhypre-dev)";
  for (const bool components : {false, true}) {
    LinearSolver amg(LinearSolverKind::Amg);
    if (components) {
      std::vector<int> xy(12);
      for (int i = 0; i < 12; ++i) xy[static_cast<std::size_t>(i)] = i % 2;
      amg.setComponents(xy);
    }
    const Eigen::SparseMatrix<double> k = tridiagonal(12, 5.0);
    const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(12, -1.0, 2.0);
    ASSERT_TRUE(amg.factorize(k));
    EXPECT_LT((amg.solve(k * x) - x).norm(), 1e-7 * x.norm());
    const Eigen::SparseMatrix<double> k2 = tridiagonal(12, 9.0);
    ASSERT_TRUE(amg.factorize(k2));
    EXPECT_LT((amg.solve(k2 * x) - x).norm(), 1e-7 * x.norm());
    ASSERT_NE(amg.amgStatistics(), nullptr);
    EXPECT_EQ(amg.amgStatistics()->solves, 2);
    EXPECT_EQ(amg.amgStatistics()->failedSolves, 0);
  }
}

TEST(LinearSolver, UmfpackIsLoadedAtItsFirstFactorisationNotByAnExplicitRun) {
  if (!available(LinearSolverKind::Umfpack)) GTEST_SKIP() << "this build has no UMFPACK";
  if (umfpackLoaded()) GTEST_SKIP() << "an earlier test of this process loaded it (ctest runs each test alone)";
  Solver explicitRun(tensionBlock(), 1);
  for (int step = 0; step < 20; ++step) explicitRun.advance();
  LinearSolver lu(LinearSolverKind::Umfpack);
  EXPECT_FALSE(umfpackLoaded()) << "an explicit run and a solver not yet used must not load UMFPACK";
  ASSERT_TRUE(lu.factorize(tridiagonal(6, 5.0)));
  EXPECT_TRUE(umfpackLoaded());
}

}  // namespace
}  // namespace ecm::mpm::test
