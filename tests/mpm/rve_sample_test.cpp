// The RVE sample generator (mpm/scene/rve_sample.hpp) and the `rve:` body of scenes: no overlaps, the
// gap and the ITZ thickness are kept, the same seed gives the same sample, the target fraction
// is hit, infeasible targets and bad values are refused; a small RVE cracks first in its ITZ.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "../io/temp_dir.hpp"
#include "mpm/scene/rve_sample.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "mpm/setup/seeding.hpp"
#include "mpm/explicit/explicit_solver.hpp"

namespace ecm::mpm::test {
namespace {

using namespace ecm::test;  // expectContains, inputError

RveParams shippedParams() {  // those of data/rve/rve-coarse.yaml
  RveParams p;
  p.side = 25.0;
  p.seed = 1;
  p.volumeFraction = 0.4;
  p.grading = fullerGrading(1.0, 4.0);
  p.itzThickness = 0.2;
  p.gap = 0.1;
  return p;
}

void expectValidLayout(const RveSample& s) {
  const RveParams& p = s.params;
  const double t = p.itzThickness, gap = p.effectiveGap();
  ASSERT_FALSE(s.inclusions.empty());
  for (std::size_t i = 0; i < s.inclusions.size(); ++i) {
    const Inclusion& a = s.inclusions[i];
    const double reach = a.radius + t + gap;
    for (int d = 0; d < 2; ++d) {
      EXPECT_GE(a.center[d] - p.origin[d], reach - 1e-12) << "inclusion " << i << " too close to the low side";
      EXPECT_LE(a.center[d] - p.origin[d], p.side - reach + 1e-12) << "inclusion " << i << " too close to the high side";
    }
    EXPECT_GE(2.0 * a.radius, p.minDiameter() - 1e-12);
    EXPECT_LE(2.0 * a.radius, p.maxDiameter() + 1e-12);
    for (std::size_t j = 0; j < i; ++j) {
      const Inclusion& b = s.inclusions[j];
      EXPECT_GE((a.center - b.center).norm(), a.radius + b.radius + 2.0 * t + gap - 1e-12) << i << " and " << j;
    }
  }
}

TEST(RveSample, InclusionsKeepTheirItzAndGapApartAndInsideTheSquare) {
  const RveSample s = generateRve(shippedParams());
  expectValidLayout(s);
  RveParams other = shippedParams();
  other.origin = Vec2(-3.0, 7.0);
  other.gap = -1.0;  // default: 0.1 d_min
  other.seed = 42;
  other.volumeFraction = 0.3;
  EXPECT_DOUBLE_EQ(other.effectiveGap(), 0.1);
  expectValidLayout(generateRve(other));
}

TEST(RveSample, SameSeedSameSampleOtherSeedOtherSample) {
  const RveSample a = generateRve(shippedParams()), b = generateRve(shippedParams());
  ASSERT_EQ(a.inclusions.size(), b.inclusions.size());
  for (std::size_t i = 0; i < a.inclusions.size(); ++i) {
    EXPECT_EQ(a.inclusions[i].center[0], b.inclusions[i].center[0]);
    EXPECT_EQ(a.inclusions[i].center[1], b.inclusions[i].center[1]);
    EXPECT_EQ(a.inclusions[i].radius, b.inclusions[i].radius);
  }
  RveParams p = shippedParams();
  p.seed = 2;
  const RveSample c = generateRve(p);
  EXPECT_NE(c.inclusions.front().center[0], a.inclusions.front().center[0]);
  // Placement is largest first (strictly so when nothing had to be drawn again).
  ASSERT_EQ(a.stats.dropped, 0u);
  for (std::size_t i = 1; i < a.inclusions.size(); ++i) EXPECT_LE(a.inclusions[i].radius, a.inclusions[i - 1].radius);
}

TEST(RveSample, TargetFractionIsHitAndStatisticsAddUp) {
  for (const double f : {0.15, 0.3, 0.4})
    for (const std::uint64_t seed : {1u, 7u, 123u}) {
      RveParams p = shippedParams();
      p.volumeFraction = f;
      p.seed = seed;
      const RveSample s = generateRve(p);
      const RveStats& st = s.stats;
      EXPECT_NEAR(st.achievedFraction, f, 0.01) << "f " << f << " seed " << seed;
      EXPECT_LE(st.achievedFraction, f + 1e-12);  // never above the target
      double inc = 0.0, itz = 0.0, lo = 1e9, hi = 0.0, sum = 0.0;
      for (const Inclusion& i : s.inclusions) {
        inc += std::numbers::pi * i.radius * i.radius;
        itz += std::numbers::pi * (std::pow(i.radius + p.itzThickness, 2) - i.radius * i.radius);
        lo = std::min(lo, 2.0 * i.radius);
        hi = std::max(hi, 2.0 * i.radius);
        sum += 2.0 * i.radius;
      }
      EXPECT_EQ(st.count, s.inclusions.size());
      EXPECT_NEAR(st.achievedFraction, inc / 625.0, 1e-12);
      EXPECT_NEAR(st.itzFraction, itz / 625.0, 1e-12);
      EXPECT_NEAR(st.matrixFraction, 1.0 - st.achievedFraction - st.itzFraction, 1e-12);
      EXPECT_DOUBLE_EQ(st.minDiameter, lo);
      EXPECT_DOUBLE_EQ(st.maxDiameter, hi);
      EXPECT_NEAR(st.meanDiameter, sum / static_cast<double>(st.count), 1e-12);
    }
}

TEST(RveSample, GradingCurvesAreFollowed) {
  const auto g = fullerGrading(2.0, 8.0, 0.5, 4);
  ASSERT_EQ(g.size(), 5u);
  EXPECT_DOUBLE_EQ(g.front().diameter, 2.0);
  EXPECT_DOUBLE_EQ(g.back().diameter, 8.0);
  EXPECT_DOUBLE_EQ(g.front().passing, 0.5);
  EXPECT_DOUBLE_EQ(g.back().passing, 1.0);
  EXPECT_NEAR(g[2].diameter, 4.0, 1e-12);  // geometric spacing

  // Two classes, the coarse one [3, 4] holding 3/4 of the area: ~3/4 of the area is coarse.
  RveParams p = shippedParams();
  p.volumeFraction = 0.3;
  p.grading = {{1.0, 0.0}, {2.0, 25.0}, {3.0, 25.0}, {4.0, 100.0}};
  const RveSample s = generateRve(p);
  expectValidLayout(s);
  double coarse = 0.0, total = 0.0;
  for (const Inclusion& i : s.inclusions) {
    EXPECT_FALSE(2.0 * i.radius > 2.0 + 1e-12 && 2.0 * i.radius < 3.0 - 1e-12) << "diameter in an empty class";
    total += i.radius * i.radius;
    if (2.0 * i.radius >= 3.0 - 1e-12) coarse += i.radius * i.radius;
  }
  EXPECT_NEAR(coarse / total, 0.75, 0.05);
}

TEST(RveSample, UnreachableTargetsAndBadParametersAreRefused) {
  RveParams p = shippedParams();
  p.volumeFraction = 0.6;
  p.attempts = 2000;
  try {
    generateRve(p);
    FAIL() << "no RveInfeasible";
  } catch (const RveInfeasible& e) {
    EXPECT_EQ(e.target, 0.6);
    EXPECT_LT(e.reached, 0.6 - p.tolerance);
    expectContains(e.what(), "0.6 not reached");
  }
  auto bad = [](auto change) {
    RveParams q = shippedParams();
    change(q);
    EXPECT_THROW(generateRve(q), std::invalid_argument);
  };
  bad([](RveParams& q) { q.side = 0.0; });
  bad([](RveParams& q) { q.side = 4.0; });  // 4 + 2 (0.2 + 0.1) > 4: the largest does not fit
  bad([](RveParams& q) { q.volumeFraction = 1.0; });
  bad([](RveParams& q) { q.itzThickness = 0.0; });
  bad([](RveParams& q) { q.grading = {{1.0, 0.0}}; });
  bad([](RveParams& q) { q.grading = {{2.0, 0.0}, {1.0, 1.0}}; });
  bad([](RveParams& q) { q.grading = {{1.0, 1.0}, {2.0, 0.5}}; });
  bad([](RveParams& q) { q.side = 1e6; });  // ~10^11 inclusions
}

// --- scenes --------------------------------------------------------------------------------

const std::string kRveScene = R"(name: rve
grid: {origin: [0, 0], cell_size: [0.25, 0.25], cells: [40, 41]}
thickness: 10
materials:
  - {file: rve-matrix.yaml}
  - {file: rve-inclusion.yaml}
  - {file: rve-itz.yaml}
bodies:
  - rve: {side: 10, seed: 3, volume_fraction: 0.3, diameters: [0.5, 2.0], itz_thickness: 0.125, gap: 0.1,
          matrix: rve-matrix, inclusion: rve-inclusion, itz: rve-itz}
end_time: 1e-3
)";

Scene rveScene(const std::string& text) {
  return readScene(io::parseYaml(text, (std::filesystem::path(ECM_SOURCE_DIR) / "data" / "rve" / "test.yaml").string()));
}

TEST(RveScene, BodyExpandsIntoMatrixItzAndInclusionsWithTheItzThickness) {
  const Scene s = rveScene(kRveScene);
  RveParams p;
  p.side = 10.0;
  p.seed = 3;
  p.volumeFraction = 0.3;
  p.grading = fullerGrading(0.5, 2.0);
  p.itzThickness = 0.125;
  p.gap = 0.1;
  const RveSample sample = generateRve(p);
  const std::size_t n = sample.inclusions.size();
  ASSERT_EQ(s.bodies.size(), 1 + 2 * n);
  EXPECT_EQ(s.bodies[0].shape.kind, ShapeKind::Rectangle);
  EXPECT_EQ(s.materials[static_cast<std::size_t>(s.bodies[0].material)].name, "rve-matrix");
  for (std::size_t i = 0; i < n; ++i) {
    const Body& itz = s.bodies[1 + i];
    const Body& inc = s.bodies[1 + n + i];
    EXPECT_EQ(s.materials[static_cast<std::size_t>(itz.material)].name, "rve-itz");
    EXPECT_EQ(s.materials[static_cast<std::size_t>(inc.material)].name, "rve-inclusion");
    EXPECT_EQ(inc.shape.center, sample.inclusions[i].center);
    EXPECT_EQ(itz.shape.center, sample.inclusions[i].center);
    EXPECT_DOUBLE_EQ(inc.shape.radius, sample.inclusions[i].radius);
    EXPECT_DOUBLE_EQ(itz.shape.radius - inc.shape.radius, 0.125);  // the ITZ thickness
  }
  // Every particle has the phase of its distance to the nearest inclusion centre.
  const Particles particles = seedParticles(s);
  std::size_t itzCount = 0;
  for (std::size_t k = 0; k < particles.size(); ++k) {
    std::string expected = "rve-matrix";
    for (const Inclusion& i : sample.inclusions) {
      const double d = (particles.position[k] - i.center).norm();
      if (d <= i.radius) expected = "rve-inclusion";
      else if (d <= i.radius + 0.125) expected = "rve-itz";
      else continue;
      break;
    }
    EXPECT_EQ(s.materials[particles.material[k]].name, expected) << "particle " << k;
    itzCount += expected == "rve-itz";
  }
  EXPECT_GT(itzCount, 0u);
}

TEST(RveScene, BadValuesAreRefusedWithFileLineAndReason) {
  auto err = [](const std::string& text) { return inputError([&] { rveScene(text); }); };
  auto with = [](const std::string& from, const std::string& to) {
    std::string t = kRveScene;
    t.replace(t.find(from), from.size(), to);
    return t;
  };
  {
    const auto e = err(with("side: 10", "side: -10"));
    EXPECT_EQ(e.line, 9);
    expectContains(e.what(), "test.yaml:9:");
    expectContains(e.what(), "side");
  }
  expectContains(err(with("volume_fraction: 0.3", "volume_fraction: 1.3")).what(), "volume_fraction");
  expectContains(err(with("seed: 3", "seed: -1")).what(), "seed");
  expectContains(err(with("diameters: [0.5, 2.0]", "diameters: [2.0, 0.5]")).what(), "d_max >= d_min");
  expectContains(err(with("diameters: [0.5, 2.0]", "diameters: [0.5]")).what(), "diameters");
  expectContains(err(with("itz_thickness: 0.125", "itz_thickness: 0")).what(), "itz_thickness");
  expectContains(err(with("gap: 0.1", "gap: -0.1")).what(), "gap");
  expectContains(err(with("side: 10", "side: 2")).what(), "cannot hold the largest inclusion");
  expectContains(err(with("itz: rve-itz", "itz: nothing")).what(), "unknown material 'nothing'");
  expectContains(err(with("diameters: [0.5, 2.0]", "diameters: [0.5, 2.0], grading: [[0.5, 0], [2, 1]]")).what(),
                 "exactly one of diameters");
  expectContains(err(with("gap: 0.1,", "gap: 0.1, colour: red,")).what(), "colour");
  expectContains(err(with("  - rve:", "  - material: rve-matrix\n    rve:")).what(), "only the rve map");
  {
    const auto e = err(with("volume_fraction: 0.3", "volume_fraction: 0.65"));
    EXPECT_EQ(e.line, 9);
    expectContains(e.what(), "target inclusion fraction 0.65 not reached");
  }
  // A custom grading curve is accepted.
  EXPECT_NO_THROW(rveScene(with("diameters: [0.5, 2.0]", "grading: [[0.5, 0], [1, 40], [2, 100]]")));
}

TEST(RveScene, ShippedScenesHoldTheSameSample) {
  const auto dir = std::filesystem::path(ECM_SOURCE_DIR) / "data" / "rve";
  const Scene coarse = loadSceneFile(dir / "rve-coarse.yaml");
  const Scene fine = loadSceneFile(dir / "rve-fine.yaml");
  const Scene xfine = loadSceneFile(dir / "rve-xfine.yaml");  // the convergence check
  for (const Scene* other : {&fine, &xfine}) {
    ASSERT_EQ(coarse.bodies.size(), other->bodies.size());
    for (std::size_t i = 0; i < coarse.bodies.size(); ++i) {
      EXPECT_EQ(coarse.bodies[i].shape.center, other->bodies[i].shape.center);
      EXPECT_EQ(coarse.bodies[i].shape.radius, other->bodies[i].shape.radius);
      EXPECT_EQ(coarse.bodies[i].material, other->bodies[i].material);
    }
    EXPECT_EQ(other->solver.effectiveSize, coarse.solver.effectiveSize);
    EXPECT_EQ(other->solver.shapeFunction, coarse.solver.shapeFunction);
    EXPECT_EQ(other->endTime, coarse.endTime);
  }
  EXPECT_DOUBLE_EQ(coarse.grid.cellSize[0], 0.25);
  EXPECT_DOUBLE_EQ(fine.grid.cellSize[0], 0.125);
  EXPECT_DOUBLE_EQ(xfine.grid.cellSize[0], 0.0625);
  EXPECT_EQ(coarse.solver.effectiveSize, EffectiveSizeRule::SquareRoot);
  for (const auto& m : coarse.materials) EXPECT_EQ(m.model, ModelKind::Enriched);
  EXPECT_GT(coarse.bodies.size(), 100u);
}

// A 5 mm RVE pulled in y (three samples): the first points to crack are in the ITZ, the
// weakest phase (f_t 1.5 MPa against 2.0 for the matrix), where the stiffer inclusions
// concentrate the stress.
std::string smallRve(int seed) {
  return R"(name: rve-small
grid: {origin: [0, 0], cell_size: [0.25, 0.25], cells: [20, 21]}
thickness: 10
materials:
  - {file: rve-matrix.yaml}
  - {file: rve-inclusion.yaml}
  - {file: rve-itz.yaml}
bodies:
  - rve: {side: 5, seed: )" + std::to_string(seed) + R"(, volume_fraction: 0.2, diameters: [0.8, 1.6], itz_thickness: 0.25,
          gap: 0.1, tolerance: 0.05, matrix: rve-matrix, inclusion: rve-inclusion, itz: rve-itz}
solver: {local_damping: 0.1, flip: 0.99, crack_path: free}   # the paper's rule, as data/rve/
end_time: 1e-4
conditions:
  - {name: base, box: {min: [0, 0], max: [5, 0]}, fixed: [y]}
  - {name: corner, box: {min: [0, 0], max: [0, 0]}, fixed: [x]}
  - {name: top, box: {min: [0, 5], max: [5, 5]}, displacement: {y: {type: linear_ramp, value: 2e-3, time: 1e-4}}}
)";
}

