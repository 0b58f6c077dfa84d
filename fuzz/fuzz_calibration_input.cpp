// Fuzz harness: an ecm-calibrate YAML input and its plan. Only InputError and
// CalibrationError may come out; an accepted plan in a cheap mode is carried out.
#include <unistd.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <string>

#include "calibration/calibration_error.hpp"
#include "calibration/calibration_input.hpp"
#include "calibration/fracture_energy.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const std::filesystem::path file =
      std::filesystem::temp_directory_path() / ("ecm-fuzz-calibration-" + std::to_string(::getpid()) + ".yaml");
  {
    std::ofstream out(file, std::ios::binary);
    out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
  }
  try {
    const ecm::calibration::CalibrationPlan plan =
        ecm::calibration::planCalibration(ecm::calibration::readCalibrationInput(file));
    if (plan.mode == ecm::calibration::CalibrationMode::Forward)
      (void)ecm::calibration::fractureEnergy(plan.law, plan.width);
  } catch (const ecm::io::InputError&) {
  } catch (const ecm::calibration::CalibrationError&) {
  }
  return 0;
}
