// Implicit quasi-static load steps (mpm/implicit/implicit_solver.hpp).
#include "mpm/implicit/implicit_solver.hpp"
#include "mpm/setup/stress_direction.hpp"

#include <omp.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "mpm/core/errors.hpp"
#include "mpm/implicit/gmres.hpp"
#include "mpm/implicit/newton_cycle.hpp"
#include "mpm/implicit/newton_ends.hpp"
#include "mpm/setup/step_setup.hpp"
#include "mpm/setup/seeding.hpp"

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

// Why an attempt at a piece failed: what the step loop does next depends on it.
enum class NewtonFailure {
  None,
  LeftGrid,         // a particle's shape-function support left the grid
  Material,         // a material update failed (its status says how; SnapBack among them)
  Singular,         // the tangent is singular
  NotConverged,     // Newton ran out of iterations or stalled (it keeps its best iterate)
  OnsetOvershoot,   // the piece carried a point past its onset by more than the scene allows
  ControlBlind,     // indirect control: c . du does not change with the load factor
};

// Newton's iterates of an attempt: the relative residual of each, and the best iterate an attempt
// keeps when it runs out of iterations or stalls (docs/implicit.md, "Load steps").
struct NewtonHistory {
  std::vector<double> residuals;
  double bestRelative = INFINITY;
  Eigen::VectorXd bestDu;
  double bestDLambda = 0.0;

  // An iterate with its relative residual; `eligible`: it may be kept (under indirect control,
  // only one that meets the control).
  void observe(double relative, bool eligible, const Eigen::VectorXd& du, double dLambda = 0.0) {
    residuals.push_back(relative);
    if (eligible && relative < bestRelative) bestRelative = relative, bestDu = du, bestDLambda = dLambda;
  }
  // Newton ends at `iteration`: out of iterations, diverged, or Newton proper (reuse 0) has
  // stalled, which the last resort does not test.
  bool ends(int iteration, int maxIterations, double reuseRatio, bool lastResort) const {
    return iteration >= maxIterations || diverged(residuals) || (reuseRatio <= 0.0 && !lastResort && stalled(residuals));
  }
  // An earlier iterate was better than the last one (`relative`).
  bool hasBetterThan(double relative) const { return bestDu.size() > 0 && bestRelative < relative; }
};

}  // namespace

// One try at a step: its geometry, the prescribed components and loads, and Newton's iterate.
struct ImplicitSolver::Attempt {
  std::vector<std::uint8_t> prescribed;  // per node component
  Eigen::VectorXd du;                    // per node component (mm)
  Eigen::VectorXd external;              // loads and gravity at the step's end, per node component (N)
  Eigen::VectorXd externalStart;         // the same at the step's start
  Eigen::VectorXd startForce;            // the internal forces at the step's start (du = 0), on its geometry
  Eigen::VectorXd direction;             // indirect control: the driven components' reference (mm per unit load factor)
  // The platens (mpm/implicit/unknown_reduction.hpp): per platen, which degrees of freedom are
  // prescribed in the step, their increments and (indirect control) their reference; the nodes
  // tied to their neighbours (mpm/implicit/node_ties.hpp); the change of unknowns (none without
  // platens and ties) and the reduced tangent last factorised.
  std::vector<std::array<bool, 3>> platenPrescribed;
  std::vector<Eigen::Vector3d> platenIncrement, platenDirection;
  std::vector<NodeTie> ties;
  std::optional<UnknownReduction> reduction;
  Eigen::SparseMatrix<double> reducedTangent;
  double dLambda = 0.0;                  // indirect control: the load factor's increment
  double dTau = 0.0;                     // indirect control: the opening's increment
  Trial trial;                           // at du
  ImplicitStepReport report;
  SnapBackPolicy snapBack = SnapBackPolicy::Stop;  // set by each attempt: Stop, or Release under the scene's release
  double reuseRatio = 0.1;               // ImplicitOptions::reuseRatio, 0 after a failed attempt (Newton proper)
  int maxIterations = 25;                // ImplicitOptions::maxIterations, 4 times that at the last halving
  bool lastResort = false;               // the last halving: no early stall test, its whole maxIterations
  bool stalled = false;                  // Newton ran out of iterations; du and trial hold its last iterate
  // The last halving under release keeps each point's release for the rest of the attempt
  // (docs/implicit.md, "Releases kept within a step").
  bool keepReleases = false;
  ReleasedStarts kept;
  const ReleasedStarts* keptStarts() const { return keepReleases ? &kept : nullptr; }
  // The points the attempt released: those of its trial, and with kept releases those of its
  // earlier iterates too, each counted once.
  long releases() const {
    if (!keepReleases) return trial.released;
    long count = static_cast<long>(kept.starts.size());
    for (const auto& [i, start] : trial.releases)
      if (kept.of.empty() || kept.of[i] < 0) ++count;
    return count;
  }
  UpdateStatus failedStatus = UpdateStatus::Converged;  // of the material update that failed
  // Why it failed: the iteration, the relative residual and the particle (SIZE_MAX: none).
  int failedIteration = 0;
  double failedResidual = 0.0;
  std::size_t failedParticle = SIZE_MAX;
  NewtonFailure reason = NewtonFailure::None;
  std::string why;  // the reason in words, for the report

  // Records why the attempt failed; returns false, for `return a.fail(...)`.
  bool fail(int iteration, double residual, NewtonFailure kind, std::string words) {
    failedIteration = iteration, failedResidual = residual, reason = kind, why = std::move(words);
    return false;
  }
  // A material update of `t` failed: the particle and its material's explanation.
  bool failInMaterial(int iteration, const Trial& t, const StepSetup& setup, const Particles& p) {
    failedParticle = t.failed;
    failedStatus = t.failure.status;
    return fail(iteration, 0.0, NewtonFailure::Material, setup.materials[p.material[t.failed]].explain(t.failure));
  }
};

namespace {

// The tangent to factorise: K, or T^T K T with platens or ties (kept in the attempt).
const Eigen::SparseMatrix<double>& tangentOfTrial(const Trial& t, std::optional<UnknownReduction>& reduction,
                                                  Eigen::SparseMatrix<double>& reduced) {
  if (!reduction) return t.tangent;
  reduced = reduceTangent(*reduction, t.tangent);
  return reduced;
}

}  // namespace

