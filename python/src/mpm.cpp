// ecm-mpm runs from Python: a scene file or dict, run with the GIL released into an output
// folder exactly as the tool writes it; a progress callback at every history row (it may stop
// the run with a checkpoint by returning False or raising; Ctrl-C does the same). Reading the
// folder back is python/ecm/mpm_output.py.
#include <pybind11/functional.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <fstream>
#include <iterator>

#include "io/checksum.hpp"
#include "io/yaml_input.hpp"
#include "mpm/scene/presets.hpp"
#include "mpm/run.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {

// A failed run's failure (mpm/core/errors.hpp) as the dict ecm.run_scene turns into the kind's
// exception (python/ecm/failures.py): the same keys as summary.json's "failure", plus the message.
py::dict failureDict(const mpm::RunFailure& f) {
  py::dict d;
  d["kind"] = std::string(mpm::toString(f.kind));
  d["exit_status"] = mpm::exitStatusOf(f.kind);
  d["message"] = f.message;
  d["step"] = f.step;
  d["particle"] = f.particle ? py::cast(*f.particle) : py::object(py::none());
  d["position_mm"] = f.position ? py::object(py::make_tuple((*f.position)[0], (*f.position)[1])) : py::object(py::none());
  d["material_status"] = f.kind == mpm::FailureKind::MaterialFailure || f.kind == mpm::FailureKind::SnapBack
                             ? py::object(py::str(toString(f.materialStatus)))
                             : py::object(py::none());
  d["residual"] = f.residual;
  d["likely_limit_point"] = f.likelyLimitPoint;
  d["file"] = f.file.empty() ? py::object(py::none()) : py::cast(f.file.string());
  return d;
}

}  // namespace

void bindMpm(py::module_& m) {
  // The failure kinds' table (name, ecm-mpm's exit status, meaning), for ecm.failures.
  m.def("_failure_kinds", [] {
    py::list kinds;
    for (const mpm::FailureKindInfo& k : mpm::kFailureKinds)
      kinds.append(py::make_tuple(std::string(k.name), k.exitStatus, std::string(k.meaning)));
    return kinds;
  });
  m.def(
      "_run_scene",
      [](const py::object& spec, const std::filesystem::path& out, int threads, const std::optional<std::string>& preset,
         bool snapshots, bool plot, bool restart, long maxSteps, const py::object& progress) {
        if (!progress.is_none() && !PyCallable_Check(progress.ptr()))
          throw py::type_error("progress must be callable as progress(time, end_time, step) or None, got " +
                               py::str(progress.get_type().attr("__name__")).cast<std::string>());
        mpm::Scene scene;
        mpm::RunOptions options;
        if (py::isinstance<py::dict>(spec)) {
          scene = readDict(spec, "<dict>", [](const io::YamlMap& map) { return mpm::readScene(map); });
          options.sceneHash = io::fnv1a64(dictText(spec, "<dict>").text);
        } else {
          const auto path = spec.cast<std::filesystem::path>();
          scene = mpm::loadSceneFile(path);
          std::ifstream in(path, std::ios::binary);
          options.sceneHash = io::fnv1a64(std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()));
        }
        if (preset) {
          const mpm::Preset* p = mpm::findPreset(*preset);
          if (!p) throw py::value_error("no preset '" + *preset + "' (" + mpm::presetNames() + ")");
          mpm::applyPreset(*p, scene);
          options.sceneHash = io::fnv1a64(*preset, options.sceneHash);  // a restart needs the same preset, as ecm-mpm's
        }
        if (threads < 0) throw py::value_error("threads must be >= 0 (0: the OpenMP default)");
        options.outputDir = out;
        options.threads = threads;
        options.snapshots = snapshots;
        options.plot = plot;
        options.progress = false;
        options.restart = restart;
        options.maxSteps = maxSteps;
        // The callback runs with the GIL taken back; an exception in it (or a pending Ctrl-C)
        // stops the run with a checkpoint and is raised once the run has closed its outputs.
        std::optional<py::error_already_set> raised;
        const double endTime = scene.endTime;
        options.onRow = [&](double time, long step) {
          py::gil_scoped_acquire held;
          try {
            if (PyErr_CheckSignals() != 0) throw py::error_already_set();
            if (!progress.is_none() && progress(time, endTime, step).is(py::bool_(false))) return false;
          } catch (py::error_already_set& e) {
            raised.emplace(std::move(e));
            return false;
          }
          return true;
        };
        mpm::RunResult r;
        {
          py::gil_scoped_release free;
          r = mpm::runScene(scene, options);
        }
        if (raised) throw std::move(*raised);
        // One shape for every scheme: error is the failure's message, None unless the run failed
        // (a stop on request is no error, whatever message the scheme keeps for it).
        py::dict result;
        result["status"] = r.completed ? "completed" : (r.stopped ? "stopped" : "failed");
        result["completed"] = r.completed;
        result["stopped"] = r.stopped;
        result["error"] = r.failure ? py::cast(r.failure->message) : py::object(py::none());
        result["failure"] = r.failure ? py::object(failureDict(*r.failure)) : py::object(py::none());
        result["steps"] = r.steps;
        result["particles"] = r.particles;
        result["peak_load_N"] = r.peakLoad;
        result["wall_time_s"] = r.wallTime;
        result["checkpoint"] = r.checkpoint.empty() ? py::object(py::none()) : py::cast(r.checkpoint);
        return result;
      },
      py::arg("scene"), py::arg("out"), py::arg("threads") = 0, py::arg("preset") = py::none(),
      py::arg("snapshots") = true, py::arg("plot") = true, py::arg("restart") = false, py::arg("max_steps") = 0,
      py::arg("progress") = py::none());
}

}  // namespace ecm::python
