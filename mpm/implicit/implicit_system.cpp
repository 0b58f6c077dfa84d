// The implicit load step's equilibrium (mpm/implicit/implicit_system.hpp).
#include "mpm/implicit/implicit_system.hpp"

#include <omp.h>

#include <algorithm>
#include <cmath>

namespace ecm::mpm {

namespace {

// A particle's stencil as S x S nodes: node index, weight and gradient of each.
struct ElementNodes {
  int count = 0;
  std::int32_t node[9];
  double gx[9], gy[9];
};

ElementNodes elementNodes(const Stencil& s, int nx, int support) {
  ElementNodes e;
  for (int j = 0; j < support; ++j)
    for (int k = 0; k < support; ++k) {
      e.node[e.count] = s.base + j * nx + k;
      e.gx[e.count] = s.gx[k] * s.wy[j];  // grad N = (N_x' N_y, N_x N_y')
      e.gy[e.count] = s.wx[k] * s.gy[j];
      ++e.count;
    }
  return e;
}

// d eps = B du (engineering shear).
Voigt strainIncrement(const ElementNodes& e, const Eigen::VectorXd& du) {
  Voigt d = Voigt::Zero();
  for (int a = 0; a < e.count; ++a) {
    const double ux = du[2 * e.node[a]], uy = du[2 * e.node[a] + 1];
    d[0] += e.gx[a] * ux;
    d[1] += e.gy[a] * uy;
    d[2] += e.gy[a] * ux + e.gx[a] * uy;
  }
  return d;
}

// The 3 x 2 block of B for node a: columns x and y.
Eigen::Matrix<double, 3, 2> blockB(const ElementNodes& e, int a) {
  Eigen::Matrix<double, 3, 2> b;
  b << e.gx[a], 0.0, 0.0, e.gy[a], e.gy[a], e.gx[a];
  return b;
}

}  // namespace

namespace {

// Adds sign V B^T D B of one particle to K's values at its positions `at`.
void addElement(const ElementNodes& e, double volume, const Tangent& d, const std::int32_t* at, int local, double* values) {
  for (int a = 0; a < e.count; ++a) {
    const Eigen::Matrix<double, 2, 3> left = volume * blockB(e, a).transpose() * d;  // V B_a^T D
    for (int b = 0; b < e.count; ++b) {
      const Eigen::Matrix2d k = left * blockB(e, b);  // K = V B_a^T D B_b
      for (int r = 0; r < 2; ++r)
        for (int c = 0; c < 2; ++c)
          if (const std::int32_t pos = at[(2 * a + r) * local + 2 * b + c]; pos >= 0) values[pos] += k(r, c);
    }
  }
}

// The point's state carries no damage: its tangent is elastic until it cracks.
bool undamagedAt(const Particles& p, std::size_t i, const Material& m) {
  if (m.params().model == ModelKind::SmearedCrack) return false;  // its integrity decides: always per trial
  return p.band[i] < 0 && (p.secondBand.empty() || p.secondBand[i] < 0);
}

// Marks, per node component, the nodes of a stencil that carry the particle: a weight or a gradient
// that is not exactly zero (`all`: every node of the stencil, as when only its first node is known).
// A uGIMP particle whose domain ends on a cell edge reaches the next node with weight and gradient
// exactly 0: such a node carries nothing and must not become an unknown (its row of K is empty).
void markReached(const Stencil& s, int nx, int support, bool all, std::vector<std::uint8_t>& reached) {
  const ElementNodes e = elementNodes(s, nx, support);
  for (int a = 0; a < e.count; ++a) {
    const int j = a / support, k = a % support;
    if (all || s.wx[k] * s.wy[j] != 0.0 || e.gx[a] != 0.0 || e.gy[a] != 0.0)
      reached[2 * static_cast<std::size_t>(e.node[a])] = reached[2 * static_cast<std::size_t>(e.node[a]) + 1] = 1;
  }
}

std::vector<std::uint8_t> reachedComponents(const Grid& grid, int support, const std::vector<Stencil>& stencils, bool all) {
  std::vector<std::uint8_t> reached(static_cast<std::size_t>(2 * grid.nodeCount()), 0);
  for (const Stencil& s : stencils) markReached(s, grid.nodesX(), support, all, reached);
  return reached;
}

// Numbers the unknowns (the reached node components in node order, the prescribed ones left out)
// and builds K's pattern and each particle's positions in it.
void buildPattern(const Grid& grid, int support, std::size_t particles, const std::vector<std::uint8_t>& prescribed,
                  std::vector<std::uint8_t> reached, StepGeometry& g) {
  const int nx = grid.nodesX();
  const auto components = static_cast<std::size_t>(2 * grid.nodeCount());
  g.dofs.unknownOf.assign(components, DofMap::kInactive);
  g.dofs.component.clear();
  for (std::size_t c = 0; c < components; ++c) {
    if (!reached[c]) continue;
    if (prescribed[c]) {
      g.dofs.unknownOf[c] = DofMap::kPrescribed;
      continue;
    }
    g.dofs.unknownOf[c] = static_cast<std::int32_t>(g.dofs.component.size());
    g.dofs.component.push_back(static_cast<std::int32_t>(c));
  }
  const int local = 2 * g.stencilNodes;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(particles * static_cast<std::size_t>(local * local));
  const auto unknownAt = [&](const ElementNodes& e, int l) { return g.dofs.unknownOf[2 * static_cast<std::size_t>(e.node[l / 2]) + static_cast<std::size_t>(l % 2)]; };
  for (const Stencil& s : g.stencils) {
    const ElementNodes e = elementNodes(s, nx, support);
    for (int r = 0; r < local; ++r)
      for (int c = 0; c < local; ++c)
        if (unknownAt(e, r) >= 0 && unknownAt(e, c) >= 0) triplets.emplace_back(unknownAt(e, r), unknownAt(e, c), 0.0);
  }
  const int n = g.dofs.unknowns();
  g.pattern.resize(n, n);
  g.pattern.setFromTriplets(triplets.begin(), triplets.end());
  g.pattern.makeCompressed();
  g.entryOf.assign(particles * static_cast<std::size_t>(local * local), -1);
  const int* outer = g.pattern.outerIndexPtr();
  const int* inner = g.pattern.innerIndexPtr();
  for (std::size_t i = 0; i < particles; ++i) {
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    for (int r = 0; r < local; ++r)
      for (int c = 0; c < local; ++c) {
        const int row = unknownAt(e, r), col = unknownAt(e, c);
        if (row < 0 || col < 0) continue;
        const int* at = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
        g.entryOf[i * static_cast<std::size_t>(local * local) + static_cast<std::size_t>(r * local + c)] = static_cast<std::int32_t>(at - inner);
      }
  }
  g.prescribed = prescribed;
  g.reached = std::move(reached);
  ++g.patternBuilds;
}

}  // namespace

bool stepGeometry(const StepSetup& setup, const Particles& p, const std::vector<std::uint8_t>& prescribed,
                  StepGeometry& g, std::size_t& outside) {
  const Grid& grid = setup.scene.grid;
  const ShapeFunction f = setup.scene.solver.shapeFunction;
  const int support = supportSize(f), nx = grid.nodesX();
  // The pattern is kept when every stencil starts at the same node as before and reaches the same nodes.
  bool samePattern = g.stencils.size() == p.size() && g.stencilNodes == support * support && g.prescribed == prescribed;
  g.stencilNodes = support * support;
  g.stencils.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const std::int32_t before = g.stencils[i].base;
    if (!computeStencil(f, grid, setup.halfWidth, p.position[i], g.stencils[i])) {
      outside = i;
      g.stencils.clear();  // no pattern to keep
      return false;
    }
    samePattern = samePattern && g.stencils[i].base == before;
  }
  std::vector<std::uint8_t> reached = reachedComponents(grid, support, g.stencils, false);
  samePattern = samePattern && reached == g.reached;
  if (!samePattern) buildPattern(grid, support, p.size(), prescribed, std::move(reached), g);
  // Each node's share of the body, in cells.
  g.share.assign(static_cast<std::size_t>(grid.nodeCount()), 0.0);
  const double cell = grid.cellArea() * setup.scene.thickness;
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Stencil& s = g.stencils[i];
    for (int j = 0; j < support; ++j)
      for (int k = 0; k < support; ++k)
        g.share[static_cast<std::size_t>(s.base + j * nx + k)] += s.wx[k] * s.wy[j] * p.volume[i] / cell;
  }
  // K's elastic part, over the points undamaged at the step's start.
  const int local = 2 * g.stencilNodes;
  g.undamaged.resize(p.size());
  g.elasticValues.setZero(g.pattern.nonZeros());
  for (std::size_t i = 0; i < p.size(); ++i) {
    const Material& m = setup.materials[p.material[i]];
    g.undamaged[i] = undamagedAt(p, i, m) ? 1 : 0;
    if (g.undamaged[i])
      addElement(elementNodes(g.stencils[i], nx, support), p.volume[i], m.stiffness(),
                 g.entryOf.data() + i * static_cast<std::size_t>(local * local), local, g.elasticValues.data());
  }
  return true;
}

