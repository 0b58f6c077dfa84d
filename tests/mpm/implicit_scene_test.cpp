// implicit_static scenes: the shipped bar read and run through runScene (the path ecm-mpm and
// the Python module take), with its energy balance; and the refusals of bad input with the line
// and the reason.
#include <gtest/gtest.h>

#include <fstream>
#include <iterator>

#include "../io/temp_dir.hpp"
#include "mpm/run.hpp"
#include "mpm/scene_yaml.hpp"

namespace ecm::mpm::test {
namespace {

using ecm::test::expectContains;
using ecm::test::inputError;

std::string shippedBar() {
  std::ifstream in(std::filesystem::path(ECM_SOURCE_DIR) / "data" / "mpm" / "bar-snapback-implicit.yaml");
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  return text.replace(at, from.size(), to);
}

TEST(ImplicitScene, TheShippedBarRunsThroughItsPeakWithItsEnergyBalanced) {
  // The first 0.002 mm of opening (200 load steps): through the peak at 9.1e-4 mm.
  const std::string text = replaced(shippedBar(), "until: 0.04 ", "until: 0.002");
  const Scene scene = readScene(io::parseYaml(text, "bar.yaml"));
  ASSERT_TRUE(scene.solver.implicit && scene.solver.implicit->indirect);
  ecm::test::TempDir dir;
  RunOptions options;
  options.outputDir = dir.path() / "out";
  options.threads = 1;
  options.progress = false;
  options.plot = false;
  const RunResult r = runScene(scene, options);
  ASSERT_TRUE(r.completed) << r.error;
  EXPECT_EQ(r.steps, 200);
  // The peak: the weak row's strength times the bar's section (20 mm x 1 mm), to 1e-3.
  EXPECT_NEAR(r.peakLoad, 2.9 * 20.0, 1e-3 * 2.9 * 20.0);
  // The external work is what is stored plus what the band dissipated (last row).
  std::ifstream in(options.outputDir / "history.csv");
  std::string header, line, last;
  std::getline(in, header);
  while (std::getline(in, line)) last = line;
  std::vector<std::string> names, values;
  for (std::stringstream h(header); std::getline(h, line, ',');) names.push_back(line);
  for (std::stringstream v(last); std::getline(v, line, ',');) values.push_back(line);
  ASSERT_EQ(names.size(), values.size());
  const auto at = [&](const std::string& name) {
    return std::stod(values[static_cast<std::size_t>(std::find(names.begin(), names.end(), name) - names.begin())]);
  };
  EXPECT_GT(at("dissipated_Nmm"), 0.0);
  EXPECT_NEAR(at("external_work_Nmm"), at("strain_Nmm") + at("dissipated_Nmm"), 1e-3 * at("external_work_Nmm"));
  EXPECT_GT(at("load_factor"), 0.0);
  EXPECT_TRUE(std::filesystem::exists(options.outputDir / "particles_final.csv"));
  EXPECT_TRUE(std::filesystem::exists(options.outputDir / "summary.json"));
}

TEST(ImplicitScene, BadInputIsRefusedWithTheLineAndTheReason) {
  const std::string bar = shippedBar();
  const auto err = [](const std::string& text) { return inputError([&] { readScene(io::parseYaml(text, "bar.yaml")); }); };
  {  // an explicit-only key on an implicit scene
    const auto e = err(replaced(bar, "  tolerance: 1e-6 ", "  cfl: 0.3\n  tolerance: 1e-6 "));
    expectContains(e.what(), "cfl");
    expectContains(e.what(), "explicit");
  }
  {  // an implicit key on an explicit scene
    const auto e = err(replaced(replaced(bar, "  scheme: implicit_static", "  scheme: usl"), "  control:", "  control_:"));
    expectContains(e.what(), "tolerance");
    expectContains(e.what(), "implicit_static");
  }
  {  // a driven condition that does not exist
    const auto e = err(replaced(bar, "driven: [top]", "driven: [roof]"));
    expectContains(e.what(), "no condition named 'roof'");
    EXPECT_EQ(e.line, 28);
  }
  {  // a control that names no node
    const std::string text = bar.substr(0, bar.find("      opening:")) + "      opening: []\n" + bar.substr(bar.find("      step: 1e-5"));
    expectContains(err(text).what(), "names no node");
  }
  {  // a tolerance out of range
    const auto e = err(replaced(bar, "tolerance: 1e-6 ", "tolerance: 0.5 "));
    expectContains(e.what(), "tolerance");
    EXPECT_EQ(e.line, 25);
  }
  {  // checkpoints are not there yet for implicit runs
    expectContains(err(bar + "checkpoint: {every_steps: 10}\n").what(), "no checkpoints yet");
  }
}

}  // namespace
}  // namespace ecm::mpm::test
