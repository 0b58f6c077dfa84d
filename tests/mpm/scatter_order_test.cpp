// The scatter order (mpm/explicit/scatter_order.hpp): the plan widens each chunk's measured rows by one
// row each way, every chunk lands in exactly one group of its colour, and two groups of one
// colour never reach the same node row, whatever the rows (so they scatter at once safely); a
// group waits for exactly the groups of earlier colours that reach one of its rows, and the
// barrier-free schedule runs every chunk once, each node row's chunks in the order (colour,
// chunk), on any number of threads.
#include <gtest/gtest.h>

#include <chrono>
#include <mutex>
#include <random>
#include <set>

#include "mpm/explicit/scatter_order.hpp"

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

// The node rows a group may reach (lo > hi: none).
std::pair<int, int> groupReach(const ScatterOrder& o, const std::vector<std::int32_t>& group) {
  int lo = INT32_MAX, hi = INT32_MIN;
  for (const std::int32_t c : group) {
    const RowSpan p = o.planned[static_cast<std::size_t>(c)];
    if (p.empty()) continue;
    lo = std::min(lo, p.lo);
    hi = std::max(hi, p.hi + o.support - 1);
  }
  return {lo, hi};
}

TEST_P(GroupSupport, AGroupWaitsForExactlyTheEarlierColoursGroupsThatReachItsRows) {
  const auto [support, spread] = GetParam();
  std::mt19937 rng(static_cast<unsigned>(31 * support + spread));
  for (int trial = 0; trial < 20; ++trial) {
    const ScatterOrder o = randomOrder(rng, support, spread);
    const GroupWaits& w = o.waits;
    std::vector<std::pair<int, std::size_t>> entries;  // per entry: colour, group
    for (int colour = 0; colour < kColours; ++colour) {
      ASSERT_EQ(w.firstOfColour[static_cast<std::size_t>(colour)], static_cast<std::int32_t>(entries.size()));
      for (std::size_t g = 0; g < o.groups[static_cast<std::size_t>(colour)].size(); ++g) entries.emplace_back(colour, g);
    }
    ASSERT_EQ(w.size(), entries.size());
    for (std::size_t a = 0; a < entries.size(); ++a) {
      const auto [ca, ga] = entries[a];
      const auto [alo, ahi] = groupReach(o, o.groups[static_cast<std::size_t>(ca)][ga]);
      std::set<std::int32_t> expected;  // by brute force over every earlier entry
      for (std::size_t b = 0; b < entries.size(); ++b) {
        const auto [cb, gb] = entries[b];
        const auto [blo, bhi] = groupReach(o, o.groups[static_cast<std::size_t>(cb)][gb]);
        if (cb < ca && alo <= ahi && blo <= bhi && blo <= ahi && alo <= bhi) expected.insert(static_cast<std::int32_t>(b));
      }
      const std::set<std::int32_t> waits(w.waits.begin() + w.waitsBegin[a], w.waits.begin() + w.waitsBegin[a + 1]);
      ASSERT_EQ(waits, expected) << "entry " << a << " (colour " << ca << ")";
      ASSERT_GE(w.bandPosition[a], 0.0);
      ASSERT_LT(w.bandPosition[a], 1.0);
    }
  }
}

// Every chunk appends itself to each node row it reaches, with no lock: the schedule alone must
// keep two threads off a row at once and give each row its chunks in the order (colour, chunk).
// The chunks take random times, so that the threads meet in many orders.
TEST_P(GroupSupport, TheBarrierFreeScheduleRunsEachRowsChunksInColourAndChunkOrder) {
  const auto [support, spread] = GetParam();
  std::mt19937 rng(static_cast<unsigned>(57 * support + spread));
  for (const int threads : {1, 2, 3, 5}) {
    for (int trial = 0; trial < 5; ++trial) {
      const ScatterOrder o = randomOrder(rng, support, spread);
      std::vector<std::vector<std::int32_t>> rows(210), expected(210);  // rows up to 200 + support
      for (int colour = 0; colour < kColours; ++colour)
        for (std::size_t c = static_cast<std::size_t>(colour); c < o.chunks(); c += kColours) {
          const RowSpan p = o.planned[c];
          if (p.empty()) continue;
          for (int r = p.lo; r <= p.hi + support - 1; ++r) expected[static_cast<std::size_t>(r)].push_back(static_cast<std::int32_t>(c));
        }
      std::vector<int> runs(o.chunks(), 0);
      std::vector<unsigned> pause(o.chunks());
      for (auto& v : pause) v = rng() % 200;
      forEachChunkByColour(o, threads, [&](std::size_t c, int) {
        ++runs[c];
        const RowSpan p = o.planned[c];
        if (p.empty()) return;
        for (int r = p.lo; r <= p.hi + support - 1; ++r) rows[static_cast<std::size_t>(r)].push_back(static_cast<std::int32_t>(c));
        const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(pause[c]);
        while (std::chrono::steady_clock::now() < until) {
        }
      });
      for (const int n : runs) ASSERT_EQ(n, 1) << threads << " threads: every chunk runs once";
      for (std::size_t r = 0; r < rows.size(); ++r) ASSERT_EQ(rows[r], expected[r]) << threads << " threads, row " << r;
    }
  }
}

INSTANTIATE_TEST_SUITE_P(SupportsAndSpreads, GroupSupport,
                         ::testing::Combine(::testing::Values(2, 3), ::testing::Values(2, 6, 40)));

}  // namespace
}  // namespace ecm::mpm::test
