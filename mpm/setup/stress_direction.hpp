#pragma once
// The averaged stress the crack paths grow by (docs/model.md, "Crack paths"): the stress of the
// intact enriched points within a radius, each in units of its tensile strength and weighted by
// its volume and (1 - (r / radius)^2)^2; a point held intact past onset counts with its stress
// scaled back onto the onset surface, and with a sharpness each point weighted also by its
// driving force's share of onset to that power (a root's direction). Cracked points are left
// out (their stress is the crack's, not that of the field the crack runs into), and so are
// points that cannot crack.
#include <vector>

#include "material/material.hpp"
#include "mpm/core/particles.hpp"
#include "mpm/setup/crack_paths.hpp"

namespace ecm::mpm {

// Over the particles' intact points; their stress a : strain, or `stresses[i]` where given (the
// implicit solver's trial stresses).
AveragedStress intactStressAverage(const std::vector<Material>& materials, const Particles& particles,
                                   const std::vector<Voigt>* stresses = nullptr);

}  // namespace ecm::mpm
