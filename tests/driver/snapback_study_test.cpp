// The snap-back study on a reduced set of effective sizes: what it is meant to show.
#include "driver/snapback_study.hpp"

#include <gtest/gtest.h>

#include <sstream>

#include "io/temp_dir.hpp"
#include "../paper_constants.hpp"

namespace ecm::driver {
namespace {

TEST(SnapBackStudy, EnrichedCurveIsOneForAllSizesAndTheSmearedCrackIsRefusedBeyondHcrit) {
  test::TempDir dir;
  SnapBackStudy s;
  s.material.name = "den-concrete";
  s.material.model = ModelKind::Enriched;
  s.material.elastic = {test::kE, test::kNu, Hypothesis::PlaneStress};
  s.material.tensileStrength = test::kFt;
  s.material.softeningModulus = test::kEp;
  s.material.softeningExponent = test::kN;
  s.material.bandWidth = test::kBandWidth;
  s.material.fractureEnergy = test::kGF;
  s.effectiveSizes = {1.0, 100.0, 500.0, 1000.0};
  s.strainIncrements = 200;
  s.openingIncrements = 300;
  std::ostringstream table;
  const SnapBackStudyResult r = runSnapBackStudy(s, dir.path(), table);
  ASSERT_TRUE(r.allRunsCompleted);
  ASSERT_EQ(r.rows.size(), 4u);
  // h (E + E_p)/E_p (docs/model.md, identities) and 2 E G_F / f_t'^2.
  EXPECT_NEAR(r.snapBackSize1D, test::kSnapBackSize, 1e-12);
  EXPECT_NEAR(r.criticalSize, 2 * test::kE * test::kGF / (test::kFt * test::kFt), 1e-9);
  // The band's curve with nu = 0.2 (closed form in material/uniaxial_closed_form.hpp) is
  // steeper: its snap-back size lies between 100 and 500 mm.
  EXPECT_GT(r.snapBackSize, 100.0);
  EXPECT_LT(r.snapBackSize, 500.0);
  const double gfBand = test::kBandWidth * dissipationToFailure({test::kE, test::kFt, test::kEp, test::kN});
  for (const StudyRow& row : r.rows) {
    SCOPED_TRACE("H = " + std::to_string(row.effectiveSize));
    EXPECT_LE(row.tractionOpeningError, 0.005);            // one traction-opening curve: <= 0.5% f_t'
    EXPECT_NEAR(row.energyRatio * test::kGF, gfBand, 0.01 * gfBand);  // H W = G_F within 1%
    EXPECT_LE(row.closedFormStressError, 1e-8);
    EXPECT_LE(row.closedFormStrainError, 1e-8);
    const bool beyond = row.effectiveSize > r.snapBackSize;
    EXPECT_EQ(row.macroSnapsBack, beyond);
    EXPECT_EQ(row.strainControlSnapBack, beyond);
    if (beyond) {
      EXPECT_GT(row.snapBackStressDrop, 0.0);
    }
    EXPECT_EQ(row.smearedRegularised, row.effectiveSize < r.criticalSize);
    if (!row.smearedRegularised) {
      EXPECT_NEAR(row.requiredStrength, std::sqrt(2 * test::kE * test::kGF / row.effectiveSize), 1e-12);
    } else {
      EXPECT_NEAR(row.smearedEnergyRatio, 1.0, 0.01);  // crack band: G_F / H per volume
      EXPECT_GT(row.smearedTractionOpeningError, 0.005);  // its curve differs from the band's
    }
  }
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "summary.json"));
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "study.csv"));
}

}  // namespace
}  // namespace ecm::driver
