#pragma once
// The material points of a scene's gauges (mpm/scene/gauge.hpp): the particles seeded nearest to
// each gauge point, found from the particles' seed positions (so a restart finds the same ones),
// and the gauges' readings.
#include <cstddef>
#include <vector>

#include "mpm/core/particles.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

struct GaugePoints {
  std::size_t at = 0, to = 0;  // particle indices (to == at for a one-point gauge)
};

// Throws std::invalid_argument naming `gauges[i]` when a point lies farther than one particle
// spacing (diagonal) from every particle (outside the body).
std::vector<GaugePoints> locateGauges(const Scene& scene, const Particles& particles);
// mm: u(to) - u(at) along the gauge's component, or u(at) for a one-point gauge.
double gaugeReading(const Gauge& gauge, const GaugePoints& points, const Particles& particles);

}  // namespace ecm::mpm
