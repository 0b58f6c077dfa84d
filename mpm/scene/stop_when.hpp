#pragma once
// Ending a softening run by its load, not its clock: "pull until the load has dropped below 10 %
// of its peak" (the DEN's end criterion). The scene names a condition; its reaction along the driven
// component is watched at the output rows (the same values history.csv holds, so the stop can be
// checked against the file), and the run ends at the first row, from `afterTime` on, where it is
// below `loadBelow` times the largest one so far. end_time stays the latest end.
#include <algorithm>
#include <cmath>
#include <string>

namespace ecm::mpm {

struct StopWhen {
  std::string condition;   // the name of the condition whose reaction is watched
  double loadBelow = 0.1;  // fraction of the peak of that reaction, in (0, 1)
  double afterTime = 0.0;  // s: rows before this time only raise the peak (e.g. a preload phase)
  // Or a gauge (mpm/scene/gauge.hpp; then `condition` is empty): the run ends at the first row
  // where the gauge reads at least `gaugeReaches` in magnitude (mm), as a test is pulled until
  // its gauge reaches a value.
  std::string gauge;
  double gaugeReaches = 0.0;
};

// The watch over the output rows: the peak of |load| so far, and whether the stop is met.
struct StopWatch {
  double peak = 0.0;  // N: the largest |load| of the rows so far

  // Takes one output row; true when the run should end at it.
  bool observe(const StopWhen& when, double time, double load) {
    const double magnitude = std::abs(load);
    peak = std::max(peak, magnitude);
    return time >= when.afterTime && peak > 0.0 && magnitude < when.loadBelow * peak;
  }
};

}  // namespace ecm::mpm
