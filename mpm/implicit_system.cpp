// The implicit load step's equilibrium (mpm/implicit_system.hpp).
#include "mpm/implicit_system.hpp"

#include <omp.h>

#include <algorithm>

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

bool stepGeometry(const StepSetup& setup, const Particles& p, const std::vector<std::uint8_t>& prescribed,
                  StepGeometry& g, std::size_t& outside) {
  const Grid& grid = setup.scene.grid;
  const ShapeFunction f = setup.scene.solver.shapeFunction;
  const int support = supportSize(f), nx = grid.nodesX();
  g.stencilNodes = support * support;
  g.stencils.resize(p.size());
  for (std::size_t i = 0; i < p.size(); ++i)
    if (!computeStencil(f, grid, setup.halfWidth, p.position[i], g.stencils[i])) {
      outside = i;
      return false;
    }
  // The unknowns: reached node components in node order, the prescribed ones left out.
  const auto components = static_cast<std::size_t>(2 * grid.nodeCount());
  std::vector<std::uint8_t> reached(components, 0);
  for (const Stencil& s : g.stencils) {
    const ElementNodes e = elementNodes(s, nx, support);
    for (int a = 0; a < e.count; ++a) reached[2 * static_cast<std::size_t>(e.node[a])] = reached[2 * static_cast<std::size_t>(e.node[a]) + 1] = 1;
  }
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
  // K's pattern and each particle's positions in it.
  const int local = 2 * g.stencilNodes;
  std::vector<Eigen::Triplet<double>> triplets;
  triplets.reserve(p.size() * static_cast<std::size_t>(local * local));
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
  g.entryOf.assign(p.size() * static_cast<std::size_t>(local * local), -1);
  const int* outer = g.pattern.outerIndexPtr();
  const int* inner = g.pattern.innerIndexPtr();
  for (std::size_t i = 0; i < p.size(); ++i) {
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    for (int r = 0; r < local; ++r)
      for (int c = 0; c < local; ++c) {
        const int row = unknownAt(e, r), col = unknownAt(e, c);
        if (row < 0 || col < 0) continue;
        const int* at = std::lower_bound(inner + outer[col], inner + outer[col + 1], row);
        g.entryOf[i * static_cast<std::size_t>(local * local) + static_cast<std::size_t>(r * local + c)] = static_cast<std::int32_t>(at - inner);
      }
  }
  return true;
}

void evaluateTrial(const StepSetup& setup, const Particles& p, const StepGeometry& g, const Eigen::VectorXd& du,
                   bool withTangent, SnapBackPolicy snapBack, Trial& t, const Eigen::VectorXd* direction) {
  withTangent = withTangent || direction;
  const std::size_t count = p.size();
  const int nx = setup.scene.grid.nodesX(), support = supportSize(setup.scene.solver.shapeFunction);
  t.strain.resize(count);
  t.stress.resize(count);
  t.band.assign(count, std::nullopt);
  t.secondBand.assign(count, std::nullopt);
  t.dissipation.assign(count, 0.0);
  t.integrity = p.integrity;
  t.failed = SIZE_MAX;
  std::vector<Tangent> tangents(withTangent ? count : 0);
  UpdateOptions options(snapBack, withTangent);
  options.substepLevels = setup.scene.solver.substepLevels;
  long released = 0;
  std::size_t failed = SIZE_MAX;
  UpdateResult failure;
  // The updates: independent per point, in parallel.
#pragma omp parallel for num_threads(setup.threads) schedule(dynamic, 256) reduction(+ : released)
  for (std::size_t i = 0; i < count; ++i) {
    const Material& m = setup.materials[p.material[i]];
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    const Voigt d = strainIncrement(e, du);
    Voigt strain = p.strain[i];
    const std::int32_t b1 = p.band[i], b2 = p.secondBand.empty() ? -1 : p.secondBand[i];
    if (b1 < 0 && b2 < 0 && m.closedFormStress(d, false, strain, t.stress[i])) {
      t.strain[i] = strain;
      if (withTangent) tangents[i] = m.stiffness();
      continue;
    }
    std::optional<BandState> band, second;
    if (b1 >= 0) band = p.bands[static_cast<std::size_t>(b1)];
    if (b2 >= 0) second = p.secondBands[static_cast<std::size_t>(b2)];
    OpenedBands opened;
    const UpdateResult r = m.update({strain, t.integrity.empty() ? nullptr : &t.integrity[i], band ? &*band : nullptr,
                                     second ? &*second : nullptr},
                                    d, setup.size, opened, options);
    if (!r.converged() || !r.stress.allFinite()) {
#pragma omp critical(ecm_implicit_failure)
      if (i < failed) {
        failed = i;
        failure = r;
      }
      continue;
    }
    if (opened.first) band = opened.first;
    if (opened.second) second = opened.second;
    t.strain[i] = strain;
    t.stress[i] = r.stress;
    t.band[i] = band;
    t.secondBand[i] = second;
    t.dissipation[i] = r.dissipation;
    released += r.released ? 1 : 0;
    if (withTangent) tangents[i] = r.tangent;
  }
  t.released = released;
  t.failed = failed;
  t.failure = failure;
  if (failed != SIZE_MAX) return;
  // The sums, particle by particle in index order.
  t.internalForce.setZero(2 * setup.scene.grid.nodeCount());
  if (direction) t.tangentTimesDirection.setZero(2 * setup.scene.grid.nodeCount());
  if (withTangent) t.tangent = g.pattern;
  double* values = withTangent ? t.tangent.valuePtr() : nullptr;
  const int local = 2 * g.stencilNodes;
  for (std::size_t i = 0; i < count; ++i) {
    const ElementNodes e = elementNodes(g.stencils[i], nx, support);
    const double v = p.volume[i];
    const Voigt& s = t.stress[i];
    for (int a = 0; a < e.count; ++a) {  // f_int = V B^T sigma
      t.internalForce[2 * e.node[a]] += v * (e.gx[a] * s[0] + e.gy[a] * s[2]);
      t.internalForce[2 * e.node[a] + 1] += v * (e.gy[a] * s[1] + e.gx[a] * s[2]);
    }
    if (!withTangent) continue;
    if (direction) {  // V B^T D (B direction)
      const Voigt s2 = v * (tangents[i] * strainIncrement(e, *direction));
      for (int a = 0; a < e.count; ++a) {
        t.tangentTimesDirection[2 * e.node[a]] += e.gx[a] * s2[0] + e.gy[a] * s2[2];
        t.tangentTimesDirection[2 * e.node[a] + 1] += e.gy[a] * s2[1] + e.gx[a] * s2[2];
      }
    }
    const std::int32_t* at = g.entryOf.data() + i * static_cast<std::size_t>(local * local);
    for (int a = 0; a < e.count; ++a) {
      const Eigen::Matrix<double, 2, 3> left = v * blockB(e, a).transpose() * tangents[i];  // V B_a^T D
      for (int b = 0; b < e.count; ++b) {
        const Eigen::Matrix2d k = left * blockB(e, b);  // K = V B_a^T D B_b
        for (int r = 0; r < 2; ++r)
          for (int c = 0; c < 2; ++c)
            if (const std::int32_t pos = at[(2 * a + r) * local + 2 * b + c]; pos >= 0) values[pos] += k(r, c);
      }
    }
  }
}

}  // namespace ecm::mpm
