#pragma once
// The plot of a field over the particles (damage_map.png): one filled square per particle,
// coloured by the field, laid out for the domain's shape. A compact domain is drawn to scale; a
// slender one (a bar 20 x 1000 mm) would be a few pixels wide to scale, so it is stretched
// across the canvas, the title says so, and the colour bar keeps its own margin.
#include <cstddef>
#include <string>

#include "io/gnuplot.hpp"

namespace ecm::io {

struct ParticleMap {
  std::string title;
  std::string dataFile;     // relative to the PNG's folder, e.g. particles_final.csv
  std::string columns;      // gnuplot `using` x:y:value, e.g. "1:2:3"
  std::string valueLabel;   // the colour bar's label, e.g. "damage"
  double width = 1.0;       // the domain's extent in x (mm)
  double height = 1.0;      // and in y (mm)
  std::size_t particles = 1;
};

// Beyond this ratio of the longer to the shorter side a domain is stretched, not drawn to scale.
inline constexpr double kSlenderRatio = 4.0;

PlotSpec particleMapSpec(const ParticleMap& map);

}  // namespace ecm::io
