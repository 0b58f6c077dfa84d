#include "io/gnuplot.hpp"

#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>

namespace ecm::io {

namespace {

// A gnuplot single-quoted string: only ' needs escaping (as '').
std::string quote(const std::string& s) {
  std::string q = "'";
  for (const char c : s) q += c == '\'' ? std::string("''") : std::string(1, c);
  return q + "'";
}

void warn(const std::filesystem::path& png, const std::string& why) {
  std::cerr << "warning: plot " << png.string() << " not produced: " << why << '\n';
}

// Runs `program script` in `dir`; returns the exit status, 127 if it could not be started.
int run(const std::string& program, const std::string& script, const std::filesystem::path& dir) {
  const pid_t pid = ::fork();
  if (pid < 0) return -1;
  if (pid == 0) {
    if (!dir.empty() && ::chdir(dir.c_str()) != 0) ::_exit(126);
    ::execlp(program.c_str(), program.c_str(), script.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) return -1;
  }
  if (WIFEXITED(status)) return WEXITSTATUS(status);
  return -1;
}

}  // namespace

std::string gnuplotScript(const PlotSpec& spec, const std::string& pngName) {
  std::ostringstream s;
  const std::string size = std::to_string(spec.width) + "," + std::to_string(spec.height);
  s << "# Written by ecm; re-run in this folder with `gnuplot THIS_FILE` to redraw " << pngName << "\n";
  s << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
    << "  set terminal pngcairo size " << size << " enhanced font 'Sans,11'\n"
    << "} else {\n"
    << "  set terminal png size " << size << "\n"
    << "}\n";
  s << "set output " << quote(pngName) << "\n";
  s << "set datafile separator ','\n";
  s << "set key autotitle columnhead\n";
  s << "set grid\n";
  if (!spec.title.empty()) s << "set title " << quote(spec.title) << " noenhanced\n";
  const char* labels = spec.enhancedLabels ? "\n" : " noenhanced\n";
  if (!spec.xLabel.empty()) s << "set xlabel " << quote(spec.xLabel) << labels;
  if (!spec.yLabel.empty()) s << "set ylabel " << quote(spec.yLabel) << labels;
  if (spec.logX) s << "set logscale x\n";
  if (spec.logY) s << "set logscale y\n";
  if (!spec.xRange.empty()) s << "set xrange " << spec.xRange << "\n";
  if (!spec.yRange.empty()) s << "set yrange " << spec.yRange << "\n";
  for (const auto& c : spec.settings) s << c << "\n";
  for (const auto& f : spec.functions) s << f << "\n";
  s << "plot ";
  for (std::size_t i = 0; i < spec.series.size(); ++i) {
    const PlotSeries& p = spec.series[i];
    if (i) s << ", \\\n     ";
    if (p.dataFile.empty()) {
      s << p.expression;
    } else {
      s << quote(p.dataFile) << " using " << p.columns;
    }
    s << " title " << quote(p.title) << " noenhanced with " << p.style;
  }
  s << "\n";
  return s.str();
}

bool renderPlot(const PlotSpec& spec, const std::filesystem::path& png) {
  if (spec.series.empty()) {
    warn(png, "nothing to plot");
    return false;
  }
  std::filesystem::path script = png;
  script.replace_extension(".gp");
  {
    std::ofstream out(script);
    out << gnuplotScript(spec, png.filename().string());
    out.close();
    if (!out) {
      warn(png, "cannot write " + script.string());
      return false;
    }
  }
  std::error_code ec;
  std::filesystem::remove(png, ec);
  const int status = run(spec.gnuplot, script.filename().string(), png.parent_path());
  if (status == 127) {
    warn(png, "'" + spec.gnuplot + "' was not found (install gnuplot, e.g. gnuplot-nox)");
    return false;
  }
  if (status != 0) {
    warn(png, spec.gnuplot + " " + script.string() + " failed (exit status " + std::to_string(status) + ")");
    return false;
  }
  if (!std::filesystem::is_regular_file(png, ec) || std::filesystem::file_size(png, ec) == 0) {
    warn(png, spec.gnuplot + " produced no image");
    return false;
  }
  return true;
}

}  // namespace ecm::io
