// Output folders, JSON summaries, gnuplot plots and the progress reporter.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "io/particle_map.hpp"
#include "io/progress.hpp"
#include "temp_dir.hpp"

namespace ecm::io {
namespace {

using namespace ecm::test;  // expectContains, readFile, TempDir

TEST(OutputDir, CreatesNestedFoldersAndLeavesNoProbe) {
  const TempDir dir;
  const auto out = dir.path() / "a" / "b" / "c";
  EXPECT_EQ(prepareOutputDir(out), out);
  EXPECT_TRUE(std::filesystem::is_directory(out));
  EXPECT_TRUE(std::filesystem::is_empty(out));
  EXPECT_NO_THROW(prepareOutputDir(out));  // existing folder is fine
}

TEST(OutputDir, RefusesAFileOrAFolderBelowAFile) {
  const TempDir dir;
  const auto file = dir.write("plain.txt", "x");
  for (const auto& bad : {file, file / "sub"}) {
    try {
      prepareOutputDir(bad);
      FAIL() << "no error for " << bad;
    } catch (const OutputError& e) {
      expectContains(e.what(), bad.string());
    }
  }
}

TEST(JsonSummary, WritesAtomicallyAndOverwrites) {
  const TempDir dir;
  const auto path = dir.path() / "summary.json";
  writeJsonSummary({{"Ep", 8.184}, {"n", 0.128}}, path);
  writeJsonSummary({{"Ep", 8.18}, {"label", "second"}}, path);
  const auto j = nlohmann::json::parse(readFile(path));
  EXPECT_EQ(j.at("Ep").get<double>(), 8.18);
  EXPECT_EQ(j.at("label"), "second");
  EXPECT_FALSE(j.contains("n"));
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "summary.json.tmp"));
}

TEST(JsonSummary, UnwritablePathThrowsNamingIt) {
  const TempDir dir;
  const auto path = dir.path() / "missing" / "summary.json";
  try {
    writeJsonSummary({{"a", 1}}, path);
    FAIL();
  } catch (const OutputError& e) {
    expectContains(e.what(), path.string());
  }
}

TEST(AtomicFile, DurableWriteReplacesAndAFailedOneKeepsTheOldFile) {
  const TempDir dir;
  const auto path = dir.path() / "state.bin";
  writeFileAtomically(path, "first", Durability::Sync);
  writeFileAtomically(path, "second", Durability::Sync);
  EXPECT_EQ(readFile(path), "second");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "state.bin.tmp"));
  {
    const test::FileSizeLimit limit(3);  // the new content does not fit: like a full disk
    EXPECT_THROW(writeFileAtomically(path, "third, longer", Durability::Sync), OutputError);
  }
  EXPECT_EQ(readFile(path), "second");
  EXPECT_FALSE(std::filesystem::exists(dir.path() / "state.bin.tmp"));
  std::filesystem::create_directory(dir.path() / "state.bin.tmp");  // the temporary cannot be created
  try {
    writeFileAtomically(path, "fourth", Durability::Sync);
    FAIL();
  } catch (const OutputError& e) {
    expectContains(e.what(), path.string());
  }
  EXPECT_EQ(readFile(path), "second");
}

PlotSpec sampleSpec() {
  PlotSpec spec;
  spec.title = "softening of 'den' concrete";
  spec.xLabel = "w (mm)";
  spec.yLabel = "sigma (MPa)";
  spec.functions = {"f(x) = 3*exp(-x/0.05)"};
  spec.series = {{"curve.csv", "1:2", "", "model", "lines"}, {"", "", "f(x)", "target", "lines dt 2"}};
  return spec;
}

TEST(Gnuplot, ScriptHasTerminalFallbackLabelsFunctionsAndSeries) {
  const std::string s = gnuplotScript(sampleSpec(), "plot.png");
  expectContains(s, "pngcairo");
  expectContains(s, "set terminal png size");
  expectContains(s, "set output 'plot.png'");
  expectContains(s, "set title 'softening of ''den'' concrete'");
  expectContains(s, "f(x) = 3*exp(-x/0.05)");
  expectContains(s, "'curve.csv' using 1:2 title 'model' noenhanced with lines");
  expectContains(s, "f(x) title 'target' noenhanced with lines dt 2");
}

TEST(Gnuplot, LabelsAndLegendsArePlainTextUnlessAsked) {
  // Issue: "sig_xx" in a legend rendered as sig, a subscript x, then x (gnuplot's enhanced text).
  PlotSpec spec = sampleSpec();
  spec.xLabel = "eps_xx";
  spec.series[0].title = "sig_xx";
  std::string s = gnuplotScript(spec, "plot.png");
  expectContains(s, "set xlabel 'eps_xx' noenhanced");
  expectContains(s, "set ylabel 'sigma (MPa)' noenhanced");
  expectContains(s, "title 'sig_xx' noenhanced with lines");
  spec.enhancedLabels = true;  // a label with markup ({/Symbol s})
  s = gnuplotScript(spec, "plot.png");
  expectContains(s, "set xlabel 'eps_xx'\n");
  expectContains(s, "title 'sig_xx' noenhanced with lines");
}

