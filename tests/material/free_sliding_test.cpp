// The least-norm solve of a two-band Jacobian with a free sliding (material/free_sliding.hpp,
// docs/model.md "Two failed bands"). Expected values are exact linear algebra: a consistent
// right-hand side is met to round-off, and the least-norm solution has no component along K's
// null space.
#include <gtest/gtest.h>

#include "material/free_sliding.hpp"

namespace ecm {
namespace {

// Rows 3 and 4 repeat rows 1 and 2 exactly, so LU's elimination leaves an exactly zero pivot:
// its reciprocal condition estimate is NaN, not small (a two-band fuzzing finding: NaN slipped
// past `rcond < threshold` and LU divided by the zero pivot).
Mat4 exactlySingular() {
  Mat4 k;
  k << 4.0, 1.0, 4.0, 1.0,  //
      1.0, 3.0, 1.0, 3.0,   //
      4.0, 1.0, 4.0, 1.0,   //
      1.0, 3.0, 1.0, 3.0;
  return k;
}

TEST(FreeSliding, AnExactlyZeroPivotIsSolvedLeastNorm) {
  const Mat4 k = exactlySingular();
  const Vec4 wanted(1.0, -2.0, 0.5, 3.0);
  const Vec4 b = k * wanted;
  const FreeSliding free(k, /*bothFailed=*/false);
  EXPECT_TRUE(free.active);
  const Vec4 x = solveJumps<1>(k, b, false);
  ASSERT_TRUE(x.allFinite()) << x.transpose();
  EXPECT_LT((k * x - b).norm(), 1e-12 * b.norm());
  // K's null space: jumps (a, b, -a, -b). The least-norm solution has no part of it.
  const Vec4 null1 = Vec4(1.0, 0.0, -1.0, 0.0).normalized(), null2 = Vec4(0.0, 1.0, 0.0, -1.0).normalized();
  EXPECT_LT(std::abs(null1.dot(x)), 1e-12 * x.norm());
  EXPECT_LT(std::abs(null2.dot(x)), 1e-12 * x.norm());
  EXPECT_LT(free.rangeNorm(b - k * x), 1e-12 * b.norm());
}

TEST(FreeSliding, AWellConditionedJacobianKeepsItsLU) {
  Mat4 k = exactlySingular();
  k.diagonal() += Vec4::Constant(2.0);
  const FreeSliding free(k, false);
  EXPECT_FALSE(free.active);
  const Vec4 b(1.0, 2.0, 3.0, 4.0);
  const Vec4 x = solveJumps<1>(k, b, false);
  EXPECT_EQ(x, Vec4(k.partialPivLu().solve(b)));  // bit for bit the LU it always was
}

}  // namespace
}  // namespace ecm
