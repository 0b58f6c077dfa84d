#pragma once
// Plots for run outputs: a small spec rendered to PNG by gnuplot. NAME.gp is written next to
// NAME.png (so the plot can be tweaked and re-run by hand: `cd DIR && gnuplot NAME.gp`) and
// gnuplot runs in that folder, so data files are named relative to it. A missing or failing
// gnuplot only warns on stderr: a plot never aborts a run.
#include <filesystem>
#include <string>
#include <vector>

namespace ecm::io {

struct PlotSeries {
  std::string dataFile;           // relative to the PNG's folder; empty for a function series
  std::string columns = "1:2";    // gnuplot `using` spec
  std::string expression;         // a gnuplot expression in x, plotted instead of a data file
  std::string title;
  std::string style = "lines";    // gnuplot `with` spec: lines, points, linespoints pt 7, ...
};

struct PlotSpec {
  std::string title;
  std::string xLabel;
  std::string yLabel;
  // Labels, titles and legend entries are plain text ("sig_xx" stays sig_xx); a spec whose axis
  // labels use gnuplot's enhanced markup ("{/Symbol s}") sets this. Legend entries stay plain.
  bool enhancedLabels = false;
  bool logX = false;
  bool logY = false;
  std::string xRange;                  // e.g. "[0:0.3]"; empty = automatic
  std::string yRange;
  std::vector<std::string> functions;  // inline definitions, e.g. "f(x) = exp(-x)"
  std::vector<std::string> settings;   // further gnuplot commands before the plot, e.g. "set ytics 1"
  std::vector<PlotSeries> series;
  int width = 900;
  int height = 600;
  std::string gnuplot = "gnuplot";     // the executable (looked up in PATH)
};

// The script that renderPlot writes (pngcairo if gnuplot has it, else png).
std::string gnuplotScript(const PlotSpec& spec, const std::string& pngName);

// Writes PNG.gp (PNG with extension .gp) and runs gnuplot on it. Returns true when the PNG was
// produced; otherwise prints a warning on stderr and returns false.
bool renderPlot(const PlotSpec& spec, const std::filesystem::path& png);

}  // namespace ecm::io
