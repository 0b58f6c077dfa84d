// ecm-study's plan and report for Python (study/): the runs a study file plans, each scene as the
// text ecm-study writes into its run folder, and the report (study.csv, summary.json, pareto.png,
// the ensemble's files) written from run folders that something else filled. The Dask path,
// python/ecm/study.py, runs the scenes on workers in between; the numbers are ecm-study's own code.
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include "io/material_yaml.hpp"
#include "io/output_dir.hpp"
#include "python/src/bindings.hpp"
#include "study/study.hpp"

namespace ecm::python {

void bindStudy(py::module_& m) {
  m.def(
      "_plan_study",
      [](const std::filesystem::path& file) {
        const study::Study s = study::loadStudyFile(file);
        const std::vector<study::PlannedRun> plan = study::planStudy(s);
        py::list runs;
        for (const study::PlannedRun& r : plan) {
          py::dict d;
          d["id"] = r.id;
          d["label"] = r.label;
          d["values"] = r.values;
          d["reference"] = r.reference;
          d["directory"] = study::runDirectory(r);
          d["scene_text"] = r.sceneText;
          d["scene_file"] = r.sceneFile;
          d["particles"] = r.particles;
          d["estimated_steps"] = r.estimatedSteps;
          runs.append(d);
        }
        py::list knobs;
        for (const study::Knob& k : s.knobs) knobs.append(k.key);
        py::dict d;
        d["name"] = s.name;
        d["kind"] = s.kind == study::StudyKind::Mpm ? "mpm" : "point";
        d["repeat"] = s.repeat;
        d["samples"] = s.samples;
        d["knobs"] = knobs;
        d["reference_scene"] = s.reference == study::ReferenceKind::Scene ? py::cast(s.referenceScene) : py::none();
        d["data_dir"] = io::defaultDataDir();
        d["runs"] = runs;
        return d;
      },
      py::arg("study"));
  m.def(
      "_report_study",
      [](const std::filesystem::path& file, const std::filesystem::path& out, int threads) {
        const study::Study s = study::loadStudyFile(file);
        std::vector<study::PlannedRun> plan = study::planStudy(s);
        study::StudyOptions o;
        o.outputDir = io::prepareOutputDir(out);
        o.threads = threads;
        o.isolate = false;
        o.progress = false;
        o.collectOnly = true;
        study::StudyResult r;
        {
          py::gil_scoped_release free;
          r = study::runStudy(s, plan, o);
        }
        py::dict d;
        d["all_completed"] = r.allCompleted;
        d["ensemble"] = toPython(r.ensemble);
        d["ensemble_text"] = study::ensembleTable(r.ensemble);  // "" unless an ensemble
        return d;
      },
      py::arg("study"), py::arg("out"), py::arg("threads"));
}

}  // namespace ecm::python
