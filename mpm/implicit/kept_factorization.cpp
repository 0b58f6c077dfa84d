// The kept factorisation (mpm/implicit/kept_factorization.hpp).
#include "mpm/implicit/kept_factorization.hpp"

#include <omp.h>

#include <cmath>

#include "mpm/implicit/gmres.hpp"

namespace ecm::mpm {

KeptFactorization::KeptFactorization(LinearSolverKind kind, double krylovTolerance, int krylovIterations)
    : lu_(kind), krylovTolerance_(krylovTolerance), krylovIterations_(krylovIterations) {
  lu_.setIterativeTolerance(krylovTolerance);
}

bool KeptFactorization::factorize(const Eigen::SparseMatrix<double>& k, long key, const DofMap& dofs,
                                  const UnknownReduction* reduction, ImplicitStepReport& report) {
  const double start = omp_get_wtime();
  if (key_ != key) {
    lu_.forgetPattern();
    if (lu_.needsComponents()) lu_.setComponents(unknownComponents(dofs, reduction));
  }
  const bool ok = lu_.factorize(k);
  key_ = ok ? key : -1;
  if (ok) factored_ = k, reduced_ = reduction != nullptr;
  report.linearSolveSeconds += omp_get_wtime() - start;
  report.factorizations++;
  return ok;
}

Eigen::VectorXd KeptFactorization::solve(const Eigen::VectorXd& b, ImplicitStepReport& report) {
  const double start = omp_get_wtime();
  Eigen::VectorXd x = lu_.solve(b);
  report.linearSolveSeconds += omp_get_wtime() - start;
  return x;
}

bool KeptFactorization::krylovStep(const Eigen::SparseMatrix<double>& k, const Border* border, const Eigen::VectorXd& r,
                                   ImplicitStepReport& report, Eigen::VectorXd& d, double* dl) {
  const double start = omp_get_wtime();
  const Eigen::Index n = k.rows();
  GmresResult result;
  if (!border) {
    result = gmres([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return k * v; },
                   [&](const Eigen::VectorXd& v) { return lu_.solve(v); }, r, krylovTolerance_, krylovIterations_, d);
  } else {
    // The border's row in force units: its residual is weighed as the forces' (K's mean diagonal).
    const double scale = k.diagonal().cwiseAbs().mean();
    const double pivot = border->c.dot(border->y) + border->cPrescribed;
    Eigen::VectorXd b(n + 1);
    b << r, scale * border->g;
    Eigen::VectorXd z;
    result = gmres(
        [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
          Eigen::VectorXd w(n + 1);
          w.head(n) = k * v.head(n) + v[n] * border->ku;
          w[n] = scale * (border->c.dot(v.head(n)) + border->cPrescribed * v[n]);
          return w;
        },
        [&](const Eigen::VectorXd& v) -> Eigen::VectorXd {
          Eigen::VectorXd w(n + 1);
          const Eigen::VectorXd x = lu_.solve(v.head(n));
          w[n] = (v[n] / scale - border->c.dot(x)) / pivot;
          w.head(n) = x + w[n] * border->y;
          return w;
        },
        b, krylovTolerance_, krylovIterations_, z);
    d = z.head(n);
    *dl = z[n];
  }
  report.krylovIterations += result.iterations;
  report.linearSolveSeconds += omp_get_wtime() - start;
  return result.converged && d.allFinite() && (!dl || std::isfinite(*dl));
}

bool KeptFactorization::restore(const Eigen::SparseMatrix<double>& k, bool reduced, long key, const DofMap& dofs,
                                const UnknownReduction* reduction) {
  if (lu_.needsComponents()) lu_.setComponents(unknownComponents(dofs, reduction));
  if (!lu_.factorize(k)) return false;
  factored_ = k;
  reduced_ = reduced;
  key_ = key;
  return true;
}

void KeptFactorization::forget() {
  key_ = -1;
  factored_ = Eigen::SparseMatrix<double>();
  lu_.forgetPattern();
}

}  // namespace ecm::mpm