std::vector<std::uint8_t> reachedNodes(const StepSetup& setup, const Particles& particles) {
  const Grid& grid = setup.scene.grid;
  const ShapeFunction f = setup.scene.solver.shapeFunction;
  const int support = supportSize(f);
  std::vector<std::uint8_t> components(static_cast<std::size_t>(2 * grid.nodeCount()), 0);
  Stencil s;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (computeStencil(f, grid, setup.halfWidth, particles.position[i], s)) markReached(s, grid.nodesX(), support, false, components);
  std::vector<std::uint8_t> nodes(static_cast<std::size_t>(grid.nodeCount()));
  for (std::size_t n = 0; n < nodes.size(); ++n) nodes[n] = components[2 * n];
  return nodes;
}

bool restoreGeometry(const StepSetup& setup, std::size_t particles, const std::vector<std::uint8_t>& prescribed,
                     const std::vector<std::int32_t>& bases, StepGeometry& g) {
  const Grid& grid = setup.scene.grid;
  const int support = supportSize(setup.scene.solver.shapeFunction);
  g = StepGeometry{};
  g.stencilNodes = support * support;
  g.stencils.resize(particles);
  for (std::size_t i = 0; i < particles; ++i) {
    const int ix = bases[i] % grid.nodesX(), iy = bases[i] / grid.nodesX();
    if (bases[i] < 0 || ix + support > grid.nodesX() || iy + support > grid.nodesY()) return false;
    g.stencils[i].base = bases[i];
  }
  buildPattern(grid, support, particles, prescribed, reachedComponents(grid, support, g.stencils, true), g);
  g.undamaged.assign(particles, 0);
  g.elasticValues.setZero(g.pattern.nonZeros());
  return true;
}

