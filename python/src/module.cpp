// ecm._ecm: the compiled part of the Python package `ecm` (python/ecm/__init__.py re-exports it).
#include "python/src/bindings.hpp"

namespace ecm::python {

py::object toPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

std::string yamlText(const py::handle& mapping) {
  return py::module_::import("json").attr("dumps")(mapping, py::arg("indent") = 1).cast<std::string>();
}

}  // namespace ecm::python

PYBIND11_MODULE(_ecm, m) {
  m.doc() = "ecm: enriched constitutive models for quasi-brittle fracture (units: mm, N, MPa, tonne, s)";
  m.attr("__version__") = ECM_VERSION;
  ecm::python::bindErrors(m);
  ecm::python::bindMaterial(m);
  ecm::python::bindPoint(m);
  ecm::python::bindPoint3D(m);
  ecm::python::bindCalibration(m);
  ecm::python::bindMpm(m);
  ecm::python::bindStudy(m);
}
