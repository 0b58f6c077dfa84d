#include "calibration/target_curve.hpp"

#include <cmath>
#include <sstream>

#include "calibration/calibration_error.hpp"
#include "material/parameter_check.hpp"

namespace ecm::calibration {

namespace {
constexpr double kC1 = 3.0, kC2 = 6.93, kCriticalOpeningFactor = 5.14;
constexpr std::size_t kMinimumPoints = 3;
}  // namespace

double hordijkCriticalOpening(double ft, double gf) { return kCriticalOpeningFactor * gf / ft; }

double hordijkStress(double w, double ft, double gf) {
  const double r = w / hordijkCriticalOpening(ft, gf);
  if (r >= 1.0) return 0.0;
  if (r <= 0.0) return ft;
  const double c1r = kC1 * r;
  return ft * ((1.0 + c1r * c1r * c1r) * std::exp(-kC2 * r) - r * (1.0 + kC1 * kC1 * kC1) * std::exp(-kC2));
}

TargetCurve hordijkCurve(double ft, double gf, int count) {
  if (count < static_cast<int>(kMinimumPoints)) throw CalibrationError("hordijk curve: at least 3 points");
  TargetCurve t;
  t.source = "hordijk";
  const double wc = hordijkCriticalOpening(ft, gf);
  for (int i = 1; i <= count; ++i) {
    const double w = wc * i / count;
    t.opening.push_back(w);
    t.stress.push_back(hordijkStress(w, ft, gf));
  }
  return t;
}

std::string hordijkGnuplot(double ft, double gf) {
  const std::string r = "(x/" + numberText(hordijkCriticalOpening(ft, gf), 12) + ")";
  return "(x < " + numberText(hordijkCriticalOpening(ft, gf), 12) + " ? " + numberText(ft, 12) + "*((1+(3*" + r + ")**3)*exp(-6.93*" + r +
         ") - " + r + "*28*exp(-6.93)) : 0)";
}

void validateTarget(const TargetCurve& t) {
  if (t.opening.size() != t.stress.size()) throw CalibrationError("target curve: as many openings as stresses needed");
  if (t.opening.size() < kMinimumPoints)
    throw CalibrationError("target curve: " + std::to_string(t.opening.size()) + " point(s); at least " +
                           std::to_string(kMinimumPoints) + " are needed");
  for (std::size_t i = 0; i < t.opening.size(); ++i) {
    if (!std::isfinite(t.opening[i]) || !std::isfinite(t.stress[i]))
      throw CalibrationError("target curve: point " + std::to_string(i + 1) + " is not finite");
    if (t.opening[i] < 0.0) throw CalibrationError("target curve: opening w = " + numberText(t.opening[i], 12) + " mm is negative");
    if (i > 0 && !(t.opening[i] > t.opening[i - 1]))
      throw CalibrationError("target curve: openings must increase strictly: w = " + numberText(t.opening[i], 12) +
                             " mm after w = " + numberText(t.opening[i - 1], 12) + " mm");
  }
}

}  // namespace ecm::calibration
