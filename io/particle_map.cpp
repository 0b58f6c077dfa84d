#include "io/particle_map.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace ecm::io {

PlotSpec particleMapSpec(const ParticleMap& map) {
  const double w = std::max(map.width, 1e-300), h = std::max(map.height, 1e-300);
  const bool slender = std::max(w / h, h / w) > kSlenderRatio;
  PlotSpec spec;
  spec.title = map.title + (slender ? " (axes not to scale)" : "");
  spec.xLabel = "x (mm)";
  spec.yLabel = "y (mm)";
  // A tall domain on a tall canvas, a wide one on a wide canvas; the colour bar on the right.
  spec.width = slender && w > h ? 1100 : 800;
  spec.height = slender && h > w ? 900 : 760;
  const double points = static_cast<double>(std::max<std::size_t>(map.particles, 1));
  // Point size: about the spacing of the particles on the canvas. To scale, sqrt(area / N); a
  // stretched domain is filled along its short side by its own particle count across it.
  double across = std::sqrt(points);
  if (slender) across = std::sqrt(points * std::min(w, h) / std::max(w, h)) * (w > h ? spec.height / 500.0 : spec.width / 500.0);
  const double size = std::clamp(8.0 / std::max(across, 1.0) * (slender ? 4.0 : 1.0), 0.05, 3.0);
  std::ostringstream ps;
  ps << size;
  spec.functions = {"set cbrange [0:1]", "set cblabel '" + map.valueLabel + "' noenhanced",
                    "set palette defined (0 '#f2f2f2', 0.3 '#9ecae1', 0.7 '#de2d26', 1 '#67000d')", "unset grid",
                    "set key off", "set colorbox vertical user origin graph 1.04, graph 0 size graph 0.03, graph 1",
                    "set rmargin at screen 0.85", "set xtics out nomirror", "set ytics out nomirror",
                    "set offsets graph 0.02, graph 0.02, graph 0.02, graph 0.02"};
  if (!slender) spec.functions.insert(spec.functions.begin(), "set size ratio -1");
  else  // few x (or y) tics on the short side, so that their labels do not overlap
    spec.functions.push_back(std::string(w < h ? "set xtics " : "set ytics ") + [&] {
      std::ostringstream t;
      t << std::min(w, h) / 2.0;
      return t.str();
    }());
  spec.series.push_back({map.dataFile, map.columns, "", "", "points pt 5 ps " + ps.str() + " lc palette"});
  return spec;
}

}  // namespace ecm::io
