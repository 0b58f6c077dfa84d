// The particle arrays: band storage order.
#include "mpm/core/particles.hpp"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace ecm::mpm::test
