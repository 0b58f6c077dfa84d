// The setup of a seeded scene and its conditions' and loads' members (mpm/setup/step_setup.hpp).
#include "mpm/setup/step_setup.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecm::mpm {

namespace {

// The grid nodes inside a box (with a tolerance of 1e-9 cells against round-off at its edges).
std::vector<std::int32_t> nodesIn(const Grid& g, const Box& box) {
  const double tol = 1e-9 * std::min(g.cellSize[0], g.cellSize[1]);
  std::vector<std::int32_t> nodes;
  for (int n = 0; n < g.nodeCount(); ++n)
    if (box.contains(g.nodePosition(n), tol)) nodes.push_back(n);
  return nodes;
}

}  // namespace

StepSetup makeStepSetup(Scene scene, std::size_t particles, int threads, std::size_t particlesPerThread) {
  StepSetup s;
  s.threads = threads > 0 ? threads
                          : static_cast<int>(std::clamp<std::size_t>(particles / particlesPerThread, 1,
                                                                     static_cast<std::size_t>(omp_get_max_threads())));
  const Grid& g = scene.grid;
  s.invCell = Vec2(1.0 / g.cellSize[0], 1.0 / g.cellSize[1]);
  s.halfWidth = Vec2::Constant(0.5 / scene.particlesPerCell);  // uGIMP half-size in cell units
  s.size = {scene.solver.effectiveSize, 0.0, g.cellSize[0], g.cellSize[1]};
  s.materials.reserve(scene.materials.size());
  double lightest = INFINITY;
  for (const auto& m : scene.materials) {
    s.materials.emplace_back(m);
    lightest = std::min(lightest, m.density);
  }
  s.fullNodeMass = scene.materials.empty() ? 0.0 : lightest * g.cellSize[0] * g.cellSize[1] * scene.thickness;
  s.constrained.assign(static_cast<std::size_t>(g.nodeCount()), 0);
  for (const auto& c : scene.conditions) {
    const bool x = c.field || c.component[0].kind != Prescribed::Free, y = c.field || c.component[1].kind != Prescribed::Free;
    for (const auto n : nodesIn(g, c.box)) s.constrained[static_cast<std::size_t>(n)] |= static_cast<std::uint8_t>((x ? 1 : 0) | (y ? 2 : 0));
  }
  for (const auto& platen : scene.platens)  // a platen's nodes move with it: no damping of their own
    for (const auto& box : platen.boxes)
      for (const auto n : nodesIn(g, box)) s.constrained[static_cast<std::size_t>(n)] = 3;
  s.scene = std::move(scene);
  return s;
}

std::vector<ConditionState> conditionStates(const Scene& scene) {
  const Grid& g = scene.grid;
  std::vector<ConditionState> conditions;
  for (const auto& c : scene.conditions) {
    ConditionState s;
    s.nodes = nodesIn(g, c.box);
    if (s.nodes.empty()) throw std::invalid_argument("condition '" + c.name + "': its box contains no grid node");
    conditions.push_back(std::move(s));
  }
  return conditions;
}

std::vector<LoadState> loadStates(const Scene& scene, const Particles& particles) {
  const Grid& g = scene.grid;
  std::vector<LoadState> loads;
  const double tol = 1e-9 * std::min(g.cellSize[0], g.cellSize[1]);
  for (const auto& l : scene.loads) {
    LoadState s;
    if (l.target == LoadTarget::Nodes) {
      s.members = nodesIn(g, l.box);
    } else {
      for (std::size_t p = 0; p < particles.size(); ++p)
        if (l.box.contains(particles.position[p], tol)) s.members.push_back(static_cast<std::int32_t>(p));
    }
    if (s.members.empty())
      throw std::invalid_argument("load '" + l.name + "': its box contains no " +
                                  (l.target == LoadTarget::Nodes ? "grid node" : "particle"));
    loads.push_back(std::move(s));
  }
  return loads;
}

std::vector<PlatenState> platenStates(const Scene& scene) {
  const Grid& g = scene.grid;
  std::vector<std::uint8_t> taken(static_cast<std::size_t>(g.nodeCount()), 0);  // 1: a condition's, 2 + i: platen i's
  for (const auto& c : scene.conditions)
    for (const auto n : nodesIn(g, c.box)) taken[static_cast<std::size_t>(n)] = 1;
  std::vector<PlatenState> platens;
  for (std::size_t i = 0; i < scene.platens.size(); ++i) {
    const Platen& p = scene.platens[i];
    PlatenState s;
    for (const Box& box : p.boxes) {
      const std::vector<std::int32_t> in = nodesIn(g, box);
      s.nodes.insert(s.nodes.end(), in.begin(), in.end());
    }
    std::sort(s.nodes.begin(), s.nodes.end());
    s.nodes.erase(std::unique(s.nodes.begin(), s.nodes.end()), s.nodes.end());
    if (s.nodes.empty()) throw std::invalid_argument("platen '" + p.name + "': its boxes contain no grid node");
    for (const auto n : s.nodes) {
      std::uint8_t& t = taken[static_cast<std::size_t>(n)];
      if (t != 0) {
        const Vec2 x = g.nodePosition(n);
        throw std::invalid_argument("platen '" + p.name + "': its node at (" + std::to_string(x[0]) + ", " + std::to_string(x[1]) +
                                    ") mm also belongs to " +
                                    (t == 1 ? std::string("a condition") : "platen '" + scene.platens[t - 2].name + "'") +
                                    " (a node moves with one platen or condition)");
      }
      t = static_cast<std::uint8_t>(std::min<std::size_t>(2 + i, 255));
    }
    if (s.nodes.size() < 2 && p.dof[kPlatenRotation].drive != PlatenDrive::Held)
      throw std::invalid_argument("platen '" + p.name + "': its rotation is not held, but it has one node (a rotation needs two or more)");
    if (p.reference) {
      s.reference = *p.reference;
    } else {
      for (const auto n : s.nodes) s.reference += g.nodePosition(n);
      s.reference /= static_cast<double>(s.nodes.size());
    }
    platens.push_back(std::move(s));
  }
  return platens;
}

}  // namespace ecm::mpm
