// Nodes the body barely reaches, tied to their neighbours (mpm/implicit/node_ties.hpp): which
// nodes are tied and to what, that the ties keep every linear displacement field exact (the
// reason for extrapolating linearly), and that transferTies is applyTies' transpose (the forces
// of the reduced system T^T r).
#include <gtest/gtest.h>

#include <random>

#include "mpm/implicit/node_ties.hpp"

namespace ecm::mpm::test {
namespace {

// A grid of 6 x 6 nodes with a body over nodes ix, iy = 0..3 (inner share 1, edges 1/2, the
// corner 1/4) and a thin overhang into the next row and column (share 1e-5).
struct Grid6 {
  static constexpr int n = 6;
  std::vector<double> share = std::vector<double>(n * n, 0.0);
  std::vector<std::uint8_t> all = std::vector<std::uint8_t>(n * n, 1);
  static int at(int ix, int iy) { return iy * n + ix; }
  Grid6() {
    for (int iy = 0; iy <= 3; ++iy)
      for (int ix = 0; ix <= 3; ++ix) share[static_cast<std::size_t>(at(ix, iy))] = (ix == 0 || ix == 3 ? 0.5 : 1.0) * (iy == 0 || iy == 3 ? 0.5 : 1.0);
    for (int k = 0; k <= 4; ++k) share[static_cast<std::size_t>(at(k, 4))] = share[static_cast<std::size_t>(at(4, k))] = 1e-5;
  }
};

const NodeTie* tieOf(const std::vector<NodeTie>& ties, int node) {
  for (const NodeTie& t : ties)
    if (t.node == node) return &t;
  return nullptr;
}

TEST(NodeTies, AWeakNodeIsExtrapolatedFromTheTwoRowsBelowIt) {
  const Grid6 g;
  const std::vector<NodeTie> ties = weakNodeTies(Grid6::n, Grid6::n, g.share, g.all, g.all);
  ASSERT_EQ(ties.size(), 9u);  // the overhang's row (ix = 0..4 at iy = 4) and column (iy = 0..3 at ix = 4)
  const NodeTie* above = tieOf(ties, Grid6::at(1, 4));
  ASSERT_NE(above, nullptr);
  ASSERT_EQ(above->sources, 2);
  EXPECT_EQ(above->source[0], Grid6::at(1, 3));
  EXPECT_EQ(above->coefficient[0], 2.0);
  EXPECT_EQ(above->source[1], Grid6::at(1, 2));
  EXPECT_EQ(above->coefficient[1], -1.0);
  // Beside the body: extrapolated along x.
  const NodeTie* beside = tieOf(ties, Grid6::at(4, 2));
  ASSERT_NE(beside, nullptr);
  ASSERT_EQ(beside->sources, 2);
  EXPECT_EQ(beside->source[0], Grid6::at(3, 2));
  EXPECT_EQ(beside->source[1], Grid6::at(2, 2));
  // The corner of the overhang has no strong node on either axis: the corner rule, (2, -1) x (2, -1).
  const NodeTie* corner = tieOf(ties, Grid6::at(4, 4));
  ASSERT_NE(corner, nullptr);
  ASSERT_EQ(corner->sources, 4);
  double sum = 0.0;
  for (int k = 0; k < 4; ++k) sum += corner->coefficient[static_cast<std::size_t>(k)];
  EXPECT_EQ(sum, 1.0);  // a rigid translation is kept
  EXPECT_EQ(corner->source[0], Grid6::at(3, 3));
  EXPECT_EQ(corner->coefficient[0], 4.0);
}

TEST(NodeTies, OnlyWeakNodesThatMayBeTiedAndHaveStrongSourcesAreTied) {
  Grid6 g;
  std::vector<std::uint8_t> mayTie = g.all, maySource = g.all;
  mayTie[static_cast<std::size_t>(Grid6::at(1, 4))] = 0;      // e.g. a prescribed node
  maySource[static_cast<std::size_t>(Grid6::at(2, 3))] = 0;   // e.g. a platen's node: the node above it has no axis rule left
  g.share[static_cast<std::size_t>(Grid6::at(3, 4))] = kWeakNodeShare;  // not weak
  const std::vector<NodeTie> ties = weakNodeTies(Grid6::n, Grid6::n, g.share, mayTie, maySource);
  EXPECT_EQ(tieOf(ties, Grid6::at(1, 4)), nullptr);
  EXPECT_EQ(tieOf(ties, Grid6::at(3, 4)), nullptr);
  EXPECT_EQ(tieOf(ties, Grid6::at(5, 5)), nullptr);  // not reached
  // (2, 4): no axis rule ((2, 3) may not be a source; along x its row is weak), so a corner rule,
  // the one whose four sources are all strong: (1, 3), (0, 3), (1, 2), (0, 2).
  const NodeTie* t = tieOf(ties, Grid6::at(2, 4));
  ASSERT_NE(t, nullptr);
  ASSERT_EQ(t->sources, 4);
  EXPECT_EQ(t->source[0], Grid6::at(1, 3));
  EXPECT_EQ(t->source[3], Grid6::at(0, 2));
  // A weak node with no strong node anywhere near stays free.
  std::vector<double> lone(36, 0.0);
  lone[7] = 1e-3;
  EXPECT_TRUE(weakNodeTies(6, 6, lone, g.all, g.all).empty());
}

TEST(NodeTies, EveryLinearDisplacementFieldIsKeptExactly) {
  const Grid6 g;
  const std::vector<NodeTie> ties = weakNodeTies(Grid6::n, Grid6::n, g.share, g.all, g.all);
  // u = a + G x at every node, then the tied nodes recomputed from their sources.
  const double a[2] = {0.3, -0.7}, grad[2][2] = {{1.25, -0.5}, {0.75, 2.0}};
  std::vector<double> u(2 * 36), exact(2 * 36);
  for (int node = 0; node < 36; ++node)
    for (int d = 0; d < 2; ++d) {
      const double x = node % 6 * 10.0, y = node / 6 * 10.0;
      exact[static_cast<std::size_t>(2 * node + d)] = a[d] + grad[d][0] * x + grad[d][1] * y;
      u[static_cast<std::size_t>(2 * node + d)] = exact[static_cast<std::size_t>(2 * node + d)];
    }
  for (const NodeTie& t : ties) u[static_cast<std::size_t>(2 * t.node)] = u[static_cast<std::size_t>(2 * t.node + 1)] = 99.0;
  applyTies(ties, u);
  for (std::size_t k = 0; k < u.size(); ++k) EXPECT_NEAR(u[k], exact[k], 1e-12) << "component " << k;
}

TEST(NodeTies, TheForceTransferIsTheTransposeOfTheTie) {
  const Grid6 g;
  const std::vector<NodeTie> ties = weakNodeTies(Grid6::n, Grid6::n, g.share, g.all, g.all);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> uniform(-1.0, 1.0);
  std::vector<double> v(72), w(72);
  for (std::size_t k = 0; k < 72; ++k) v[k] = uniform(random), w[k] = uniform(random);
  std::vector<double> tv = v, tw = w;
  applyTies(ties, tv);     // T v (on the node components)
  transferTies(ties, tw);  // T^T w
  double left = 0.0, right = 0.0;
  for (std::size_t k = 0; k < 72; ++k) left += tv[k] * w[k], right += v[k] * tw[k];
  EXPECT_NEAR(left, right, 1e-12);
}

}  // namespace
}  // namespace ecm::mpm::test
