// The implicit steps' sparse LU (mpm/implicit/linear_solver.hpp): each solver the build has solves a small
// unsymmetric system to round-off and refuses a singular one, and UMFPACK's shared library is
// loaded by the first UMFPACK factorisation, not before: an explicit run does not carry it (nor
// the BLAS, LAPACK and Fortran run-time it pulls in, 3.6 MB resident).
#include <gtest/gtest.h>

#include <cstdint>
#include <fstream>
#include <string>

#include "mpm/implicit/factor_runs.hpp"
#include "mpm/implicit/linear_solver.hpp"
#include "mpm/explicit/explicit_solver.hpp"
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

// What a solver can do follows from its kind, chosen once when it is made: the LUs solve exactly
// (their factors may precondition Krylov steps on later tangents) and ignore the unknowns'
// components; AMG solves to a tolerance and needs them; only UMFPACK copies its factors.
TEST(LinearSolver, ItsCapabilitiesFollowItsKind) {
  for (const LinearSolverKind kind : {LinearSolverKind::SparseLU, LinearSolverKind::Umfpack, LinearSolverKind::Amg}) {
    if (!available(kind)) continue;
    const LinearSolver solver(kind);
    const bool amg = kind == LinearSolverKind::Amg;
    EXPECT_EQ(solver.solvesExactly(), !amg) << toString(kind);
    EXPECT_EQ(solver.needsComponents(), amg) << toString(kind);
    EXPECT_EQ(solver.factorCopies().has_value(), kind == LinearSolverKind::Umfpack) << toString(kind);
    EXPECT_EQ(solver.amgStatistics(), nullptr) << toString(kind) << ": no statistics before its first solve";
  }
}

// A 2D convection-diffusion stencil on an m x m grid: unsymmetric, with fill in its LU and runs
// of every length in its factors' lines.
Eigen::SparseMatrix<double> convectionDiffusion(int m) {
  const int n = m * m;
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < m; ++j)
    for (int i = 0; i < m; ++i) {
      const int row = j * m + i;
      entries.emplace_back(row, row, 4.5 + 0.01 * row);
      if (i > 0) entries.emplace_back(row, row - 1, -1.6);
      if (i + 1 < m) entries.emplace_back(row, row + 1, -0.4);
      if (j > 0) entries.emplace_back(row, row - m, -1.3);
      if (j + 1 < m) entries.emplace_back(row, row + m, -0.7);
    }
  Eigen::SparseMatrix<double> k(n, n);
  k.setFromTriplets(entries.begin(), entries.end());
  return k;
}

// UMFPACK's factors copied by runs (mpm/implicit/factor_runs.hpp): made at the copyAfter-th
// solve with a factorisation, it solves as UMFPACK does, to round-off (this matrix's condition
// number is near 10: 1e-13 has room), and a new factorisation drops it.
TEST(LinearSolver, TheFactorsCopiedByRunsSolveAsUmfpackDoes) {
  if (!available(LinearSolverKind::Umfpack)) GTEST_SKIP() << "this build has no UMFPACK";
  LinearSolver lu(LinearSolverKind::Umfpack);
  lu.setCopyAfter(3);
  const Eigen::SparseMatrix<double> k = convectionDiffusion(20);
  const Eigen::VectorXd x = Eigen::VectorXd::LinSpaced(k.rows(), -1.0, 2.0);
  const Eigen::VectorXd b = k * x;
  ASSERT_TRUE(lu.factorize(k));
  for (int solve = 1; solve <= 2; ++solve) {
    EXPECT_LT((lu.solve(b) - x).norm(), 1e-13 * x.norm());  // UMFPACK's own, before the copy
    EXPECT_EQ(lu.factorCopies().value_or(-1), 0);
  }
  for (int solve = 3; solve <= 4; ++solve) {
    EXPECT_LT((lu.solve(b) - x).norm(), 1e-13 * x.norm());
    EXPECT_EQ(lu.factorCopies().value_or(-1), 1);
  }
  const Eigen::SparseMatrix<double> k2 = 2.0 * k;
  ASSERT_TRUE(lu.factorize(k2));
  EXPECT_LT((lu.solve(b) - 0.5 * x).norm(), 1e-13 * x.norm());  // not the old copy's answer
  EXPECT_EQ(lu.factorCopies().value_or(-1), 1);
}

// The runs of a triangle's lines, without the diagonal each line ends with: a row [0, 1, 3, 4,
// 5 | 6] has the runs 0-1 and 3-5, and the values follow them in order.
TEST(LinearSolver, ARunCoversConsecutiveIndices) {
  const std::vector<std::int32_t> pointers{0, 1, 7}, indices{0, 0, 1, 3, 4, 5, 1};
  const std::vector<double> values{1.0, 10.0, 11.0, 13.0, 14.0, 15.0, 1.0};
  const RunTriangle t = runsOf(2, pointers.data(), indices.data(), values.data(), true);
  EXPECT_EQ(t.firstRun, (std::vector<std::int32_t>{0, 0, 2}));
  EXPECT_EQ(t.runStart, (std::vector<std::int32_t>{0, 3}));
  EXPECT_EQ(t.runLength, (std::vector<std::int32_t>{2, 3}));
  EXPECT_EQ(t.firstValue, (std::vector<std::int32_t>{0, 0, 5}));
  EXPECT_EQ(t.values, (std::vector<double>{10.0, 11.0, 13.0, 14.0, 15.0}));
}

