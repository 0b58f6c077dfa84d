#pragma once
// Inputs no law of the form of Eq. (13) can satisfy (or that are out of range): the message
// names the quantity, its value and the bound it violates.
#include <stdexcept>

namespace ecm::calibration {

struct CalibrationError : std::invalid_argument {
  using std::invalid_argument::invalid_argument;
};

}  // namespace ecm::calibration
