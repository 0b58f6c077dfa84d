#pragma once
// The check both point drivers (2D and 3D) make of a row before they record it: a row that is
// not all numbers ends the run, named (the rows before it stay).
#include <cmath>
#include <string>

namespace ecm::driver {

template <class Row>
bool isAllNumbers(const Row& r) {
  return r.strain.allFinite() && r.stress.allFinite() && std::isfinite(r.work) && std::isfinite(r.dissipation);
}

inline std::string notANumberFailure(int increment, int segment) {
  return "increment " + std::to_string(increment) + " (segment " + std::to_string(segment) +
         "): the material update gave a stress or an energy that is not a number";
}

}  // namespace ecm::driver
