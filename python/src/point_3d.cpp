// Point runs in 3D (ecm-point with hypothesis: three_dimensional) from Python: a scene file or
// dict, the history as history.csv's columns, the summary as summary.json's content.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "driver/point_driver_3d.hpp"
#include "io/output_dir.hpp"
#include "io/yaml_input.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

void bindPoint3D(py::module_& m) {
  m.def(
      "_run_point_3d",
      [](const py::object& scene, const std::filesystem::path& out) {
        const bool path = py::isinstance<py::str>(scene) || py::isinstance(scene, py::module_::import("os").attr("PathLike"));
        if (!path && !py::isinstance<py::dict>(scene)) throw py::type_error("a point scene is a path or a dict");
        const driver::PointScene3 s = path ? driver::loadPointScene3(scene.cast<std::filesystem::path>())
                                           : readDict(scene, "<dict>", [](const io::YamlMap& m) { return driver::readPointScene3(m); });
        const std::filesystem::path dir = io::prepareOutputDir(out);
        driver::PointRun3 run;
        {
          py::gil_scoped_release free;
          run = driver::runPoint3D(s);
        }
        driver::writePointOutputs3(s, run, dir);
        return py::make_tuple(run.completed, dir);
      },
      py::arg("scene"), py::arg("out"));
}

}  // namespace ecm::python
