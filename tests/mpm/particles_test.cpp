// The particle arrays: band storage order; the mass and volume a material's points share.
#include "mpm/core/particles.hpp"

#include <gtest/gtest.h>

#include "mpm/setup/seeding.hpp"
#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

TEST(Particles, SortingBandsKeepsEveryParticlesBandAndPutsThemInParticleOrder) {
  // Five particles, three cracked in the order 3, 0, 4 (as onsets arrive over the steps).
  Particles p;
  p.resize(5, false);
  std::fill(p.band.begin(), p.band.end(), -1);
  for (const int i : {3, 0, 4}) {
    BandState b;
    b.integrity = 0.1 * (i + 1);  // a value that identifies the particle
    b.jump = Vec2(i, -i);
    p.band[static_cast<std::size_t>(i)] = static_cast<std::int32_t>(p.bands.size());
    p.bands.push_back(b);
  }
  EXPECT_FALSE(p.bandsInParticleOrder());
  p.sortBandsByParticle();
  EXPECT_TRUE(p.bandsInParticleOrder());
  ASSERT_EQ(p.bands.size(), 3u);
  EXPECT_EQ(p.band, (std::vector<std::int32_t>{0, -1, -1, 1, 2}));
  for (const int i : {0, 3, 4}) {
    const BandState& b = p.bands[static_cast<std::size_t>(p.band[static_cast<std::size_t>(i)])];
    EXPECT_EQ(b.integrity, 0.1 * (i + 1));
    EXPECT_EQ(b.jump, Vec2(i, -i));
  }
}

// Seeding gives every point the cell's share of the volume, cell area / k^2 x thickness, and
// mass = density x volume: each material's points share both (the fused pass reads them once).
TEST(SharedMassAndVolume, SeededPointsOfAMaterialShareThem) {
  const Scene scene = notchedCrackingBlock();
  Particles p = seedParticles(scene);
  const std::vector<SharedMassVolume> shared = sharedMassAndVolume(p, scene.materials.size());
  ASSERT_EQ(shared.size(), 1u);
  const double volume = scene.grid.cellArea() / (scene.particlesPerCell * scene.particlesPerCell) * scene.thickness;
  EXPECT_EQ(shared[0].volume, volume);
  EXPECT_EQ(shared[0].mass, scene.materials[0].density * volume);
  p.mass[5] *= 2.0;  // one point with a mass of its own: nothing is shared
  EXPECT_TRUE(sharedMassAndVolume(p, scene.materials.size()).empty());
}

// A point with a mass and volume of its own (the arrays, not the shared values) is scattered
// with them by the fused pass: it follows the plain phases as every other point does (to the
// order of the sums). With the shared values it would carry a third of its mass.
TEST(SharedMassAndVolume, APointWithItsOwnMassIsScatteredWithIt) {
  Scene scene = notchedCrackingBlock();
  ExplicitSolver fused(scene, 1), plain(scene, 1);
  for (ExplicitSolver* s : {&fused, &plain}) {
    Particles& p = s->editParticles();
    p.mass[100] *= 3.0;
    p.volume[100] *= 3.0;
  }
  for (int n = 0; n < 300; ++n) {
    fused.advance();
    plain.advanceByPhases();
  }
  const Particles &a = fused.particles(), &b = plain.particles();
  double worst = 0.0, scale = 0.0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    worst = std::max(worst, (a.velocity[i] - b.velocity[i]).norm());
    scale = std::max(scale, b.velocity[i].norm());
  }
  EXPECT_LT(worst, 1e-9 * scale);
}

}  // namespace
}  // namespace ecm::mpm::test
