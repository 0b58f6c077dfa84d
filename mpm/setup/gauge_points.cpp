// The material points of the gauges and their readings (mpm/setup/gauge_points.hpp).
#include "mpm/setup/gauge_points.hpp"

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace ecm::mpm {

namespace {

std::size_t nearestSeed(const Particles& p, const Vec2& x, double reach, std::size_t gauge, const char* which) {
  std::size_t best = 0;
  double bestDistance = INFINITY;
  for (std::size_t i = 0; i < p.size(); ++i)
    if (const double d = (p.origin[i] - x).squaredNorm(); d < bestDistance) bestDistance = d, best = i;
  if (!(std::sqrt(bestDistance) <= reach)) {
    std::ostringstream msg;
    msg << "gauges[" << gauge << "]." << which << ": (" << x[0] << ", " << x[1]
        << ") mm is outside the body (no particle within one particle spacing of it)";
    throw std::invalid_argument(msg.str());
  }
  return best;
}

}  // namespace

std::vector<GaugePoints> locateGauges(const Scene& scene, const Particles& particles) {
  // A point of the body lies within half a particle spacing (diagonal) of a seed; one spacing
  // (diagonal) allows a point on the body's edge.
  const double reach = std::sqrt(2.0) * scene.grid.cellSize.maxCoeff() / scene.particlesPerCell;
  std::vector<GaugePoints> points;
  for (std::size_t g = 0; g < scene.gauges.size(); ++g) {
    const Gauge& gauge = scene.gauges[g];
    GaugePoints p;
    p.at = nearestSeed(particles, gauge.at, reach, g, "at");
    p.to = gauge.to ? nearestSeed(particles, *gauge.to, reach, g, "to") : p.at;
    points.push_back(p);
  }
  return points;
}

double gaugeReading(const Gauge& gauge, const GaugePoints& points, const Particles& particles) {
  const int c = gauge.component;
  const double at = particles.displacement(points.at)[c];
  return gauge.to ? particles.displacement(points.to)[c] - at : at;
}

}  // namespace ecm::mpm
