#pragma once
// Gauges: what an extensometer or an LVDT measures on a specimen, as history.csv columns
// (`gauges:` of a scene; docs/inputs.md). A gauge follows material points, not grid nodes: each
// of its points is the particle seeded nearest to it (a point farther than one particle spacing
// from every particle is outside the body and refused). The tests of fracture mechanics are controlled and
// reported by such gauges (the DEN's delta is the mean of LVDTs across the notches), so
// stop_when and the implicit solver's indirect control may act on a gauge too.
#include <optional>
#include <string>

#include "material/voigt.hpp"

namespace ecm::mpm {

struct Gauge {
  std::string name;
  Vec2 at = Vec2::Zero();     // mm: the (first) material point
  std::optional<Vec2> to;     // mm: a second point: the gauge reads u(to) - u(at) (an extensometer)
  int component = 1;          // 0 x, 1 y: the displacement component it reads
};

}  // namespace ecm::mpm
