// Implicit quasi-static load steps (mpm/implicit_solver.hpp).
#include "mpm/implicit_solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>
#include <utility>

#include "mpm/errors.hpp"
#include "mpm/phases.hpp"
#include "mpm/seeding.hpp"

namespace ecm::mpm {

namespace {

// The prescribed displacement of a component over [t, t + dt], or NaN when it is free.
double prescribedIncrement(const ComponentCondition& c, double t, double dt) {
  switch (c.kind) {
    case Prescribed::Free: return NAN;
    case Prescribed::Fixed: return 0.0;
    case Prescribed::Velocity: return dt * c.history(t + dt);
    case Prescribed::Displacement: return c.history(t + dt) - c.history(t);
  }
  return NAN;
}

}  // namespace

// One try at a step: its geometry, the prescribed components and loads, and Newton's iterate.
struct ImplicitSolver::Attempt {
  StepGeometry geometry;
  std::vector<std::uint8_t> prescribed;  // per node component
  Eigen::VectorXd du;                    // per node component (mm)
  Eigen::VectorXd external;              // loads and gravity at the step's end, per node component (N)
  Eigen::VectorXd direction;             // indirect control: the driven components' reference (mm per unit load factor)
  double dLambda = 0.0;                  // indirect control: the load factor's increment
  Trial trial;                           // at du
  ImplicitStepReport report;
  SnapBackPolicy snapBack = SnapBackPolicy::Stop;
  // Why it failed: the iteration, the relative residual and the particle (SIZE_MAX: none).
  int failedIteration = 0;
  double failedResidual = 0.0;
  std::size_t failedParticle = SIZE_MAX;
  std::string why;

  // Records why the attempt failed; returns false, for `return a.fail(...)`.
  bool fail(int iteration, double residual, std::string reason) {
    failedIteration = iteration, failedResidual = residual, why = std::move(reason);
    return false;
  }
  // A material update of `t` failed: the particle and its material's explanation.
  bool failInMaterial(int iteration, const Trial& t, const StepSetup& setup, const Particles& p) {
    failedParticle = t.failed;
    return fail(iteration, 0.0, setup.materials[p.material[t.failed]].explain(t.failure));
  }
};

ImplicitSolver::ImplicitSolver(Scene scene, int threads, ImplicitOptions options) : options_(options) {
  Particles seeded = seedParticles(scene);
  setup_ = makeStepSetup(std::move(scene), seeded.size(), threads, 4096);
  MpmState st = initialState(setup_, std::move(seeded));
  particles_ = std::move(st.particles);
  conditions_ = std::move(st.conditions);
  loads_ = std::move(st.loads);
  for (Vec2& v : particles_.velocity) v.setZero();  // quasi-static: no initial velocities
}

Energies ImplicitSolver::energies() const {
  double strain = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) strain += 0.5 * particles_.volume[i] * particles_.stress[i].dot(particles_.strain[i]);
  return {0.0, strain, totals_.externalWork, totals_.dissipated, 0.0};
}

bool ImplicitSolver::prepare(double dt, const IndirectControl* control, Attempt& a) {
  const Scene& scene = setup_.scene;
  const Grid& grid = scene.grid;
  const double t0 = time_, t1 = time_ + dt;
  const auto components = static_cast<Eigen::Index>(2 * grid.nodeCount());
  // The prescribed components and their increments.
  // (Under indirect control the driven conditions' components follow the load factor instead:
  // their direction is the reference, their increment found by the step.)
  a.prescribed.assign(static_cast<std::size_t>(components), 0);
  a.du.setZero(components);
  a.direction.setZero(components);
  for (std::size_t c = 0; c < scene.conditions.size(); ++c) {
    const NodeCondition& cond = scene.conditions[c];
    const bool driven = control && std::find(control->driven.begin(), control->driven.end(), c) != control->driven.end();
    for (const std::int32_t node : conditions_[c].nodes) {
      Vec2 du(prescribedIncrement(cond.component[0], t0, dt), prescribedIncrement(cond.component[1], t0, dt));
      if (cond.field) du = dt * cond.field->scale(t1) * cond.field->gradient * (grid.nodePosition(node) - cond.field->origin);
      for (int d = 0; d < 2; ++d) {
        if (std::isnan(du[d])) continue;
        a.prescribed[2 * static_cast<std::size_t>(node) + static_cast<std::size_t>(d)] = 1;
        const bool follows = driven && !cond.field && cond.component[static_cast<std::size_t>(d)].kind != Prescribed::Fixed;
        if (follows)
          a.direction[2 * node + d] = control->reference[d];
        else
          a.du[2 * node + d] = du[d];
      }
    }
  }
  std::size_t outside = 0;
  if (!stepGeometry(setup_, particles_, a.prescribed, a.geometry, outside)) {
    a.failedParticle = outside;
    return a.fail(0, 0.0, "its shape-function support left the grid");
  }
  // Loads and gravity at the step's end.
  a.external.setZero(components);
  const int nx = grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  const auto spread = [&](const Stencil& s, const Vec2& f) {
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) {
        const Eigen::Index n = s.base + j * nx + k;
        a.external.segment<2>(2 * n) += s.wx[k] * s.wy[j] * f;
      }
  };
  if (scene.solver.gravity.squaredNorm() > 0.0)
    for (std::size_t i = 0; i < particles_.size(); ++i) spread(a.geometry.stencils[i], particles_.mass[i] * scene.solver.gravity);
  for (std::size_t l = 0; l < scene.loads.size(); ++l) {
    const Load& load = scene.loads[l];
    const Vec2 each = load.force * load.history(t1) / static_cast<double>(loads_[l].members.size());
    for (const std::int32_t m : loads_[l].members) {
      if (load.target == LoadTarget::Nodes)
        a.external.segment<2>(2 * static_cast<Eigen::Index>(m)) += each;
      else
        spread(a.geometry.stencils[static_cast<std::size_t>(m)], each);
    }
  }
  return true;
}

