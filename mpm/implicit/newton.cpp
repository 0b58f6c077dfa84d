// The Newton driver (mpm/implicit/newton.hpp).
#include "mpm/implicit/newton.hpp"

#include <cmath>
#include <vector>

#include "mpm/implicit/newton_ends.hpp"

namespace ecm::mpm {

namespace {

// Newton's iterates of an attempt: the relative residual of each, and the best iterate an attempt
// keeps when it runs out of iterations or stalls (docs/implicit.md, "Load steps").
struct NewtonHistory {
  std::vector<double> residuals;
  double bestRelative = INFINITY;
  Iterate best;

  // An iterate with its relative residual; `eligible`: it may be kept (under indirect control,
  // only one that meets the control). `iterate` gives it, asked only for a new best.
  template <class F>
  void observe(double relative, bool eligible, F&& iterate) {
    residuals.push_back(relative);
    if (eligible && relative < bestRelative) bestRelative = relative, best = iterate();
  }
  // Newton ends at `iteration`: out of iterations, diverged, or Newton proper (reuse 0) has
  // stalled, which the last resort does not test.
  bool ends(int iteration, int maxIterations, double reuseRatio, bool lastResort) const {
    return iteration >= maxIterations || diverged(residuals) || (reuseRatio <= 0.0 && !lastResort && stalled(residuals));
  }
  // An earlier iterate was better than the last one (`relative`).
  bool hasBetterThan(double relative) const { return best.du.size() > 0 && bestRelative < relative; }
};

// y = -K0^-1 ku of the border on the kept factorisation: solved again when the factorisation or
// ku changed (ku stays put while the driven conditions' points stay elastic).
struct BorderSolution {
  Eigen::VectorXd y, kuAtY;
  int factorizationsAtY = -1;

  void update(const Eigen::VectorXd& ku, KeptFactorization& factors, ImplicitStepReport& report) {
    if (report.factorizations != factorizationsAtY || y.size() != ku.size() || ku != kuAtY)
      y = -factors.solve(ku, report), kuAtY = ku, factorizationsAtY = report.factorizations;
  }
};

// Newton's correction of iteration `it` from the residual: GMRES on the current tangent
// preconditioned by the kept factorisation where it reaches its tolerance, otherwise the solve
// on the kept factorisation, or on a fresh one (`refactor`, or the unknowns changed). Under
// indirect control the system is bordered by the control's row: d = x + dl y with
// x = K^-1 r, y = -K^-1 ku and dl from c . (d + dl u^) = g.
bool correction(const StepContext& context, Attempt& a, const Residual& res, bool refactor, CycleGuard& cycle,
                BorderSolution& border, int it, Correction& d) {
  KeptFactorization& factors = context.factors;
  bool fresh = refactor || !factors.isOf(context.factorKey);
  const Eigen::SparseMatrix<double>* current = nullptr;  // the tangent over the unknowns, once reduced
  if (!fresh && factors.krylovOn()) {  // the current tangent's step on the kept factorisation, or a fresh one
    if (res.border) border.update(res.border->ku, factors, a.report);
    assembleTangent(context.setup, context.particles, context.geometry, a.trial);
    current = &a.tangentOf(a.trial);
    bool solved = false;
    if (!res.border) {
      solved = factors.krylovStep(*current, nullptr, res.r, a.report, d.step, nullptr);
    } else {
      const ControlRow& row = *res.border;
      const Border b{row.ku, *row.c, row.cPrescribed, border.y, row.g};
      solved = border.y.allFinite() && factors.krylovStep(*current, &b, res.r, a.report, d.step, &d.loadFactor);
    }
    cycle.solvedWithFreshTangent(true);
    if (solved) return true;
    fresh = true;
  } else {
    cycle.solvedWithFreshTangent(fresh);
    if (fresh) assembleTangent(context.setup, context.particles, context.geometry, a.trial);
  }
  if (fresh && !factors.factorize(current ? *current : a.tangentOf(a.trial), context.factorKey, context.geometry.dofs,
                                  a.unknownReduction(), a.report))
    return a.fail(it, res.relative, NewtonFailure::Singular, "the tangent is singular");
  const Eigen::VectorXd x = factors.solve(res.r, a.report);
  if (!res.border) {
    if (!x.allFinite()) return a.fail(it, res.relative, NewtonFailure::Singular, "the tangent is singular");
    d.step = x;
    return true;
  }
  const ControlRow& row = *res.border;
  border.update(row.ku, factors, a.report);
  const Eigen::VectorXd& y = border.y;
  if (!x.allFinite() || !y.allFinite()) return a.fail(it, res.relative, NewtonFailure::Singular, "the tangent is singular");
  double cx = 0.0, cy = 0.0;
  for (Eigen::Index u = 0; u < x.size(); ++u) {
    const double ck = (*row.c)[u];
    cx += ck * x[u], cy += ck * y[u];
  }
  const double denominator = cy + row.cPrescribed;
  if (!(std::abs(denominator) > 0.0))
    return a.fail(it, res.relative, NewtonFailure::ControlBlind,
                  "the control does not see the driven conditions (c . du does not change with the load factor)");
  d.loadFactor = (row.g - cx) / denominator;
  d.step = x + d.loadFactor * y;
  return true;
}

}  // namespace

bool solveNewton(StepProblem& problem, const StepContext& context, Attempt& a) {
  if (!problem.start()) return false;
  NewtonHistory history;  // a stalled attempt keeps its best iterate
  CycleGuard cycle;       // mpm/implicit/newton_cycle.hpp
  BorderSolution border;
  double previous = INFINITY;  // the last iterate's |r|
  for (int it = 0;; ++it) {
    if (a.trial.failed != SIZE_MAX) return a.failInMaterial(it, a.trial, context.setup, context.particles);
    if (a.keepReleases) keepReleases(a.trial, context.particles.size(), a.kept);
    const Residual res = problem.residual(it);
    a.report.totalIterations++;
    if (res.mayConverge && res.meetsControl && res.relative <= context.settings.tolerance) {
      a.report.iterations = it;
      a.report.residual = res.relative;
      problem.finish();
      return true;
    }
    history.observe(res.relative, res.meetsControl, [&] { return problem.iterate(); });
    cycle.observe(a.trial.dissipation, res.relative);
    if (history.ends(it, a.maxIterations, a.reuseRatio, a.lastResort)) {
      a.stalled = true;  // the attempt holds the best iterate
      a.report.iterations = it;
      double relative = res.relative;
      if (history.hasBetterThan(relative)) {
        problem.backTo(&history.best, cycle);
        if (a.trial.failed != SIZE_MAX) return a.failInMaterial(it, a.trial, context.setup, context.particles);
        relative = history.bestRelative;
        if (a.keepReleases) relative = problem.residual(it).relative;  // releases kept since that iterate start points elsewhere
      } else {
        problem.backTo(nullptr, cycle);
      }
      problem.finish();
      return a.fail(it, relative, NewtonFailure::NotConverged, "Newton did not converge");
    }
    // The kept factorisation is renewed where it no longer contracts the residual well enough
    // (with Krylov on it the step is the current tangent's already), and at every iteration of
    // Newton proper (reuse 0).
    const double norm = res.r.norm();
    const bool refactor = context.factors.krylovOn() ? it == 0 && a.reuseRatio <= 0.0
                                                     : a.reuseRatio <= 0.0 || (it > 0 && norm > a.reuseRatio * previous);
    previous = norm;
    Correction d;
    if (!correction(context, a, res, refactor, cycle, border, it, d)) return false;
    problem.move(d, res, cycle);
  }
}

}  // namespace ecm::mpm