TEST(RveScene, SmallRveCracksFirstInTheItz) {
  for (const int seed : {1, 2, 3}) {
    const Scene s = rveScene(smallRve(seed));
    ExplicitSolver solver(s, 1);
    while (solver.particles().bands.empty() && solver.time() < s.endTime) solver.advance();
    const Particles& p = solver.particles();
    ASSERT_FALSE(p.bands.empty()) << "seed " << seed << ": nothing cracked by t = " << solver.time() << " s";
    std::size_t itz = 0, cracked = 0;
    for (std::size_t k = 0; k < p.size(); ++k) {
      if (p.band[k] < 0) continue;
      ++cracked;
      itz += s.materials[p.material[k]].name == "rve-itz";
    }
    std::printf("[ rve ] seed %d: first crack at step %ld, t = %.3g s: %zu points, %zu in the ITZ\n", seed, solver.step(),
                solver.time(), cracked, itz);
    EXPECT_EQ(itz, cracked) << "seed " << seed;
  }
}

// The same RVE pulled to a mean strain of 4e-4 (about five times the strain at the peak): the
// mean stress rises, peaks, and softens as micro-cracks localise (the snap-back releases of the
// enriched update keep the run going, ecm-mpm's default).
TEST(RveScene, SmallRveSoftensAfterItsPeak) {
  const Scene s = rveScene(smallRve(1));
  ExplicitSolver solver(s, 1);
  double peak = 0.0, peakStrain = 0.0, last = 0.0;
  while (solver.time() < s.endTime) {
    solver.advance();
    last = solver.conditions()[2].reaction[1] / (5.0 * s.thickness);  // mean stress (MPa)
    if (last > peak) peak = last, peakStrain = solver.conditions()[2].displacement[1] / 5.0;
  }
  std::printf("[ rve ] seed 1: peak mean stress %.3f MPa at strain %.3g, final %.3f MPa at %.3g; %zu cracked, %ld "
              "snap-back releases\n",
              peak, peakStrain, last, solver.conditions()[2].displacement[1] / 5.0, solver.particles().bands.size(),
              solver.snapBackReleases());
  EXPECT_GT(peak, 1.0);  // of the order of the phase strengths 1.5-3 MPa
  EXPECT_LT(peakStrain, 0.6 * 4e-4);
  EXPECT_LT(last, 0.7 * peak);
}

}  // namespace
}  // namespace ecm::mpm::test