ImplicitSolver::ImplicitSolver(Scene scene, int threads)
    : settings_(scene.solver.implicit.value_or(ImplicitSettings{})), lu_(settings_.linearSolver) {
  Particles seeded = seedParticles(scene);
  setup_ = makeStepSetup(std::move(scene), seeded.size(), threads, 4096);
  particles_ = std::move(seeded);
  conditions_ = conditionStates(setup_.scene);
  loads_ = loadStates(setup_.scene, particles_);
  platens_ = platenStates(setup_.scene);
  crackPaths_ = crackPathsFor(setup_.scene, particles_);
  for (Vec2& v : particles_.velocity) v.setZero();  // quasi-static: no initial velocities
  lu_.setIterativeTolerance(settings_.krylovTolerance);
  lu_.setThreads(setup_.threads);
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
  // The platens: their nodes' components stay unknowns; the increments of their prescribed
  // degrees of freedom (or, driven by the load factor, their reference) move them rigidly.
  a.platenPrescribed.assign(platens_.size(), {true, true, true});
  a.platenIncrement.assign(platens_.size(), Eigen::Vector3d::Zero());
  a.platenDirection.assign(platens_.size(), Eigen::Vector3d::Zero());
  for (std::size_t p = 0; p < platens_.size(); ++p) {
    const Platen& platen = scene.platens[p];
    const bool driven = control && std::find(control->drivenPlatens.begin(), control->drivenPlatens.end(), p) != control->drivenPlatens.end();
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = platen.dof[static_cast<std::size_t>(d)];
      // (Under indirect control a driven platen's displacements follow the load factor, free_until aside.)
      const bool followsControl = driven && d < 2 && dof.drive == PlatenDrive::Displacement;
      a.platenPrescribed[p][static_cast<std::size_t>(d)] = dof.drive == PlatenDrive::Held || dof.drivenAt(t0) || followsControl;
      if (followsControl)
        a.platenDirection[p][d] = control->reference[d];
      else if (dof.drivenAt(t0))
        a.platenIncrement[p][d] = dof.history(t1) - dof.history(t0);
    }
    for (const std::int32_t node : platens_[p].nodes) {
      const Eigen::Matrix<double, 2, 3> b = rigidMap(grid.nodePosition(node), platens_[p].reference);
      a.du.segment<2>(2 * static_cast<Eigen::Index>(node)) = b * a.platenIncrement[p];
      a.direction.segment<2>(2 * static_cast<Eigen::Index>(node)) = b * a.platenDirection[p];
    }
  }
  // The geometry of the committed state (the pieces of a halved step share it).
  if (geometryStep_ != steps_ || geometry_.prescribed != a.prescribed) {
    std::size_t outside = 0;
    geometryStep_ = -1;
    if (!stepGeometry(setup_, particles_, a.prescribed, geometry_, outside)) {
      a.failedParticle = outside;
      return a.fail(0, 0.0, NewtonFailure::LeftGrid, "its shape-function support left the grid");
    }
    geometryStep_ = steps_;
  }
  geometry_.crackPaths = &crackPaths_;
  // Nodes the body barely reaches: tied to their neighbours (neither a prescribed component nor a
  // platen's node is tied; a platen's node is no source).
  {
    const auto nodes = static_cast<std::size_t>(grid.nodeCount());
    std::vector<std::uint8_t> mayTie(nodes, 1), maySource(nodes, 1);
    for (std::size_t n = 0; n < nodes; ++n) mayTie[n] = !a.prescribed[2 * n] && !a.prescribed[2 * n + 1];
    for (const PlatenState& platen : platens_)
      for (const std::int32_t node : platen.nodes) mayTie[static_cast<std::size_t>(node)] = maySource[static_cast<std::size_t>(node)] = 0;
    a.ties = weakNodeTies(grid.nodesX(), grid.nodesY(), geometry_.share, mayTie, maySource);
  }
  a.reduction.reset();
  if (!platens_.empty() || !a.ties.empty()) {
    a.reduction = unknownReduction(scene, platens_, geometry_.dofs, a.platenPrescribed, a.ties);
    if (a.platenPrescribed != platenLayout_ || a.ties != tieLayout_)  // a factorisation of other unknowns
      platenLayout_ = a.platenPrescribed, tieLayout_ = a.ties, ++reductionLayouts_;
    applyTies(a.ties, a.du);  // a prescribed source's increment (the others are 0 here)
    applyTies(a.ties, a.direction);
  }
  // Loads and gravity at the step's start and end.
  const int nx = grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  const auto spread = [&](Eigen::VectorXd& into, const Stencil& s, const Vec2& f) {
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) {
        const Eigen::Index n = s.base + j * nx + k;
        into.segment<2>(2 * n) += s.wx[k] * s.wy[j] * f;
      }
  };
  for (const auto& [into, t] : {std::pair<Eigen::VectorXd*, double>{&a.externalStart, t0}, {&a.external, t1}}) {
    into->setZero(components);
    if (scene.solver.gravity.squaredNorm() > 0.0)
      for (std::size_t i = 0; i < particles_.size(); ++i) spread(*into, geometry_.stencils[i], particles_.mass[i] * scene.solver.gravity);
    for (std::size_t l = 0; l < scene.loads.size(); ++l) {
      const Load& load = scene.loads[l];
      const Vec2 each = load.force * load.history(t) / static_cast<double>(loads_[l].members.size());
      for (const std::int32_t m : loads_[l].members) {
        if (load.target == LoadTarget::Nodes)
          into->segment<2>(2 * static_cast<Eigen::Index>(m)) += each;
        else
          spread(*into, geometry_.stencils[static_cast<std::size_t>(m)], each);
      }
    }
    // A platen's force histories, spread over its nodes that carry the body so that their
    // generalized force is the history's: f_k = B_k A^-1 F with A = sum_k B_k^T B_k.
    for (std::size_t p = 0; p < platens_.size(); ++p) {
      Eigen::Vector3d force = Eigen::Vector3d::Zero();
      for (int d = 0; d < 3; ++d)
        if (scene.platens[p].dof[static_cast<std::size_t>(d)].drive == PlatenDrive::Force)
          force[d] = scene.platens[p].dof[static_cast<std::size_t>(d)].history(t);
      if (force.isZero()) continue;
      Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
      for (const std::int32_t node : platens_[p].nodes)
        if (geometry_.reached[2 * static_cast<std::size_t>(node)]) {
          const Eigen::Matrix<double, 2, 3> b = rigidMap(grid.nodePosition(node), platens_[p].reference);
          sum += b.transpose() * b;
        }
      const Eigen::Vector3d each = solveRigid(sum, force);
      for (const std::int32_t node : platens_[p].nodes)
        if (geometry_.reached[2 * static_cast<std::size_t>(node)])
          into->segment<2>(2 * static_cast<Eigen::Index>(node)) += rigidMap(grid.nodePosition(node), platens_[p].reference) * each;
    }
  }
  return true;
}

