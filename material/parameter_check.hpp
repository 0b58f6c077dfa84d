#pragma once
// Range checks for material parameters: out-of-range values throw naming the parameter,
// its value and the allowed range.
#include <stdexcept>
#include <string>

namespace ecm {

struct ParameterError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

// Requires lo < value < hi (open bounds) unless the corresponding *Closed flag is set.
void requireInRange(const char* name, double value, double lo, double hi, bool loClosed = false,
                    bool hiClosed = false);

}  // namespace ecm
