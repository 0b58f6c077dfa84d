#include "mpm/scene/time_function.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace ecm::mpm {

double TimeFunction::operator()(double t) const {
  switch (kind) {
    case TimeFunctionKind::Hold: return value;
    case TimeFunctionKind::LinearRamp: return t >= rampTime ? value : value * std::max(t, 0.0) / rampTime;
    case TimeFunctionKind::SmoothRamp: {
      if (t >= rampTime) return value;
      const double r = std::max(t, 0.0) / rampTime;
      return value * r * r * r * (10.0 + r * (-15.0 + 6.0 * r));
    }
    case TimeFunctionKind::Table: {
      if (t <= times.front()) return values.front();
      if (t >= times.back()) return values.back();
      const auto hi = std::upper_bound(times.begin(), times.end(), t);
      const std::size_t i = static_cast<std::size_t>(hi - times.begin());
      const double w = (t - times[i - 1]) / (times[i] - times[i - 1]);
      return (1.0 - w) * values[i - 1] + w * values[i];
    }
  }
  return value;
}

void TimeFunction::validate() const {
  if (!std::isfinite(value)) throw std::invalid_argument("history value must be finite");
  if ((kind == TimeFunctionKind::LinearRamp || kind == TimeFunctionKind::SmoothRamp) && !(rampTime > 0.0))
    throw std::invalid_argument("ramp time must be > 0 s");
  if (kind == TimeFunctionKind::Table) {
    if (times.empty() || times.size() != values.size())
      throw std::invalid_argument("history table needs equally many (>= 1) times and values");
    for (std::size_t i = 1; i < times.size(); ++i)
      if (!(times[i] > times[i - 1])) throw std::invalid_argument("history table times must increase strictly");
    for (double v : values)
      if (!std::isfinite(v)) throw std::invalid_argument("history table values must be finite");
  }
}

}  // namespace ecm::mpm