ImplicitSolver::SavedState ImplicitSolver::saved() const {
  SavedState s;
  s.time = time_, s.loadFactor = lambda_, s.nextPiece = nextPiece_, s.nextOpening = nextOpening_, s.steps = steps_;
  s.externalWork = totals_.externalWork, s.internalWork = internalWork_, s.dissipated = totals_.dissipated;
  s.released = totals_.released;
  for (const ConditionState& c : conditions_) {
    s.reactions.push_back(c.reaction);
    s.conditionDisplacements.push_back(c.displacement);
  }
  for (const Stencil& st : geometry_.stencils) s.stencilBases.push_back(st.base);
  s.prescribed = geometry_.prescribed;
  if (luPattern_ >= 0 && luPattern_ == factorKey()) {
    s.factored = factored_;
    s.factoredReduced = factoredReduced_;
    if (factoredReduced_) s.platenLayout = platenLayout_, s.tieLayout = tieLayout_;
  }
  s.lastIncrement = lastIncrement_, s.lastLoadFactorIncrement = lastLoadFactorIncrement_, s.lastOpening = lastOpening_;
  return s;
}

void ImplicitSolver::restore(const SavedState& s) {
  if (s.reactions.size() != conditions_.size() || s.conditionDisplacements.size() != conditions_.size())
    throw std::invalid_argument("it has " + std::to_string(s.reactions.size()) + " conditions, the scene " +
                                std::to_string(conditions_.size()));
  if (s.lastIncrement.size() != 0 && s.lastIncrement.size() != 2 * static_cast<Eigen::Index>(setup_.scene.grid.nodeCount()))
    throw std::invalid_argument("its last increment does not fit the scene's grid");
  time_ = s.time, lambda_ = s.loadFactor, nextPiece_ = s.nextPiece, nextOpening_ = s.nextOpening, steps_ = s.steps;
  lastIncrement_ = s.lastIncrement, lastLoadFactorIncrement_ = s.lastLoadFactorIncrement, lastOpening_ = s.lastOpening;
  totals_.externalWork = s.externalWork, internalWork_ = s.internalWork, totals_.dissipated = s.dissipated;
  totals_.released = s.released;
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    conditions_[c].reaction = s.reactions[c];
    conditions_[c].displacement = s.conditionDisplacements[c];
  }
  // The geometry the next step compares its stencils with, and the factorisation on it: the
  // next step then keeps or rebuilds the pattern, and reuses or renews K, as the saved run would.
  geometry_ = StepGeometry{};
  geometryStep_ = -1;
  luPattern_ = -1;
  factored_ = Eigen::SparseMatrix<double>();
  lu_.forgetPattern();
  if (s.stencilBases.empty()) return;
  if (s.stencilBases.size() != particles_.size() || s.prescribed.size() != static_cast<std::size_t>(2 * setup_.scene.grid.nodeCount()))
    throw std::invalid_argument("its step geometry does not fit the scene's particles and grid");
  if (!restoreGeometry(setup_, particles_.size(), s.prescribed, s.stencilBases, geometry_))
    throw std::invalid_argument("its step geometry has a stencil outside the grid");
  if (s.factored.size() == 0) return;
  const Eigen::SparseMatrix<double>& k = s.factored;
  std::optional<UnknownReduction> reduction;
  if (s.factoredReduced) {
    // Of reduced unknowns: the layout it was made for becomes the solver's, so that the next step
    // reuses it exactly when the saved run did.
    if (s.platenLayout.size() != platens_.size()) throw std::invalid_argument("its platen layout does not fit the scene's platens");
    const auto onGrid = [&](std::int32_t node) { return node >= 0 && node < setup_.scene.grid.nodeCount(); };
    for (const NodeTie& tie : s.tieLayout) {
      bool fits = onGrid(tie.node) && tie.sources >= 1 && tie.sources <= 4;
      for (int i = 0; fits && i < tie.sources; ++i) fits = onGrid(tie.source[static_cast<std::size_t>(i)]);
      if (!fits) throw std::invalid_argument("its node ties do not fit the scene's grid");
    }
    platenLayout_ = s.platenLayout, tieLayout_ = s.tieLayout, ++reductionLayouts_;
    reduction = unknownReduction(setup_.scene, platens_, geometry_.dofs, platenLayout_, tieLayout_);
    if (k.rows() != reduction->reduced() || k.cols() != reduction->reduced())
      throw std::invalid_argument("its factorised tangent does not fit its step geometry");
  } else {
    const Eigen::SparseMatrix<double>& pattern = geometry_.pattern;
    const bool samePattern = k.rows() == pattern.rows() && k.cols() == pattern.cols() && k.nonZeros() == pattern.nonZeros() &&
                             std::equal(k.outerIndexPtr(), k.outerIndexPtr() + k.cols() + 1, pattern.outerIndexPtr()) &&
                             std::equal(k.innerIndexPtr(), k.innerIndexPtr() + k.nonZeros(), pattern.innerIndexPtr());
    if (!samePattern) throw std::invalid_argument("its factorised tangent does not fit its step geometry");
  }
  if (settings_.linearSolver == LinearSolverKind::Amg) lu_.setComponents(unknownComponents(geometry_.dofs, reduction ? &*reduction : nullptr));
  if (!lu_.factorize(k)) throw std::invalid_argument("its factorised tangent is singular");
  factored_ = k;
  factoredReduced_ = s.factoredReduced;
  luPattern_ = factorKey();
}

Eigen::SparseMatrix<double> ImplicitSolver::tangentAtStart(double dt, std::vector<int>* components) {
  Attempt a;
  if (!prepare(dt, nullptr, a)) return {};
  if (components) *components = unknownComponents(geometry_.dofs, a.reduction ? &*a.reduction : nullptr);
  evaluateTrial(setup_, particles_, geometry_, Eigen::VectorXd::Zero(a.du.size()), true, a.snapBack, a.trial);
  return a.trial.tangent;
}

bool ImplicitSolver::factorize(const Eigen::SparseMatrix<double>& k, Attempt& a) {
  const double start = omp_get_wtime();
  if (luPattern_ != factorKey()) {
    lu_.forgetPattern();
    if (settings_.linearSolver == LinearSolverKind::Amg) lu_.setComponents(unknownComponents(geometry_.dofs, a.reduction ? &*a.reduction : nullptr));
  }
  const bool ok = lu_.factorize(k);
  luPattern_ = ok ? factorKey() : -1;
  if (ok) factored_ = k, factoredReduced_ = a.reduction.has_value();
  a.report.linearSolveSeconds += omp_get_wtime() - start;
  a.report.factorizations++;
  return ok;
}

Eigen::VectorXd ImplicitSolver::solve(const Eigen::VectorXd& b, Attempt& a) {
  const double start = omp_get_wtime();
  Eigen::VectorXd x = lu_.solve(b);
  a.report.linearSolveSeconds += omp_get_wtime() - start;
  return x;
}

