// The two traction-opening laws of the cohesive reference: consistent tangents against central
// finite differences, the energy to complete failure, irreversibility and compression.
#include <gtest/gtest.h>

#include <cmath>

#include "cohesive/band_interface.hpp"
#include "cohesive/hordijk_interface.hpp"
#include "material/parameter_check.hpp"

namespace ecm::cohesive {
namespace {

// The paper's DEN concrete (docs/model.md): h int F dD = 0.1100 N/mm.
BandInterface denBand() { return {{32000.0, 3.0, 8.184, 0.128}, 0.05}; }
// Hordijk's curve for the same concrete behind K0 = E/h.
HordijkInterface denHordijk() { return {3.0, 0.11, 32000.0 / 0.05}; }

// dt/d delta by central differences from the same state at the start of the increment.
template <class Law, class State, class Update>
double numericalTangent(const Law& law, const State& start, double jump, Update update) {
  const double step = 1e-5 * std::abs(jump);  // round-off ~1e-16 t / step stays below 1e-8 t
  State a = start, b = start;
  return (update(law, a, jump + step).traction - update(law, b, jump - step).traction) / (2.0 * step);
}

TEST(BandInterface, TangentMatchesFiniteDifferencesOnLoadingAndUnloading) {
  const BandInterface p = denBand();
  const double onset = p.bandWidth * 3.0 / 32000.0;  // delta at f_t'
  for (double factor : {1.5, 3.0, 10.0, 100.0, 1000.0}) {
    BandState start;  // loading from the undamaged state (the increment crosses the onset)
    BandState s = start;
    const double jump = factor * onset;
    const double tangent = updateBand(p, s, jump).tangent;
    EXPECT_NEAR(tangent, numericalTangent(p, start, jump, updateBand), 1e-6 * std::abs(tangent)) << "loading at " << factor;
    // Unloading from there: the secant x E / h.
    BandState damaged = s;
    BandState u = damaged;
    const double t = updateBand(p, u, 0.5 * jump).tangent;
    EXPECT_NEAR(t, numericalTangent(p, damaged, 0.5 * jump, updateBand), 1e-6 * t) << "unloading at " << factor;
    EXPECT_NEAR(t, damaged.integrity * 32000.0 / 0.05, 1e-12 * t);
  }
}

TEST(BandInterface, DissipatesItsFractureEnergyToCompleteFailure) {
  const BandInterface p = denBand();
  // docs/model.md: h int_0^1 F dD = 0.1100 N/mm for the DEN concrete (0.110036 by ecm-calibrate).
  EXPECT_NEAR(bandFractureEnergy(p), 0.110036, 2e-6);
  // Monotonic loading to x = 1e-14 in increments of x: the sum of the increments' dissipation
  // plus the energy still stored equals h int F dD (the rest, ~x^(1-2n), is below 1e-8 of it).
  // Independently, the work int t d delta (trapezoidal on a fine path) approaches it too.
  BandState s;
  double dissipated = 0.0, work = 0.0, lastJump = 0.0, lastTraction = 0.0, stored = 0.0;
  for (int k = 0; k <= 20000; ++k) {
    const double x = std::pow(10.0, -14.0 * k / 20000.0);
    const double jump = p.bandWidth * std::sqrt(2.0 * damageFunction(p.law, x) / p.law.youngsModulus) * (1.0 + 1e-13);
    const InterfaceResponse r = updateBand(p, s, jump);
    dissipated += r.dissipation;
    stored = r.stored;
    work += 0.5 * (r.traction + lastTraction) * (jump - lastJump);
    lastJump = jump;
    lastTraction = r.traction;
  }
  EXPECT_NEAR((dissipated + stored) / bandFractureEnergy(p), 1.0, 1e-7);
  EXPECT_NEAR(work / bandFractureEnergy(p), 1.0, 1e-4);
}

TEST(BandInterface, DamageIsIrreversibleAndClosingGetsNoStiffnessBack) {
  const BandInterface p = denBand();
  BandState s;
  const double jump = 20.0 * p.bandWidth * 3.0 / 32000.0;
  const InterfaceResponse loaded = updateBand(p, s, jump);
  const double x = s.integrity;
  ASSERT_LT(x, 1.0);
  BandState back = s;
  const InterfaceResponse unloaded = updateBand(p, back, 0.5 * jump);
  EXPECT_EQ(back.integrity, x);
  EXPECT_EQ(unloaded.dissipation, 0.0);
  EXPECT_NEAR(unloaded.traction, 0.5 * loaded.traction, 1e-14 * loaded.traction);
  // Compression: the damaged stiffness x E / h (the spectral split acts on Y only), no damage.
  BandState closed = s;
  const InterfaceResponse c = updateBand(p, closed, -jump);
  EXPECT_EQ(closed.integrity, x);
  EXPECT_NEAR(c.traction, -loaded.traction, 1e-14 * loaded.traction);
  EXPECT_EQ(c.dissipation, 0.0);
}

TEST(HordijkInterface, TangentMatchesFiniteDifferencesOnLoadingAndUnloading) {
  const HordijkInterface p = denHordijk();
  const double wc = p.criticalOpening();
  for (double w : {0.01, 0.05, 0.2, 0.5, 0.9}) {
    HordijkState start;
    start.cracked = true;
    start.maxOpening = 0.5 * w * wc;  // the increment loads from there
    const double jump = w * wc + hordijkTraction(p, w * wc) / p.initialStiffness;
    HordijkState s = start;
    const double tangent = updateHordijk(p, s, jump).tangent;
    EXPECT_NEAR(tangent, numericalTangent(p, start, jump, updateHordijk), 1e-6 * std::abs(tangent)) << "loading at w/wc " << w;
    EXPECT_NEAR(s.maxOpening, w * wc, 1e-12 * wc);
    HordijkState damaged = s, u = s;
    const double t = updateHordijk(p, u, 0.7 * jump).tangent;
    EXPECT_NEAR(t, numericalTangent(p, damaged, 0.7 * jump, updateHordijk), 1e-6 * t) << "unloading at w/wc " << w;
    EXPECT_NEAR(t, hordijkTraction(p, w * wc) / jump, 1e-12 * t);  // secant to the origin
  }
}

TEST(HordijkInterface, DissipatesTheAreaUnderTheCurveCutAtWc) {
  const HordijkInterface p = denHordijk();
  const double wc = p.criticalOpening();
  // The area under T(w) on [0, wc] by composite Simpson (independent of the closed form).
  const int n = 20000;
  double simpson = hordijkTraction(p, 0.0) + hordijkTraction(p, wc * (1.0 - 1e-15));
  for (int k = 1; k < n; ++k) simpson += (k % 2 ? 4.0 : 2.0) * hordijkTraction(p, wc * k / n);
  simpson *= wc / n / 3.0;
  EXPECT_NEAR(hordijkArea(p, wc), simpson, 1e-12 * simpson);
  // The curve ends at wc with T = 0: its area is G_F times 1.000768, not 1 (5.14 x the integral
  // of the normalised curve on [0, 1], 0.194702...; Simpson with 1e5 cells in Python gives
  // 1.000768041721147).
  EXPECT_NEAR(hordijkAreaFactor(), simpson / p.fractureEnergy, 1e-12);
  EXPECT_NEAR(hordijkAreaFactor(), 1.000768041721147, 1e-12);
  // Along the envelope to past wc, the dissipation increments add up to the area.
  HordijkState s;
  double dissipated = 0.0;
  for (int k = 1; k <= 4000; ++k) dissipated += updateHordijk(p, s, 1.1 * wc * k / 4000.0).dissipation;
  EXPECT_NEAR(dissipated, simpson, 1e-12 * simpson);
  EXPECT_EQ(updateHordijk(p, s, 2.0 * wc).traction, 0.0);
}

TEST(HordijkInterface, IsIrreversibleAndClosesWithFullStiffness) {
  const HordijkInterface p = denHordijk();
  HordijkState s;
  const double jump = 0.2 * p.criticalOpening();
  const InterfaceResponse loaded = updateHordijk(p, s, jump);
  const double wMax = s.maxOpening;
  HordijkState back = s;
  const InterfaceResponse unloaded = updateHordijk(p, back, 0.25 * jump);
  EXPECT_EQ(back.maxOpening, wMax);
  EXPECT_EQ(unloaded.dissipation, 0.0);
  EXPECT_NEAR(unloaded.traction, 0.25 * loaded.traction, 1e-14 * loaded.traction);
  HordijkState reload = back;
  EXPECT_NEAR(updateHordijk(p, reload, jump).traction, loaded.traction, 1e-12 * loaded.traction);
  // Compression: contact with K0, no damage.
  HordijkState closed = s;
  const InterfaceResponse c = updateHordijk(p, closed, -1e-4);
  EXPECT_EQ(c.traction, -1e-4 * p.initialStiffness);
  EXPECT_EQ(closed.maxOpening, wMax);
  // Up to f_t': elastic with K0.
  HordijkState fresh;
  EXPECT_NEAR(updateHordijk(p, fresh, 0.99 * 3.0 / p.initialStiffness).traction, 0.99 * 3.0, 1e-12);
  EXPECT_FALSE(fresh.cracked);
}

TEST(HordijkInterface, RefusesAStiffnessBelowTheCurvesSteepestSlope) {
  HordijkInterface p = denHordijk();
  p.initialStiffness = 50.0;  // Hordijk's slope at w = 0: -(c2 + 28 e^-c2) f_t/wc = -110.8 MPa/mm here
  EXPECT_THROW(p.validate(), ParameterError);
  p.initialStiffness = 120.0;
  EXPECT_NO_THROW(p.validate());
}

}  // namespace
}  // namespace ecm::cohesive
