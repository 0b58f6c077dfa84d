#pragma once
// What a scene will need in memory, estimated before anything is allocated, against what the
// machine has: a scene that cannot fit is refused at its grid's line instead of ending in an
// allocation failure or the kernel's out-of-memory killer.
#include <cstddef>
#include <optional>

#include "mpm/scene/scene.hpp"

namespace ecm::mpm {

struct MemoryEstimate {
  std::size_t particles = 0;  // at most: the bodies' areas (clipped to the grid) times k^2 per cell
  std::size_t nodes = 0;
  std::size_t bytes = 0;      // particles, grid fields and scatter order (cracked bands not included)
};

MemoryEstimate estimateMemory(const Scene& scene);
// The memory the machine can give a new process now (Linux: MemAvailable of /proc/meminfo); none
// when it cannot be read.
std::optional<std::size_t> availableMemory();
// Throws io::ValueError at key "grid" when the estimate exceeds the available memory.
void checkMemory(const Scene& scene);

}  // namespace ecm::mpm