bool ImplicitSolver::krylovOn() const {
  return settings_.krylovIterations > 0 && settings_.linearSolver != LinearSolverKind::Amg;
}

// Newton's step on the current tangent k, by GMRES preconditioned with the kept factorisation
// (docs/implicit.md, "Krylov on the kept factorisation"). With a border (indirect control) the
// system is [k, ku; c, cP] [d; dl] = [r; g], preconditioned by the same border on the kept
// factorisation: M^-1 [p; q] = [x + dl y; dl], x = K0^-1 p, y = -K0^-1 ku, dl from the border's
// row. False where GMRES needs more than krylovIterations vectors: then the caller factorises.
bool ImplicitSolver::krylovStep(const Eigen::SparseMatrix<double>& k, const Border* border, const Eigen::VectorXd& r,
                                Attempt& a, Eigen::VectorXd& d, double* dl) {
  const double start = omp_get_wtime();
  const Eigen::Index n = k.rows();
  GmresResult result;
  if (!border) {
    result = gmres([&](const Eigen::VectorXd& v) -> Eigen::VectorXd { return k * v; },
                   [&](const Eigen::VectorXd& v) { return lu_.solve(v); }, r, settings_.krylovTolerance,
                   settings_.krylovIterations, d);
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
        b, settings_.krylovTolerance, settings_.krylovIterations, z);
    d = z.head(n);
    *dl = z[n];
  }
  a.report.krylovIterations += result.iterations;
  a.report.linearSolveSeconds += omp_get_wtime() - start;
  return result.converged && d.allFinite() && (!dl || std::isfinite(*dl));
}

