// ecm-point's driver: elastic closed forms, mixed control, the enriched point against its
// closed form, the energy identity, snap-back detection and tracing, cyclic secant unloading.
#include <algorithm>

#include "driver/mixed_control.hpp"
#include "driver/point_driver.hpp"
#include "driver/point_output.hpp"
#include "driver/point_scene_yaml.hpp"
#include "io/csv_reader.hpp"
#include "io/temp_dir.hpp"

#include <gtest/gtest.h>

#include "../paper_constants.hpp"
#include "material/uniaxial_closed_form.hpp"

namespace ecm::driver {
namespace {

MaterialParams concrete(ModelKind kind, double nu = test::kNu) {
  MaterialParams p{.name = "den-concrete", .model = kind, .elastic = {test::kE, nu, Hypothesis::PlaneStress},
                   .tensileStrength = test::kFt, .softeningModulus = test::kEp, .softeningExponent = test::kN,
                   .bandWidth = test::kBandWidth, .fractureEnergy = test::kGF};
  return p;
}

PresetPath preset(const std::string& name, double strain, int increments) {
  PresetPath p;
  p.name = name;
  p.strain = strain;
  p.increments = increments;
  return p;
}

PointScene scene(ModelKind kind, double bigH, const PresetPath& preset, double nu = test::kNu) {
  PointScene s;
  s.material = concrete(kind, nu);
  s.effectiveSize = bigH;
  s.path = presetSegments(preset, nu);
  return s;
}

const DamageLawParams kLaw{test::kE, test::kFt, test::kEp, test::kN};

TEST(PointDriver, ARowThatIsNotANumberEndsTheRunAndNamesItsIncrement) {
  // E eps overflows a double (32000 x 1e305): the first increment's stress is infinite and its
  // work NaN. The run stops there, names the increment, and keeps the rows before it.
  PointRun run = runPoint(scene(ModelKind::LinearElastic, 10.0, preset("uniaxial_strain", 1e305, 4)));
  EXPECT_FALSE(run.completed);
  EXPECT_NE(run.failure.find("increment 1 (segment 1)"), std::string::npos) << run.failure;
  EXPECT_NE(run.failure.find("not a number"), std::string::npos) << run.failure;
  ASSERT_EQ(run.history.size(), 1u);
  EXPECT_EQ(run.history[0].increment, 0);
}

TEST(PointDriver, AHugeIncrementAtDamageNearOneStaysANumber) {
  // Found by fuzz/fuzz_point_scene.cpp: after a tension path to D = 0.993, increments of strain
  // 4e22 gave an integrity of -4e-121 (the stress changed sign) and a NaN dissipation, and the run
  // said it had completed. Now each band fails completely (integrity in [0, 1e-100]) and the
  // dissipation stays a number, at most the two bands' whole energy: H x (dissipation per volume)
  // <= 2 h g_f, g_f the band law's energy per band volume to failure (docs/model.md, identities).
  const PointScene s = readPointScene(io::parseYaml(R"(
name: huge-increment
material: {model: enriched, hypothesis: plane_stress, youngs_modulus: 41246, poisson_ratio: 0.15, tensile_strength: 2.5,
           softening_modulus: 12, softening_exponent: 0.2, band_width: 0.1, second_band: orthogonal}
effective_size: 20
path:
  segments:
    - {eps_xx: 1.0131e-4, sig_yy: 0.0, sig_xy: 0.0, increments: 200}
    - {eps_xx: 4.0381e24, eps_yy: 8.7378e-5, gamma_xy: 2.05e-4, increments: 100}
)", "huge.yaml"));
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  const DamageLawParams law{41246, 2.5, 12, 0.2};
  const double limit = 2.0 * 0.1 * dissipationToFailure(law);
  for (const HistoryRow& r : run.history) {
    ASSERT_TRUE(std::isfinite(r.dissipation)) << "increment " << r.increment;
    EXPECT_GE(r.integrity, 0.0) << "increment " << r.increment;
    EXPECT_LE(20.0 * r.dissipation, (1.0 + 1e-9) * limit) << "increment " << r.increment;
  }
  EXPECT_LT(run.history.back().integrity, 1e-100);
}

TEST(PointDriver, ASnapBackTraceThatCannotReachItsTargetStallsAndSaysSo) {
  // Found by fuzz/fuzz_point_scene.cpp: a shear stress of 5 MPa held while eps_xx grows by 0.12
  // per increment. The band snaps back, opens fully (D = 1) and cannot carry the shear; no jump
  // step but one at round-off converges, and the trace spent its 100 000 tries (39 s) before it
  // failed. Now it stalls after 200 tries at round-off, with the band fully open and the
  // increment's target not reached (docs/model.md, "Snap-back on the path").
  const PointScene s = readPointScene(io::parseYaml(R"(
name: stalled-trace
material: {model: enriched, hypothesis: plane_stress, youngs_modulus: 71223, poisson_ratio: 0.15, tensile_strength: 3.5,
           softening_modulus: 6, softening_exponent: 0.2, band_width: 0.1, second_band: orthogonal}
effective_size: 21
path:
  segments:
    - {eps_xx: 120131e-4, sig_yy: 0.0, sig_xy: 5.0, increments: 100}
)", "stalled.yaml"));
  const PointRun run = runPoint(s);
  EXPECT_FALSE(run.completed);
  EXPECT_TRUE(run.snapBack.detected);
  EXPECT_TRUE(run.snapBack.stalled);
  ASSERT_FALSE(run.history.empty());
  EXPECT_LT(run.history.back().integrity, 1e-6);  // the band fully open where it stalled
}

TEST(PointDriver, ElasticPathsFollowHookesLaw) {
  // Closed forms of plane-stress Hooke's law: uniaxial stress, uniaxial strain, pure shear.
  const double e = 5e-5;
  PointRun a = runPoint(scene(ModelKind::LinearElastic, 10.0, preset("uniaxial_tension", e, 10)));
  ASSERT_TRUE(a.completed) << a.failure;
  EXPECT_NEAR(a.history.back().stress[0], test::kE * e, 1e-9);
  EXPECT_NEAR(a.history.back().strain[1], -test::kNu * e, 1e-15);
  PointRun b = runPoint(scene(ModelKind::LinearElastic, 10.0, preset("uniaxial_strain", e, 10)));
  EXPECT_NEAR(b.history.back().stress[0], test::kE / (1 - test::kNu * test::kNu) * e, 1e-9);
  EXPECT_NEAR(b.history.back().stress[1], test::kNu * test::kE / (1 - test::kNu * test::kNu) * e, 1e-9);
  PointRun c = runPoint(scene(ModelKind::LinearElastic, 10.0, preset("pure_shear", e, 10)));
  EXPECT_NEAR(c.history.back().stress[2], test::kE / (2 * (1 + test::kNu)) * e, 1e-9);
}

TEST(PointDriver, MixedControlKeepsTheControlledStressesAtZero) {
  // Uniaxial tension then shear (sig_yy controlled throughout): residual <= 1e-8 f_t'.
  PresetPath p = preset("tension_then_shear", 2e-4, 100);
  p.shear = 4e-4;
  PointRun run = runPoint(scene(ModelKind::Enriched, 2.5, p));
  ASSERT_TRUE(run.completed) << run.failure;
  for (const HistoryRow& r : run.history) {
    EXPECT_LE(std::abs(r.stress[1]), 1e-8 * test::kFt) << "increment " << r.increment;
    if (r.segment == 1) {
      EXPECT_LE(std::abs(r.stress[2]), 1e-8 * test::kFt);
    }
  }
  EXPECT_GT(run.history.back().damage, 0.9);
}

TEST(PointDriver, EnrichedUniaxialRunMatchesTheClosedForm) {
  // Strain control, pre-snap-back (H = 100 mm < 195.6 mm): the macro curve eps = sigma/E + w/H
  // with the band's exact response (frozen lateral band strain, nu = 0.2), compared at equal
  // strain by interpolating the closed form; tolerance 0.5% of f_t'.
  const double bigH = 100.0;
  PointRun run = runPoint(scene(ModelKind::Enriched, bigH, preset("uniaxial_tension", 4e-4, 400)));
  ASSERT_TRUE(run.completed) << run.failure;
  // The closed-form curve, parameterised by the band integrity x (monotonic in strain here).
  std::vector<std::pair<double, double>> curve;
  for (double lx = 0.0; lx > -12.0; lx -= 0.002) {
    const auto band = uniaxialBandResponse(kLaw, test::kNu, test::kBandWidth, std::pow(10.0, lx));
    curve.emplace_back(uniaxialMacroStrain(band, test::kE, bigH), band.stress);
  }
  double worst = 0.0;
  for (const HistoryRow& r : run.history) {
    if (!r.crackNormal.any()) continue;
    for (size_t i = 1; i < curve.size(); ++i) {
      if ((curve[i - 1].first - r.strain[0]) * (curve[i].first - r.strain[0]) > 0.0) continue;
      const double s = (r.strain[0] - curve[i - 1].first) / (curve[i].first - curve[i - 1].first);
      const double sigma = curve[i - 1].second + s * (curve[i].second - curve[i - 1].second);
      worst = std::max(worst, std::abs(sigma - r.stress[0]));
      break;
    }
  }
  EXPECT_LT(worst, 0.005 * test::kFt);
}

TEST(PointDriver, EnrichedPointDissipatesTheFractureEnergyUnderOpeningControl) {
  // Energy identity (docs/model.md, identities): H x dissipation per volume = h int F dD = 0.110 N/mm.
  for (double bigH : {1.0, 100.0, 500.0, 2000.0}) {
    PresetPath p = preset("uniaxial_tension", 5e-5, 20);
    p.opening = 20.0;  // mm: far into the tail (the stress there is < 1e-4 f_t')
    PointScene s = scene(ModelKind::Enriched, bigH, p);
    s.path.back().increments = 4000;
    PointRun run = runPoint(s);
    ASSERT_TRUE(run.completed) << run.failure;
    const PointSummary sum = summarise(s, run);
    const double gf = test::kBandWidth * dissipationToFailure(kLaw);
    EXPECT_NEAR(sum.energyPerArea, gf, 0.01 * gf) << "H = " << bigH;
    // The band law's peak in uniaxial stress (nu = 0.2): f_t' at onset, then the frozen
    // tangential strain lifts the traction, never above f_t' / sqrt(1 - nu^2) (docs/model.md).
    EXPECT_GE(sum.peakStress, test::kFt * (1.0 - 1e-9)) << "H = " << bigH;
    EXPECT_LE(sum.peakStress, test::kFt / std::sqrt(1.0 - test::kNu * test::kNu)) << "H = " << bigH;
  }
}

TEST(PointDriver, SnapBackIsDetectedUnderStrainControlAndTracedUnderOpeningControl) {
  // H = 500 mm > h (E + E_p)/E_p: under strain control the first post-peak increment has no
  // branch; the driver reports it (first increment, stress drop > 0) and jumps. Under opening
  // control the branch is traced: the macro strain decreases while the opening grows.
  const double bigH = 500.0;
  PointRun strain = runPoint(scene(ModelKind::Enriched, bigH, preset("uniaxial_tension", 3e-4, 300), 0.0));
  ASSERT_TRUE(strain.completed) << strain.failure;
  ASSERT_TRUE(strain.snapBack.detected);
  EXPECT_NEAR(strain.snapBack.stressBefore, test::kFt, 0.01 * test::kFt);
  EXPECT_LT(strain.snapBack.stressAfter, strain.snapBack.stressBefore - 0.1 * test::kFt);
  EXPECT_EQ(strain.snapBack.increment, 1 + static_cast<int>(test::kFt / test::kE / 1e-6));
  PresetPath p = preset("uniaxial_tension", 5e-5, 10);
  p.opening = 0.5;
  PointScene s = scene(ModelKind::Enriched, bigH, p, 0.0);
  s.path.back().increments = 500;
  PointRun opening = runPoint(s);
  ASSERT_TRUE(opening.completed) << opening.failure;
  EXPECT_FALSE(opening.snapBack.detected);
  double minStrainAfterPeak = INFINITY;
  const double peakStrain = test::kFt / test::kE;
  for (const HistoryRow& r : opening.history) {
    if (r.openingControl) minStrainAfterPeak = std::min(minStrainAfterPeak, r.strain[0]);
    // 1D closed form on the whole branch, snap-back included (nu = 0).
    if (r.damage > 0.0) {
      const double x = r.integrity;
      const double sigma = uniaxialStress(kLaw, x);
      EXPECT_NEAR(r.stress[0], sigma, 1e-8 * test::kFt);
      EXPECT_NEAR(r.opening, test::kBandWidth * (sigma / (x * test::kE) - sigma / test::kE), 1e-9);
      EXPECT_NEAR(r.strain[0], sigma / test::kE + r.opening / bigH, 1e-12);
    }
  }
  EXPECT_LT(minStrainAfterPeak, (1.0 - 5e-3) * peakStrain);  // the branch turns back
}

TEST(PointDriver, CyclicUnloadingIsSecantToTheOrigin) {
  // Eq. (11) with D frozen while unloading: sigma = (1 - D) a eps for the smeared crack, and
  // for the enriched point with nu = 0 the macro response is secant to the origin as well.
  PresetPath p = preset("cyclic", 0.0, 50);
  p.cycleStrains = {1.5e-4, 3e-4, 6e-4};
  for (ModelKind kind : {ModelKind::SmearedCrack, ModelKind::Enriched}) {
    PointScene s = scene(kind, 50.0, p, 0.0);
    PointRun run = runPoint(s);
    ASSERT_TRUE(run.completed) << run.failure;
    // Unloading segments are the even ones; the row before each is the top of its cycle.
    const HistoryRow* top = nullptr;
    for (size_t i = 1; i < run.history.size(); ++i) {
      const HistoryRow& r = run.history[i];
      if (r.segment % 2 == 1) continue;
      if (run.history[i - 1].segment != r.segment) top = &run.history[i - 1];
      if (std::abs(r.strain[0]) < 1e-9) continue;  // at the origin
      EXPECT_NEAR(r.stress[0] / r.strain[0], top->stress[0] / top->strain[0], 1e-6 * test::kE) << toString(kind);
      EXPECT_EQ(r.integrity, top->integrity);  // no damage while unloading
    }
    // back at zero strain, zero stress
    EXPECT_NEAR(run.history.back().stress[0], 0.0, 1e-8 * test::kFt);
  }
}

// The locking path with the second band (docs/model.md, "A second band"): uniaxial stress along
// x past the first band's failure, then eps_yy with eps_xx and gamma_xy held.
PointScene lockingPath(double bigH, double exx, double eyy, int increments) {
  PointScene s;
  s.material = concrete(ModelKind::Enriched);
  s.material.secondBand = SecondBandOption::Orthogonal;
  s.effectiveSize = bigH;
  s.path = {Segment{{Control::Strain, Control::Stress, Control::Stress}, Voigt(exx, 0.0, 0.0), increments},
            Segment{{Control::Strain, Control::Strain, Control::Strain}, Voigt(exx, eyy, 0.0), increments}};
  return s;
}

TEST(PointDriver, TheSecondBandSoftensTheLockedStressAndDissipatesAnotherGF) {
  // Both bands to failure: H x dissipation = 2 h int_0^1 F dD (docs/model.md, identities).
  const PointScene s = lockingPath(2.5, 0.5, 0.9, 2000);
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  const HistoryRow& last = run.history.back();
  ASSERT_TRUE(last.secondBand);
  EXPECT_NEAR(last.secondNormal[1], 1.0, 1e-12);
  EXPECT_GT(last.secondDamage, 1.0 - 1e-9);
  EXPECT_LT(std::abs(last.stress[1]), 1e-6 * test::kFt) << "no locked stress left";
  const double gf = test::kBandWidth * dissipationToFailure(kLaw);
  EXPECT_NEAR(summarise(s, run).energyPerArea, 2.0 * gf, 1e-3 * gf);
  EXPECT_FALSE(run.snapBack.detected);
}

TEST(PointDriver, ASnapBackWithTwoBandsIsReleasedAtTheIncrementsStrain) {
  // H = 500 mm: each band snaps back (docs/model.md, identities: beyond h (E + E_p) / E_p). The
  // first is traced under opening control; the second, opening inside an increment, is
  // released: the row before it is marked as the last stable one, the landed row as a jump.
  const PointScene s = lockingPath(500.0, 0.01, 0.02, 2000);
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  ASSERT_TRUE(run.snapBack.detected);
  int released = 0;
  for (std::size_t i = 1; i < run.history.size(); ++i) {
    const HistoryRow& r = run.history[i];
    if (r.segment != 2 || !r.snapBackRelease) continue;
    ++released;
    EXPECT_TRUE(run.history[i - 1].event & kLastStableRow);
    EXPECT_LT(r.stress[1], run.history[i - 1].stress[1]) << "the release drops the stress";
    EXPECT_TRUE(r.secondBand);
  }
  EXPECT_EQ(released, 1);
  EXPECT_TRUE(run.history.back().secondBand);
  const double gf = test::kBandWidth * dissipationToFailure(kLaw);
  EXPECT_NEAR(summarise(s, run).energyPerArea, 2.0 * gf, 1e-3 * gf);
}

TEST(PointDriver, HistoryAndSummaryShowTheSecondBand) {
  const PointScene s = lockingPath(2.5, 0.05, 0.1, 200);
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  test::TempDir tmp;
  writeHistoryCsv(run, tmp.path() / "history.csv", true);
  const io::CsvTable h = io::readCsv(tmp.path() / "history.csv");
  ASSERT_EQ(h.header.size(), 29u);
  EXPECT_EQ(h.header[24], "damage_2");
  EXPECT_EQ(h.header[28], "normal_y_2");
  EXPECT_EQ(h.rows.front()[24], 0.0);
  EXPECT_GT(h.rows.back()[24], 0.9);
  EXPECT_EQ(h.rows.back()[28], 1.0);
  const nlohmann::json j = pointSummaryJson(s, run);
  EXPECT_EQ(j["second_band"], "orthogonal");
  EXPECT_EQ(j["two_bands"], 1);
  EXPECT_EQ(j["final"]["second_band"]["normal"][1], 1.0);
}

// The path of a second band opening beside a first band that still carries traction: the
// material E 25000, nu 0.15, f_t' 2.5, E_p 12, n 0.2, h 0.1, H 20 mm, plane stress; uniaxial
// stress to eps_xx = 1.0131e-4 in 100 increments, then d eps_xx = d eps_yy = d gamma_xy / 2 to
// (2.0381e-4, 8.7378e-5, 2.05e-4) in 100 increments.
MaterialParams loadedFirstBandMaterial() {
  MaterialParams p{.name = "second-band-beside-a-loaded-first", .model = ModelKind::Enriched,
                   .elastic = {25000.0, 0.15, Hypothesis::PlaneStress}, .tensileStrength = 2.5,
                   .softeningModulus = 12.0, .softeningExponent = 0.2, .bandWidth = 0.1,
                   .secondBand = SecondBandOption::Orthogonal};
  return p;
}
const Voigt kLoadedFirstBandEnd(2.0381e-4, 8.7378e-5, 2.05e-4);

TEST(PointDriver, ASecondBandOpeningBesideALoadedFirstBandIsReportedAsASnapBack) {
  // Its Y starts above F(0) (the effective stress is biaxial), so its damage catches up at
  // fixed strain (sigma_yy 2.48 -> 2.20 MPa, D2 0 -> 0.965 on main): a jump with no continuous
  // branch, which the run recorded as an ordinary increment (snapback_detected: false).
  PointScene s;
  s.name = "loaded-first-band";
  s.material = loadedFirstBandMaterial();
  s.effectiveSize = 20.0;
  Segment pull;
  pull.control = {Control::Strain, Control::Stress, Control::Stress};
  pull.target = Voigt(1.0131e-4, 0.0, 0.0);
  pull.increments = 100;
  Segment shear;
  shear.target = kLoadedFirstBandEnd;
  shear.increments = 100;
  s.path = {pull, shear};
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  EXPECT_TRUE(run.snapBack.detected);
  EXPECT_TRUE(run.snapBack.jumped);
  EXPECT_GT(run.snapBack.stressBefore - run.snapBack.stressAfter, 0.0);
  const auto opened = std::find_if(run.history.begin(), run.history.end(), [](const HistoryRow& r) { return r.secondBand; });
  ASSERT_NE(opened, run.history.end());
  EXPECT_TRUE(opened->snapBackRelease);
  EXPECT_GT(opened->secondDamage, 0.9);
  EXPECT_TRUE((opened - 1)->event & kLastStableRow);
  // and the stop policy stops there
  s.snapBack = SnapBackPolicy::Stop;
  const PointRun stopped = runPoint(s);
  EXPECT_FALSE(stopped.completed);
  EXPECT_TRUE(stopped.snapBack.detected);
}

TEST(PointDriver, TheSecondBandsJumpBooksTheStoredEnergyItReleases) {
  // At fixed strain no work is done, so the jump dissipates all the stored energy it releases:
  // psi before minus psi after. Over an increment |d eps| <= 1e-11 that straddles the trigger,
  // the work is at most 2 max|sigma| |d eps| (< 1e-10 MPa with |sigma| < 4 MPa), so the booked
  // dissipation equals psi(start) - psi(end) to 1e-10 MPa; f2 int Y dD along the envelope
  // booked 1.68e-5 of the 1.89e-5 MPa released.
  const Material m(loadedFirstBandMaterial());
  const auto size = EffectiveSize::fixed(20.0);
  MixedControlSettings settings;
  settings.tolerance = 1e-8 * 2.5;
  MaterialPoint p;
  Voigt stress = Voigt::Zero();
  MixedTarget pull;
  pull.control = {Control::Strain, Control::Stress, Control::Stress};
  pull.strainIncrement = Voigt(1.0131e-6, 0.0, 0.0);
  for (int i = 0; i < 100; ++i) {
    const StepOutcome out = mixedControlStep(m, p, stress, pull, size, settings, SnapBackPolicy::Release);
    ASSERT_TRUE(out.converged()) << i;
    stress = out.result.stress;
  }
  const UpdateOptions release(SnapBackPolicy::Release);
  const Voigt start = p.strain;
  Voigt d = Voigt::Zero();
  for (int i = 1; i <= 100; ++i) {
    d = start + i / 100.0 * (kLoadedFirstBandEnd - start) - p.strain;
    MaterialPoint q = p;
    ASSERT_TRUE(m.update(q, d, size, release).converged()) << i;
    if (q.secondBand) break;
    p = q;
  }
  ASSERT_FALSE(p.secondBand);
  // Bisect the increment to a piece of at most 1e-11 strain that opens the band.
  double lo = 0.0, hi = 1.0;
  while ((hi - lo) * d.norm() > 1e-11) {
    const double mid = 0.5 * (lo + hi);
    MaterialPoint q = p;
    ASSERT_TRUE(m.update(q, mid * d, size, release).converged());
    (q.secondBand ? hi : lo) = mid;
  }
  ASSERT_TRUE(m.update(p, lo * d, size, release).converged());
  ASSERT_FALSE(p.secondBand);
  const double before = m.enriched()->storedEnergy(*p.band, nullptr, p.strain);
  const UpdateResult jump = m.update(p, (hi - lo) * d, size, release);
  ASSERT_TRUE(jump.converged());
  ASSERT_TRUE(p.secondBand);
  EXPECT_TRUE(jump.released);
  EXPECT_GT(p.secondBand->damage(), 0.9);
  const double after = m.enriched()->storedEnergy(*p.band, &*p.secondBand, p.strain);
  EXPECT_GT(before - after, 1e-5);
  EXPECT_NEAR(jump.dissipation, before - after, 1e-10);
}

TEST(PointDriver, OnlyMaximaOfTheLoadingBranchAreFlagged) {
  // A uniaxial pull far past failure (E 25000, nu 0.15, f_t' 2.5, E_p 12, n 0.2, h 0.1 mm,
  // H = 100 mm, eps_xx to 5e-2 in 20000 increments): the one maximum is the band's peak,
  // 2.5241 MPa just after onset (nu > 0). Near failure the stress falls to ~3e-6 MPa by
  // round-off, where main flagged five more "maxima" (rows 16912 to 17541).
  PointScene s;
  s.material = loadedFirstBandMaterial();
  s.material.secondBand = SecondBandOption::Off;
  s.effectiveSize = 100.0;
  s.path = presetSegments(preset("uniaxial_tension", 5e-2, 20000), 0.15);
  const PointRun run = runPoint(s);
  ASSERT_TRUE(run.completed) << run.failure;
  int maxima = 0;
  for (const HistoryRow& r : run.history)
    if (r.event & kPeakRow) {
      ++maxima;
      EXPECT_GT(r.stress[0], 2.5) << "row " << r.increment;
    }
  EXPECT_EQ(maxima, 1);
}

}  // namespace
}  // namespace ecm::driver
