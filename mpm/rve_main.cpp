// ecm-rve: generates the mesoscale sample(s) of an RVE and writes their phase map and statistics.
//   ecm-rve SCENE_OR_PARAMS.yaml [--out DIR]
// A scene (a map with `bodies`) is read in full, seeded, and its particles are written coloured
// by phase; a parameter file holds only a top-level `rve:` map (the keys of an rve body without
// the material names) and its circles are drawn. Outputs in DIR: rve_stats.json (parameters and
// statistics of every sample), inclusions.csv (sample, x, y, diameter in mm), phases.csv and
// phases.png (+ .gp). Exit status (io/cli_exit.hpp): 0 written, 1 an output could not be written
// (what was written is kept), 2 bad input (infeasible target included) or output folder.
#include <CLI/CLI.hpp>
#include <optional>
#include <cstdio>
#include <exception>
#include <nlohmann/json.hpp>

#include "io/cli_exit.hpp"
#include "io/command_line.hpp"
#include "io/csv_writer.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "io/output_error.hpp"
#include "mpm/scene/rve_sample.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "mpm/setup/seeding.hpp"

namespace {

using namespace ecm;

nlohmann::json toJson(const mpm::RveSample& s) {
  const mpm::RveParams& p = s.params;
  const mpm::RveStats& st = s.stats;
  nlohmann::json grading = nlohmann::json::array();
  for (const auto& g : p.grading) grading.push_back({g.diameter, g.passing});
  return {{"side_mm", p.side},
          {"origin_mm", {p.origin[0], p.origin[1]}},
          {"seed", p.seed},
          {"itz_thickness_mm", p.itzThickness},
          {"gap_mm", p.effectiveGap()},
          {"grading_mm_passing", grading},
          {"target_fraction", st.targetFraction},
          {"achieved_fraction", st.achievedFraction},
          {"itz_fraction", st.itzFraction},
          {"matrix_fraction", st.matrixFraction},
          {"count", st.count},
          {"min_diameter_mm", st.minDiameter},
          {"mean_diameter_mm", st.meanDiameter},
          {"max_diameter_mm", st.maxDiameter},
          {"dropped", st.dropped}};
}

// `running` turns true once the input is read and the output folder is ready: a failure from
// there on is the run's (exit 1), one before it bad input (exit 2).
int run(const std::string& input, const std::filesystem::path& out, bool& running) {
  const io::YamlMap map = io::loadYamlFile(input);
  const bool isScene = map.has("bodies");
  std::vector<mpm::RveParams> params;
  mpm::Scene scene;
  if (isScene) {
    scene = mpm::loadSceneFile(input);  // checks everything
    params = mpm::sceneRveParams(map);
    if (params.empty()) map.fail("bodies", "the scene has no rve body");
  } else {
    if (!map.has("rve")) map.failHere("expected a scene (with bodies) or a parameter file with an rve map");
    params.push_back(mpm::readRveParams(map.child("rve")));
    map.finish();
  }
  std::vector<mpm::RveSample> samples;
  for (const auto& p : params) {
    try {
      samples.push_back(mpm::generateRve(p));
    } catch (const mpm::RveInfeasible& e) {
      map.fail(isScene ? "bodies" : "rve", e.what());  // a scene has failed in loadSceneFile already
    }
  }

  io::prepareOutputDir(out);
  running = true;
  nlohmann::json stats = {{"input", input}, {"samples", nlohmann::json::array()}};
  {
    io::CsvWriter inc(out / "inclusions.csv", {"sample", "x_mm", "y_mm", "diameter_mm"});
    for (std::size_t k = 0; k < samples.size(); ++k) {
      stats["samples"].push_back(toJson(samples[k]));
      for (const auto& i : samples[k].inclusions) inc.row({double(k), i.center[0], i.center[1], 2.0 * i.radius});
    }
    inc.close();
  }

  io::PlotSpec plot;
  plot.title = "RVE phases: " + std::filesystem::path(input).filename().string();
  plot.xLabel = "x (mm)";
  plot.yLabel = "y (mm)";
  plot.width = plot.height = 900;
  plot.functions = {"set size ratio -1", "unset grid", "set key outside top center horizontal"};
  if (isScene) {
    const mpm::Particles particles = mpm::seedParticles(scene);
    std::vector<std::size_t> perMaterial(scene.materials.size(), 0);
    io::CsvWriter ph(out / "phases.csv", {"x_mm", "y_mm", "material"});
    for (std::size_t n = 0; n < particles.size(); ++n) {
      ph.row({particles.position[n][0], particles.position[n][1], double(particles.material[n])});
      ++perMaterial[particles.material[n]];
    }
    ph.close();
    nlohmann::json counts = nlohmann::json::object();
    const char* colours[] = {"rgb '#c8c8c8'", "rgb '#505050'", "rgb '#e03020'"};  // matrix, inclusion, ITZ in rve order
    for (std::size_t m = 0; m < scene.materials.size(); ++m) {
      counts[scene.materials[m].name] = perMaterial[m];
      const std::string colour = m < 3 ? colours[m] : std::to_string(m + 1);
      plot.series.push_back({"phases.csv", "1:($3 == " + std::to_string(m) + " ? $2 : 1/0)", "", scene.materials[m].name,
                             "points pt 5 ps 0.3 lc " + colour});
    }
    stats["particles_per_material"] = counts;
  } else {
    io::CsvWriter ph(out / "phases.csv", {"x_mm", "y_mm", "radius_mm", "phase"});
    for (const auto& s : samples)
      for (const auto& i : s.inclusions) {
        ph.row({i.center[0], i.center[1], i.radius + s.params.itzThickness, 1.0});
        ph.row({i.center[0], i.center[1], i.radius, 2.0});
      }
    ph.close();
    const auto& p = samples.front().params;
    plot.xRange = "[" + std::to_string(p.origin[0]) + ":" + std::to_string(p.origin[0] + p.side) + "]";
    plot.yRange = "[" + std::to_string(p.origin[1]) + ":" + std::to_string(p.origin[1] + p.side) + "]";
    plot.series.push_back({"phases.csv", "1:($4 == 1 ? $2 : 1/0):3", "", "ITZ", "circles fs solid 1.0 noborder lc rgb 'red'"});
    plot.series.push_back({"phases.csv", "1:($4 == 2 ? $2 : 1/0):3", "", "inclusion", "circles fs solid 1.0 noborder lc rgb 'gray40'"});
  }
  io::writeJsonSummary(stats, out / "rve_stats.json");
  io::renderPlot(plot, out / "phases.png");
  for (const auto& s : samples)
    std::fprintf(stderr, "RVE %g mm, seed %llu: fraction %.4f (target %.4f), ITZ %.4f, %zu inclusions, d %.3g/%.3g/%.3g mm\n",
                 s.params.side, static_cast<unsigned long long>(s.params.seed), s.stats.achievedFraction,
                 s.stats.targetFraction, s.stats.itzFraction, s.stats.count, s.stats.minDiameter, s.stats.meanDiameter,
                 s.stats.maxDiameter);
  return io::kExitDone;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"ecm-rve: mesoscale RVE samples, their phase map and statistics (units: mm)"};
  std::string input, out = "rve-out";
  app.add_option("input", input, "scene with an rve body, or a file with a top-level rve map (YAML)")
      ->required()
      ->check(CLI::ExistingFile);
  app.add_option("-o,--out", out, "output folder (default: rve-out)");
  if (const std::optional<int> status = ecm::io::parseCommandLine(app, "ecm-rve", argc, argv)) return *status;
  bool running = false;
  try {
    return run(input, out, running);
  } catch (const ecm::io::InputError& e) {
    ecm::io::printError("ecm-rve", e.what());
    return ecm::io::kExitBadInput;
  } catch (const ecm::io::OutputError& e) {
    ecm::io::printError("ecm-rve", e.what());
  } catch (const std::exception& e) {
    ecm::io::printError("ecm-rve", input + ": " + e.what());
  }
  return running ? ecm::io::kExitRunFailed : ecm::io::kExitBadInput;
}