bool ImplicitSolver::attempt(double dt, Attempt& a) {
  if (!prepare(dt, nullptr, a)) return false;
  const auto components = a.du.size();
  // Newton on the unknowns.
  const DofMap& dofs = geometry_.dofs;
  const UnknownReduction* reduction = a.reduction ? &*a.reduction : nullptr;  // the platens' and ties' change of unknowns
  const int n = reduction ? reduction->reduced() : dofs.unknowns();
  const auto residualOf = [&](const Trial& t, double& relative) {
    const Eigen::VectorXd r = onUnknowns(dofs, reduction, [&](std::int32_t c) { return a.external[c] - t.internalForce[c]; });
    relative = r.norm() / std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
    return r;
  };
  // The predictor: linearised at the step's start (du = 0), loaded by the prescribed increments
  // through the coupling K_fp: K_ff du_f = (f_ext - f_int)_f - (K du_p)_f. Starting Newton at the
  // prescribed increments alone would strain the boundary's layer of particles with all of them.
  // K_ff is the last factorisation while the unknowns are those it was made for.
  if (n > 0) {
    const Eigen::VectorXd prescribedIncrements = a.du;
    Trial start;
    evaluateTrial(setup_, particles_, geometry_, Eigen::VectorXd::Zero(components), false, a.snapBack, start, &prescribedIncrements);
    if (start.failed != SIZE_MAX) return a.failInMaterial(0, start, setup_, particles_);
    a.startForce = start.internalForce;
    const Eigen::VectorXd rhs = onUnknowns(dofs, reduction, [&](std::int32_t c) {
      return a.external[c] - start.internalForce[c] - start.tangentTimesDirection[c];
    });
    if (luPattern_ != factorKey() || a.reuseRatio <= 0.0) {
      assembleTangent(setup_, particles_, geometry_, start);
      if (!factorize(tangentOfTrial(start, a.reduction, a.reducedTangent), a)) return a.fail(0, 0.0, NewtonFailure::Singular, "the tangent at the step's start is singular");
    }
    const Eigen::VectorXd delta = solve(rhs, a);
    if (!delta.allFinite()) return a.fail(0, 0.0, NewtonFailure::Singular, "the tangent at the step's start is singular");
    if (!reduction) {
      for (int u = 0; u < n; ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
    } else {  // a platen's or a tie's node components carry their prescribed increments already
      const Eigen::VectorXd onNodes = toUnknowns(reduction, delta);
      for (int u = 0; u < dofs.unknowns(); ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] += onNodes[u];
    }
  }
  evaluateTrial(setup_, particles_, geometry_, a.du, false, a.snapBack, a.trial, nullptr, nullptr, a.keptStarts());
  // A predictor far past the onset limit is not worth converging: the piece is cut at once (not on
  // the last halving under release, which has no smaller piece to go to).
  const bool lastUnderRelease = a.lastResort && a.snapBack == SnapBackPolicy::Release;
  if (!lastUnderRelease && a.trial.failed == SIZE_MAX && a.trial.onsetOvershoot > 1.5 * settings_.onsetOvershoot)
    return a.fail(0, 0.0, NewtonFailure::OnsetOvershoot, "the predictor carried a point past its onset by " + std::to_string(a.trial.onsetOvershoot) + " of its strength");
  bool refactor = a.reuseRatio <= 0.0;
  NewtonHistory history;  // a stalled attempt keeps its best iterate
  CycleGuard cycle;       // mpm/implicit/newton_cycle.hpp
  for (int it = 0;; ++it) {
    if (a.trial.failed != SIZE_MAX) return a.failInMaterial(it, a.trial, setup_, particles_);
    if (a.keepReleases) keepReleases(a.trial, particles_.size(), a.kept);
    double relative = 0.0;
    const Eigen::VectorXd r = residualOf(a.trial, relative);
    a.report.totalIterations++;
    if (relative <= settings_.tolerance) {
      a.report.iterations = it;
      a.report.residual = relative;
      return true;
    }
    history.observe(relative, true, a.du);
    cycle.observe(a.trial.dissipation, relative);
    if (history.ends(it, a.maxIterations, a.reuseRatio, a.lastResort)) {
      a.stalled = true;  // a.du and a.trial hold the best iterate
      a.report.iterations = it;
      if (history.hasBetterThan(relative)) {
        a.du = history.bestDu;
        evaluateTrial(setup_, particles_, geometry_, a.du, false, a.snapBack, a.trial, nullptr, cycle.secantFlags(), a.keptStarts());
        if (a.trial.failed != SIZE_MAX) return a.failInMaterial(it, a.trial, setup_, particles_);
        relative = history.bestRelative;
        if (a.keepReleases) residualOf(a.trial, relative);  // releases kept since that iterate start points elsewhere
      }
      return a.fail(it, relative, NewtonFailure::NotConverged, "Newton did not converge");
    }
    bool fresh = refactor || luPattern_ != factorKey();
    Eigen::VectorXd onUnknownsStep;
    const Eigen::SparseMatrix<double>* current = nullptr;  // the tangent over the unknowns, once reduced
    if (!fresh && krylovOn()) {  // the current tangent's step on the kept factorisation, or a fresh one
      assembleTangent(setup_, particles_, geometry_, a.trial);
      current = &tangentOfTrial(a.trial, a.reduction, a.reducedTangent);
      fresh = !krylovStep(*current, nullptr, r, a, onUnknownsStep, nullptr);
      cycle.solvedWithFreshTangent(true);
    } else {
      cycle.solvedWithFreshTangent(fresh);
      if (fresh) assembleTangent(setup_, particles_, geometry_, a.trial);
    }
    if (fresh) {
      if (!factorize(current ? *current : tangentOfTrial(a.trial, a.reduction, a.reducedTangent), a)) return a.fail(it, relative, NewtonFailure::Singular, "the tangent is singular");
      onUnknownsStep = solve(r, a);
    } else if (!krylovOn()) {
      onUnknownsStep = solve(r, a);
    }
    const Eigen::VectorXd delta = toUnknowns(reduction, onUnknownsStep);
    if (!delta.allFinite()) return a.fail(it, relative, NewtonFailure::Singular, "the tangent is singular");
    // Backtracking line search on |r|: the full step, then halves, the best kept.
    Eigen::VectorXd full = Eigen::VectorXd::Zero(a.du.size());
    for (int u = 0; u < dofs.unknowns(); ++u) full[dofs.component[static_cast<std::size_t>(u)]] = delta[u];
    Trial best;
    double bestNorm = INFINITY, alpha = 1.0;
    Eigen::VectorXd bestDu;
    for (int tries = 0; tries < 6; ++tries, alpha *= 0.5) {
      Trial t;
      const Eigen::VectorXd du = a.du + alpha * full;
      evaluateTrial(setup_, particles_, geometry_, du, false, a.snapBack, t, nullptr, cycle.secantFlags(), a.keptStarts());
      if (t.failed != SIZE_MAX) continue;
      double rel = 0.0;
      const double norm = residualOf(t, rel).norm();
      if (norm < bestNorm) bestNorm = norm, best = std::move(t), bestDu = du;
      if (norm <= (1.0 - 1e-4 * alpha) * r.norm()) break;
    }
    if (!std::isfinite(bestNorm)) {  // every length failed in the material: report the full step's failure
      evaluateTrial(setup_, particles_, geometry_, a.du + full, false, a.snapBack, a.trial, nullptr, cycle.secantFlags(), a.keptStarts());
      continue;
    }
    // A stale factorisation that no longer contracts the residual well enough is renewed.
    // (With Krylov on the kept factorisation the step is the current tangent's already.)
    refactor = !krylovOn() && (a.reuseRatio <= 0.0 || bestNorm > a.reuseRatio * r.norm());
    a.du = std::move(bestDu);
    a.trial = std::move(best);
  }
}

bool ImplicitSolver::attemptIndirect(const IndirectControl& control, double dTau, Attempt& a) {
  if (!prepare(0.0, &control, a)) return false;
  const auto components = a.du.size();
  const DofMap& dofs = geometry_.dofs;
  const UnknownReduction* reduction = a.reduction ? &*a.reduction : nullptr;  // the platens' and ties' change of unknowns
  const int n = reduction ? reduction->reduced() : dofs.unknowns();
  // The control's coefficients per node component, and over the (reduced) unknowns.
  Eigen::VectorXd c = Eigen::VectorXd::Zero(components);
  for (const auto& [k, coefficient] : control.terms) c[k] += coefficient;
  const Eigen::VectorXd cUnknowns = onUnknowns(dofs, reduction, [&](std::int32_t k) { return c[k]; });
  const double cPrescribed = c.dot(a.direction);  // d tau per unit load factor through the driven components
  double dLambda = 0.0, previous = INFINITY;
  bool refactor = a.reuseRatio <= 0.0;
  Eigen::VectorXd y, kuAtY;  // y = -K_ff^-1 (K u^)_f, and the K u^ it was solved for
  int factorizationsAtY = -1;
  // Points that make Newton cycle take their secant tangent (mpm/implicit/newton_cycle.hpp); a stalled
  // attempt keeps its best iterate that meets the control.
  CycleGuard cycle;
  NewtonHistory history;
  // The start: the last step's increments scaled to this step's opening (docs/implicit.md, "The
  // extrapolated start"): it meets the control exactly, and Newton begins near the solution of a
  // smooth path. The internal forces at du = 0 (for the work) are then evaluated apart.
  bool extrapolated = false;
  if (settings_.extrapolate && lastOpening_ != 0.0 && lastIncrement_.size() == components) {
    Trial zero;
    evaluateTrial(setup_, particles_, geometry_, Eigen::VectorXd::Zero(components), false, a.snapBack, zero);
    if (zero.failed != SIZE_MAX) return a.failInMaterial(0, zero, setup_, particles_);
    a.startForce = zero.internalForce;
    const double scale = dTau / lastOpening_;
    for (int u = 0; u < dofs.unknowns(); ++u) {  // (a platen's node components: without the load factor's share)
      const auto k = dofs.component[static_cast<std::size_t>(u)];
      const double d = a.direction[k];
      a.du[k] = scale * (d == 0.0 ? lastIncrement_[k] : lastIncrement_[k] - lastLoadFactorIncrement_ * d);
    }
    applyTies(a.ties, a.du);  // the last step may have tied other nodes
    dLambda = scale * lastLoadFactorIncrement_;
    extrapolated = true;
  }
  // Newton on (du_f, d lambda) with the bordered system, from that start or from du = 0 (then the
  // first iteration is the predictor): K_ff d_f + (K u^)_f d_lambda = r_f and c . (d_f + d_lambda u^) = d tau - c . du,
  // solved with one factorisation: d_f = a + d_lambda b, a = K_ff^-1 r_f, b = -K_ff^-1 (K u^)_f.
  // K_ff is refactorised as in attempt().
  const auto addStep = [&](const Eigen::VectorXd& step, double deltaLambda) {
    if (!reduction) {
      for (int u = 0; u < n; ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] += step[u];
    } else {
      const Eigen::VectorXd onNodes = toUnknowns(reduction, step);
      for (int u = 0; u < dofs.unknowns(); ++u) a.du[dofs.component[static_cast<std::size_t>(u)]] += onNodes[u];
    }
    dLambda += deltaLambda;
  };
  for (int it = 0;; ++it) {
    Trial& t = a.trial;
    const Eigen::VectorXd du = a.du + dLambda * a.direction;
    evaluateTrial(setup_, particles_, geometry_, du, false, a.snapBack, t, &a.direction, cycle.secantFlags(), a.keptStarts());
    a.report.totalIterations++;
    if (t.failed != SIZE_MAX) return a.failInMaterial(it, t, setup_, particles_);
    if (a.keepReleases) keepReleases(t, particles_.size(), a.kept);
    if (it == 0 && !extrapolated) a.startForce = t.internalForce;  // du = 0
    const Eigen::VectorXd r = onUnknowns(dofs, reduction, [&](std::int32_t k) { return a.external[k] - t.internalForce[k]; });
    const Eigen::VectorXd ku = onUnknowns(dofs, reduction, [&](std::int32_t k) { return t.tangentTimesDirection[k]; });
    const double reference = std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
    double relative = r.norm() / reference;
    const double g = dTau - c.dot(du);
    if ((it > 0 || extrapolated) && relative <= settings_.tolerance && std::abs(g) <= 1e-10 * std::abs(dTau)) {
      a.report.iterations = it;
      a.report.residual = relative;
      a.du = du;
      a.dLambda = dLambda;
      a.dTau = dTau;
      return true;
    }
    history.observe(relative, std::abs(g) <= 1e-10 * std::abs(dTau), a.du, dLambda);
    cycle.observe(t.dissipation, relative);
    if (history.ends(it, a.maxIterations, a.reuseRatio, a.lastResort)) {
      a.stalled = true;  // the best iterate, as a converged one is kept
      a.report.iterations = it;
      if (history.hasBetterThan(relative)) {
        dLambda = history.bestDLambda;
        a.du = history.bestDu + dLambda * a.direction;
        relative = history.bestRelative;
        evaluateTrial(setup_, particles_, geometry_, a.du, false, a.snapBack, t, &a.direction, cycle.secantFlags(), a.keptStarts());
        if (t.failed != SIZE_MAX) return a.failInMaterial(it, t, setup_, particles_);
        if (a.keepReleases) {  // releases kept since that iterate start points elsewhere: its residual now
          const Eigen::VectorXd rBest = onUnknowns(dofs, reduction, [&](std::int32_t k) { return a.external[k] - t.internalForce[k]; });
          relative = rBest.norm() / std::max({a.external.norm(), t.internalForce.norm(), 1e-300});
        }
      } else {
        a.du = du;
      }
      a.dLambda = dLambda;
      a.dTau = dTau;
      return a.fail(it, relative, NewtonFailure::NotConverged, "Newton did not converge");
    }
    if (!krylovOn() && it > 0 && r.norm() > a.reuseRatio * previous) refactor = true;
    previous = r.norm();
    bool fresh = refactor || luPattern_ != factorKey();
    // y depends on the factorisation and on K u^ only: solved again when either changed (K u^
    // stays put while the driven conditions' points stay elastic).
    const auto updateY = [&] {
      if (a.report.factorizations != factorizationsAtY || y.size() != n || ku != kuAtY)
        y = -solve(ku, a), kuAtY = ku, factorizationsAtY = a.report.factorizations;
    };
    const Eigen::SparseMatrix<double>* current = nullptr;  // the tangent over the unknowns, once reduced
    if (!fresh && krylovOn()) {  // the current tangent's step on the kept factorisation, or a fresh one
      updateY();
      assembleTangent(setup_, particles_, geometry_, t);
      Eigen::VectorXd d;
      double deltaLambda = 0.0;
      const Border border{ku, cUnknowns, cPrescribed, y, g};
      current = &tangentOfTrial(t, a.reduction, a.reducedTangent);
      if (y.allFinite() && krylovStep(*current, &border, r, a, d, &deltaLambda)) {
        cycle.solvedWithFreshTangent(true);
        addStep(d, deltaLambda);
        continue;
      }
      fresh = true;
    } else if (fresh) {
      assembleTangent(setup_, particles_, geometry_, t);
    }
    cycle.solvedWithFreshTangent(fresh);
    if (fresh) {
      if (!factorize(current ? *current : tangentOfTrial(t, a.reduction, a.reducedTangent), a)) return a.fail(it, relative, NewtonFailure::Singular, "the tangent is singular");
      refactor = a.reuseRatio <= 0.0 && !krylovOn();
    }
    const Eigen::VectorXd x = solve(r, a);
    updateY();
    if (!x.allFinite() || !y.allFinite()) return a.fail(it, relative, NewtonFailure::Singular, "the tangent is singular");
    double cx = 0.0, cy = 0.0;
    for (int u = 0; u < n; ++u) {
      const double ck = cUnknowns[u];
      cx += ck * x[u], cy += ck * y[u];
    }
    const double denominator = cy + cPrescribed;
    if (!(std::abs(denominator) > 0.0))
      return a.fail(it, relative, NewtonFailure::ControlBlind, "the control does not see the driven conditions (c . du does not change with the load factor)");
    const double deltaLambda = (g - cx) / denominator;
    addStep(x + deltaLambda * y, deltaLambda);
  }
}

void ImplicitSolver::commit(const Attempt& a, double dt) {
  const Scene& scene = setup_.scene;
  const Trial& t = a.trial;
  Particles& p = particles_;
  const int nx = scene.grid.nodesX(), support = supportSize(scene.solver.shapeFunction);
  double internal = 0.0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Stencil& s = geometry_.stencils[i];
    Vec2 move = Vec2::Zero();
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k) move += s.wx[k] * s.wy[j] * a.du.segment<2>(2 * static_cast<Eigen::Index>(s.base + j * nx + k));
    p.position[i] += move;
    internal += 0.5 * p.volume[i] * (p.stress[i] + t.stress[i]).dot(t.strain[i] - p.strain[i]);
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
  // Reactions: what the constraints add to the loads to balance the internal forces (a tied
  // node's unbalanced force belongs to its sources: T^T).
  Eigen::VectorXd unbalanced = t.internalForce - a.external;
  transferTies(a.ties, unbalanced);
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    ConditionState& state = conditions_[c];
    const NodeCondition& cond = scene.conditions[c];
    state.reaction.setZero();
    for (const std::int32_t node : state.nodes)
      for (int d = 0; d < 2; ++d)
        if (a.prescribed[2 * static_cast<std::size_t>(node) + static_cast<std::size_t>(d)])
          state.reaction[d] += unbalanced[2 * node + d];
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
  // The works of the step, trapezoidal (docs/implicit.md, "Energies"): the external work of the
  // forces the loads and the constraints apply (at a prescribed component the internal force, at a
  // free one the load), and the internal work sum_p V (sigma_n + sigma_n+1)/2 : d eps_p.
  // They differ by the work of the residual: the check of equilibrium in energy.
  // A tied node's forces are its sources' (T^T) and its increment theirs: it is skipped.
  double external = 0.0;
  {
    Eigen::VectorXd startForce = a.startForce, endForce = t.internalForce, loadStart = a.externalStart, load = a.external;
    std::vector<std::uint8_t> tied;
    if (!a.ties.empty()) {
      for (Eigen::VectorXd* v : {&startForce, &endForce, &loadStart, &load}) transferTies(a.ties, *v);
      tied.assign(static_cast<std::size_t>(a.du.size()), 0);
      for (const NodeTie& tie : a.ties) tied[2 * static_cast<std::size_t>(tie.node)] = tied[2 * static_cast<std::size_t>(tie.node) + 1] = 1;
    }
    for (Eigen::Index k = 0; k < a.du.size(); ++k) {
      if (a.du[k] == 0.0 || (!tied.empty() && tied[static_cast<std::size_t>(k)])) continue;
      const bool held = geometry_.dofs.unknownOf[static_cast<std::size_t>(k)] == DofMap::kPrescribed;
      external += 0.5 * (held ? startForce[k] + endForce[k] : loadStart[k] + load[k]) * a.du[k];
    }
  }
  // The platens: where they went (the prescribed increments, and the rest fitted to their nodes'
  // increments, which move rigidly), what they put on the specimen (sum_k B_k^T (f_int - f_ext)
  // over their nodes, plus their force histories, which f_ext holds spread over the nodes) and the
  // work of their prescribed degrees of freedom (the rest is in the nodes' loads above).
  for (std::size_t p = 0; p < platens_.size(); ++p) {
    PlatenState& state = platens_[p];
    const Platen& platen = scene.platens[p];
    Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
    Eigen::Vector3d fit = Eigen::Vector3d::Zero(), onSpecimen = Eigen::Vector3d::Zero(), atStart = Eigen::Vector3d::Zero();
    for (const std::int32_t node : state.nodes) {
      const Eigen::Matrix<double, 2, 3> b = rigidMap(scene.grid.nodePosition(node), state.reference);
      const Eigen::Index k = 2 * static_cast<Eigen::Index>(node);
      onSpecimen += b.transpose() * (t.internalForce.segment<2>(k) - a.external.segment<2>(k));
      if (a.startForce.size() > 0) atStart += b.transpose() * (a.startForce.segment<2>(k) - a.externalStart.segment<2>(k));
      if (!geometry_.reached[static_cast<std::size_t>(k)]) continue;
      sum += b.transpose() * b;
      fit += b.transpose() * a.du.segment<2>(k);
    }
    const Eigen::Vector3d rigid = solveRigid(sum, fit);
    for (int d = 0; d < 3; ++d) {
      const PlatenDof& dof = platen.dof[static_cast<std::size_t>(d)];
      const bool prescribed = a.platenPrescribed[p][static_cast<std::size_t>(d)];
      const double increment = prescribed ? a.platenIncrement[p][d] + a.dLambda * a.platenDirection[p][d] : rigid[d];
      if (dof.drive == PlatenDrive::Force) {
        onSpecimen[d] += dof.history(time_ + dt);
        atStart[d] += dof.history(time_);
      }
      if (prescribed) external += 0.5 * (atStart[d] + onSpecimen[d]) * increment;
      state.displacement[d] += increment;
    }
    state.force = onSpecimen;
  }
  totals_.externalWork += external;
  internalWork_ += internal;
  totals_.released += a.releases();
  if (a.dTau != 0.0) lastIncrement_ = a.du, lastLoadFactorIncrement_ = a.dLambda, lastOpening_ = a.dTau;
  lambda_ += a.dLambda;
  time_ += dt;
  ++steps_;
}

