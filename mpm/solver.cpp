#include "mpm/solver.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpm/ordered_sum.hpp"
#include "mpm/seeding.hpp"

namespace ecm::mpm {

Solver::Solver(Scene scene, int threads)
    : scene_(std::move(scene)), threads_(threads > 0 ? threads : omp_get_max_threads()) {
  const Grid& g = scene_.grid;
  particles_ = seedParticles(scene_);
  if (threads <= 0)
    threads_ = static_cast<int>(std::clamp<std::size_t>(particles_.size() / kParticlesPerThread, 1,
                                                        static_cast<std::size_t>(threads_)));
  invCell_ = Vec2(1.0 / g.cellSize[0], 1.0 / g.cellSize[1]);
  halfWidth_ = Vec2::Constant(0.5 / scene_.particlesPerCell);  // uGIMP half-size in cell units
  size_ = {scene_.solver.effectiveSize, 0.0, g.cellSize[0], g.cellSize[1]};
  grid_.resize(g.nodeCount());
  scratch_.resize(static_cast<std::size_t>(threads_ - 1));
  for (auto& s : scratch_) s.resize(g.nodeCount());
  touched_.assign(scratch_.size(), {0, g.nodeCount()});

  materials_.reserve(scene_.materials.size());
  for (const auto& m : scene_.materials) materials_.emplace_back(m);

  // dt = cfl * min cell size / the largest P-wave speed sqrt(a_11 / rho) of the materials present.
  std::vector<bool> used(materials_.size(), false);
  for (const auto id : particles_.material) used[id] = true;
  double speed = 0.0;
  for (std::size_t i = 0; i < materials_.size(); ++i)
    if (used[i]) speed = std::max(speed, std::sqrt(pWaveModulus(scene_.materials[i].elastic) / scene_.materials[i].density));
  dt_ = scene_.solver.cfl * std::min(g.cellSize[0], g.cellSize[1]) / speed;

  constrained_.assign(static_cast<std::size_t>(g.nodeCount()), 0);
  const double tol = 1e-9 * std::min(g.cellSize[0], g.cellSize[1]);
  for (const auto& c : scene_.conditions) {
    ConditionState s;
    for (int n = 0; n < g.nodeCount(); ++n)
      if (c.box.contains(g.nodePosition(n), tol)) s.nodes.push_back(n);
    if (s.nodes.empty()) throw std::invalid_argument("condition '" + c.name + "': its box contains no grid node");
    const bool x = c.field || c.component[0].kind != Prescribed::Free, y = c.field || c.component[1].kind != Prescribed::Free;
    for (const auto n : s.nodes) constrained_[static_cast<std::size_t>(n)] |= static_cast<std::uint8_t>((x ? 1 : 0) | (y ? 2 : 0));
    conditions_.push_back(std::move(s));
  }
  for (const auto& l : scene_.loads) {
    LoadState s;
    if (l.target == LoadTarget::Nodes) {
      for (int n = 0; n < g.nodeCount(); ++n)
        if (l.box.contains(g.nodePosition(n), tol)) s.members.push_back(n);
    } else {
      for (std::size_t p = 0; p < particles_.size(); ++p)
        if (l.box.contains(particles_.position[p], tol)) s.members.push_back(static_cast<std::int32_t>(p));
    }
    if (s.members.empty())
      throw std::invalid_argument("load '" + l.name + "': its box contains no " +
                                  (l.target == LoadTarget::Nodes ? "grid node" : "particle"));
    loads_.push_back(std::move(s));
  }
}

Energies Solver::energies() const {
  const Particles& p = particles_;
  const Vec2 e = orderedSum(threads_, static_cast<long>(p.size()), Vec2(Vec2::Zero()), [&](long i) {
    const auto k = static_cast<std::size_t>(i);
    return Vec2(0.5 * p.mass[k] * p.velocity[k].squaredNorm(), 0.5 * p.volume[k] * p.stress[k].dot(p.strain[k]));
  });
  return {e[0], e[1], externalWork_, dissipated_, damping_};  // kinetic, strain
}

Solver::StepState Solver::stepState() const {
  StepState s{time_, dt_, step_, externalWork_, dissipated_, damping_, substepped_, released_, {}, {}, {}, deferred_};
  for (const auto& c : conditions_) {
    s.reactions.push_back(c.reaction);
    s.conditionDisplacements.push_back(c.displacement);
  }
  for (const auto& l : loads_) s.appliedLoads.push_back(l.applied);
  return s;
}

void Solver::restoreStepState(const StepState& s) {
  if (s.reactions.size() != conditions_.size() || s.conditionDisplacements.size() != conditions_.size() ||
      s.appliedLoads.size() != loads_.size())
    throw std::invalid_argument("the state has " + std::to_string(s.reactions.size()) + " conditions and " +
                                std::to_string(s.appliedLoads.size()) + " loads, the scene " +
                                std::to_string(conditions_.size()) + " and " + std::to_string(loads_.size()));
  time_ = s.time;
  dt_ = s.timeStep;
  step_ = s.step;
  externalWork_ = s.externalWork;
  dissipated_ = s.dissipated;
  damping_ = s.damping;
  substepped_ = s.substepped;
  released_ = s.released;
  for (std::size_t i = 0; i < conditions_.size(); ++i) {
    conditions_[i].reaction = s.reactions[i];
    conditions_[i].displacement = s.conditionDisplacements[i];
  }
  for (std::size_t i = 0; i < loads_.size(); ++i) loads_[i].applied = s.appliedLoads[i];
  if (!std::is_sorted(s.deferred.begin(), s.deferred.end()) ||
      (!s.deferred.empty() && s.deferred.back() >= particles_.size()))
    throw std::invalid_argument("the deferred particle list is not sorted or names a particle beyond " +
                                std::to_string(particles_.size()));
  deferred_ = s.deferred;
  rebuildGridNextStep();
}

double Solver::damage(std::size_t i) const {
  if (particles_.band[i] >= 0) return particles_.bands[static_cast<std::size_t>(particles_.band[i])].damage();
  if (!particles_.integrity.empty()) return 1.0 - particles_.integrity[i];
  return 0.0;
}

}  // namespace ecm::mpm