bool ImplicitSolver::attempt(double dt, Attempt& a) {
  if (!prepare(dt, nullptr, a)) return false;
  const auto components = a.du.size();
  // Newton on the unknowns.
  const DofMap& dofs = a.geometry.dofs;
  const int n = dofs.unknowns();
  LinearSolver lu(options_.linearSolver);
  const auto residualOf = [&](const Trial& t, double& relative) {
    Eigen::VectorXd r(n);
    double reference = 0.0;
    for (int u = 0; u < n; ++u) r[u] = a.external[dofs.component[static_cast<std::size_t>(u)]] - t.internalForce[dofs.component[static_cast<std::size_t>(u)]];
    reference = std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
    relative = r.norm() / reference;
    return r;
  };
  // The predictor: linearised at the step's start (du = 0), loaded by the prescribed increments
  // through the coupling K_fp: K_ff du_f = (f_ext - f_int)_f - (K du_p)_f. Starting Newton at the
  // prescribed increments alone would strain the boundary's layer of particles with all of them.
  {
    const Eigen::VectorXd prescribedIncrements = a.du;
    Trial start;
    evaluateTrial(setup_, particles_, a.geometry, Eigen::VectorXd::Zero(components), true, a.snapBack, start,
                  &prescribedIncrements);
    if (start.failed != SIZE_MAX) {
      return a.failInMaterial(0, start, setup_, particles_);
    }
    Eigen::VectorXd rhs(n);
    for (int u = 0; u < n; ++u) {
      const auto c = dofs.component[static_cast<std::size_t>(u)];
      rhs[u] = a.external[c] - start.internalForce[c] - start.tangentTimesDirection[c];
    }
    if (n > 0) {
      const double t0 = omp_get_wtime();
      const bool factored = lu.factorize(start.tangent);
      Eigen::VectorXd delta;
      if (factored) delta = lu.solve(rhs);
      a.report.linearSolveSeconds += omp_get_wtime() - t0;
      if (!factored || !delta.allFinite()) {
        return a.fail(0, 0.0, "the tangent at the step's start is singular");
      }
      for (int u = 0; u < n; ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
    }
  }
  evaluateTrial(setup_, particles_, a.geometry, a.du, true, a.snapBack, a.trial);
  for (int it = 0;; ++it) {
    if (a.trial.failed != SIZE_MAX) {
      return a.failInMaterial(it, a.trial, setup_, particles_);
    }
    double relative = 0.0;
    const Eigen::VectorXd r = residualOf(a.trial, relative);
    a.report.totalIterations++;
    if (relative <= options_.tolerance) {
      a.report.iterations = it;
      a.report.residual = relative;
      return true;
    }
    if (it >= options_.maxIterations) {
      return a.fail(it, relative, "Newton did not converge");
    }
    const double start = omp_get_wtime();
    const bool factored = lu.factorize(a.trial.tangent);
    Eigen::VectorXd delta;
    if (factored) delta = lu.solve(r);
    a.report.linearSolveSeconds += omp_get_wtime() - start;
    if (!factored || !delta.allFinite()) {
      return a.fail(it, relative, "the tangent is singular");
    }
    // Backtracking line search on |r|: the full step, then halves, the best kept.
    Eigen::VectorXd full = Eigen::VectorXd::Zero(a.du.size());
    for (int u = 0; u < n; ++u) full[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
    Trial best;
    double bestNorm = INFINITY, alpha = 1.0;
    Eigen::VectorXd bestDu;
    for (int tries = 0; tries < 6; ++tries, alpha *= 0.5) {
      Trial t;
      const Eigen::VectorXd du = a.du + alpha * full;
      evaluateTrial(setup_, particles_, a.geometry, du, true, a.snapBack, t);
      if (t.failed != SIZE_MAX) continue;
      double rel = 0.0;
      const double norm = residualOf(t, rel).norm();
      if (norm < bestNorm) {
        bestNorm = norm, best = std::move(t), bestDu = du;
      }
      if (norm <= (1.0 - 1e-4 * alpha) * r.norm()) break;
    }
    if (!std::isfinite(bestNorm)) {  // every length failed in the material: report the full step's failure
      evaluateTrial(setup_, particles_, a.geometry, a.du + full, true, a.snapBack, a.trial);
      continue;
    }
    a.du = std::move(bestDu);
    a.trial = std::move(best);
  }
}

bool ImplicitSolver::attemptIndirect(const IndirectControl& control, double dTau, Attempt& a) {
  if (!prepare(0.0, &control, a)) return false;
  const auto components = a.du.size();
  const DofMap& dofs = a.geometry.dofs;
  const int n = dofs.unknowns();
  // The control's coefficients per node component.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(components);
  for (const auto& [k, coefficient] : control.terms) c[k] += coefficient;
  const double cPrescribed = c.dot(a.direction);  // d tau per unit load factor through the driven components
  LinearSolver lu(options_.linearSolver);
  double dLambda = 0.0;
  // Newton on (du_f, d lambda) with the bordered system, from du = 0 (the first iteration is the
  // predictor): K_ff d_f + (K u^)_f d_lambda = r_f and c . (d_f + d_lambda u^) = d tau - c . du,
  // solved with one factorisation: d_f = a + d_lambda b, a = K_ff^-1 r_f, b = -K_ff^-1 (K u^)_f.
  for (int it = 0;; ++it) {
    Trial& t = a.trial;
    const Eigen::VectorXd du = a.du + dLambda * a.direction;
    evaluateTrial(setup_, particles_, a.geometry, du, true, a.snapBack, t, &a.direction);
    a.report.totalIterations++;
    if (t.failed != SIZE_MAX) {
      return a.failInMaterial(it, t, setup_, particles_);
    }
    Eigen::VectorXd r(n), ku(n);
    for (int u = 0; u < n; ++u) {
      const auto k = dofs.component[static_cast<std::size_t>(u)];
      r[u] = a.external[k] - t.internalForce[k];
      ku[u] = t.tangentTimesDirection[k];
    }
    const double reference = std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
    const double relative = r.norm() / reference, g = dTau - c.dot(du);
    if (it > 0 && relative <= options_.tolerance && std::abs(g) <= 1e-10 * std::abs(dTau)) {
      a.report.iterations = it;
      a.report.residual = relative;
      a.du = du;
      a.dLambda = dLambda;
      return true;
    }
    if (it >= options_.maxIterations) {
      return a.fail(it, relative, "Newton did not converge");
    }
    const double start = omp_get_wtime();
    const bool factored = lu.factorize(t.tangent);
    Eigen::VectorXd x, y;
    if (factored) x = lu.solve(r), y = -lu.solve(ku);
    a.report.linearSolveSeconds += omp_get_wtime() - start;
    if (!factored || !x.allFinite() || !y.allFinite()) {
      return a.fail(it, relative, "the tangent is singular");
    }
    double cx = 0.0, cy = 0.0;
    for (int u = 0; u < n; ++u) {
      const double ck = c[dofs.component[static_cast<std::size_t>(u)]];
      cx += ck * x[u], cy += ck * y[u];
    }
    const double denominator = cy + cPrescribed;
    if (!(std::abs(denominator) > 0.0)) {
      return a.fail(it, relative, "the control does not see the driven conditions (c . du does not change with the load factor)");
    }
    const double deltaLambda = (g - cx) / denominator;
    for (int u = 0; u < n; ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] += x[u] + deltaLambda * y[u];
    dLambda += deltaLambda;
  }
}

void ImplicitSolver::commit(const Attempt& a, double dt) {
  const Scene& scene = setup_.scene;
  const Trial& t = a.trial;
  Particles& p = particles_;
  const int nx = scene.grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Stencil& s = a.geometry.stencils[i];
    Vec2 move = Vec2::Zero();
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) move += s.wx[k] * s.wy[j] * a.du.segment<2>(2 * static_cast<Eigen::Index>(s.base + j * nx + k));
    p.position[i] += move;
    p.strain[i] = t.strain[i];
    p.stress[i] = t.stress[i];
    if (t.band[i]) {
      if (p.band[i] < 0) {
        p.band[i] = static_cast<std::int32_t>(p.bands.size());
        p.bands.push_back(*t.band[i]);
      } else {
        p.bands[static_cast<std::size_t>(p.band[i])] = *t.band[i];
      }
    }
    if (t.secondBand[i] && !p.secondBand.empty()) {
      if (p.secondBand[i] < 0) {
        p.secondBand[i] = static_cast<std::int32_t>(p.secondBands.size());
        p.secondBands.push_back(*t.secondBand[i]);
      } else {
        p.secondBands[static_cast<std::size_t>(p.secondBand[i])] = *t.secondBand[i];
      }
    }
    totals_.dissipated += p.volume[i] * t.dissipation[i];
  }
  if (!t.integrity.empty()) p.integrity = t.integrity;
  // Reactions: what the constraints add to the loads to balance the internal forces.
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    ConditionState& state = conditions_[c];
    const NodeCondition& cond = scene.conditions[c];
    state.reaction.setZero();
    for (const std::int32_t node : state.nodes)
      for (int d = 0; d < 2; ++d)
        if (a.prescribed[2 * static_cast<std::size_t>(node) + static_cast<std::size_t>(d)])
          state.reaction[d] += t.internalForce[2 * node + d] - a.external[2 * node + d];
    for (int d = 0; d < 2; ++d) {
      const ComponentCondition& k = cond.component[static_cast<std::size_t>(d)];
      if (cond.field) continue;
      if (!state.nodes.empty() && a.direction.size() > 0 && a.direction[2 * state.nodes[0] + d] != 0.0) {
        state.displacement[d] += a.dLambda * a.direction[2 * state.nodes[0] + d];  // driven by the load factor
        continue;
      }
      if (k.kind == Prescribed::Displacement) state.displacement[d] = k.history(time_ + dt);
      if (k.kind == Prescribed::Velocity) state.displacement[d] += dt * k.history(time_ + dt);
    }
  }
  // External work, trapezoidal: at equilibrium the forces the loads and constraints apply are
  // the internal forces, node component by node component.
  totals_.externalWork += 0.5 * (t.internalForce.dot(a.du) + (previousForce_.size() == t.internalForce.size() ? previousForce_.dot(a.du) : 0.0));
  previousForce_ = t.internalForce;
  totals_.released += t.released;
  lambda_ += a.dLambda;
  time_ += dt;
  ++steps_;
}