ImplicitStepReport ImplicitSolver::advance(const IndirectControl* control, double largest, double remaining) {
  ImplicitStepReport total;
  double& nextPiece = control ? nextOpening_ : nextPiece_;  // of pseudo-time, or of opening (mm)
  const double smallest = std::abs(largest) * std::ldexp(1.0, -settings_.maxHalvings);  // of the adaptive piece
  double piece = nextPiece > 0.0 ? std::clamp(nextPiece, smallest, std::abs(largest)) : std::abs(largest);
  piece = std::copysign(std::min(piece, std::abs(remaining)), largest);
  // The last piece before `remaining` ends takes what is left when that is at most 1.5 pieces.
  if (std::abs(remaining) <= 1.5 * std::abs(piece)) piece = remaining;
  // Attempts: the piece with the kept factorisation, then (if Newton did not converge) the same
  // piece factorising at every iteration, then halves of it, the last with 4 times the iterations.
  // A material snap-back under release: the band fails onto its stable branch wherever the piece's
  // converged state puts it past its limit, as in explicit runs, with no halving first. Under stop it
  // gets one halving and, if it persists, ends the run (docs/implicit.md, "Load steps").
  const bool release = setup_.scene.solver.snapBack == SnapBackPolicy::Release;
  bool retried = false;
  int snapBackCuts = 0;  // halvings because a point snapped back (stop): after the first, it persists
  int pathRedos = 0;     // tries of the same piece after its converged state grew the crack paths
  for (int cuts = 0;; ++cuts) {
    Attempt a;
    const bool finest = cuts >= settings_.maxHalvings;
    a.reuseRatio = cuts > 0 || retried ? 0.0 : settings_.reuseRatio;
    a.maxIterations = finest ? 4 * settings_.maxIterations : settings_.maxIterations;
    a.lastResort = finest;
    a.snapBack = release ? SnapBackPolicy::Release : SnapBackPolicy::Stop;
    a.keepReleases = finest && release;
    bool ok = control ? attemptIndirect(*control, piece, a) : attempt(piece, a);
    // A piece whose Newton (proper) stalls below the acceptance tolerance is kept: its residual
    // is carried into the next step's equilibrium (docs/implicit.md, "Load steps").
    bool relaxed = false;
    if (!ok && a.stalled && a.reuseRatio == 0.0 && a.failedResidual <= settings_.acceptTolerance) ok = relaxed = true;
    // A piece that carries a point far past its onset is cut (docs/implicit.md, "Load steps").
    if (ok && !finest && a.trial.onsetOvershoot > settings_.onsetOvershoot)
      ok = a.fail(a.report.iterations, a.report.residual, NewtonFailure::OnsetOvershoot,
                  "a point passed its onset by " + std::to_string(a.trial.onsetOvershoot) + " of its strength");
    total.totalIterations += a.report.totalIterations;
    total.factorizations += a.report.factorizations;
    total.krylovIterations += a.report.krylovIterations;
    total.linearSolveSeconds += a.report.linearSolveSeconds;
    // Tracked crack paths: the converged state grows them (its new bands move the tips, its held
    // points start cracks); where that puts held points on a path, the piece is solved again with
    // the grown paths, so that a crack runs on within the step (docs/model.md, "Crack paths").
    if (ok && crackPaths_.tracked() && growCrackPaths(a.trial) > 0 && pathRedos < kMaxPathRedos) {
      ++pathRedos;
      --cuts;
      continue;
    }
    if (ok) {
      commit(a, control ? 0.0 : piece);
      checkBalance();
      total.size = piece;
      total.cuts = cuts;
      total.iterations = a.report.iterations;
      total.residual = relaxed ? a.failedResidual : a.report.residual;
      total.relaxed = relaxed ? 1 : 0;
      total.released = a.releases();
      total.onsetOvershoot = a.trial.onsetOvershoot;
      // The next piece: longer after an easy step, shorter after a hard one.
      double grow = a.report.iterations <= settings_.easyIterations ? 2.0
                    : a.report.iterations >= settings_.hardIterations ? 0.5 : 1.0;
      if (a.trial.onsetOvershoot > 0.0)  // aim at 0.6 of the overshoot limit
        grow = std::min(grow, std::max(0.5, 0.6 * settings_.onsetOvershoot / a.trial.onsetOvershoot));
      nextPiece = std::abs(piece) * grow;
      return total;
    }
    if (!finest && !retried && cuts == 0 && a.reuseRatio > 0.0 && a.reason == NewtonFailure::NotConverged) {
      retried = true;  // the same piece with Newton proper
      --cuts;
      continue;
    }
    if (a.failedStatus == UpdateStatus::SnapBack) ++snapBackCuts;
    const bool persistingSnapBack = !release && snapBackCuts > 1 && a.failedStatus == UpdateStatus::SnapBack;
    if (!finest && !persistingSnapBack) {
      // The overshoot grows about linearly with the piece: cut to where it would meet the limit.
      const double overshootCut = a.trial.onsetOvershoot > settings_.onsetOvershoot && a.reason == NewtonFailure::OnsetOvershoot
                                      ? std::max(0.1, 0.8 * settings_.onsetOvershoot / a.trial.onsetOvershoot)
                                      : 0.5;
      piece *= std::min(0.5, overshootCut);
      continue;
    }
    std::ostringstream msg;
    msg << "implicit step " << steps_ + 1 << " (t = " << time_ << " s, load factor " << lambda_ << ", a piece of "
        << piece << " after " << cuts << " halvings): "
        << (persistingSnapBack ? "a material snap-back persists after a halving: " : "") << a.why << " at Newton iteration " << a.failedIteration
        << ", relative residual " << a.failedResidual;
    Vec2 where = Vec2::Zero();
    if (a.failedParticle != SIZE_MAX) {
      where = particles_.position[a.failedParticle];
      msg << "; particle " << a.failedParticle << " at (" << where[0] << ", " << where[1] << ") mm";
    }
    // Under displacement control a cracked structure whose Newton fails on the smallest piece has
    // most likely passed a limit point: past a structural snap-back no state of the structure
    // has the prescribed displacement on the softening branch (docs/implicit.md).
    const bool cracked = std::any_of(particles_.band.begin(), particles_.band.end(), [](std::int32_t b) { return b >= 0; }) ||
                         std::any_of(a.trial.band.begin(), a.trial.band.end(), [](const auto& b) { return b.has_value(); });
    if (!control && cracked && (a.reason == NewtonFailure::NotConverged || a.reason == NewtonFailure::Singular))
      msg << ". The structure has most likely passed a limit point (a structural snap-back: past its peak the load and "
             "the displacement fall together), which displacement control cannot follow; indirect control "
             "(solver: {control: {indirect: ...}}, docs/implicit.md) traces it";
    throw SimulationError(a.reason == NewtonFailure::LeftGrid ? FailureKind::LeftGrid : FailureKind::MaterialFailure,
                          steps_ + 1, a.failedParticle == SIZE_MAX ? 0 : a.failedParticle, where, msg.str(),
                          a.failedStatus, a.failedResidual);
  }
}

