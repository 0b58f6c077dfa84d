#pragma once
// The parts of the Python module `ecm._ecm`, one file each (python/src/).
#include <pybind11/pybind11.h>

#include <nlohmann/json.hpp>

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
// A dict (or any JSON-like Python object) as YAML text for the tools' readers: JSON is YAML, and
// one key per line keeps the readers' line numbers useful in messages.
std::string yamlText(const py::handle& mapping);

}  // namespace ecm::python
