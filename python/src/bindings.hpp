#pragma once
// The parts of the Python module `ecm._ecm`, one file each (python/src/).
#include <pybind11/pybind11.h>

#include <filesystem>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "io/yaml_input.hpp"

namespace ecm::python {

namespace py = pybind11;

void bindErrors(py::module_& m);       // exceptions carrying the tools' FILE:LINE: reason messages
void bindMaterial(py::module_& m);     // Material, PointState, BandState, UpdateResult, PointArray
void bindPoint(py::module_& m);        // point runs and the snap-back study (driver/)
void bindPoint3D(py::module_& m);      // 3D point runs (driver/point_driver_3d.hpp)
void bindCalibration(py::module_& m);  // ecm-calibrate's computations (calibration/)
void bindMpm(py::module_& m);          // ecm-mpm runs (mpm/)
void bindStudy(py::module_& m);        // ecm-study's plan and report (study/), for the Dask path

// A JSON document (the tools' summary.json) as Python objects, through Python's json module:
// numbers are written with 17 significant digits and read back to the same doubles.
py::object toPython(const nlohmann::json& j);

// A dict (or keywords) as YAML text for the tools' readers: JSON, which is YAML, one key or item
// per line, with the key path of each line. NumPy scalars and arrays are numbers and lists;
// strings stay strings (quoted), so '1e-6' is refused where a number is expected.
struct DictText {
  std::string name;                        // "<dict>", "<keywords>": the file name in messages
  std::string text;
  std::vector<std::string> keyPathOfLine;  // [line - 1]: "solver.tolerance", "materials[0]"
  std::string keyPath(int line) const;     // "" where unknown
};
DictText dictText(const py::handle& mapping, const std::string& name);

// An input error in a dict: "<dict>: key 'solver.tolerance': reason", the key path instead of a
// line of a text the user never saw. Raised in Python as ecm.InputError.
struct DictInputError : std::runtime_error {
  DictInputError(const DictText& t, const io::InputError& e);
};

// Reads a dict with a tool's reader `read(io::YamlMap)`; its input errors name key paths.
template <class Read>
auto readDict(const py::handle& mapping, const std::string& name, Read&& read) {
  const DictText t = dictText(mapping, name);
  try {
    return read(io::parseYaml(t.text, t.name));
  } catch (const io::InputError& e) {
    if (e.file != t.name) throw;
    throw DictInputError(t, e);
  }
}

// A YAML file as the tools read it, as a dict: scalars typed as the readers type them, and
// relative `file` references made absolute (ecm.load_scene).
py::dict loadYamlAsDict(const std::filesystem::path& file);

}  // namespace ecm::python
