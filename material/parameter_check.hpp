#pragma once
// Range checks for material parameters: out-of-range values throw naming the parameter,
// its value and the allowed range.
#include <stdexcept>
#include <string>

namespace ecm {

struct ParameterError : std::invalid_argument {
  explicit ParameterError(const std::string& what, std::string parameterKey = {})
      : std::invalid_argument(what), key(std::move(parameterKey)) {}
  std::string key;  // the parameter's key as input files spell it ("" where no one key is at fault)
};

// Requires lo < value < hi (open bounds) unless the corresponding *Closed flag is set. `name` is the
// parameter's key, then (after a space) its symbol and unit: "youngs_modulus E (MPa)".
void requireInRange(const char* name, double value, double lo, double hi, bool loClosed = false,
                    bool hiClosed = false);

// A number in a message, in `digits` significant digits ("inf", "nan" as the stream writes them).
std::string numberText(double v, int digits);

}  // namespace ecm
