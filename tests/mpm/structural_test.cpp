// Structural runs of the shipped scenes through the whole program path (YAML -> run -> output
// folder). Labelled `slow` (ctest -LE slow skips them).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "beam_check.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // readFile, TempDir

std::filesystem::path scenePath(const char* name) { return std::filesystem::path(ECM_SOURCE_DIR) / "data" / "mpm" / name; }

// Fixed-free bar released with v0: the clamp force is a square wave of amplitude rho c v0 A and
// period 4 L / c (d'Alembert solution, e.g. Graff, Wave Motion in Elastic Solids, sec. 1.2).
TEST(Structural, ElasticBarSceneReactionIsTheSquareWaveOfTheClosedForm) {
  TempDir tmp;
  const Scene s = loadSceneFile(scenePath("elastic-bar.yaml"));
  ASSERT_TRUE(runScene(s, quietRun(tmp.path())).completed);
  const io::CsvTable h = io::readCsv(tmp.path() / "history.csv");
  const double c = std::sqrt(32000.0 / 2.4e-9), v0 = 100.0, area = 1.5625 * 1.0, length = 100.0;
  const double amplitude = 2.4e-9 * c * v0 * area, period = 4.0 * length / c;
  std::vector<double> plateau;  // |R| in the middle of each half period
  std::vector<double> crossings;
  for (std::size_t i = 1; i < h.rows.size(); ++i) {
    ASSERT_EQ(h.header[4], "clamp_rx_N");
    const double t = h.rows[i][0], r = h.rows[i][4];
    const double phase = std::fmod(t / (0.5 * period), 1.0);
    if (phase > 0.3 && phase < 0.7) plateau.push_back(std::abs(r));
    const double r0 = h.rows[i - 1][4];
    if (i > 1 && (r0 < 0.0) != (r < 0.0))
      crossings.push_back(h.rows[i - 1][0] + (h.rows[i][0] - h.rows[i - 1][0]) * r0 / (r0 - r));
  }
  std::sort(plateau.begin(), plateau.end());
  const double median = plateau[plateau.size() / 2];
  EXPECT_NEAR(median, amplitude, 0.01 * amplitude);
  ASSERT_GE(crossings.size(), 3u);
  EXPECT_NEAR(crossings[2] - crossings[0], period, 0.01 * period);
  std::printf("[ structural ] bar: reaction plateau %.5f N (closed form %.5f), period %.5e s (closed form %.5e)\n",
              median, amplitude, crossings[2] - crossings[0], period);
}

// The double-notched block cracks at the ligament; its peak load is of the order of the
// ligament capacity f_t' b t = 3 MPa x 60 mm x 50 mm = 9 kN.
TEST(Structural, TensionBlockSceneCracksAtTheLigament) {
  TempDir tmp;
  const Scene s = loadSceneFile(scenePath("tension-block.yaml"));
  RunOptions o = quietRun(tmp.path());
  o.snapshots = true;
  const RunResult r = runScene(s, o);
  ASSERT_TRUE(r.completed) << r.message();
  EXPECT_GT(r.peakLoad, 0.8 * 9000.0);
  EXPECT_LT(r.peakLoad, 1.15 * 9000.0);
  const auto j = nlohmann::json::parse(readFile(tmp.path() / "summary.json"));
  EXPECT_GT(j["cracked_particles"].get<int>(), 0);
  const io::CsvTable h = io::readCsv(tmp.path() / "history.csv");
  const auto col = std::find(h.header.begin(), h.header.end(), "top_ry_N") - h.header.begin();
  ASSERT_LT(static_cast<std::size_t>(col), h.header.size());
  const double last = h.rows.back()[static_cast<std::size_t>(col)];  // at the end: softened
  EXPECT_LT(last, 0.8 * r.peakLoad);
  EXPECT_TRUE(std::filesystem::exists(tmp.path() / "particles.pvd"));
  std::printf("[ structural ] tension block: peak %.1f N, final %.1f N, %d cracked, %.2f s\n", r.peakLoad, last,
              j["cracked_particles"].get<int>(), r.wallTime);
}

// A shipped DEN scene (data/den/NAME.yaml) run in full on 2 threads into `out`, without snapshots,
// plots or progress.
RunResult runDenScene(const std::string& name, const std::filesystem::path& out) {
  const Scene s = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "den" / (name + ".yaml"));
  RunOptions o = quietRun(out);
  o.threads = 2;
  return runScene(s, o);
}

// The DEN (Nooru-Mohamed's panel, load path 4b), each mesh run in full: the mesh-objectivity
// and quasi-static criteria of docs/den.md ("The three meshes"), against the coarse run's values
// (scripts/den.sh, 2 threads, summary.json: peak 18518.4 N, dissipated 980.1 N mm; the medium
// and fine meshes are within 1 % and 5 % of them). Criteria: peak within 5 %, dissipated energy
// within 10 %, kinetic energy below 1 % of the external work while the top is pulled.
class DenFullRun : public ::testing::TestWithParam<const char*> {};

