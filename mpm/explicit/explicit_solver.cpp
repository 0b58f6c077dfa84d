#include "mpm/explicit/explicit_solver.hpp"

#include <algorithm>
#include <stdexcept>

#include "mpm/core/ordered_sum.hpp"
#include "mpm/setup/seeding.hpp"

namespace ecm::mpm {

ExplicitSolver::ExplicitSolver(Scene scene, int threads) {
  Particles particles = seedParticles(scene);
  setup_ = makeStepSetup(std::move(scene), particles.size(), threads, kParticlesPerThread);
  state_ = initialState(setup_, std::move(particles));
}

const char* toString(StepPhase p) {
  switch (p) {
    case StepPhase::P2G: return "p2g";
    case StepPhase::Grid: return "grid";
    case StepPhase::G2P: return "g2p";
    case StepPhase::Strain: return "strain";
    case StepPhase::Stress: return "stress";
    case StepPhase::Fused: return "fused_pass";
    case StepPhase::DeferredScatter: return "deferred_scatter";
    case StepPhase::Rebuild: return "rebuild";
  }
  return "?";
}

void ExplicitSolver::storeIntactStresses() const {
  if (!intactStressesUnstored_) return;
  storeStressesOfIntactPoints(setup_, const_cast<Particles&>(state_.particles));
  intactStressesUnstored_ = false;
}

Energies ExplicitSolver::energies() const {
  const Particles& p = particles();
  const Vec2 e = orderedSum(setup_.threads, static_cast<long>(p.size()), Vec2(Vec2::Zero()), [&](long i) {
    const auto k = static_cast<std::size_t>(i);
    return Vec2(0.5 * p.mass[k] * p.velocity[k].squaredNorm(), 0.5 * p.volume[k] * p.stress[k].dot(p.strain[k]));
  });
  const RunTotals& t = state_.totals;
  return {e[0], e[1], t.externalWork, t.dissipated, t.damping};  // kinetic, strain
}

ExplicitSolver::StepState ExplicitSolver::stepState() const {
  const Clock& c0 = state_.clock;
  const RunTotals& t = state_.totals;
  StepState s{c0.time, c0.dt, c0.step, t.externalWork, t.dissipated, t.damping, t.substepped, t.released, t.massScaled,
              {}, {}, {}, fused_.deferred};
  std::sort(s.deferred.begin(), s.deferred.end());  // a set: the rebuild orders it by the particles' bins
  for (const auto& c : state_.conditions) {
    s.reactions.push_back(c.reaction);
    s.conditionDisplacements.push_back(c.displacement);
  }
  for (const auto& l : state_.loads) s.appliedLoads.push_back(l.applied);
  return s;
}

void ExplicitSolver::restoreStepState(const StepState& s) {
  std::vector<ConditionState>& conditions = state_.conditions;
  std::vector<LoadState>& loads = state_.loads;
  if (s.reactions.size() != conditions.size() || s.conditionDisplacements.size() != conditions.size() ||
      s.appliedLoads.size() != loads.size())
    throw std::invalid_argument("the state has " + std::to_string(s.reactions.size()) + " conditions and " +
                                std::to_string(s.appliedLoads.size()) + " loads, the scene " +
                                std::to_string(conditions.size()) + " and " + std::to_string(loads.size()));
  state_.clock = {s.time, s.timeStep, s.step};
  state_.totals = {s.externalWork, s.dissipated, s.damping, s.substepped, s.released, s.massScaled};
  for (std::size_t i = 0; i < conditions.size(); ++i) {
    conditions[i].reaction = s.reactions[i];
    conditions[i].displacement = s.conditionDisplacements[i];
  }
  for (std::size_t i = 0; i < loads.size(); ++i) loads[i].applied = s.appliedLoads[i];
  if (!std::is_sorted(s.deferred.begin(), s.deferred.end()) ||
      (!s.deferred.empty() && s.deferred.back() >= state_.particles.size()))
    throw std::invalid_argument("the deferred particle list is not sorted or names a particle beyond " +
                                std::to_string(state_.particles.size()));
  fused_.deferred = s.deferred;
  rebuildGridNextStep();
}

double ExplicitSolver::damage(std::size_t i) const { return state_.particles.damage(i); }

}  // namespace ecm::mpm
