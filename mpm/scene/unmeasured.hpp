#pragma once
// Settings a valid scene may combine that this project has not measured together. ecm-mpm runs
// them and notes each on stderr (docs/model.md, "Crack paths", Limits).
#include <string>
#include <vector>

#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

// One sentence per unmeasured combination in `scene`; empty when every setting was measured.
std::vector<std::string> unmeasuredCombinations(const Scene& scene);

}  // namespace ecm::mpm