void evaluateTrial(const StepSetup& setup, const Particles& p, const StepGeometry& g, const Eigen::VectorXd& du,
                   bool withTangent, SnapBackPolicy snapBack, Trial& t, const Eigen::VectorXd* direction,
                   const std::vector<std::uint8_t>* secant, const ReleasedStarts* kept, const Dashpots& dashpots) {
  const std::size_t count = p.size();
  const int nx = setup.scene.grid.nodesX(), support = supportSize(setup.scene.solver.shapeFunction);
  t.strain.resize(count);
  t.stress.resize(count);
  t.band.assign(count, std::nullopt);
  t.secondBand.assign(count, std::nullopt);
  t.dissipation.assign(count, 0.0);
  t.tangents.resize(count);
  const double stabilization = dashpots.alpha;
  if (stabilization > 0.0) t.dashpot.assign(count, Voigt::Zero());
  else t.dashpot.clear();
  t.elastic.assign(count, 0);
  t.integrity = p.integrity;
  t.failed = SIZE_MAX;
  t.tangent.resize(0, 0);
  t.releases.clear();
  t.held.clear();
  const CrackPaths* paths = g.crackPaths && g.crackPaths->tracked() ? g.crackPaths : nullptr;
  std::vector<std::uint8_t> held(paths ? count : 0, 0);
  UpdateOptions options(snapBack, true);
  options.substepLevels = setup.scene.solver.substepLevels;
  long released = 0;
  double overshoot = 0.0;
  std::size_t failed = SIZE_MAX;
  UpdateResult failure;
  // The updates: independent per point, in parallel.
#pragma omp parallel for num_threads(setup.threads) schedule(dynamic, 256) reduction(+ : released) reduction(max : overshoot)
  for (std::size_t i = 0; i < count; ++i) {
    const Material& m = setup.materials[p.material[i]];
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    // A point released earlier in the attempt goes on from its released state.
    const ReleasedStart* start = kept && !kept->of.empty() && kept->of[i] >= 0 ? &kept->starts[static_cast<std::size_t>(kept->of[i])] : nullptr;
    const Voigt total = strainIncrement(e, du);
    const Voigt d = start ? Voigt(total - start->increment) : total;
    Voigt strain = start ? start->strain : p.strain[i];
    const std::int32_t b1 = p.band[i], b2 = p.secondBand.empty() ? -1 : p.secondBand[i];
    if (!start && b1 < 0 && b2 < 0 && m.closedFormStress(d, false, strain, t.stress[i])) {
      t.strain[i] = strain;
      t.tangents[i] = m.stiffness();
      t.elastic[i] = 1;
      continue;
    }
    std::optional<BandState> band, second;
    if (start) {
      band = start->band;
      second = start->secondBand;
    } else {
      if (b1 >= 0) band = p.bands[static_cast<std::size_t>(b1)];
      if (b2 >= 0) second = p.secondBands[static_cast<std::size_t>(b2)];
    }
    // Tracked crack paths: an intact enriched point opens its band only on a path, with the path's
    // normal; elsewhere it stays intact (docs/model.md, "Crack paths").
    UpdateOptions pointOptions = options;
    Vec2 pathNormal;
    EffectiveSize pathSize = setup.size;
    if (paths && !band && !second && m.enriched()) {
      if (const std::optional<PathCrossing> n = paths->crossingAt(p.position[i])) {
        pathNormal = n->normal;
        pathSize = EffectiveSize::fixed(n->effectiveSize);
        pointOptions.onsetNormal = &pathNormal;
      } else {
        t.strain[i] = strain + d;
        t.stress[i] = m.intactStress(t.strain[i]);
        t.tangents[i] = m.stiffness();
        t.elastic[i] = g.undamaged[i];
        held[i] = 1;
        continue;
      }
    }
    OpenedBands opened;
    const UpdateResult r = m.update({strain, t.integrity.empty() ? nullptr : &t.integrity[i], band ? &*band : nullptr,
                                     second ? &*second : nullptr},
                                    d, pathSize, opened, pointOptions);
    if (!r.converged() || !r.stress.allFinite()) {
#pragma omp critical(ecm_implicit_failure)
      if (i < failed) {
        failed = i;
        failure = r;
      }
      continue;
    }
    if (opened.first && m.enriched()) {  // how far past onset the elastic trial stress goes
      const TwoPhasePoint& e2 = *m.enriched();
      // (a point a crack path reached while it was held past onset starts there: not the step's doing)
      const bool startedPast = paths && e2.intactDrivingForce(p.strain[i]) >= e2.bandLaw().onsetDrivingForce();
      if (!startedPast)
        overshoot = std::max(overshoot, std::sqrt(e2.intactDrivingForce(p.strain[i] + d) / e2.bandLaw().onsetDrivingForce()) - 1.0);
    }
    if (opened.first) band = opened.first;
    if (opened.second) second = opened.second;
    t.strain[i] = strain;
    t.stress[i] = r.stress;
    t.band[i] = band;
    t.secondBand[i] = second;
    t.dissipation[i] = r.dissipation + (start ? start->dissipation : 0.0);
    released += r.released ? 1 : 0;
    if (kept && r.released && band) {  // (an enriched point: its bands hold its state)
#pragma omp critical(ecm_implicit_releases)
      t.releases.emplace_back(i, ReleasedStart{total, strain, band, second, t.dissipation[i]});
    }
    t.tangents[i] = secant && (*secant)[i] && band && !second && m.enriched() ? m.enriched()->secantTangent(*band) : r.tangent;
    t.elastic[i] = g.undamaged[i] && !band && !second && r.tangent == m.stiffness() ? 1 : 0;
    const bool cracked = band || second || (!t.integrity.empty() && t.integrity[i] < 1.0);
    if (stabilization > 0.0 && cracked) {  // the dashpot in parallel (docs/implicit.md, "Stabilised steps")
      const Voigt stretch = dashpots.from ? Voigt(total - strainIncrement(e, *dashpots.from)) : total;
      t.dashpot[i] = stabilization * (m.stiffness() * stretch);
      t.tangents[i] += stabilization * m.stiffness();
      t.elastic[i] = 0;
    }
  }
  t.released = released;
  std::sort(t.releases.begin(), t.releases.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t i = 0; i < held.size(); ++i) {  // the held points past onset, in particle order
    if (!held[i]) continue;
    const TwoPhasePoint& e = *setup.materials[p.material[i]].enriched();
    const double y = e.intactDrivingForce(t.strain[i]);
    if (y >= e.bandLaw().onsetDrivingForce()) {
      const double overstress = std::sqrt(y / e.bandLaw().onsetDrivingForce());
      t.held.push_back({i, p.position[i], overstress, t.stress[i] / overstress});
    }
  }
  t.onsetOvershoot = overshoot;
  t.failed = failed;
  t.failure = failure;
  if (failed != SIZE_MAX) return;
  // The sums, particle by particle in index order.
  t.internalForce.setZero(2 * setup.scene.grid.nodeCount());
  if (direction) t.tangentTimesDirection.setZero(2 * setup.scene.grid.nodeCount());
  for (std::size_t i = 0; i < count; ++i) {
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    const double v = p.volume[i];
    const Voigt s = t.dashpot.empty() ? t.stress[i] : Voigt(t.stress[i] + t.dashpot[i]);
    for (int a = 0; a < e.count; ++a) {  // f_int = V B^T sigma
      t.internalForce[2 * e.node[a]] += v * (e.gx[a] * s[0] + e.gy[a] * s[2]);
      t.internalForce[2 * e.node[a] + 1] += v * (e.gy[a] * s[1] + e.gx[a] * s[2]);
    }
    if (direction) {  // V B^T D (B direction)
      const Voigt s2 = v * (t.tangents[i] * strainIncrement(e, *direction));
      for (int a = 0; a < e.count; ++a) {
        t.tangentTimesDirection[2 * e.node[a]] += e.gx[a] * s2[0] + e.gy[a] * s2[2];
        t.tangentTimesDirection[2 * e.node[a] + 1] += e.gy[a] * s2[1] + e.gx[a] * s2[2];
      }
    }
  }
  if (withTangent) assembleTangent(setup, p, g, t);
}

