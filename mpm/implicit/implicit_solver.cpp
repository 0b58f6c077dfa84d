// The implicit solver's state (mpm/implicit/implicit_solver.hpp): construction, energies, what a
// checkpoint keeps, the crack paths' growth and the work balance.
#include "mpm/implicit/implicit_solver.hpp"

#include "mpm/setup/damping_limit.hpp"
#include "mpm/setup/stress_direction.hpp"

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
#include "mpm/setup/seeding.hpp"
#include "mpm/setup/step_setup.hpp"

namespace ecm::mpm {

ImplicitSolver::ImplicitSolver(Scene scene, int threads)
    : settings_(scene.solver.implicit.value_or(ImplicitSettings{})),
      factors_(settings_.linearSolver, settings_.krylovTolerance, settings_.krylovIterations) {
  Particles seeded = seedParticles(scene);
  setup_ = makeStepSetup(std::move(scene), seeded.size(), threads, 4096);
  particles_ = std::move(seeded);
  conditions_ = conditionStates(setup_.scene);
  loads_ = loadStates(setup_.scene, particles_);
  platens_ = platenStates(setup_.scene);
  crackPaths_ = crackPathsFor(setup_.scene, particles_);
  for (Vec2& v : particles_.velocity) v.setZero();  // quasi-static: no initial velocities
  factors_.setThreads(setup_.threads);
}

Energies ImplicitSolver::energies() const {
  double strain = 0.0;
  for (std::size_t i = 0; i < particles_.size(); ++i) strain += 0.5 * particles_.volume[i] * particles_.stress[i].dot(particles_.strain[i]);
  return {0.0, strain, totals_.externalWork, totals_.dissipated, totals_.damping};  // damping: the stabilised steps' dashpots
}

ImplicitSolver::SavedState ImplicitSolver::saved() const {
  SavedState s;
  s.time = time_, s.loadFactor = lambda_, s.nextPiece = nextPiece_, s.nextOpening = nextOpening_, s.steps = steps_;
  s.externalWork = totals_.externalWork, s.internalWork = internalWork_, s.dissipated = totals_.dissipated;
  s.released = totals_.released;
  s.dashpotWork = totals_.damping;
  for (const ConditionState& c : conditions_) {
    s.reactions.push_back(c.reaction);
    s.conditionDisplacements.push_back(c.displacement);
  }
  for (const Stencil& st : geometry_.stencils) s.stencilBases.push_back(st.base);
  s.prescribed = geometry_.prescribed;
  if (factors_.isOf(factorKey())) {
    s.factored = factors_.matrix();
    s.factoredReduced = factors_.reduced();
    if (s.factoredReduced) s.platenLayout = platenLayout_, s.tieLayout = tieLayout_;
  }
  s.lastIncrement = lastIncrement_.du, s.lastLoadFactorIncrement = lastIncrement_.loadFactor, s.lastOpening = lastIncrement_.opening;
  return s;
}

void ImplicitSolver::restore(const SavedState& s) {
  if (s.reactions.size() != conditions_.size() || s.conditionDisplacements.size() != conditions_.size())
    throw std::invalid_argument("it has " + std::to_string(s.reactions.size()) + " conditions, the scene " +
                                std::to_string(conditions_.size()));
  if (s.lastIncrement.size() != 0 && s.lastIncrement.size() != 2 * static_cast<Eigen::Index>(setup_.scene.grid.nodeCount()))
    throw std::invalid_argument("its last increment does not fit the scene's grid");
  time_ = s.time, lambda_ = s.loadFactor, nextPiece_ = s.nextPiece, nextOpening_ = s.nextOpening, steps_ = s.steps;
  lastIncrement_ = {s.lastIncrement, s.lastLoadFactorIncrement, s.lastOpening};
  totals_.externalWork = s.externalWork, internalWork_ = s.internalWork, totals_.dissipated = s.dissipated;
  totals_.released = s.released;
  totals_.damping = s.dashpotWork;
  for (std::size_t c = 0; c < conditions_.size(); ++c) {
    conditions_[c].reaction = s.reactions[c];
    conditions_[c].displacement = s.conditionDisplacements[c];
  }
  // The geometry the next step compares its stencils with, and the factorisation on it: the
  // next step then keeps or rebuilds the pattern, and reuses or renews K, as the saved run would.
  geometry_ = StepGeometry{};
  geometryStep_ = -1;
  factors_.forget();
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
  if (!factors_.restore(k, s.factoredReduced, factorKey(), geometry_.dofs, reduction ? &*reduction : nullptr))
    throw std::invalid_argument("its factorised tangent is singular");
}

Eigen::SparseMatrix<double> ImplicitSolver::tangentAtStart(double dt, std::vector<int>* components) {
  Attempt a;
  if (!prepare(dt, nullptr, a)) return {};
  if (components) *components = unknownComponents(geometry_.dofs, a.unknownReduction());
  evaluateTrial(setup_, particles_, geometry_, Eigen::VectorXd::Zero(a.du.size()), true, a.snapBack, a.trial);
  return a.trial.tangent;
}

std::size_t ImplicitSolver::growCrackPaths(const Trial& t) {
  std::vector<Vec2> opened;
  for (std::size_t i = 0; i < particles_.size(); ++i)
    if (t.band[i] && particles_.band[i] < 0) opened.push_back(particles_.position[i]);
  crackPaths_.noteHeld(t.held);
  if (opened.empty() && t.held.empty()) return 0;
  return crackPaths_.grow(opened, t.held, intactStressAverage(setup_.materials, particles_, &t.stress));
}

void ImplicitSolver::checkBalance() const {
  if (dampingOutrunsInput(totals_, 0.0)) {  // a stabilised step's dashpots (mpm/setup/damping_limit.hpp)
    std::ostringstream msg;
    msg << "implicit step " << steps_ << " (t = " << time_ << " s, load factor " << lambda_ << "): the energy the stabilised "
        << "steps' dashpots took, " << totals_.damping << " N mm, is beyond the energy put into the run, " << totals_.externalWork
        << " N mm: the stabilised step did not end at a state of lower energy";
    throw SimulationError(FailureKind::DampingWork, steps_, std::nullopt, Vec2::Zero(), msg.str(), UpdateStatus::Converged,
                          totals_.damping / std::max(std::abs(totals_.externalWork), 1e-300));
  }
  const double scale = std::max({std::abs(totals_.externalWork), std::abs(internalWork_), 1e-9});
  const double gap = std::abs(totals_.externalWork - internalWork_);
  if (gap <= kBalanceTolerance * scale) return;
  std::ostringstream msg;
  msg << "implicit step " << steps_ << " (t = " << time_ << " s, load factor " << lambda_ << "): the external work "
      << totals_.externalWork << " N mm and the internal work " << internalWork_ << " N mm differ by " << gap / scale
      << " of the work (allowed " << kBalanceTolerance << "): the steps are not in equilibrium";
  throw SimulationError(FailureKind::WorkImbalance, steps_, std::nullopt, Vec2::Zero(), msg.str(), UpdateStatus::Converged, gap / scale);
}

}  // namespace ecm::mpm
