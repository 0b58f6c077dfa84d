#pragma once
// Filling the scene's bodies with k x k particles per cell; particle volume = cell area / k^2
// times the thickness, mass = density * volume.
#include "mpm/core/particles.hpp"
#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

// Throws std::invalid_argument if nothing is filled, or (quadratic B-spline) if a particle lies
// within 1.5 cells of the grid edge.
Particles seedParticles(const Scene& scene);

}  // namespace ecm::mpm
