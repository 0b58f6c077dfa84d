// The state at time 0 of an explicit run (mpm/explicit/phases.hpp).
#include <omp.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "mpm/explicit/phases.hpp"

namespace ecm::mpm {

MpmState initialState(const StepSetup& setup, Particles particles) {
  const Scene& scene = setup.scene;
  const Grid& g = scene.grid;
  MpmState st;
  st.particles = std::move(particles);
  st.grid.resize(g.nodeCount());
  st.crackPaths = crackPathsFor(scene, st.particles);
  // The scatter order (mpm/explicit/scatter_order.hpp): the rows the stencils start on, then the plan.
  layOutChunks(g, scene.particlesPerCell, supportSize(scene.solver.shapeFunction), st.particles.size(), st.order);
  withShapeFunction(scene.solver.shapeFunction, [&]<ShapeFunction F>() {
    for (std::size_t c = 0; c < st.order.chunks(); ++c) {
      BaseSpan span;
      const auto [first, last] = st.order.range(c, st.particles.size());
      for (std::size_t i = first; i < last; ++i) {
        StencilAt at;
        if (locateStencil<F>(g, setup.invCell, setup.halfWidth, st.particles.position[i], at)) span.add(at.base);
      }
      st.order.measured[c] = span.rows(g.nodesX());
    }
  });
  planScatter(st.order, g.nodesY());

  // dt = cfl * min cell size / the largest P-wave speed sqrt(a_11 / rho) of the materials present.
  std::vector<bool> used(scene.materials.size(), false);
  for (const auto id : st.particles.material) used[id] = true;
  double speed = 0.0;
  for (std::size_t i = 0; i < scene.materials.size(); ++i)
    if (used[i]) speed = std::max(speed, std::sqrt(pWaveModulus(scene.materials[i].elastic) / scene.materials[i].density));
  st.clock.dt = scene.solver.explicitScheme.cfl * std::min(g.cellSize[0], g.cellSize[1]) / speed;

  st.conditions = conditionStates(scene);
  st.loads = loadStates(scene, st.particles);
  st.platens = platenStates(scene);
  return st;
}

}  // namespace ecm::mpm
