#include "material/parameter_check.hpp"

#include <cmath>
#include <sstream>
#include <string>

namespace ecm {

void requireInRange(const char* name, double value, double lo, double hi, bool loClosed, bool hiClosed) {
  const bool aboveLo = loClosed ? value >= lo : value > lo;
  const bool belowHi = hiClosed ? value <= hi : value < hi;
  if (std::isfinite(value) && aboveLo && belowHi) return;
  std::ostringstream msg;
  msg.precision(10);
  msg << "parameter '" << name << "' = " << value << " is outside the allowed range "
      << (loClosed ? "[" : "(") << lo << ", " << hi << (hiClosed ? "]" : ")");
  const std::string key(name);
  throw ParameterError(msg.str(), key.substr(0, key.find(' ')));
}

std::string numberText(double v, int digits) {
  std::ostringstream s;
  s.precision(digits);
  s << v;
  return s.str();
}

}  // namespace ecm
