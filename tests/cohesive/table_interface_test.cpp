// The table law: the band law's envelope as a table reproduces the band law, loading and
// unloading; consistent tangents; the energy to its last row; irreversibility and compression;
// an opening past the last row and tables that cannot be laws are refused.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "band_table.hpp"
#include "cohesive/interface_law.hpp"
#include "material/parameter_check.hpp"

namespace ecm::cohesive {
namespace {

// The beam's band law (data/reference/beam-band-node.yaml): E 37000, f_t' 3.9, h 0.05, (E_p, n)
// fitted to Hordijk's curve; its start softens at -E_p / h = -1213 MPa/mm.
BandInterface beamBand() { return {{37000.0, 3.9, 60.64893565, 0.2826059341}, 0.05}; }

// A small table for the mechanics: f_t' 3, a hardening segment, softening, a flat end.
TableInterface smallTable() {
  TableInterface t;
  t.opening = {0.0, 0.001, 0.01, 0.05, 0.1};
  t.traction = {3.0, 3.1, 2.0, 0.5, 0.5};
  t.initialStiffness = 640000.0;
  return t;
}

TEST(TableInterface, TheBandLawsEnvelopeAsATableReproducesTheBandLaw) {
  const BandInterface band = beamBand();
  const TableInterface table = test::bandEnvelopeTable(band);
  ASSERT_NO_THROW(table.validate());
  // Loading: on 400 openings from 1e-6 mm (elastic: the onset is at 5.3e-6 mm) to 0.5 mm, both
  // laws along the same path, each from its own state. Measured: 3e-8 of the traction at worst,
  // unloading 2e-8, the dissipation 1e-8.
  BandState bs;
  TableState ts;
  double bandDissipated = 0.0, tableDissipated = 0.0;
  std::vector<std::pair<BandState, TableState>> visited;
  for (int k = 0; k <= 400; ++k) {
    const double w = 1e-6 * std::pow(0.5 / 1e-6, k / 400.0);
    const InterfaceResponse b = updateBand(band, bs, w), t = updateTable(table, ts, w);
    EXPECT_NEAR(t.traction, b.traction, 1e-4 * b.traction) << "loading at " << w << " mm";
    bandDissipated += b.dissipation;
    tableDissipated += t.dissipation;
    if (k % 50 == 25) visited.emplace_back(bs, ts);
  }
  // The work dissipated along the way, too (the band law's exact, the table's trapezoidal).
  EXPECT_NEAR(tableDissipated, bandDissipated, 1e-4 * bandDissipated);
  // Unloading and reloading below w_max from eight states along the way, and closing (the
  // damaged secant: a closing crack gets no stiffness back).
  for (const auto& [bandState, tableState] : visited) {
    for (double f : {0.99, 0.5, 0.1, -0.3}) {
      BandState b = bandState;
      TableState t = tableState;
      const double w = f * tableState.maxOpening;
      const InterfaceResponse rb = updateBand(band, b, w), rt = updateTable(table, t, w);
      EXPECT_NEAR(rt.traction, rb.traction, 1e-4 * std::abs(rb.traction)) << "unloading to " << w << " mm";
      EXPECT_NEAR(rt.tangent, rb.tangent, 1e-4 * rb.tangent) << "unloading to " << w << " mm";
      EXPECT_EQ(rt.dissipation, 0.0);
      EXPECT_EQ(t.maxOpening, tableState.maxOpening);
    }
  }
}

// dt/d delta by central differences from the same state at the start of the increment.
double numericalTangent(const TableInterface& p, const TableState& start, double jump) {
  const double step = 1e-7 * jump;  // inside one segment at the openings below
  TableState a = start, b = start;
  return (updateTable(p, a, jump + step).traction - updateTable(p, b, jump - step).traction) / (2.0 * step);
}

TEST(TableInterface, TangentMatchesFiniteDifferencesOnLoadingAndUnloading) {
  const TableInterface p = smallTable();
  for (double w : {2e-6, 0.0005, 0.005, 0.03, 0.07}) {  // elastic, hardening, softening, softening, flat
    TableState start;
    start.maxOpening = 0.5 * w;
    TableState s = start;
    const InterfaceResponse r = updateTable(p, s, w);
    EXPECT_NEAR(r.tangent, numericalTangent(p, start, w), 1e-6 * std::max(std::abs(r.tangent), 1.0)) << "loading at " << w;
    EXPECT_EQ(s.maxOpening, w);
    const InterfaceResponse u = updateTable(p, s, 0.6 * w);
    EXPECT_NEAR(u.tangent, numericalTangent(p, s, 0.6 * w), 1e-6 * u.tangent) << "unloading at " << w;
    EXPECT_NEAR(u.tangent, tableEnvelope(p, w) / w, 1e-12 * u.tangent);  // the secant to the origin
  }
  // The elastic line meets the first segment at w_e = T_0 / (K0 - s_0).
  EXPECT_NEAR(p.elasticLimit(), 3.0 / (640000.0 - 100.0), 1e-18);
  EXPECT_NEAR(tableEnvelope(p, p.elasticLimit()), 640000.0 * p.elasticLimit(), 1e-12);
}

TEST(TableInterface, DissipatesTheAreaUnderItsEnvelopeToTheLastRow) {
  const TableInterface p = smallTable();
  // By hand: the triangle to w_e, then the trapezoids.
  const double we = p.elasticLimit(), twe = 640000.0 * we;
  const double area = 0.5 * twe * we + 0.5 * (twe + 3.1) * (0.001 - we) + 0.5 * (3.1 + 2.0) * 0.009 + 0.5 * (2.0 + 0.5) * 0.04 +
                      0.5 * (0.5 + 0.5) * 0.05;
  InterfaceLaw law;
  law.kind = LawKind::table;
  law.table = p;
  EXPECT_NEAR(law.energyToFailure(), area, 1e-15);
  EXPECT_EQ(law.tensileStrength(), 3.0);
  // Along the envelope in uneven increments that straddle rows, the dissipation plus the energy
  // stored at the end is the work, the area under the envelope.
  TableState s;
  double dissipated = 0.0, stored = 0.0;
  for (int k = 1; k <= 137; ++k) {
    const InterfaceResponse r = updateTable(p, s, 0.1 * std::pow(k / 137.0, 1.5));
    EXPECT_GE(r.dissipation, 0.0);
    dissipated += r.dissipation;
    stored = r.stored;
  }
  EXPECT_NEAR(dissipated + stored, area, 1e-14);
  EXPECT_NEAR(stored, 0.5 * 0.5 * 0.1, 1e-15);
  // The elastic line dissipates nothing.
  TableState fresh;
  EXPECT_EQ(updateTable(p, fresh, 0.9 * we).dissipation, 0.0);
}

TEST(TableInterface, IsIrreversibleAndClosesAlongTheDamagedSecant) {
  const TableInterface p = smallTable();
  TableState s;
  const InterfaceResponse loaded = updateTable(p, s, 0.03);
  EXPECT_NEAR(loaded.traction, 2.0 - 1.5 * 0.5, 1e-14);  // T(0.03) on the segment 2.0 -> 0.5
  TableState back = s;
  const InterfaceResponse unloaded = updateTable(p, back, 0.01);
  EXPECT_EQ(back.maxOpening, 0.03);
  EXPECT_NEAR(unloaded.traction, loaded.traction / 3.0, 1e-14);
  TableState reload = back;
  EXPECT_NEAR(updateTable(p, reload, 0.03).traction, loaded.traction, 1e-14);
  // Compression keeps the secant (the band law's x E / h), no damage, no dissipation.
  TableState closed = s;
  const InterfaceResponse c = updateTable(p, closed, -0.001);
  EXPECT_NEAR(c.traction, -0.001 * loaded.traction / 0.03, 1e-15);
  EXPECT_EQ(c.dissipation, 0.0);
  EXPECT_EQ(closed.maxOpening, 0.03);
  // Undamaged: K0 both ways.
  TableState fresh;
  EXPECT_DOUBLE_EQ(updateTable(p, fresh, -1e-5).traction, -1e-5 * 640000.0);
  EXPECT_EQ(updateTable(p, fresh, 1e-6).tangent, 640000.0);
}

TEST(TableInterface, RefusesAnOpeningPastItsLastRow) {
  TableInterface p = smallTable();
  p.source = "law.csv";
  TableState s;
  updateTable(p, s, 0.1);  // the last row itself is on the table
  try {
    updateTable(p, s, 0.1000001);
    FAIL() << "no error past the table's end";
  } catch (const InterfaceLawError& e) {
    const std::string m = e.what();
    EXPECT_NE(m.find("opening 0.1000001 mm"), std::string::npos) << m;
    EXPECT_NE(m.find("law.csv"), std::string::npos) << m;
    EXPECT_NE(m.find("0.1 mm"), std::string::npos) << m;
  }
  EXPECT_EQ(s.maxOpening, 0.1);  // the state is left as it was
}

TEST(TableInterface, RefusesTablesThatCannotBeALaw) {
  const auto rowError = [](TableInterface t) -> std::size_t {
    try {
      t.checkRows();
    } catch (const TableRowError& e) {
      return e.row;
    }
    return 99;
  };
  TableInterface t = smallTable();
  EXPECT_NO_THROW(t.validate());
  t.opening[3] = 0.005;  // below the row before
  EXPECT_EQ(rowError(t), 3u);
  t = smallTable();
  t.traction[2] = -0.1;
  EXPECT_EQ(rowError(t), 2u);
  t = smallTable();
  t.opening[0] = 1e-4;
  EXPECT_EQ(rowError(t), 0u);
  t = smallTable();
  t.traction[0] = 0.0;
  EXPECT_EQ(rowError(t), 0u);
  t.opening = {0.0};
  t.traction = {3.0};
  EXPECT_EQ(rowError(t), 0u);
  // K0 w must stay above the table from its second row: 3.1 MPa at 0.001 mm needs K0 > 3100.
  t = smallTable();
  t.initialStiffness = 3000.0;
  EXPECT_THROW(t.checkStiffness(), ParameterError);
  t.initialStiffness = 3200.0;
  EXPECT_NO_THROW(t.checkStiffness());
}

}  // namespace
}  // namespace ecm::cohesive
