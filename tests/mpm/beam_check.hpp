#pragma once
// The notched beam (data/validation/beam-*.yaml, docs/validation.md) run and held against the
// cohesive references (ecm-cohesive, plane-stress Q4, single-node supports and load, 0.3125 mm
// mesh): data/reference/beam-point-node.csv, whose cohesive law is the traction-opening curve an
// enriched point follows in uniaxial stress (the law ecm's crack carries), and
// data/reference/beam-band-node.csv, whose law is the 1D band law (0.7 % below the point's near
// the peak, 1-3 % above it at openings of 0.06-0.3 mm). Shared by the default suite (the coarse
// mesh) and the slow one (the medium and fine meshes).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "../io/temp_dir.hpp"
#include "io/csv_reader.hpp"
#include "run_helpers.hpp"
#include "material/damage_function.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"

namespace ecm::mpm::test {

struct BeamCurve {
  std::vector<double> cmod, load;
  double at(double c) const {
    for (std::size_t i = 1; i < cmod.size(); ++i)
      if (cmod[i] >= c) return load[i - 1] + (c - cmod[i - 1]) / (cmod[i] - cmod[i - 1]) * (load[i] - load[i - 1]);
    return NAN;
  }
  double peak() const { return *std::max_element(load.begin(), load.end()); }
};

inline BeamCurve beamReference(const std::string& name) {
  const io::CsvTable t = io::readCsv(std::filesystem::path(ECM_SOURCE_DIR) / "data/reference" / name);
  BeamCurve c;
  for (const auto& row : t.rows) {
    c.cmod.push_back(row[0]);
    c.load.push_back(row[1]);
  }
  return c;
}

// Runs the scene and checks it. Against the point's law (1149.5 N): the peak within 3 %,
// |P - P_ref| at most `tailShare` of the peak for every CMOD up to 0.2 mm, the dissipation at
// CMOD 0.2 mm within 5 % of the reference's 72.64 N mm. Against the 1D band law (1134.1 N): the
// peak within 4 % and |P - P_ref| at most 5 % (the coarse mesh is 3.5 % above its peak). One
// crack, its path within one cell of the ligament x = 87.5 mm; every open band beside it, its
// normal along x, carrying at most 1.1 times the band law's traction at its damage (the
// envelope's uniaxial stress) across the ligament. Returns the run's peak.
inline double checkBeam(const std::string& scenePath, double cell, double tailShare) {
  const Scene scene = loadSceneFile(std::filesystem::path(ECM_SOURCE_DIR) / scenePath);
  ecm::test::TempDir dir;
  const RunResult r = runScene(scene, quietRun(dir.path() / "out"));
  EXPECT_TRUE(r.completed) << r.message();
  const auto history = historyRows(dir.path() / "out" / "history.csv");
  BeamCurve run, energy;
  for (const auto& row : history) {
    run.cmod.push_back(row.at("cmod_mm"));
    run.load.push_back(-row.at("load_Fy_N"));
    energy.cmod.push_back(row.at("cmod_mm"));
    energy.load.push_back(row.at("dissipated_Nmm"));
  }
  const BeamCurve ref = beamReference("beam-point-node.csv"), band = beamReference("beam-band-node.csv");
  EXPECT_GT(ref.cmod.size(), 1000u);
  EXPECT_NEAR(run.peak(), ref.peak(), 0.03 * ref.peak());
  EXPECT_NEAR(run.peak(), band.peak(), 0.04 * band.peak());
  for (double c = 0.002; c <= 0.2 + 1e-12; c += 0.002) {
    EXPECT_LE(std::abs(run.at(c) - ref.at(c)), tailShare * ref.peak()) << "CMOD " << c;
    EXPECT_LE(std::abs(run.at(c) - band.at(c)), 0.05 * band.peak()) << "CMOD " << c;
  }
  EXPECT_NEAR(energy.at(0.2), 72.64, 0.05 * 72.64);

  const DamageLawParams law{37000.0, 3.9, 60.648935647284965, 0.2826059340689524};  // beam-concrete-hordijk
  const io::CsvTable particles = io::readCsv(dir.path() / "out" / "particles_final.csv");
  int open = 0;
  for (const auto& v : particles.rows) {
    const double x = v[0], damage = v[2], opening = v[4], nx = v[5], sxx = v[7];
    if (opening < 1e-3) continue;
    ++open;
    // (a crossed cell's points lie within a cell of the path, and have moved with their half)
    EXPECT_LE(std::abs(x - 87.5), 1.5 * cell) << "an open band off the ligament at x = " << x;
    EXPECT_GT(std::abs(nx), 0.99);
    EXPECT_LE(sxx, 1.1 * uniaxialStress(law, 1.0 - damage) + 0.02 * law.tensileStrength) << "at (" << x << ", " << v[1] << ")";
  }
  EXPECT_GE(open, static_cast<int>(0.9 * 2.0 * 25.0 / cell));  // the whole ligament, 25 mm: two points per cell row
  // The crack path itself (crack_paths.csv: arm, point, x, y, ahead) within one cell of the
  // ligament over the ligament's height, and one crack only (its two arms).
  int vertices = 0;
  for (const auto& v : io::readCsv(dir.path() / "out" / "crack_paths.csv").rows) {
    if (v[4] != 0.0 || v[3] < 25.0 || v[3] > 50.0) continue;
    ++vertices;
    EXPECT_LE(v[0], 1.0) << "more than one crack";
    EXPECT_LE(std::abs(v[2] - 87.5), cell) << "the crack path off the ligament at y = " << v[3];
  }
  EXPECT_GT(vertices, 10);
  return run.peak();
}

}  // namespace ecm::mpm::test
