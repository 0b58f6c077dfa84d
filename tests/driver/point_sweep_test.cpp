// The point driver over the whole range of effective sizes and increment sizes: every run
// completes, shows its onset and its peak, reports a snap-back exactly where the closed form's
// macro curve turns back, with a positive stress drop, and dissipates G_F once the band has failed.
#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <vector>

#include "driver/point_driver.hpp"
#include "io/value_error.hpp"
#include "../paper_constants.hpp"
#include "material/uniaxial_closed_form.hpp"

namespace ecm::driver {
namespace {

struct Case {
  std::string path;  // preset
  double nu;
  double size;       // H (mm)
  int increments;    // per segment
};

PointScene sweepScene(const Case& c) {
  PointScene s;
  s.material.name = "den-concrete";
  s.material.model = ModelKind::Enriched;
  s.material.elastic = {test::kE, c.nu, Hypothesis::PlaneStress};
  s.material.tensileStrength = test::kFt;
  s.material.softeningModulus = test::kEp;
  s.material.softeningExponent = test::kN;
  s.material.bandWidth = test::kBandWidth;
  s.effectiveSize = c.size;
  PresetPath p;
  p.name = c.path;
  p.strain = 5e-2;  // far beyond failure for H >= 10 mm; the sweep's path in docs/point-driver.md
  p.shear = 5e-2;
  p.increments = c.increments;
  s.path = presetSegments(p, c.nu);
  return s;
}

// The closed form's snap-back size for a uniaxial path (material/uniaxial_closed_form.hpp).
double closedFormSnapBackSize(const std::string& path, double nu) {
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  if (path == "uniaxial_strain") {
    const double a11 = test::kE / (1.0 - nu * nu);  // plane stress
    return snapBackEffectiveSize([&](double x) { return uniaxialStrainBandResponse(law, a11, test::kBandWidth, x); }, a11);
  }
  return snapBackEffectiveSize([&](double x) { return uniaxialBandResponse(law, nu, test::kBandWidth, x); }, test::kE);
}

// The largest stress of the band's curve in uniaxial tension (closed form, scanned in log x and
// refined by golden section): f_t' for nu = 0, 3.0570 MPa for nu = 0.2.
double tensionPeak(double nu) {
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  const auto stress = [&](double lx) { return uniaxialBandResponse(law, nu, test::kBandWidth, std::pow(10.0, lx)).stress; };
  double best = stress(0.0), at = 0.0;
  for (double lx = -1e-3; lx > -14.0; lx -= 1e-3)
    if (stress(lx) > best) best = stress(lx), at = lx;
  const double g = 0.5 * (std::sqrt(5.0) - 1.0);
  double lo = at - 1e-3, hi = std::min(at + 1e-3, 0.0);
  for (int it = 0; it < 60; ++it) {
    const double a = hi - g * (hi - lo), b = lo + g * (hi - lo);
    if (stress(a) > stress(b)) hi = b;
    else lo = a;
  }
  return std::max(best, stress(0.5 * (lo + hi)));
}

TEST(PointSweep, ClosedFormSnapBackSizes) {
  // nu = 0: the 1D law, h (E + E_p) / E_p = 195.56 mm (its steepest point is the onset).
  // The scan starts a hair inside the curve (x = 1 - 2e-5), so it sees a slope 1e-6 flatter.
  EXPECT_NEAR(closedFormSnapBackSize("uniaxial_tension", 0.0), test::kBandWidth * (test::kE + test::kEp) / test::kEp, 1e-3);
  EXPECT_NEAR(closedFormSnapBackSize("uniaxial_strain", 0.0), test::kBandWidth * (test::kE + test::kEp) / test::kEp, 1e-3);
  // nu = 0.2 in tension: 323.65 mm (docs/point-driver.md; a scan in steps of 0.1 % in log x gives 323.6495).
  EXPECT_NEAR(closedFormSnapBackSize("uniaxial_tension", 0.2), 323.6495, 1e-3);
  // The traction's maximum: f_t' at onset for nu = 0; 3.0570 MPa for nu = 0.2 (docs/point-driver.md), below
  // the laterally constrained bound f_t' / sqrt(1 - nu^2) = 3.0619 MPa.
  EXPECT_NEAR(tensionPeak(0.0), test::kFt, 1e-12);
  EXPECT_NEAR(tensionPeak(0.2), 3.0570, 1e-4);
}

// Increment counts of the sweep. A sanitised Debug build, some 100 times slower, leaves out the
// 20000 (its memory checks see the same code paths at 200).
#ifdef NDEBUG
constexpr int kIncrementCounts[] = {1, 2, 10, 200, 20000};
#else
constexpr int kIncrementCounts[] = {1, 2, 10, 200};
#endif
constexpr int kMostIncrements = 20000;

// One path of the sweep, both Poisson's ratios.
void sweep(const std::string& path) {
  const DamageLawParams law{test::kE, test::kFt, test::kEp, test::kN};
  const double fractureEnergy = test::kBandWidth * dissipationToFailure(law);  // G_F of the law itself
  const std::vector<double> sizes = {minimumEffectiveSize(test::kBandWidth), 1.0, 10.0, 195.0, 197.0,
                                     323.0, 325.0, 1e3, 1e4, 1e6};
  std::ostringstream table;
  table << "path nu H increments | peak onset snapback drop H*diss/G_F\n";
  int runs = 0;
  for (double nu : {0.0, 0.2}) {
    const double snapSize = closedFormSnapBackSize(path == "uniaxial_strain" ? path : "uniaxial_tension", nu);
    for (double size : sizes)
      for (int increments : kIncrementCounts) {
        if (increments == kMostIncrements && path == "tension_then_shear") continue;  // two segments: covered by the others
        const Case c{path, nu, size, increments};
        const PointScene scene = sweepScene(c);
        const PointRun run = runPoint(scene);
        const PointSummary s = summarise(scene, run);
        ++runs;
        std::ostringstream where;
        where << path << " nu=" << nu << " H=" << size << " increments=" << increments;
        ASSERT_TRUE(run.completed) << where.str() << ": " << run.failure;
        // The onset has its own row (f_t' in tension, f_t'/sqrt(1 - nu^2) in uniaxial strain).
        ASSERT_GT(s.onsetStress, 0.0) << where.str();
        EXPECT_GE(s.peakStress, s.onsetStress) << where.str();
        const double onsetExpected = path == "uniaxial_strain" ? test::kFt / std::sqrt(1.0 - nu * nu) : test::kFt;
        // The peak, even inside an increment: the band curve's maximum (tension: the traction
        // rises after onset when nu > 0); a maximum is flat, so its golden section gives it to
        // far better than 1e-6 f_t'.
        const double peakExpected = path == "uniaxial_strain" ? onsetExpected : tensionPeak(nu);
        EXPECT_NEAR(s.peakStress, peakExpected, 1e-6 * test::kFt) << where.str();
        // To the traction tolerance of the material, 1e-10 f_t' + 1e-13 |a eps| f / (1 - f)
        // near f = 1 (two_phase_point.cpp): 3e-7 MPa at the smallest H.
        const double f = test::kBandWidth / size;
        EXPECT_NEAR(s.onsetStress, onsetExpected, 1e-9 * onsetExpected + 2e-13 * onsetExpected / (1.0 - f)) << where.str();
        // Snap-back exactly where the closed form's macro curve turns back (the tension
        // segment decides for tension_then_shear: H <= 10 mm never fails in tension).
        if (path != "tension_then_shear" || size > 100.0) {
          EXPECT_EQ(run.snapBack.detected, size > snapSize) << where.str() << " (closed form: " << snapSize << " mm)";
        }
        if (run.snapBack.detected) {
          EXPECT_TRUE(run.snapBack.jumped) << where.str();
          EXPECT_GT(run.snapBack.stressBefore - run.snapBack.stressAfter, 0.0) << where.str();
        }
        // Once the band has failed, H x dissipation = G_F (MODEL identity: h int_0^1 F dD).
        const HistoryRow& last = run.history.back();
        const Vec2 n = last.crackNormal;
        const double traction = std::hypot(n[0] * last.stress[0] + n[1] * last.stress[2], n[0] * last.stress[2] + n[1] * last.stress[1]);
        double ratio = s.energyPerArea / fractureEnergy;
        if (traction < 1e-4 * test::kFt) EXPECT_NEAR(ratio, 1.0, 1e-3) << where.str();
        else ratio = NAN;
        table << path << " " << nu << " " << size << " " << increments << " | " << s.peakStress << " "
              << s.onsetStress << " " << run.snapBack.detected << " "
              << (run.snapBack.detected ? run.snapBack.stressBefore - run.snapBack.stressAfter : 0.0) << " " << ratio << "\n";
      }
  }
  ::testing::Test::RecordProperty("runs", runs);
  std::cout << table.str();
}

TEST(PointSweep, EveryEffectiveSizeAndIncrementSizeTellsTheTruthInUniaxialTension) { sweep("uniaxial_tension"); }
TEST(PointSweep, EveryEffectiveSizeAndIncrementSizeTellsTheTruthInUniaxialStrain) { sweep("uniaxial_strain"); }
TEST(PointSweep, EveryEffectiveSizeAndIncrementSizeTellsTheTruthInTensionThenShear) { sweep("tension_then_shear"); }

TEST(PointSweep, AtTheSmallestEffectiveSizeThePointIsThePureBandAsTheSmearedCrack) {
  // f = 1 / (1 + 1e-6): the bulk holds a millionth of the point, so the macro strain is the
  // band's; with nu = 0 the band is the 1D law, which is the smeared crack with the band's own
  // E_p (the same law on the whole strain). Both to eps = 2e-3 (band opening 1e-4 mm, on the
  // softening branch near 0.9 f_t', MODEL identities) in 400 increments.
  const Case c{"uniaxial_tension", 0.0, minimumEffectiveSize(test::kBandWidth), 400};
  PointScene enriched = sweepScene(c);
  for (Segment& s : enriched.path) s.target[0] = 2e-3;
  PointScene smeared = enriched;
  smeared.material.model = ModelKind::SmearedCrack;
  const PointRun a = runPoint(enriched), b = runPoint(smeared);
  ASSERT_TRUE(a.completed) << a.failure;
  ASSERT_TRUE(b.completed) << b.failure;
  // Rows of the end of each increment (the onset rows differ by the 1e-13 past the root).
  std::vector<const HistoryRow*> ra, rb;
  for (const HistoryRow& r : a.history) if (r.event == 0) ra.push_back(&r);
  for (const HistoryRow& r : b.history) if (r.event == 0) rb.push_back(&r);
  ASSERT_EQ(ra.size(), rb.size());
  double worst = 0.0;
  for (std::size_t i = 0; i < ra.size(); ++i) {
    ASSERT_NEAR(ra[i]->strain[0], rb[i]->strain[0], 1e-15);
    worst = std::max(worst, std::abs(ra[i]->stress[0] - rb[i]->stress[0]));
  }
  // The bulk's share moves the band strain by (1 - f)(eps_b - eps_L) ~ 1e-6 eps: 1e-6 of the
  // stress at most, on the tolerance floor of f near 1 (3e-7 MPa, docs/model.md).
  EXPECT_LT(worst, 1e-5 * test::kFt);
  EXPECT_GT(b.history.back().damage, 0.9);  // well into softening, so the comparison means something
}

TEST(PointSweep, AnEffectiveSizeBelowTheBoundIsRefusedBeforeRunning) {
  // H = h (1 + 1e-9): the bound is h (1 + 1e-6) (docs/model.md).
  const Case c{"uniaxial_tension", 0.2, test::kBandWidth * (1.0 + 1e-9), 10};
  try {
    runPoint(sweepScene(c));
    FAIL() << "expected a refusal";
  } catch (const io::ValueError& e) {
    EXPECT_EQ(e.key, "effective_size");
    EXPECT_NE(std::string(e.what()).find("0.05000005"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace ecm::driver