std::size_t ImplicitSolver::growCrackPaths(const Trial& t) {
  std::vector<Vec2> opened;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    if (t.band[i] && particles_.band[i] < 0) opened.push_back(particles_.position[i]);
  if (opened.empty() && t.held.empty()) return 0;
  return crackPaths_.grow(opened, t.held, intactStressAverage(setup_.materials, particles_, &t.stress));
}

void ImplicitSolver::checkBalance() const {
  const double scale = std::max({std::abs(totals_.externalWork), std::abs(internalWork_), 1e-9});
  const double gap = std::abs(totals_.externalWork - internalWork_);
  if (gap <= kBalanceTolerance * scale) return;
  std::ostringstream msg;
  msg << "implicit step " << steps_ << " (t = " << time_ << " s, load factor " << lambda_ << "): the external work "
      << totals_.externalWork << " N mm and the internal work " << internalWork_ << " N mm differ by " << gap / scale
      << " of the work (allowed " << kBalanceTolerance << "): the steps are not in equilibrium";
  throw SimulationError(FailureKind::MaterialFailure, steps_, 0, Vec2::Zero(), msg.str(), UpdateStatus::Converged, gap / scale);
}

ImplicitStepReport ImplicitSolver::advance(double largest, double remaining) { return advance(nullptr, largest, remaining); }

