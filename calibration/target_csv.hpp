#pragma once
// Measured (w, sigma) points from a CSV file, for the fit (the file side of target_curve.hpp).
#include <filesystem>

#include "calibration/target_curve.hpp"

namespace ecm::calibration {

// Exactly two columns, at least 3 rows, w >= 0 strictly increasing. Violations are
// io::InputError "FILE:LINE: reason" naming the value and the bound.
TargetCurve readTargetCsv(const std::filesystem::path& path);

}  // namespace ecm::calibration
