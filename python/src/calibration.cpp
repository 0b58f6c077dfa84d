// ecm-calibrate from Python: the same plan (keys of the calibration input file as keywords,
// and/or the file), the same computation and summary; measured (w, traction) arrays fit as a CSV
// file would. Thin functions over the library for E_p from G_F and the forward G_F.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <sstream>

#include "calibration/calibration_input.hpp"
#include "calibration/calibration_run.hpp"
#include "calibration/fracture_energy.hpp"
#include "io/output_dir.hpp"
#include "io/yaml_input.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {

DamageLawParams law(double youngsModulus, double tensileStrength, double softeningModulus, double softeningExponent) {
  return {youngsModulus, tensileStrength, softeningModulus, softeningExponent};
}

}  // namespace

void bindCalibration(py::module_& m) {
  m.def(
      "_calibrate",
      [](const std::optional<std::filesystem::path>& file, const py::dict& keys, const std::optional<std::vector<double>>& w,
         const std::optional<std::vector<double>>& traction, const std::optional<std::filesystem::path>& out) {
        calibration::CalibrationInput in;
        if (file) in = calibration::readCalibrationInput(*file);
        if (!keys.empty()) calibration::overlay(in, readDict(keys, "<keywords>", [](const io::YamlMap& m) { return calibration::readCalibrationInput(m); }));
        if (w || traction) {
          if (!w || !traction) throw py::value_error("give both w and traction");
          in.fitPoints = calibration::TargetCurve{"points given in code", *w, *traction};
        }
        const calibration::CalibrationPlan plan = calibration::planCalibration(in);
        if (out) io::prepareOutputDir(*out);
        calibration::CalibrationResult result;
        {
          py::gil_scoped_release free;
          result = calibration::runCalibration(plan);
        }
        if (out) calibration::writeOutputs(result, *out);  // (false: only the plot could not be made)
        std::ostringstream written;  // write_material, write_umat: the files, as the tool writes them
        calibration::writeRequestedFiles(result, plan, written);
        return toPython(calibration::summaryJson(result));
      },
      py::arg("file") = py::none(), py::arg("keys") = py::dict(), py::arg("w") = py::none(),
      py::arg("traction") = py::none(), py::arg("out") = py::none());

  m.def(
      "softening_modulus",
      [](double youngsModulus, double tensileStrength, double softeningExponent, double fractureEnergy, double bandWidth) {
        return calibration::solveSofteningModulus(law(youngsModulus, tensileStrength, 0.0, softeningExponent),
                                                  fractureEnergy, bandWidth)
            .softeningModulus;
      },
      py::arg("E"), py::arg("ft"), py::arg("n"), py::arg("GF"), py::arg("h"),
      "E_p (MPa) such that a band of width h (mm) with E (MPa), f_t' (MPa) and n dissipates G_F (N/mm)");
  m.def(
      "fracture_energy",
      [](double youngsModulus, double tensileStrength, double softeningModulus, double softeningExponent, double bandWidth) {
        const DamageLawParams p = law(youngsModulus, tensileStrength, softeningModulus, softeningExponent);
        p.validate();
        return calibration::fractureEnergy(p, bandWidth);
      },
      py::arg("E"), py::arg("ft"), py::arg("Ep"), py::arg("n"), py::arg("h"),
      "G_F (N/mm) = h int_0^1 F(D) dD of the band's damage law (Eq. (13))");
}

}  // namespace ecm::python