TEST(Gnuplot, RendersAPngWhenGnuplotIsThere) {
  const TempDir dir;
  dir.write("curve.csv", "w,sigma\n0,3\n0.05,1.1\n0.1,0.4\n");
  const bool ok = renderPlot(sampleSpec(), dir.path() / "plot.png");
  EXPECT_TRUE(std::filesystem::exists(dir.path() / "plot.gp"));
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  EXPECT_TRUE(ok);
  EXPECT_GT(std::filesystem::file_size(dir.path() / "plot.png"), 1000u);
}

TEST(ParticleMap, ASlenderDomainIsStretchedAndACompactOneDrawnToScale) {
  // Issue: the damage map of the 20 x 1000 mm bar (grid 40 x 1020 mm) drawn to scale was a
  // sliver under the colour bar, with overlapping x labels.
  ParticleMap bar{"bar: damage at the end", "particles_final.csv", "1:2:3", "damage", 40.0, 1020.0, 8000};
  const PlotSpec slender = particleMapSpec(bar);
  std::string s = gnuplotScript(slender, "damage_map.png");
  EXPECT_EQ(s.find("set size ratio -1"), std::string::npos);
  expectContains(slender.title, "(axes not to scale)");
  expectContains(s, "set colorbox vertical user origin graph 1.04");
  expectContains(s, "set xtics 20");  // two tics across the 40 mm, labels apart
  EXPECT_GT(slender.height, slender.width);
  ParticleMap panel = bar;
  panel.width = panel.height = 205.0;  // the DEN panel: to scale
  s = gnuplotScript(particleMapSpec(panel), "damage_map.png");
  expectContains(s, "set size ratio -1");
  EXPECT_EQ(particleMapSpec(panel).title, "bar: damage at the end");
}

TEST(ParticleMap, RendersWhenGnuplotIsThere) {
  const TempDir dir;
  std::string csv = "x_mm,y_mm,damage\n";
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 200; ++j) csv += std::to_string(2.5 + 5 * i) + "," + std::to_string(2.5 + 5 * j) + "," + (j == 98 ? "1" : "0") + "\n";
  dir.write("particles_final.csv", csv);
  const bool ok = renderPlot(particleMapSpec({"bar", "particles_final.csv", "1:2:3", "damage", 20.0, 1000.0, 800}),
                             dir.path() / "damage_map.png");
  if (std::system("gnuplot --version > /dev/null 2>&1") != 0) GTEST_SKIP() << "gnuplot not installed";
  EXPECT_TRUE(ok);
}

TEST(Gnuplot, MissingOrFailingGnuplotOnlyWarns) {
  const TempDir dir;
  PlotSpec spec = sampleSpec();
  spec.gnuplot = "ecm-no-such-gnuplot";
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(renderPlot(spec, dir.path() / "plot.png"));
  const std::string err = ::testing::internal::GetCapturedStderr();
  expectContains(err, "warning: plot");
  expectContains(err, "not found");
  spec.gnuplot = "false";  // starts, then fails
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(renderPlot(spec, dir.path() / "plot.png"));
  expectContains(::testing::internal::GetCapturedStderr(), "failed");
}

std::string captured(std::FILE* f) {
  std::fflush(f);
  std::rewind(f);
  std::string s;
  for (int c; (c = std::fgetc(f)) != EOF;) s += static_cast<char>(c);
  return s;
}

TEST(Progress, PlainModePrintsLinesAndOneFinalLine) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p(200.0, {"run", 0.0, f, false});
    EXPECT_FALSE(p.terminal());
    p.update(50.0);
    p.update(100.0);
    p.finish();
    p.update(150.0);  // ignored after finish
  }                   // no second final line from the destructor
  const std::string s = captured(f);
  std::fclose(f);
  expectContains(s, "run:  25.0%");
  expectContains(s, "run:  50.0%");
  expectContains(s, "ETA");
  expectContains(s, "run: done (50.0%) in");
  EXPECT_EQ(s.find("75.0%"), std::string::npos);
  EXPECT_EQ(s.find("done", s.find("done") + 1), std::string::npos);
  EXPECT_EQ(s.find('\r'), std::string::npos);
}

TEST(Progress, TerminalModeRedrawsInPlace) {
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p(10.0, {"mpm", 0.0, f, true});
    p.update(10.0);  // within 0.1 s of the start: not drawn
  }
  const std::string s = captured(f);
  std::fclose(f);
  expectContains(s, "\r\033[Kmpm: done (100.0%)");
}

TEST(Progress, ANaNProgressCountsAsNone) {
  // The bar's width is cast to an int: a NaN fraction there was undefined behaviour (the same
  // pattern as the fuzzer's finding in the path's sample count); NaN now counts as 0 done.
  std::FILE* f = std::tmpfile();
  ASSERT_NE(f, nullptr);
  {
    Progress p(10.0, {"mpm", 0.0, f, true});
    p.update(NAN);
  }
  const std::string s = captured(f);
  std::fclose(f);
  expectContains(s, "mpm: done (0.0%)");
}

TEST(Progress, Durations) {
  EXPECT_EQ(formatDuration(12.34), "12.3 s");
  EXPECT_EQ(formatDuration(125.0), "2:05");
  EXPECT_EQ(formatDuration(3725.0), "1:02:05");
  EXPECT_EQ(formatDuration(-1.0), "?");
}

}  // namespace
}  // namespace ecm::io
