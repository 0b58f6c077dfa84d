#include "mpm/setup/seeding.hpp"

#include <sstream>
#include <stdexcept>

namespace ecm::mpm {

namespace {

// Material at a point: the last body containing it decides (-1: empty or subtracted).
int materialAt(const Scene& scene, const Vec2& x) {
  for (auto b = scene.bodies.rbegin(); b != scene.bodies.rend(); ++b)
    if (b->shape.contains(x)) return b->subtract ? -1 : static_cast<int>(b - scene.bodies.rbegin());
  return -1;
}

}  // namespace

Particles seedParticles(const Scene& scene) {
  const Grid& g = scene.grid;
  const int k = scene.particlesPerCell;
  const double volume = g.cellArea() / (k * k) * scene.thickness;
  struct Seed {
    Vec2 x;
    int body;
  };
  std::vector<Seed> seeds;
  for (int j = 0; j < g.cellsY; ++j)
    for (int b = 0; b < k; ++b)
      for (int i = 0; i < g.cellsX; ++i)
        for (int a = 0; a < k; ++a) {
          const Vec2 x = g.origin + Vec2((i + (a + 0.5) / k) * g.cellSize[0], (j + (b + 0.5) / k) * g.cellSize[1]);
          const int r = materialAt(scene, x);  // reverse index
          if (r >= 0) seeds.push_back({x, static_cast<int>(scene.bodies.size()) - 1 - r});
        }
  if (seeds.empty()) throw std::invalid_argument("no particle lies inside the bodies of the scene (check the grid)");

  // The optional arrays exist only if a particle's material needs them: a material listed in the
  // scene but used by no particle costs nothing.
  ParticleFields fields;
  for (const Seed& sd : seeds) fields |= fieldsFor(scene.materials[static_cast<std::size_t>(scene.bodies[static_cast<std::size_t>(sd.body)].material)]);
  Particles p;
  p.resize(seeds.size(), fields.integrity, fields.secondBand);
  const Vec2 lo = g.origin + 1.5 * g.cellSize, hi = g.origin + g.extent() - 1.5 * g.cellSize;
  for (std::size_t n = 0; n < seeds.size(); ++n) {
    const Body& body = scene.bodies[static_cast<std::size_t>(seeds[n].body)];
    const Vec2& x = seeds[n].x;
    if (scene.solver.shapeFunction == ShapeFunction::BSpline2 &&
        !(x[0] >= lo[0] && x[0] <= hi[0] && x[1] >= lo[1] && x[1] <= hi[1])) {
      std::ostringstream msg;
      msg << "particle " << n << " at (" << x[0] << ", " << x[1]
          << ") mm lies within 1.5 cells of the grid edge: quadratic B-splines have no boundary treatment "
             "here; enlarge the grid by 2 cells on each side (or use linear / uGIMP)";
      throw std::invalid_argument(msg.str());
    }
    p.position[n] = x;
    p.origin[n] = x;
    p.velocity[n] = body.initialVelocity;
    p.volume[n] = volume;
    p.mass[n] = scene.materials[static_cast<std::size_t>(body.material)].density * volume;
    p.material[n] = static_cast<std::uint8_t>(body.material);
  }
  return p;
}

}  // namespace ecm::mpm
