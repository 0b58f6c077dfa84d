// The fused USL pass does not store the stress of a point whose stress follows its strain
// (elastic, intact enriched: a : strain, Material::stressFollowsStrain); ExplicitSolver::particles()
// stores it when someone reads the particles (docs/performance.md, "Fewer
// bytes per particle"). That is only right if every update of such a point ends with exactly
// that product (tests/material/stress_follows_strain_test.cpp), and if storing on read changes
// nothing that follows (here).
#include <gtest/gtest.h>

#include <bit>
#include <cstdint>
#include <vector>

#include "test_scenes.hpp"

namespace ecm::mpm::test {
namespace {

// Bitwise equality of two stresses (EXPECT_EQ on Eigen vectors compares values; -0 == 0 there, so
// the bits are compared one by one).
bool sameBits(const Voigt& a, const Voigt& b) {
  for (int c = 0; c < 3; ++c)
    if (std::bit_cast<std::uint64_t>(a[c]) != std::bit_cast<std::uint64_t>(b[c])) return false;
  return true;
}

// A run whose particles are read after every step (stored each time) and one read only at the
// end follow the same trajectory bit for bit, in the fused USL and in MUSL; and the stresses the
// fused pass left unstored are really stored on read (the test would pass vacuously otherwise),
// while MUSL's passes store every stress themselves.
void expectStoringOnReadChangesNothing(Scene scene, int steps, bool leavesStressesUnstored) {
  ExplicitSolver readEveryStep(scene, 2), readAtEnd(scene, 2);
  long unstoredSeen = 0;
  for (int n = 0; n < steps; ++n) {
    readAtEnd.advance();
    readEveryStep.advance();
    const std::vector<Voigt> before = readEveryStep.kinematics().stress;
    const Particles& stored = readEveryStep.particles();
    for (std::size_t i = 0; i < stored.size(); ++i) unstoredSeen += sameBits(before[i], stored.stress[i]) ? 0 : 1;
  }
  if (leavesStressesUnstored) {
    EXPECT_GT(unstoredSeen, 0) << "some stresses should have been left unstored by the step";
  } else {
    EXPECT_EQ(unstoredSeen, 0) << "every stress should have been stored by the step";
  }
  const Particles &a = readAtEnd.particles(), &b = readEveryStep.particles();
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(a.bands.size(), b.bands.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a.position[i], b.position[i]) << "particle " << i;
    ASSERT_EQ(a.velocity[i], b.velocity[i]) << "particle " << i;
    ASSERT_TRUE(sameBits(a.stress[i], b.stress[i])) << "particle " << i;
    const Material& m = readAtEnd.materials()[a.material[i]];
    if (m.stressFollowsStrain(a.band[i] >= 0)) {
      ASSERT_TRUE(sameBits(a.stress[i], m.intactStress(a.strain[i]))) << "particle " << i;
    }
  }
  EXPECT_EQ(readAtEnd.energies().strain, readEveryStep.energies().strain);
  EXPECT_EQ(readAtEnd.energies().dissipated, readEveryStep.energies().dissipated);
}

TEST(UnstoredStress, StoringOnReadChangesNothingInTheFusedUsl) {
  expectStoringOnReadChangesNothing(notchedCrackingBlock(), 200, true);
}

TEST(UnstoredStress, StoringOnReadChangesNothingInMusl) {
  Scene scene = notchedCrackingBlock();
  scene.solver.explicitScheme.scheme = UpdateScheme::MUSL;
  expectStoringOnReadChangesNothing(scene, 200, false);
}

}  // namespace
}  // namespace ecm::mpm::test
