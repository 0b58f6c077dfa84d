#pragma once
// GMRES (Saad and Schultz 1986) with right preconditioning and no restart: the Krylov correction
// of a Newton step on the kept factorisation (docs/implicit.md, "Krylov on the kept
// factorisation"). The preconditioner is the LU of an earlier tangent; where the tangent has
// changed little (a few points soften), a few Krylov vectors give the current tangent's step.
#include <Eigen/Dense>
#include <functional>

namespace ecm::mpm {

using LinearMap = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

struct GmresResult {
  int iterations = 0;           // Krylov vectors built (operator applications)
  bool converged = false;       // |b - A x| <= tolerance |b|
  double relativeResidual = 0.0;
};

// Solves A x = b from x = 0 with A x = apply(x) and the right preconditioner M^-1 v =
// precondition(v), in at most maxIterations Krylov vectors. x is the minimal-residual solution in
// the space built, converged or not. Zero b gives x = 0 at once.
GmresResult gmres(const LinearMap& apply, const LinearMap& precondition, const Eigen::VectorXd& b, double tolerance,
                  int maxIterations, Eigen::VectorXd& x);

}  // namespace ecm::mpm
