#pragma once
// Time functions of prescribed quantities (displacements, velocities, loads): value(t); a scene
// writes one under a `history:` key.
// Plain data with a switch, so it can sit in inner loops without virtual calls.
#include <vector>

namespace ecm::mpm {

enum class TimeFunctionKind {
  Hold,         // value for all t
  LinearRamp,   // value * t / rampTime, then value
  SmoothRamp,   // value * s(t / rampTime), s = 10 r^3 - 15 r^4 + 6 r^5 (zero rate and acceleration at both ends), then value
  Table,        // piecewise linear through (times[i], values[i]); constant outside
};

struct TimeFunction {
  TimeFunctionKind kind = TimeFunctionKind::Hold;
  double value = 0.0;
  double rampTime = 0.0;       // s (ramps)
  std::vector<double> times;   // s (table), strictly increasing
  std::vector<double> values;  // (table)

  static TimeFunction hold(double v) { return {TimeFunctionKind::Hold, v, 0.0, {}, {}}; }
  static TimeFunction linearRamp(double v, double t) { return {TimeFunctionKind::LinearRamp, v, t, {}, {}}; }
  static TimeFunction smoothRamp(double v, double t) { return {TimeFunctionKind::SmoothRamp, v, t, {}, {}}; }
  static TimeFunction table(std::vector<double> t, std::vector<double> v) {
    return {TimeFunctionKind::Table, 0.0, 0.0, std::move(t), std::move(v)};
  }

  double operator()(double t) const;
  // Throws std::invalid_argument when the parameters make no sense (negative ramp time, unsorted table).
  void validate() const;
};

}  // namespace ecm::mpm
