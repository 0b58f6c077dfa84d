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
  // Each particle a filled square of its share of the domain, sqrt(w h / N) wide: no gaps in a
  // stretched domain (points of a fixed pixel size left its few columns apart).
  const double half = 0.5 * std::sqrt(w * h / static_cast<double>(std::max<std::size_t>(map.particles, 1)));
  std::ostringstream d;
  d << half;
  spec.functions = {"set cbrange [0:1]", "set cblabel '" + map.valueLabel + "' noenhanced",
                    "set palette defined (0 '#f2f2f2', 0.3 '#9ecae1', 0.7 '#de2d26', 1 '#67000d')", "unset grid",
                    "set key off", "set colorbox vertical user origin graph 1.04, graph 0 size graph 0.03, graph 1",
                    "set rmargin at screen 0.85", "set xtics out nomirror", "set ytics out nomirror",
                    "set autoscale fix", "set offsets graph 0.02, graph 0.02, graph 0.02, graph 0.02"};
  if (!slender) spec.functions.insert(spec.functions.begin(), "set size ratio -1");
  else  // few x (or y) tics on the short side, so that their labels do not overlap
    spec.functions.push_back(std::string(w < h ? "set xtics " : "set ytics ") + [&] {
      std::ostringstream t;
      t << std::min(w, h) / 2.0;
      return t.str();
    }());
  // columns "x:y:value" -> x:y:(x-d):(x+d):(y-d):(y+d):value
  const std::size_t c1 = map.columns.find(':'), c2 = map.columns.find(':', c1 + 1);
  const std::string x = std::string("$") + map.columns.substr(0, c1), y = std::string("$") + map.columns.substr(c1 + 1, c2 - c1 - 1),
                    value = map.columns.substr(c2 + 1);
  std::string box = map.columns.substr(0, c2);  // "x:y" as columns
  for (const std::string& part : {":(" + x + "-" + d.str() + "):(" + x + "+" + d.str() + ")",
                                  ":(" + y + "-" + d.str() + "):(" + y + "+" + d.str() + "):" + value})
    box += part;
  spec.series.push_back({map.dataFile, box, "", "", "boxxyerror fs solid noborder lc palette"});
  return spec;
}

}  // namespace ecm::io