TEST_P(DenFullRun, MeetsTheMeshObjectivityAndQuasiStaticCriteria) {
  TempDir tmp;
  const RunResult r = runDenScene(std::string("den-4b-") + GetParam(), tmp.path());
  ASSERT_TRUE(r.completed) << r.message();
  const io::CsvTable h = io::readCsv(tmp.path() / "history.csv");
  const auto column = [&](const std::string& name) {
    const auto it = std::find(h.header.begin(), h.header.end(), name);
    EXPECT_NE(it, h.header.end()) << name;
    return static_cast<std::size_t>(it - h.header.begin());
  };
  const std::size_t delta = column("top_uy_mm"), kinetic = column("kinetic_Nmm"), work = column("external_work_Nmm"),
                    dissipated = column("dissipated_Nmm");
  double kineticRatio = 0.0;
  for (const auto& row : h.rows)
    if (row[delta] > 0.0 && row[work] > 0.0) kineticRatio = std::max(kineticRatio, row[kinetic] / row[work]);
  const double energy = h.rows.back()[dissipated];
  std::printf("[ structural ] DEN %s: peak %.1f N, dissipated %.1f N mm, max KE/W %.4f, %.0f s\n", GetParam(),
              r.peakLoad, energy, kineticRatio, r.wallTime);
  EXPECT_NEAR(r.peakLoad, 18518.4, 0.05 * 18518.4);
  EXPECT_NEAR(energy, 980.1, 0.10 * 980.1);
  EXPECT_LT(kineticRatio, 0.01);
}

INSTANTIATE_TEST_SUITE_P(Meshes, DenFullRun, ::testing::Values("coarse", "medium", "fine"));

// The implicit DEN scenes that go below 10 % of their peak (docs/implicit.md, "The DEN 4b"), run
// to their stop_when: the peak against the measured rate-free values (2026-12-02: 18,376.0 N for
// the coarse mesh; 18,304.4 and 18,343.2 N with the second band), and the energy balance of every
// step (external work against internal work, measured 1e-5). The medium second-band run needed the
// cycle guard of the implicit Newton and the two-band release of docs/model.md to get there.
struct ImplicitDen {
  const char* scene;
  double peak;  // N
};

void PrintTo(const ImplicitDen& d, std::ostream* os) { *os << d.scene; }

class DenImplicitRun : public ::testing::TestWithParam<ImplicitDen> {};

TEST_P(DenImplicitRun, GoesBelowATenthOfItsPeakInEquilibrium) {
  TempDir tmp;
  const RunResult r = runDenScene(GetParam().scene, tmp.path());
  ASSERT_TRUE(r.completed) << r.message();
  const auto j = nlohmann::json::parse(readFile(tmp.path() / "summary.json"));
  ASSERT_TRUE(j["stop_when"]["met"].get<bool>()) << "the run should end by P < 10 % of its peak";
  EXPECT_LT(std::abs(j["stop_when"]["load_at_stop_N"].get<double>()), 0.1 * r.peakLoad);
  EXPECT_NEAR(r.peakLoad, GetParam().peak, 1e-3 * GetParam().peak);
  EXPECT_LT(j["energy_balance"].get<double>(), 1e-4);
  std::printf("[ structural ] %s: peak %.1f N, %d steps, %d factorisations, %.0f s\n", GetParam().scene, r.peakLoad,
              j["steps"].get<int>(), j["factorizations"].get<int>(), r.wallTime);
}

INSTANTIATE_TEST_SUITE_P(Scenes, DenImplicitRun,
                         ::testing::Values(ImplicitDen{"den-4b-coarse-implicit", 18376.0},
                                           ImplicitDen{"den-4b-coarse-second-band-implicit", 18304.4},
                                           ImplicitDen{"den-4b-medium-second-band-implicit", 18343.2}),
                         [](const auto& info) {
                           std::string name = info.param.scene;
                           std::replace(name.begin(), name.end(), '-', '_');
                           return name;
                         });

}  // namespace
}  // namespace ecm::mpm::test

// The notched beam on the medium and fine meshes, implicit, against the cohesive references
// (tests/mpm/beam_check.hpp); the three meshes' peaks within 3 % of each other (measured
// 2026-12-06: 1174 / 1151 / 1151 N). Against the point's law the medium and fine meshes' tails
// are within 0.6 and 0.3 % of the peak (docs/validation.md, "3. Gregoire's notched beam"): 2 % is
// asserted.
namespace ecm::mpm::test {
namespace {

TEST(Structural, TheNotchedBeamOnThreeMeshesAgainstItsCohesiveReference) {
  const double coarse = checkBeam("data/validation/beam-coarse-implicit.yaml", 2.5, 0.05);
  const double medium = checkBeam("data/validation/beam-medium-implicit.yaml", 1.25, 0.02);
  const double fine = checkBeam("data/validation/beam-fine-implicit.yaml", 0.625, 0.02);
  const double lo = std::min({coarse, medium, fine}), hi = std::max({coarse, medium, fine});
  EXPECT_LE(hi - lo, 0.03 * lo);
}

// The same beam, explicit, on the medium mesh at 1.2 mm/s (data/validation/beam-medium.yaml): the
// crack starts as the stress averaged around its root asks, not as one notch corner's points do
// (docs/model.md, "Crack paths"). Measured 2026-12-07: peak 1150 N, against the point's law +0.0 %
// and its tail within 0.6 % of the peak; before that rule the crack started 17 degrees off the
// ligament, wandered a cell and locked (the tail 13.8 % high). 2 % is asserted, as implicit.
TEST(Structural, TheExplicitBeamOnTheMediumMeshAgainstItsCohesiveReference) {
  checkBeam("data/validation/beam-medium.yaml", 1.25, 0.02);
}

}  // namespace
}  // namespace ecm::mpm::test