// Factors by hand, P = Q = R = I: lines 0 and 1 joined by L(1, 0), line 2 alone, lines 3 and 4
// joined to both by L(3, 0), L(3, 2), U(1, 4) and U(2, 4); unit diagonal of L, U's diagonal 2 to 6.
FactorRuns handMadeFactors() {
  FactorRuns f;
  f.n = 5;
  f.rowOfPivot = f.columnOfPivot = {0, 1, 2, 3, 4};
  f.rowScale.assign(5, 1.0);
  f.diagonal = {2.0, 3.0, 4.0, 5.0, 6.0};
  // L by rows and U by columns, each line ending on its diagonal entry (left out by runsOf).
  const std::vector<std::int32_t> lp{0, 1, 3, 4, 7, 8}, li{0, 0, 1, 2, 0, 2, 3, 4};
  const std::vector<double> lv{1, 0.5, 1, 1, -0.25, 0.75, 1, 1};
  const std::vector<std::int32_t> up{0, 1, 2, 3, 4, 7}, ui{0, 1, 2, 3, 1, 2, 4};
  const std::vector<double> uv{2, 3, 4, 5, 1.5, -2.0, 6};
  f.lower = runsOf(5, lp.data(), li.data(), lv.data(), true);
  f.upper = runsOf(5, up.data(), ui.data(), uv.data(), true);
  return f;
}

// The split of the lines for two threads (mpm/implicit/factor_runs.hpp), on the factors above:
// lines 0-1 and 2 are the two groups, 3-4 the serial tail. Entries per line plus one: 1, 2, 1, 3,
// 3 (10 in all); a tail from line 3 costs the longer group's 3 plus the tail's 6, every other tail
// 10. The answer on two threads is bitwise the one-thread answer, and both are L U's inverse
// applied (to 1e-15: entries of order 1). A factorisation with an entry across the groups
// (L(2, 1)) does not keep the split.
TEST(LinearSolver, TwoThreadsSolveTheCopiedFactorsBitwiseAsOne) {
  FactorRuns f = handMadeFactors();
  f.split = splitOf(f);
  EXPECT_EQ(f.split.serialFrom, 3);
  EXPECT_EQ(f.split.groups[0], (std::vector<std::int32_t>{0, 1}));
  EXPECT_EQ(f.split.groups[1], (std::vector<std::int32_t>{2}));
  EXPECT_TRUE(holds(f.split, f));
  Eigen::MatrixXd l = Eigen::MatrixXd::Identity(5, 5), u = Eigen::MatrixXd::Zero(5, 5);
  l(1, 0) = 0.5, l(3, 0) = -0.25, l(3, 2) = 0.75;
  for (int i = 0; i < 5; ++i) u(i, i) = 2.0 + i;
  u(1, 4) = 1.5, u(2, 4) = -2.0;
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(5, -1.0, 3.0);
  const Eigen::VectorXd exact = (l * u).lu().solve(b);
  Eigen::VectorXd one, two;
  std::vector<double> work;
  solveByRuns(f, b, one, work, 1);
  solveByRuns(f, b, two, work, 2);
  EXPECT_TRUE((one.array() == two.array()).all());
  EXPECT_LT((one - exact).norm(), 1e-15 * exact.norm());

  FactorRuns crossed = handMadeFactors();
  const std::vector<std::int32_t> lp{0, 1, 3, 5, 8, 9}, li{0, 0, 1, 1, 2, 0, 2, 3, 4};
  const std::vector<double> lv{1, 0.5, 1, 0.1, 1, -0.25, 0.75, 1, 1};
  crossed.lower = runsOf(5, lp.data(), li.data(), lv.data(), true);
  EXPECT_FALSE(holds(f.split, crossed));
  const TwoWaySplit fresh = splitOf(crossed, &f.split);
  EXPECT_TRUE(fresh.empty() || holds(fresh, crossed));
}

// The same on UMFPACK's factors of a 2D stencil (their lines do split: two groups below a tail),
// through the solver: a solve on two threads is bitwise the one on one.
TEST(LinearSolver, TwoThreadsPreconditionBitwiseAsOneOnUmfpacksFactors) {
  if (!available(LinearSolverKind::Umfpack)) GTEST_SKIP() << "this build has no UMFPACK";
  const Eigen::SparseMatrix<double> k = convectionDiffusion(40);
  const Eigen::VectorXd b = Eigen::VectorXd::LinSpaced(k.rows(), -1.0, 2.0);
  Eigen::VectorXd answers[2];
  for (const int threads : {1, 2}) {
    LinearSolver lu(LinearSolverKind::Umfpack);
    lu.setThreads(threads);
    ASSERT_TRUE(lu.factorize(k));
    answers[threads - 1] = lu.solve(b);
    EXPECT_EQ(lu.factorCopies().value_or(-1), 1);
    EXPECT_LT((k * answers[threads - 1] - b).norm(), 1e-12 * b.norm());
  }
  EXPECT_TRUE((answers[0].array() == answers[1].array()).all());
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
  ExplicitSolver explicitRun(tensionBlock(), 1);
  for (int step = 0; step < 20; ++step) explicitRun.advance();
  LinearSolver lu(LinearSolverKind::Umfpack);
  EXPECT_FALSE(umfpackLoaded()) << "an explicit run and a solver not yet used must not load UMFPACK";
  ASSERT_TRUE(lu.factorize(tridiagonal(6, 5.0)));
  EXPECT_TRUE(umfpackLoaded());
}

}  // namespace
}  // namespace ecm::mpm::test
