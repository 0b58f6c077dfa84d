// ecm-point --umat (driver/umat_driver.hpp): a third-party-style Fortran UMAT (isotropic
// elasticity, tests/driver/elastic_umat.f) against its closed form, its requests for smaller
// increments (PNEWDT) honoured by halving, and ecm's own libecm_umat.so driven this way equal to
// ecm-point's 3D point (the same update behind both: docs/fe-codes.md) to 1e-12 f_t'.
#include "driver/umat_driver.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "io/csv_reader.hpp"
#include "run_tool.hpp"

namespace ecm::driver {
namespace {

// Uniaxial stress along x to eps_xx = 1e-3 in 10 increments; PROPS: E, nu, the largest
// accepted strain increment component.
UmatScene elasticScene(double largestIncrement, int substepLevels = 10) {
  std::ostringstream props;
  props << "[30000, 0.25, " << largestIncrement << "]";
  return readUmatScene(io::parseYaml(
      "name: elastic\numat: {props: " + props.str() + ", nstatv: 1}\n"
      "substep_levels: " + std::to_string(substepLevels) + "\n"
      "path: {preset: uniaxial_tension, strain: 1.0e-3, increments: 10}\n", "elastic.yaml"));
}

#ifdef ECM_ELASTIC_UMAT
TEST(UmatDriver, AnElasticUmatInUniaxialStressFollowsHookesLaw) {
  // sig_xx = E eps, eps_yy = eps_zz = -nu eps, every other stress 0; work = SSE = E eps^2 / 2.
  const UmatLibrary lib(ECM_ELASTIC_UMAT);
  EXPECT_EQ(lib.entry(), "umat_");
  const UmatRun run = runUmat(elasticScene(0.0), lib);
  ASSERT_TRUE(run.completed) << run.failure;
  ASSERT_EQ(run.history.size(), 11u);
  for (const UmatRow& r : run.history) {
    const double eps = 1e-4 * r.increment;
    EXPECT_NEAR(r.strain[0], eps, 1e-18);
    EXPECT_NEAR(r.stress[0], 30000 * eps, 1e-9);
    EXPECT_NEAR(r.strain[1], -0.25 * eps, 1e-15);
    EXPECT_NEAR(r.strain[2], -0.25 * eps, 1e-15);
    EXPECT_LE(r.stress.tail<5>().cwiseAbs().maxCoeff(), 1e-6);  // the stress tolerance (MPa)
    EXPECT_NEAR(r.work, 0.5 * 30000 * eps * eps, 1e-12);
    EXPECT_NEAR(r.sse, 0.5 * 30000 * eps * eps, 1e-12);
    EXPECT_EQ(r.state[0], r.increment);  // one call with a moving strain per increment committed
    EXPECT_EQ(r.substeps, 1);
  }
}

TEST(UmatDriver, AnIncrementTheUmatRefusesIsHalvedUntilItIsAccepted) {
  // Increments of 1e-4 against a largest accepted component of 0.6e-4: each is taken in two
  // pieces (STATEV(1) counts 20 calls), the path unchanged.
  const UmatRun run = runUmat(elasticScene(0.6e-4), UmatLibrary(ECM_ELASTIC_UMAT));
  ASSERT_TRUE(run.completed) << run.failure;
  ASSERT_EQ(run.history.size(), 11u);
  EXPECT_EQ(run.history.back().substeps, 2);
  EXPECT_EQ(run.history.back().state[0], 20.0);
  EXPECT_NEAR(run.history.back().stress[0], 30.0, 1e-9);
}

TEST(UmatDriver, AnIncrementRefusedInEveryPieceEndsTheRunAndSaysWhy) {
  const UmatRun run = runUmat(elasticScene(1e-9, 2), UmatLibrary(ECM_ELASTIC_UMAT));
  EXPECT_FALSE(run.completed);
  EXPECT_NE(run.failure.find("increment 1 (segment 1) did not converge in 4 pieces"), std::string::npos) << run.failure;
  EXPECT_NE(run.failure.find("PNEWDT = 0.5"), std::string::npos) << run.failure;
  EXPECT_EQ(run.history.size(), 1u);
}

TEST(UmatDriver, TheToolWritesTheHistoryWithEveryStateVariableAndTheSummary) {
  const auto dir = std::filesystem::temp_directory_path() / "ecm-umat-driver-tool";
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  {
    std::ofstream scene(dir / "elastic.yaml");
    scene << "# units: mm, N, MPa\nname: elastic\numat: {props: [30000, 0.25, 0], nstatv: 1}\n"
             "path: {preset: uniaxial_tension, strain: 1.0e-3, increments: 10}\n";
  }
  const test::ToolRun r = test::runTool(ECM_POINT, test::shellQuoted(dir / "elastic.yaml") + " --umat " +
                                                        test::shellQuoted(ECM_ELASTIC_UMAT) + " --out " +
                                                        test::shellQuoted(dir / "out"), dir);
  ASSERT_EQ(r.status, 0) << r.err;
  const io::CsvTable h = io::readCsv(dir / "out" / "history.csv");
  ASSERT_EQ(h.rows.size(), 11u);
  ASSERT_EQ(h.header.size(), 21u);  // 20 columns, then STATEV 1
  EXPECT_EQ(h.header[8], "sig_xx");
  EXPECT_EQ(h.header[20], "statev_1");
  EXPECT_NEAR(h.rows.back()[8], 30.0, 1e-9);
  EXPECT_EQ(h.rows.back()[20], 10.0);
  EXPECT_TRUE(std::filesystem::exists(dir / "out" / "summary.json"));
  // Without --umat the scene is refused with the reason.
  const test::ToolRun bad = test::runTool(ECM_POINT, test::shellQuoted(dir / "elastic.yaml"), dir);
  EXPECT_EQ(bad.status, io::kExitBadInput);
  EXPECT_NE(bad.err.find("give its library with --umat"), std::string::npos) << bad.err;
}
#endif

TEST(UmatDriver, ALibraryWithoutAUmatEntryIsRefusedByName) {
  try {
    const UmatLibrary lib(ECM_NOT_A_UMAT);
    FAIL() << "libm loaded as a UMAT";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("has no UMAT entry"), std::string::npos) << e.what();
  }
  EXPECT_THROW(UmatLibrary("/nonexistent/libumat.so"), std::runtime_error);
}

TEST(UmatDriver, AUmatSceneRejectsAMissingNstatvAndAStatevOfTheWrongLength) {
  const auto read = [](const std::string& umat) {
    return readUmatScene(io::parseYaml("umat: " + umat + "\npath: {preset: uniaxial_tension, strain: 1.0e-3, increments: 1}\n", "u.yaml"));
  };
  EXPECT_THROW(read("{props: [1, 2]}"), io::InputError);
  EXPECT_THROW(read("{props: [1, 2], nstatv: 2, statev: [0]}"), io::InputError);
  EXPECT_THROW(read("{props: [1, 2], nstatv: 1, colour: red}"), io::InputError);
  EXPECT_NO_THROW(read("{props: [1, 2], nstatv: 2, statev: [0, 1], celent: 2.5, material_name: ABAQUS_X}"));
}

#ifdef ECM_UMAT_LIB
// The same scene with every component strain-controlled (a stress target of 0 becomes a strain
// target of 0): the path a finite element code gives a point whose nodes are all prescribed.
PointScene3 strainControlled(PointScene3 scene) {
  for (Segment3& s : scene.path) s.control.fill(Control::Strain);
  return scene;
}

struct Difference {
  double stress = 0.0, strain = 0.0, damage = 0.0, dissipation = 0.0;  // worst over the increments
  std::size_t compared = 0;
};

// ecm's UMAT on an ecm 3D scene (PROPS from its material) against the 3D point on the same scene,
// both with the stress control converged to 1e-13 f_t': every increment's row (the point's own
// rows at onset and at a stress maximum have no counterpart). Stress relative to f_t', strain to
// f_t'/E.
Difference umatAgainstPoint(PointScene3 scene) {
  scene.relativeTolerance = 1e-13;
  const PointRun3 point = runPoint3D(scene);
  EXPECT_TRUE(point.completed) << point.failure;
  const UmatRun umat = runUmat(umatSceneFor(scene), UmatLibrary(ECM_UMAT_LIB));
  EXPECT_TRUE(umat.completed) << umat.failure;
  EXPECT_GT(umat.history.back().state[0], 0.5) << "the scene cracks";
  const double ft = scene.material.tensileStrength, strainScale = ft / scene.material.elastic.youngsModulus;
  Difference d;
  std::size_t u = 0;
  for (const HistoryRow3& p : point.history) {
    if (p.onset || (p.iterations == 0 && p.increment > 0)) continue;  // the point's own extra rows
    while (u < umat.history.size() && umat.history[u].increment < p.increment) ++u;
    if (u == umat.history.size() || umat.history[u].increment != p.increment) break;
    const UmatRow& r = umat.history[u];
    d.stress = std::max(d.stress, (r.stress - p.stress).cwiseAbs().maxCoeff() / ft);
    d.strain = std::max(d.strain, (r.strain - p.strain).cwiseAbs().maxCoeff() / strainScale);
    d.damage = std::max(d.damage, std::abs(r.state[16] - p.damage));  // STATEV(17) = D
    d.dissipation = std::max(d.dissipation, std::abs(r.spd - p.dissipation) / std::max(p.dissipation, 1e-300));
    ++d.compared;
  }
  EXPECT_EQ(d.compared, static_cast<std::size_t>(totalIncrements(scene)) + 1);
  return d;
}

PointScene3 shippedScene(const std::string& file) { return loadPointScene3(std::string(ECM_SOURCE_DIR) + "/data/point/" + file); }

TEST(UmatDriver, TheShippedUmatSceneGivesEcmsUmatThePropsOfItsMaterialScene) {
  // data/point/umat-tension-then-shear.yaml writes out what ecm-point derives for
  // 3d-tension-then-shear.yaml's material (a template for a UMAT user's own PROPS).
  const UmatScene written = readUmatScene(io::loadYamlFile(std::string(ECM_SOURCE_DIR) + "/data/point/umat-tension-then-shear.yaml"));
  const UmatScene derived = umatSceneFor(shippedScene("3d-tension-then-shear.yaml"));
  EXPECT_EQ(written.props, derived.props);
  EXPECT_EQ(written.initialState, derived.initialState);
  EXPECT_EQ(written.path.size(), derived.path.size());
}

TEST(UmatDriver, EcmsUmatDrivenThisWayEqualsThe3DPointOnTheSameStrainPath) {
  // Every strain given: both drivers hand the material the same increments, and the same update
  // is behind both (docs/fe-codes.md): equal to round-off.
  for (const char* file : {"3d-tension-then-shear.yaml", "3d-rotated-axis.yaml"}) {
    const Difference d = umatAgainstPoint(strainControlled(shippedScene(file)));
    std::cout << file << ", strain-controlled: worst stress " << d.stress << " f_t', strain " << d.strain
              << " f_t'/E, damage " << d.damage << ", dissipation " << d.dissipation << " relative\n";
    EXPECT_LE(d.stress, 1e-12) << file;
    EXPECT_LE(d.strain, 1e-12) << file;
    EXPECT_LE(d.damage, 1e-12) << file;
    EXPECT_LE(d.dissipation, 1e-12) << file;
  }
}

TEST(UmatDriver, UnderMixedControlOnlyThePointsStepToOnsetSetsThemApart) {
  // With stresses controlled, the 3D point steps to the exact onset on the stress-controlled path
  // and opens its band there (a row of its own); a UMAT driver sees one straight increment, and
  // the material opens the band where that increment crosses onset, at other lateral strains.
  // The bands differ by what one increment moves them; measured (2026-12-07) with 200 and 2000
  // increments per segment: the worst stress 6.1e-6 -> 7.9e-7 f_t', damage 2.6e-4 -> 3.5e-5, about
  // first order in the increment.
  PointScene3 coarse = shippedScene("3d-tension-then-shear.yaml"), fine = coarse;
  for (Segment3& s : fine.path) s.increments *= 10;
  const Difference a = umatAgainstPoint(coarse), b = umatAgainstPoint(fine);
  for (const Difference* d : {&a, &b})
    std::cout << (d == &a ? "200" : "2000") << " increments a segment: worst stress " << d->stress << " f_t', damage "
              << d->damage << ", dissipation " << d->dissipation << " relative\n";
  EXPECT_GT(a.damage, 1e-6);  // the difference is there (it is not round-off)
  EXPECT_LE(a.stress, 1e-2);
  EXPECT_LE(b.damage, 0.2 * a.damage);
  EXPECT_LE(b.stress, 0.2 * a.stress);
}
#endif

}  // namespace
}  // namespace ecm::driver