template <class Try>
ImplicitStepReport ImplicitSolver::halving(double size, Try&& tryPiece) {
  ImplicitStepReport total;
  double done = 0.0, piece = size;
  int cuts = 0;
  while (std::abs(done) < std::abs(size) * (1.0 - 1e-12)) {
    piece = std::abs(piece) < std::abs(size - done) ? piece : size - done;
    Attempt a;
    const bool finest = cuts >= options_.maxCuts;
    a.snapBack = finest ? SnapBackPolicy::Release : SnapBackPolicy::Stop;  // a persisting snap-back is released
    const bool ok = tryPiece(piece, a);
    total.totalIterations += a.report.totalIterations;
    total.linearSolveSeconds += a.report.linearSolveSeconds;
    if (ok) {
      done += piece;
      total.iterations = std::max(total.iterations, a.report.iterations);
      total.residual = std::max(total.residual, a.report.residual);
      total.released += a.trial.released;
      continue;
    }
    if (!finest) {
      piece *= 0.5;
      ++cuts;
      total.cuts = cuts;
      continue;
    }
    std::ostringstream msg;
    msg << "implicit step " << steps_ + 1 << " (t = " << time_ << " s, load factor " << lambda_ << ", a piece of "
        << piece << " after " << cuts << " halvings): " << a.why << " at Newton iteration " << a.failedIteration
        << ", relative residual " << a.failedResidual;
    Vec2 where = Vec2::Zero();
    if (a.failedParticle != SIZE_MAX) {
      where = particles_.position[a.failedParticle];
      msg << "; particle " << a.failedParticle << " at (" << where[0] << ", " << where[1] << ") mm";
    }
    throw SimulationError(a.why.find("grid") != std::string::npos ? FailureKind::LeftGrid : FailureKind::MaterialFailure,
                          steps_ + 1, a.failedParticle == SIZE_MAX ? 0 : a.failedParticle, where, msg.str(),
                          a.trial.failure.status, a.failedResidual);
  }
  return total;
}

ImplicitStepReport ImplicitSolver::step(double dt) {
  return halving(dt, [&](double piece, Attempt& a) {
    if (!attempt(piece, a)) return false;
    commit(a, piece);
    return true;
  });
}

ImplicitStepReport ImplicitSolver::step(const IndirectControl& control, double dTau) {
  return halving(dTau, [&](double piece, Attempt& a) {
    if (!attemptIndirect(control, piece, a)) return false;
    commit(a, 0.0);
    return true;
  });
}

}  // namespace ecm::mpm
