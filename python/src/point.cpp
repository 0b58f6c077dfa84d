// Point runs (ecm-point) from Python: a scene from a file or a dict, run with the GIL released;
// the history as the columns of history.csv, the summary as summary.json's content. With an
// output folder the run also writes the files the tool writes there.
#include <pybind11/numpy.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <sstream>

#include "driver/point_output.hpp"
#include "driver/point_scene_yaml.hpp"
#include "driver/snapback_study.hpp"
#include "io/output_dir.hpp"
#include "io/yaml_input.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {

bool isPath(const py::handle& o) {
  return py::isinstance<py::str>(o) || py::isinstance(o, py::module_::import("os").attr("PathLike"));
}

driver::PointScene pointScene(const py::object& scene) {
  if (isPath(scene)) return driver::loadPointScene(scene.cast<std::filesystem::path>());
  if (!py::isinstance<py::dict>(scene)) throw py::type_error("a point scene is a path or a dict");
  return readDict(scene, "<dict>", [](const io::YamlMap& m) { return driver::readPointScene(m); });
}

driver::SnapBackStudy study(const py::object& s) {
  if (isPath(s)) return driver::loadSnapBackStudy(s.cast<std::filesystem::path>());
  if (!py::isinstance<py::dict>(s)) throw py::type_error("a snap-back study is a path or a dict");
  return readDict(s, "<dict>", [](const io::YamlMap& m) { return driver::readSnapBackStudy(m); });
}

// Rows of equal length as an (rows, columns) array.
py::array_t<double> table(const std::vector<std::vector<double>>& rows, std::size_t columns) {
  py::array_t<double> a({static_cast<py::ssize_t>(rows.size()), static_cast<py::ssize_t>(columns)});
  double* out = a.mutable_data();
  for (const auto& r : rows) out = std::copy(r.begin(), r.end(), out);
  return a;
}

}  // namespace

void bindPoint(py::module_& m) {
  m.def(
      "_run_point",
      [](const py::object& scene, const std::optional<std::filesystem::path>& out) {
        const driver::PointScene s = pointScene(scene);
        std::filesystem::path dir;
        if (out) dir = io::prepareOutputDir(*out);
        driver::PointRun run;
        {
          py::gil_scoped_release free;
          run = driver::runPoint(s);
        }
        if (out) driver::writePointOutputs(s, run, dir);
        const driver::HistoryTable t = driver::historyTable(run, s.material.secondBand != SecondBandOption::Off);
        return py::make_tuple(t.columns, table(t.rows, t.columns.size()), toPython(driver::pointSummaryJson(s, run)));
      },
      py::arg("scene"), py::arg("out") = py::none());

  m.def(
      "_snapback_study",
      [](const py::object& spec, const std::filesystem::path& out) {
        const driver::SnapBackStudy s = study(spec);
        const std::filesystem::path dir = io::prepareOutputDir(out);
        std::ostringstream printed;
        driver::SnapBackStudyResult r;
        {
          py::gil_scoped_release free;
          r = driver::runSnapBackStudy(s, dir, printed);
        }
        py::dict rows;
        const auto column = [&](const char* name, auto member) {
          py::array_t<double> a(static_cast<py::ssize_t>(r.rows.size()));
          for (std::size_t i = 0; i < r.rows.size(); ++i) a.mutable_at(static_cast<py::ssize_t>(i)) = static_cast<double>(r.rows[i].*member);
          rows[name] = a;
        };
        column("H", &driver::StudyRow::effectiveSize);
        column("strain_control_snapback", &driver::StudyRow::strainControlSnapBack);
        column("snapback_increment", &driver::StudyRow::snapBackIncrement);
        column("snapback_stress_drop", &driver::StudyRow::snapBackStressDrop);
        column("peak_stress", &driver::StudyRow::peakStress);
        column("energy_ratio", &driver::StudyRow::energyRatio);
        column("macro_snaps_back", &driver::StudyRow::macroSnapsBack);
        column("closed_form_stress_error", &driver::StudyRow::closedFormStressError);
        column("closed_form_strain_error", &driver::StudyRow::closedFormStrainError);
        column("traction_opening_error", &driver::StudyRow::tractionOpeningError);
        column("enriched_completed", &driver::StudyRow::enrichedCompleted);
        column("smeared_regularised", &driver::StudyRow::smearedRegularised);
        column("smeared_softening_modulus", &driver::StudyRow::smearedSofteningModulus);
        column("smeared_peak_stress", &driver::StudyRow::smearedPeakStress);
        column("smeared_energy_ratio", &driver::StudyRow::smearedEnergyRatio);
        column("smeared_traction_opening_error", &driver::StudyRow::smearedTractionOpeningError);
        py::dict result;
        result["rows"] = rows;
        result["snapback_size_1d"] = r.snapBackSize1D;
        result["snapback_size"] = r.snapBackSize;
        result["critical_size"] = r.criticalSize;
        result["all_runs_completed"] = r.allRunsCompleted;
        result["table"] = printed.str();
        return result;
      },
      py::arg("study"), py::arg("out"));
}

}  // namespace ecm::python