void keepReleases(const Trial& trial, std::size_t particles, ReleasedStarts& kept) {
  if (trial.releases.empty()) return;
  if (kept.of.empty()) kept.of.assign(particles, -1);
  for (const auto& [i, start] : trial.releases) {
    if (kept.of[i] < 0) {
      kept.of[i] = static_cast<std::int32_t>(kept.starts.size());
      kept.starts.push_back(start);
    } else {
      kept.starts[static_cast<std::size_t>(kept.of[i])] = start;
    }
  }
}

void assembleTangent(const StepSetup& setup, const Particles& p, const StepGeometry& g, Trial& t) {
  const int nx = setup.scene.grid.nodesX(), support = supportSize(setup.scene.solver.shapeFunction);
  const int local = 2 * g.stencilNodes;
  t.tangent = g.pattern;
  double* values = t.tangent.valuePtr();
  std::copy(g.elasticValues.data(), g.elasticValues.data() + g.elasticValues.size(), values);
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (t.elastic[i]) continue;
    const Material& m = setup.materials[p.material[i]];
    // An undamaged point is in the elastic part already: add what its trial changes.
    const Tangent d = g.undamaged[i] ? Tangent(t.tangents[i] - m.stiffness()) : t.tangents[i];
    addElement(elementNodes(g.stencils[i], nx, support), p.volume[i], d, g.entryOf.data() + i * static_cast<std::size_t>(local * local), local,
               values);
  }
}

}  // namespace ecm::mpm
