// The output folder of a run: history.csv, summary.json, VTU snapshots with a .pvd index; and
// a failed run still leaves readable outputs and a summary saying why.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <nlohmann/json.hpp>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "mpm/output/run_files.hpp"
#include "mpm/run.hpp"
#include "mpm/output/vtu_writer.hpp"
#include "test_scenes.hpp"
#include "run_helpers.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // readFile, TempDir

TEST(Run, WritesHistorySummarySnapshots) {
  TempDir tmp;
  Scene s = tensionBlock();
  s.endTime = 1e-4;
  s.outputInterval = 2e-5;
  RunOptions o = quietRun(tmp.path() / "out");
  o.snapshots = true;
  const RunResult r = runScene(s, o);
  ASSERT_TRUE(r.completed) << r.message();
  const io::CsvTable h = io::readCsv(o.outputDir / "history.csv");
  EXPECT_EQ(h.header, historyColumns(s));
  EXPECT_EQ(h.rows.size(), 6u);  // t = 0, 2e-5, ..., 1e-4
  EXPECT_NEAR(h.rows.back()[0], 1e-4, 1e-6);
  const auto j = nlohmann::json::parse(readFile(o.outputDir / "summary.json"));
  for (const char* key : {"peak_load", "wall_time_s", "steps", "particles", "bytes_per_particle_uncracked",
                          "bytes_per_particle_cracked"})
    EXPECT_TRUE(j.contains(key)) << key;
  EXPECT_EQ(j["status"], "completed");
  EXPECT_EQ(j["particles"].get<std::size_t>(), r.particles);
  EXPECT_LE(j["bytes_per_particle_uncracked"].get<int>(), 300);
  const std::string pvd = readFile(o.outputDir / "particles.pvd");
  EXPECT_NE(pvd.find("particles_00005.vtu"), std::string::npos);
  const std::string vtu = readFile(o.outputDir / "particles_00005.vtu");
  for (const char* field : {"displacement", "stress", "damage", "crack_normal", "opening", "material", "cracked"})
    EXPECT_NE(vtu.find(std::string("Name=\"") + field + "\""), std::string::npos) << field;
  EXPECT_NE(vtu.find("NumberOfPoints=\"" + std::to_string(r.particles) + "\""), std::string::npos);
  // Raw appended arrays (VTK XML): after '_', per array a UInt64 byte count then the values. The
  // positions of the last snapshot are those of particles_final.csv (same step).
  const std::size_t tag = vtu.find("Name=\"position\" NumberOfComponents=\"3\" format=\"appended\" offset=\"");
  ASSERT_NE(tag, std::string::npos);
  const std::size_t offset = std::stoul(vtu.substr(vtu.find("offset=\"", tag) + 8));
  const std::size_t start = vtu.find('_', vtu.find("<AppendedData encoding=\"raw\">")) + 1;
  std::uint64_t bytes = 0;
  std::memcpy(&bytes, vtu.data() + start + offset, sizeof bytes);
  EXPECT_EQ(bytes, 3 * 8 * r.particles);
  const io::CsvTable final = io::readCsv(o.outputDir / "particles_final.csv");
  for (std::size_t i : {std::size_t{0}, r.particles - 1}) {
    double xy[2];
    std::memcpy(xy, vtu.data() + start + offset + 8 + 24 * i, sizeof xy);
    EXPECT_EQ(xy[0], final.rows[i][0]) << i;
    EXPECT_EQ(xy[1], final.rows[i][1]) << i;
  }
  // Field values are Float32: the displacement of the last snapshot is the final position less
  // the seeding position (particles_final.csv, first snapshot's positions), rounded to float.
  const std::string first = readFile(o.outputDir / "particles_00000.vtu");
  const std::size_t firstStart = first.find('_', first.find("<AppendedData encoding=\"raw\">")) + 1;
  const std::size_t dtag = vtu.find("<DataArray type=\"Float32\" Name=\"displacement\" NumberOfComponents=\"3\" format=\"appended\" offset=\"");
  ASSERT_NE(dtag, std::string::npos);
  const std::size_t doffset = std::stoul(vtu.substr(vtu.find("offset=\"", dtag) + 8));
  std::memcpy(&bytes, vtu.data() + start + doffset, sizeof bytes);
  EXPECT_EQ(bytes, 3 * 4 * r.particles);
  double largest = 0.0;
  for (std::size_t i = 0; i < r.particles; i += 7) {
    float u[3];
    double x0[2];
    std::memcpy(u, vtu.data() + start + doffset + 8 + 12 * i, sizeof u);
    std::memcpy(x0, first.data() + firstStart + offset + 8 + 24 * i, sizeof x0);
    for (int c = 0; c < 2; ++c) {
      const double exact = final.rows[i][static_cast<std::size_t>(c)] - x0[c];
      EXPECT_NEAR(u[c], exact, 1e-6 * std::abs(exact) + 1e-12) << i;
      largest = std::max(largest, std::abs(exact));
    }
    EXPECT_EQ(u[2], 0.0f);
  }
  EXPECT_GT(largest, 1e-6) << "the check needs a block that moved";
  EXPECT_EQ(vtu.substr(vtu.size() - 30), "\n  </AppendedData>\n</VTKFile>\n");
}