ImplicitStepReport ImplicitSolver::advance(const IndirectControl& control, double largest, double remaining) {
  return advance(&control, largest, remaining);
}

// A whole step of `size` in adaptive pieces: the reports summed.
ImplicitStepReport ImplicitSolver::stepInPieces(const IndirectControl* control, double size) {
  ImplicitStepReport total;
  double done = 0.0;
  while (std::abs(done) < std::abs(size) * (1.0 - 1e-12)) {
    const ImplicitStepReport r = advance(control, size, size - done);
    done += r.size;
    total.size += r.size;
    total.iterations = std::max(total.iterations, r.iterations);
    total.totalIterations += r.totalIterations;
    total.factorizations += r.factorizations;
    total.krylovIterations += r.krylovIterations;
    total.cuts += r.cuts;
    total.residual = std::max(total.residual, r.residual);
    total.released += r.released;
    total.relaxed += r.relaxed;
    total.linearSolveSeconds += r.linearSolveSeconds;
    total.onsetOvershoot = std::max(total.onsetOvershoot, r.onsetOvershoot);
  }
  return total;
}

ImplicitStepReport ImplicitSolver::step(double dt) { return stepInPieces(nullptr, dt); }

ImplicitStepReport ImplicitSolver::step(const IndirectControl& control, double dTau) { return stepInPieces(&control, dTau); }

}  // namespace ecm::mpm
