// GMRES with right preconditioning (mpm/implicit/gmres.hpp), against what Krylov theory says:
// - with the exact inverse as preconditioner, one vector solves the system;
// - with the inverse of a matrix that differs from A by a change of rank k, A M^-1 = I + (rank k),
//   whose minimal polynomial has degree at most k + 1: GMRES ends in at most k + 1 vectors, to
//   round-off. That is the case of a softening tangent against the kept factorisation, where a few
//   points change (docs/implicit.md, "Krylov on the kept factorisation");
// - a vector budget too small returns converged = false with the minimal residual in that space,
//   whose residual is never above |b| (x = 0 is in every Krylov space).
#include <gtest/gtest.h>

#include <Eigen/Dense>

#include "mpm/implicit/gmres.hpp"

namespace ecm::mpm::test {
namespace {

// An unsymmetric, diagonally dominant n x n matrix (deterministic).
Eigen::MatrixXd unsymmetric(int n) {
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    a(i, i) = 10.0 + 0.1 * i;
    if (i > 0) a(i, i - 1) = -1.0 - 0.01 * i;
    if (i + 1 < n) a(i, i + 1) = -2.0;
    a(i, (i * 7 + 3) % n) += 0.5;
  }
  return a;
}

Eigen::VectorXd rightHandSide(int n) {
  Eigen::VectorXd b(n);
  for (int i = 0; i < n; ++i) b[i] = std::sin(0.3 * i) + 0.1;
  return b;
}

TEST(Gmres, TheExactInverseSolvesInOneVector) {
  const int n = 60;
  const Eigen::MatrixXd a = unsymmetric(n);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(a);
  const Eigen::VectorXd b = rightHandSide(n);
  Eigen::VectorXd x;
  const GmresResult r = gmres([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return a * v; },
                              [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return lu.solve(v); }, b, 1e-12, 20, x);
  EXPECT_TRUE(r.converged);
  EXPECT_EQ(r.iterations, 1);
  EXPECT_LT((b - a * x).norm(), 1e-12 * b.norm());
}

TEST(Gmres, ARankKChangeOfThePreconditionedMatrixEndsInKPlusOneVectors) {
  const int n = 80;
  const Eigen::MatrixXd kept = unsymmetric(n);
  const Eigen::PartialPivLU<Eigen::MatrixXd> lu(kept);
  const Eigen::VectorXd b = rightHandSide(n);
  for (const int rank : {1, 3, 6}) {
    Eigen::MatrixXd a = kept;  // k rows softened: a softening point changes its nodes' rows
    for (int j = 0; j < rank; ++j) a.row(10 * j + 5) *= 0.3, a(10 * j + 5, 10 * j + 6) += 1.5;
    Eigen::VectorXd x;
    const GmresResult r = gmres([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return a * v; },
                                [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return lu.solve(v); }, b, 1e-10, 40, x);
    EXPECT_TRUE(r.converged) << rank;
    EXPECT_LE(r.iterations, rank + 1) << rank;
    EXPECT_GE(r.iterations, 2) << rank;  // the preconditioner is not A's inverse
    EXPECT_LT((b - a * x).norm(), 1e-9 * b.norm()) << rank;
  }
}

TEST(Gmres, ASmallBudgetReturnsTheBestItCouldAndSaysItDidNotConverge) {
  const int n = 80;
  const Eigen::MatrixXd a = unsymmetric(n);
  const Eigen::VectorXd b = rightHandSide(n);
  const auto identity = [](const Eigen::VectorXd& v) -> Eigen::VectorXd { return v; };
  const auto apply = [&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return a * v; };
  double last = b.norm();
  for (const int budget : {1, 2, 4, 8}) {  // unpreconditioned: the residual falls as the space grows
    Eigen::VectorXd x;
    const GmresResult r = gmres(apply, identity, b, 1e-14, budget, x);
    EXPECT_FALSE(r.converged) << budget;
    EXPECT_EQ(r.iterations, budget);
    const double residual = (b - a * x).norm();
    EXPECT_NEAR(residual / b.norm(), r.relativeResidual, 1e-10) << budget;  // the reported residual is x's
    EXPECT_LT(residual, last) << budget;
    last = residual;
  }
  Eigen::VectorXd x;
  EXPECT_TRUE(gmres(apply, identity, Eigen::VectorXd::Zero(n), 1e-10, 5, x).converged);
  EXPECT_EQ(x.norm(), 0.0);
}

}  // namespace
}  // namespace ecm::mpm::test
