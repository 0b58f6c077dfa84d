// Sub-stepping of increments whose stress return fails: rescued when smaller steps converge,
// reported clearly when they cannot.
#include "driver/mixed_control.hpp"

#include <gtest/gtest.h>

#include "../paper_constants.hpp"

namespace ecm::driver {
namespace {

const ElasticParams kElastic{test::kE, test::kNu, Hypothesis::PlaneStress};

// An elastic update that reports NotConverged for any increment larger than `limit` (norm),
// standing in for a return that only converges in small steps.
PointUpdate failsAbove(double limit, int* calls) {
  return [limit, calls](MaterialPoint& p, const Voigt& d) {
    ++*calls;
    UpdateResult r;
    if (d.norm() > limit) {
      r.status = UpdateStatus::NotConverged;
      r.residual = 1.0;
      r.iterations = 60;
      return r;
    }
    p.strain += d;
    r.stress = elasticStiffness(kElastic) * p.strain;
    r.tangent = elasticStiffness(kElastic);
    r.dissipation = 1e-3;
    return r;
  };
}

TEST(MixedControl, SubstepsAFailingIncrementUntilItConverges) {
  // 1e-4 in pieces of at most 3e-5: 4 sub-steps (two halvings); the result is the elastic one.
  int calls = 0;
  MaterialPoint p;
  MixedTarget t;
  t.control = {Control::Strain, Control::Stress, Control::Stress};
  t.strainIncrement = Voigt(1e-4, 0.0, 0.0);
  const StepOutcome out = mixedControlStep(failsAbove(3e-5, &calls), elasticStiffness(kElastic), p, Voigt::Zero(), t, {});
  ASSERT_TRUE(out.converged());
  EXPECT_EQ(out.substeps, 4);
  EXPECT_NEAR(p.strain[0], 1e-4, 1e-18);
  EXPECT_NEAR(p.strain[1], -0.2e-4, 1e-15);       // sigma_yy = 0: eps_yy = -nu eps_xx
  EXPECT_NEAR(out.result.stress[0], 3.2, 1e-9);   // E eps_xx
  EXPECT_NEAR(out.dissipation, 4e-3, 1e-15);      // summed over the sub-steps
}

TEST(MixedControl, ReportsAnIncrementThatCannotBeRescued) {
  // Never converges: after 2^10 pieces the failure comes back, with its status and residual,
  // and the point is unchanged.
  int calls = 0;
  MaterialPoint p;
  MixedTarget t;
  t.strainIncrement = Voigt(1e-4, 0.0, 0.0);
  const StepOutcome out = mixedControlStep(failsAbove(0.0, &calls), elasticStiffness(kElastic), p, Voigt::Zero(), t, {});
  EXPECT_FALSE(out.converged());
  EXPECT_EQ(out.result.status, UpdateStatus::NotConverged);
  EXPECT_EQ(out.result.residual, 1.0);
  EXPECT_EQ(p.strain, Voigt::Zero());
  EXPECT_EQ(calls, 11);  // the full step and one failing half per level, 10 levels deep
}

}  // namespace
}  // namespace ecm::driver