// snapshot_every N: VTU snapshots at output rows 0, N, 2N, ... and at the last row; the history
// keeps every row. Times in the .pvd index are those of the history rows.
TEST(Run, SnapshotEveryNthOutputRowAndTheLast) {
  TempDir tmp;
  Scene s = tensionBlock();
  s.endTime = 1e-4;
  s.outputInterval = 1e-5;  // 11 rows: 0 .. 10
  s.snapshotEvery = 4;      // rows 0, 4, 8 and the last, 10
  RunOptions o = quietRun(tmp.path() / "out");
  o.snapshots = true;
  const RunResult r = runScene(s, o);
  ASSERT_TRUE(r.completed) << r.message();
  const io::CsvTable h = io::readCsv(o.outputDir / "history.csv");
  ASSERT_EQ(h.rows.size(), 11u);
  const std::string pvd = readFile(o.outputDir / "particles.pvd");
  std::vector<double> times;
  for (std::size_t at = pvd.find("timestep=\""); at != std::string::npos; at = pvd.find("timestep=\"", at + 1))
    times.push_back(std::stod(pvd.substr(at + 10)));
  const std::vector<std::size_t> rows{0, 4, 8, 10};
  ASSERT_EQ(times.size(), rows.size());
  for (std::size_t k = 0; k < rows.size(); ++k) EXPECT_DOUBLE_EQ(times[k], h.rows[rows[k]][0]) << k;
  EXPECT_TRUE(std::filesystem::exists(o.outputDir / "particles_00003.vtu"));
  EXPECT_FALSE(std::filesystem::exists(o.outputDir / "particles_00004.vtu"));
}

TEST(Run, ParticleSnapshotsAtTheRequestedTimes) {
  // One CSV per requested time, written at the first step at or past it, with one row per
  // particle; the file of the last time equals particles_final.csv when that time ends the run.
  TempDir tmp;
  Scene s = tensionBlock();
  s.endTime = 1e-4;
  s.particleSnapshots = {3e-5, 1e-4};
  RunOptions o = quietRun(tmp.path() / "out");
  const RunResult r = runScene(s, o);
  ASSERT_TRUE(r.completed) << r.message();
  const io::CsvTable a = io::readCsv(o.outputDir / "particles_t3e-05.csv");
  EXPECT_EQ(a.header, (std::vector<std::string>{"x_mm", "y_mm", "damage", "material", "opening_mm", "normal_x",
                                                "normal_y", "sig_xx_MPa", "sig_yy_MPa", "sig_xy_MPa"}));
  EXPECT_EQ(a.rows.size(), r.particles);
  EXPECT_EQ(readFile(o.outputDir / "particles_t0.0001.csv"), readFile(o.outputDir / "particles_final.csv"));
  EXPECT_NE(readFile(o.outputDir / "particles_t3e-05.csv"), readFile(o.outputDir / "particles_final.csv"));
}

TEST(Run, FailureKeepsOutputsReadableAndExplainsInSummary) {
  TempDir tmp;
  Scene s;
  s.grid = {Vec2::Zero(), Vec2(10.0, 10.0), 10, 4};
  s.materials = {elasticMaterial()};
  s.bodies = {{Shape::rectangle(Vec2(60.0, 10.0), Vec2(90.0, 30.0)), 0, false, Vec2(2e5, 0.0)}};
  s.endTime = 1e-3;
  s.outputInterval = 1e-5;
  s.snapshotEvery = 1000;  // only row 0 on schedule: the failure's own snapshot must still be written
  RunOptions o = quietRun(tmp.path() / "out");
  o.snapshots = true;
  const RunResult r = runScene(s, o);
  EXPECT_FALSE(r.completed);
  ASSERT_TRUE(r.failure);
  EXPECT_EQ(r.failure->kind, FailureKind::LeftGrid) << r.message();
  ASSERT_TRUE(r.failure->position);
  EXPECT_GT((*r.failure->position)[0], 100.0);  // past the grid's right edge
  const io::CsvTable h = io::readCsv(o.outputDir / "history.csv");
  EXPECT_GE(h.rows.size(), 2u);
  EXPECT_TRUE(std::filesystem::exists(o.outputDir / "particles_00001.vtu")) << "the state at the failure";
  const auto j = nlohmann::json::parse(readFile(o.outputDir / "summary.json"));
  EXPECT_EQ(j["status"], "failed");
  EXPECT_EQ(j["error"], r.message());  // the message, for people
  EXPECT_EQ(j["failure"]["kind"], "left_grid");
  EXPECT_EQ(j["failure"]["exit_status"], 10);  // io/cli_exit.hpp
  EXPECT_EQ(j["failure"]["step"], r.failure->step);
  EXPECT_EQ(j["failure"]["particle"].get<std::size_t>(), *r.failure->particle);
  EXPECT_EQ(j["failure"]["position_mm"][0].get<double>(), (*r.failure->position)[0]);
  EXPECT_FALSE(j["failure"].contains("material_status"));  // not a material failure
}

}  // namespace
}  // namespace ecm::mpm::test
