// The scatter order (mpm/scatter_order.hpp): the plan widens each chunk's measured rows by one
// row each way, every chunk lands in exactly one group of its colour, and two groups of one
// colour never reach the same node row, whatever the rows (so they scatter at once safely).
#include <gtest/gtest.h>

#include <random>

#include "mpm/scatter_order.hpp"

namespace ecm::mpm::test {
namespace {

ScatterOrder randomOrder(std::mt19937& rng, int support, int spread) {
  const Grid g{Vec2::Zero(), Vec2(1.0, 1.0), 60, 200};
  ScatterOrder o;
  layOutChunks(g, 2, support, 60000, o);
  std::uniform_int_distribution<int> start(0, 190), width(0, spread), none(0, 20);
  for (auto& m : o.measured) {
    if (none(rng) == 0) continue;  // a chunk none of whose stencils was located
    m.lo = start(rng);
    m.hi = std::min(g.nodesY() - 1, m.lo + width(rng));
  }
  planScatter(o, g.nodesY());
  return o;
}

TEST(ScatterOrder, PlanWidensTheMeasuredRowsByOneEachWay) {
  std::mt19937 rng(3);
  const ScatterOrder o = randomOrder(rng, 2, 4);
  ASSERT_EQ(o.chunk, 480u);  // two rows of 60 cells, 2 x 2 particles per cell
  ASSERT_EQ(o.chunks(), 125u);
  for (std::size_t c = 0; c < o.chunks(); ++c) {
    const RowSpan m = o.measured[c], p = o.planned[c];
    if (m.empty()) {
      EXPECT_TRUE(p.empty());
      continue;
    }
    EXPECT_EQ(p.lo, std::max(0, m.lo - 1));
    EXPECT_EQ(p.hi, std::min(200, m.hi + 1));
  }
}

class GroupSupport : public ::testing::TestWithParam<std::tuple<int, int>> {};

TEST_P(GroupSupport, GroupsOfOneColourReachNoCommonNodeRow) {
  const auto [support, spread] = GetParam();
  std::mt19937 rng(static_cast<unsigned>(17 * support + spread));
  for (int trial = 0; trial < 20; ++trial) {
    const ScatterOrder o = randomOrder(rng, support, spread);
    std::vector<int> seen(o.chunks(), 0);
    for (int colour = 0; colour < kColours; ++colour) {
      const auto& groups = o.groups[static_cast<std::size_t>(colour)];
      std::vector<std::pair<int, int>> reach;  // per group: the node rows its chunks may reach
      for (const auto& g : groups) {
        ASSERT_TRUE(std::is_sorted(g.begin(), g.end())) << "a group's chunks scatter in index order";
        int lo = INT32_MAX, hi = INT32_MIN;
        for (const std::int32_t c : g) {
          ASSERT_EQ(c % kColours, colour);
          ++seen[static_cast<std::size_t>(c)];
          const RowSpan p = o.planned[static_cast<std::size_t>(c)];
          if (p.empty()) continue;
          lo = std::min(lo, p.lo);
          hi = std::max(hi, p.hi + support - 1);
        }
        reach.emplace_back(lo, hi);
      }
      for (std::size_t a = 0; a < reach.size(); ++a)
        for (std::size_t b = a + 1; b < reach.size(); ++b)
          ASSERT_TRUE(reach[a].second < reach[b].first || reach[b].second < reach[a].first)
              << "colour " << colour << ": groups " << a << " and " << b << " reach the same node rows";
    }
    for (const int n : seen) ASSERT_EQ(n, 1) << "every chunk in exactly one group";
  }
}

INSTANTIATE_TEST_SUITE_P(SupportsAndSpreads, GroupSupport,
                         ::testing::Combine(::testing::Values(2, 3), ::testing::Values(2, 6, 40)));

}  // namespace
}  // namespace ecm::mpm::test
