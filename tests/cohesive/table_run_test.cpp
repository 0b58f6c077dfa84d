// The table law in the structure: the notched beam with the band law's envelope as a table gives
// the band law's curve; table runs balance their energy like the other laws; a run that opens
// the interface past the table's last row stops and says where.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "band_table.hpp"
#include "cohesive/report.hpp"
#include "cohesive/scene.hpp"
#include "cohesive/solver.hpp"
#include "test_scenes.hpp"

namespace ecm::cohesive {
namespace {

const std::filesystem::path kReference = std::filesystem::path(ECM_SOURCE_DIR) / "data/reference";

using test::Curve;
Curve curve(const Scene& s) { return test::curveOf(s); }

// data/reference/beam-band-node.yaml on the 2.5 mm mesh at its own steps (max CMOD step
// 0.0002 mm, to 0.3), with its band law and with that law's envelope as a table (20001 rows to
// 0.5 mm). Measured: 1145.0014 / 821.5843 / 441.7428 N (band) and 1145.0015 / 821.5843 /
// 441.7429 N (table), energy balance 1.06e-6 of the work at the end for both.
TEST(CohesiveTable, TheBandLawsEnvelopeAsATableGivesTheBandLawsBeam) {
  const Scene band = readScene(kReference / "beam-band-node.yaml", {2.5, std::nullopt});
  Scene table = band;
  table.law.kind = LawKind::table;
  table.law.table = test::bandEnvelopeTable(band.law.band);
  ASSERT_NO_THROW(table.law.table.validate());
  const Curve b = curve(band), t = curve(table);
  EXPECT_NEAR(t.peak, b.peak, 0.002 * b.peak);
  EXPECT_NEAR(t.at01, b.at01, 0.002 * b.at01);
  EXPECT_NEAR(t.at02, b.at02, 0.002 * b.at02);
  // The energy balance at the scene's default steps, as for the other laws (< 3e-6 of the work
  // at the end: CohesiveBeam.EnergyBalancesToThreeMillionthsOfTheWorkAtTheDefaultSteps).
  EXPECT_LT(t.finalBalance, 3e-6);
}

// The reference scene with ecm's point law (data/reference/beam-point-node.yaml, its table read
// from data/reference/beam-point-law.csv) on the 2.5 mm mesh: the energy balances as for the other
// laws (measured 9.7e-7 of the work at the end).
TEST(CohesiveTable, ThePointLawsBeamBalancesItsEnergy) {
  const Scene s = readScene(kReference / "beam-point-node.yaml", {2.5, std::nullopt});
  ASSERT_EQ(s.law.kind, LawKind::table);
  EXPECT_LT(curve(s).finalBalance, 3e-6);
}

// A bar whose table ends at 0.02 mm, pulled to 0.05 mm: the run stops at the smallest step with
// the law's message (the opening and where the table ends), and keeps what converged.
TEST(CohesiveTable, ARunPastTheTablesEndStopsAndNamesTheOpening) {
  Scene s = test::barScene(LawKind::band, 0.05, 0.001);
  s.law.kind = LawKind::table;
  s.law.table = test::bandEnvelopeTable(s.law.band, 2000, 0.02);
  try {
    solveControlled(buildModel(s), s.law, s.solver);
    FAIL() << "the run went past the table's end";
  } catch (const SolveFailure& f) {
    const std::string m = f.what();
    EXPECT_NE(m.find("past the end of the traction-opening table band-envelope.csv"), std::string::npos) << m;
    EXPECT_NE(m.find("(its last row is at 0.02 mm)"), std::string::npos) << m;
    EXPECT_NE(m.find("opening 0.02"), std::string::npos) << m;
    ASSERT_FALSE(f.partial.history.empty());
    EXPECT_GT(f.partial.history.back().control, 0.015);  // the jump is most of the elongation
    EXPECT_LE(f.partial.history.back().control, 0.05);
  }
}

}  // namespace
}  // namespace ecm::cohesive
