// The band's kinematics (mpm/setup/band_kinematics.hpp, docs/model.md "Crack paths"): which side
// of a path a node lies on, grad phi in a cell, and the level lines' length.
#include <gtest/gtest.h>

#include <cmath>

#include "mpm/setup/band_kinematics.hpp"

namespace ecm::mpm {
namespace {

// A path running up the x = 0.5 line: left is x < 0.5; on the path counts as left; the path runs
// on past its ends along its end segments.
TEST(BandKinematics, TheLeftOfAPathRunsOnPastItsEnds) {
  const std::vector<Vec2> up{Vec2(0.5, 0.0), Vec2(0.5, 1.0)};
  EXPECT_TRUE(onLeftOf(up, Vec2(0.0, 0.5)));
  EXPECT_FALSE(onLeftOf(up, Vec2(1.0, 0.5)));
  EXPECT_TRUE(onLeftOf(up, Vec2(0.5, 0.5)));
  EXPECT_TRUE(onLeftOf(up, Vec2(0.0, 5.0)));    // past the end
  EXPECT_FALSE(onLeftOf(up, Vec2(1.0, -5.0)));  // before the start
  EXPECT_FALSE(onLeftOf({Vec2(1.0, 1.0)}, Vec2(0.0, 0.0)));  // a point has no left
}

// Round a vertex the side is that of the two segments' summed normals: a path turning right by
// 90 degrees at (0, 1) has (-1, 2) on its left and (0.5, 0.5) (inside the turn) on its right.
TEST(BandKinematics, RoundAVertexTheSideIsTheTurnsSide) {
  const std::vector<Vec2> turn{Vec2(0.0, 0.0), Vec2(0.0, 1.0), Vec2(1.0, 1.0)};
  EXPECT_TRUE(onLeftOf(turn, Vec2(-1.0, 2.0)));
  EXPECT_FALSE(onLeftOf(turn, Vec2(0.5, 0.5)));
  EXPECT_TRUE(onLeftOf(turn, Vec2(0.5, 1.5)));
}

// The left column of a cell's nodes labelled: phi = 1 - x / h_x, grad phi = (-1 / h_x, 0)
// everywhere; the level lines are the cell's height long. One corner labelled: grad phi =
// (y, x) / h at the upper right's, zero at the opposite corner; its level lines' mean length on
// a unit cell, at 2 x 2 points, is (sqrt(1/8) + 2 sqrt(5/8) + sqrt(9/8)) / 4.
TEST(BandKinematics, GradPhiAndItsLevelLines) {
  const Vec2 h(2.0, 3.0);
  const NodeSides left = 0b0101;  // lower left and upper left
  for (const Vec2& at : {Vec2(0.1, 0.2), Vec2(0.9, 0.7)}) {
    EXPECT_NEAR(sideGradient(left, at, h)[0], -0.5, 1e-15);
    EXPECT_NEAR(sideGradient(left, at, h)[1], 0.0, 1e-15);
  }
  EXPECT_TRUE(straddles(left));
  EXPECT_FALSE(straddles(0b1111));
  EXPECT_FALSE(straddles(0));
  EXPECT_NEAR(sideGradientIntegral(left, h, 2, 0.1), 3.0, 1e-14);
  EXPECT_NEAR(sideGradientIntegral(left, h, 3, 0.1), 3.0, 1e-14);
  const NodeSides corner = 0b1000;  // upper right
  EXPECT_EQ(sideGradient(corner, Vec2(0.0, 0.0), Vec2::Ones()), Vec2::Zero());
  EXPECT_NEAR(sideGradient(corner, Vec2(0.25, 0.75), Vec2::Ones())[0], 0.75, 1e-15);
  const double expected = (std::sqrt(0.125) + 2.0 * std::sqrt(0.625) + std::sqrt(1.125)) / 4.0;
  EXPECT_NEAR(sideGradientIntegral(corner, Vec2::Ones(), 2, 0.1), expected, 1e-14);
  // The points below the floor on |grad phi| (here the one nearest the opposite corner, 0.354) count nothing.
  EXPECT_NEAR(sideGradientIntegral(corner, Vec2::Ones(), 2, 0.4), expected - std::sqrt(0.125) / 4.0, 1e-14);
}

}  // namespace
}  // namespace ecm::mpm
