// ecm-study: the study file read and checked (readStudy), and the plan: the runs of the design,
// each a scene edited by the knobs, read back and checked before anything runs (planStudy).
#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>
#include <stdexcept>

#include "driver/point_scene_yaml.hpp"
#include "material/linear_elastic.hpp"
#include "mpm/scene/scene_yaml.hpp"
#include "mpm/setup/seeding.hpp"
#include "study/study.hpp"
#include "study/internal.hpp"

namespace ecm::study {

using namespace detail;

namespace {

using io::InputError;
using io::Range;
using io::YamlMap;

constexpr const char* kRefinement = "grid.refinement";
constexpr const char* kTimeScale = "time_scale";
constexpr const char* kScene = "scene";

// Derived knobs: not key paths of the scene, but edits of it (the numeric ones) or the scene itself.
bool numericKnob(const std::string& key) { return key == kRefinement || key == kTimeScale; }
bool derivedKnob(const std::string& key) { return numericKnob(key) || key == kScene; }

int lineOf(const YAML::Node& n, int fallback) {
  const YAML::Mark m = n.Mark();
  return m.is_null() || m.line < 0 ? fallback : m.line + 1;
}

bool sameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const auto x = parseNumber(a), y = parseNumber(b);
  return x && y && *x == *y;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// The study file

std::vector<std::string> availableMetrics(StudyKind kind, ReferenceKind reference) {
  if (kind == StudyKind::Point) return {"stress_path", "dissipation", "peak_stress"};
  if (reference == ReferenceKind::BarVibration) return {"period", "amplitude"};
  return {"peak_load", "peak_reaction", "dissipated_energy", "post_peak_curve"};
}

namespace {

std::vector<Setting> readSettings(const YamlMap& map) {
  std::vector<Setting> out;
  for (auto it = map.node().begin(); it != map.node().end(); ++it) {
    const std::string key = it->first.Scalar();
    map.has(key);  // declared: every key of this map is a key path
    try {
      parsePath(key);
    } catch (const std::invalid_argument& e) {
      map.fail(key, e.what());
    }
    if (it->second.IsNull()) map.fail(key, "has no value");
    out.push_back({key, it->second, map.line(key)});
  }
  return out;
}

double positiveNumber(const YamlMap& map, const std::string& key, const YAML::Node& v) {
  const auto x = v.IsScalar() && v.Tag() != "!" ? parseNumber(v.Scalar()) : std::nullopt;
  if (!x || !(*x > 0.0))
    throw InputError(map.file(), lineOf(v, map.line(key)),
                     "key '" + map.path() + "." + key + "': expected a positive number, got " + valueText(v));
  return *x;
}

}  // namespace

SceneChoice readSceneChoice(const YAML::Node& value, const std::string& studyFile, int line) {
  const std::filesystem::path folder = std::filesystem::path(studyFile).parent_path();
  SceneChoice c;
  std::string name;
  if (value.IsScalar()) {
    name = value.Scalar();
  } else if (value.IsMap()) {
    const YamlMap map(value, studyFile, "knobs.scene");
    name = map.get<std::string>("file");
    if (map.has("set")) c.set = readSettings(map.child("set"));
    map.finish();
  } else {
    throw InputError(studyFile, lineOf(value, line), "key 'knobs.scene': expected a scene file or {file: NAME, set: {key path: value}}");
  }
  const std::filesystem::path file = name;
  c.file = file.is_absolute() ? file : (folder / file).lexically_normal();
  std::error_code ec;
  if (name.empty() || !std::filesystem::is_regular_file(c.file, ec))
    throw InputError(studyFile, lineOf(value, line), "key 'knobs.scene': no such file: " + c.file.string());
  c.text = c.file.stem().string();
  for (const Setting& s : c.set) c.text += " " + s.key + "=" + valueText(s.value);
  return c;
}

Study readStudy(const YamlMap& m) {
  Study s;
  s.file = m.file();
  s.name = m.getOr<std::string>("name", std::filesystem::path(m.file()).stem().string());
  s.kind = m.getEnumOr("kind", {"mpm", "point"}, "mpm") == "point" ? StudyKind::Point : StudyKind::Mpm;
  const std::filesystem::path scene = m.get<std::string>("scene");
  s.scene = scene.is_absolute() ? scene : (m.directory() / scene).lexically_normal();
  std::error_code ec;
  if (!std::filesystem::is_regular_file(s.scene, ec)) m.fail("scene", "no such file: " + s.scene.string());
  if (m.has("set")) s.set = readSettings(m.child("set"));
  s.design = m.getEnumOr("design", {"grid", "one_at_a_time"}, "grid") == "grid" ? StudyDesign::Grid : StudyDesign::OneAtATime;

  const bool sampled = m.has("samples");
  const YamlMap knobs = m.has("knobs") || !sampled ? m.child("knobs") : m;  // (m: none, samples: is the only knob)
  const std::vector<Setting> knobSettings = m.has("knobs") ? readSettings(knobs) : std::vector<Setting>{};
  for (const Setting& k : knobSettings) {
    if (!k.value.IsSequence() || k.value.size() == 0)
      knobs.fail(k.key, "expected a non-empty sequence of values, e.g. [0.1, 0.3]");
    if (numericKnob(k.key) && s.kind != StudyKind::Mpm) knobs.fail(k.key, "applies to mpm scenes only");
    Knob knob{k.key, {}, k.line};
    const auto text = [&](const YAML::Node& v) { return k.key == kScene ? readSceneChoice(v, m.file(), k.line).text : valueText(v); };
    for (std::size_t i = 0; i < k.value.size(); ++i) {
      const YAML::Node v = k.value[i];
      if (v.IsNull()) throw InputError(m.file(), lineOf(v, k.line), "key 'knobs." + k.key + "': a value is empty");
      if (numericKnob(k.key)) positiveNumber(knobs, k.key, v);
      const std::string written = text(v);  // a scene value is read (and its file found) here
      for (const YAML::Node& earlier : knob.values)
        if (sameValue(text(earlier), written))
          throw InputError(m.file(), lineOf(v, k.line), "key 'knobs." + k.key + "': value " + valueText(v) + " is given twice");
      knob.values.push_back(v);
    }
    s.knobs.push_back(std::move(knob));
  }
  if (sampled) {  // the ensemble shorthand: the last knob, seeds 1..N (see study.hpp)
    if (s.kind != StudyKind::Mpm) m.fail("samples", "applies to mpm studies (an RVE scene) only");
    s.samples = m.get<int>("samples", Range::closed(2.0, 100000.0));
    for (const Knob& k : s.knobs)
      if (k.key == kSampleSeed) knobs.fail(k.key, "is what samples: sets; give one or the other");
    Knob seeds{kSampleSeed, {}, m.line("samples")};
    for (int i = 1; i <= s.samples; ++i) seeds.values.emplace_back(i);
    s.knobs.push_back(std::move(seeds));
  }
  if (s.knobs.empty()) m.fail("knobs", "needs at least one knob (key path: [values])");

  const YamlMap ref = m.child("reference");
  s.referenceLine = ref.line();
  if (static_cast<int>(ref.has("closed_form")) + static_cast<int>(ref.has("run")) + static_cast<int>(ref.has("scene")) != 1)
    ref.failHere("give exactly one of closed_form, run and scene");
  if (ref.has("scene")) {
    if (s.kind != StudyKind::Mpm) ref.fail("scene", "applies to mpm studies only");
    s.reference = ReferenceKind::Scene;
    s.referenceLine = ref.line("scene");
    const std::filesystem::path scene = ref.get<std::string>("scene");
    s.referenceScene = scene.is_absolute() ? scene : (m.directory() / scene).lexically_normal();
    std::error_code ec;
    if (!std::filesystem::is_regular_file(s.referenceScene, ec)) ref.fail("scene", "no such file: " + s.referenceScene.string());
    s.condition = ref.getOr<std::string>("condition", "");
  } else if (ref.has("closed_form")) {
    if (s.kind == StudyKind::Mpm) {
      ref.getEnum("closed_form", {"bar_vibration"});
      s.reference = ReferenceKind::BarVibration;
      s.condition = ref.get<std::string>("condition");
    } else {
      ref.getEnum("closed_form", {"uniaxial_tension"});
      s.reference = ReferenceKind::UniaxialTension;
      ref.reject("condition", "applies to mpm studies only");
    }
    s.referenceLine = ref.line("closed_form");
  } else {
    s.reference = ReferenceKind::Run;
    if (s.kind == StudyKind::Mpm) s.condition = ref.getOr<std::string>("condition", "");
    else ref.reject("condition", "applies to mpm studies only");
    const YamlMap run = ref.child("run");
    s.referenceLine = ref.line("run");
    s.referenceSettings = readSettings(run);
    for (const Setting& r : s.referenceSettings) {
      const bool known = std::any_of(s.knobs.begin(), s.knobs.end(), [&](const Knob& k) { return k.key == r.key; });
      if (!known) run.fail(r.key, "is not a knob of the study (the reference run differs from the base in knobs only)");
      if (numericKnob(r.key)) positiveNumber(run, r.key, r.value);
      if (r.key == kScene) readSceneChoice(r.value, m.file(), r.line);
    }
  }
  std::vector<std::string> available = availableMetrics(s.kind, s.reference);
  const bool againstRun = s.reference == ReferenceKind::Run || s.reference == ReferenceKind::Scene;
  if (s.kind == StudyKind::Mpm && againstRun && s.condition.empty())
    for (const char* needsCondition : {"peak_reaction", "post_peak_curve"})
      available.erase(std::find(available.begin(), available.end(), needsCondition));
  if (ref.has("metrics")) {
    for (const std::string& name : ref.scalarSequence<std::string>("metrics")) {
      if (std::find(available.begin(), available.end(), name) == available.end()) {
        std::string list;
        for (const auto& a : available) list += (list.empty() ? "" : ", ") + a;
        ref.fail("metrics", "'" + name + "' is not a metric of this reference (available: " + list + ")");
      }
      if (std::find(s.metrics.begin(), s.metrics.end(), name) != s.metrics.end())
        ref.fail("metrics", "'" + name + "' is given twice");
      s.metrics.push_back(name);
    }
    if (s.metrics.empty()) ref.fail("metrics", "needs at least one metric");
  } else if (s.kind == StudyKind::Mpm && againstRun) {
    s.metrics = {s.condition.empty() ? "peak_load" : "peak_reaction", "dissipated_energy"};
    if (!s.condition.empty()) s.metrics.push_back("post_peak_curve");
  } else {
    s.metrics = available;
  }
  s.repeat = m.getOr<int>("repeat", 1, Range::closed(1.0, 100.0));
  if (sampled && (s.condition.empty() || s.reference == ReferenceKind::BarVibration))
    m.fail("samples", "needs a reference run or scene with a condition (the pulled edge, whose largest reaction is the "
                      "sample's strength), e.g. reference: {run: {\"" + std::string(kSampleSeed) + "\": 1}, condition: top}");
  m.finish();
  return s;
}

Study loadStudyFile(const std::filesystem::path& path) { return readStudy(io::loadYamlFile(path)); }

// ---------------------------------------------------------------------------------------------
// The plan

namespace detail {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 1, "cannot open file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

}  // namespace detail

namespace {

// A run's choice: per knob, a value from the study file (or none: the base value).
struct Choice {
  std::vector<std::optional<YAML::Node>> values;
  bool reference = false;
};

}  // namespace

std::vector<PlannedRun> planStudy(const Study& study) {
  // A run's document: its scene file (the `scene` knob's, or the base), the study's set: and the
  // scene value's own set:.
  auto base = [&](const SceneChoice* scene) {
    const std::filesystem::path& file = scene ? scene->file : study.scene;
    YAML::Node root = io::parseYaml(readText(file), file.string()).node();
    std::vector<Setting> settings = study.set;
    if (scene) settings.insert(settings.end(), scene->set.begin(), scene->set.end());
    for (const Setting& s : settings) {
      try {
        setKeyPath(root, s.key, YAML::Clone(s.value));
      } catch (const std::invalid_argument& e) {
        throw InputError(study.file, s.line, "set '" + s.key + "': " + e.what());
      }
    }
    return root;
  };
  const std::size_t n = study.knobs.size();
  const auto valueOf = [&](std::size_t k, const YAML::Node& v) {
    return study.knobs[k].key == kScene ? readSceneChoice(v, study.file, study.knobs[k].line).text : valueText(v);
  };
  std::vector<std::string> baseValues(n);
  {
    const YAML::Node root = base(nullptr);
    for (std::size_t k = 0; k < n; ++k) {
      if (study.knobs[k].key == kScene) {
        baseValues[k] = study.scene.stem().string();
      } else if (derivedKnob(study.knobs[k].key)) {
        baseValues[k] = "1";
      } else {
        try {
          const auto v = findKeyPath(root, study.knobs[k].key);
          baseValues[k] = v ? valueText(*v) : "default";
        } catch (const std::invalid_argument& e) {
          throw InputError(study.file, study.knobs[k].line, "knob '" + study.knobs[k].key + "': " + e.what());
        }
      }
    }
  }

  // The choices of the design.
  std::vector<Choice> choices;
  if (study.design == StudyDesign::Grid) {
    std::vector<std::size_t> index(n, 0);
    for (bool more = true; more;) {
      Choice c;
      for (std::size_t k = 0; k < n; ++k) c.values.push_back(study.knobs[k].values[index[k]]);
      choices.push_back(std::move(c));
      more = false;
      for (std::size_t k = n; k-- > 0;) {  // the last knob varies fastest
        if (++index[k] < study.knobs[k].values.size()) {
          more = true;
          break;
        }
        index[k] = 0;
      }
    }
  } else {
    choices.push_back({std::vector<std::optional<YAML::Node>>(n), false});
    for (std::size_t k = 0; k < n; ++k)
      for (const YAML::Node& v : study.knobs[k].values) {
        if (sameValue(valueOf(k, v), baseValues[k])) continue;
        Choice c{std::vector<std::optional<YAML::Node>>(n), false};
        c.values[k] = v;
        choices.push_back(std::move(c));
      }
  }
  auto texts = [&](const Choice& c) {
    std::vector<std::string> t(n);
    for (std::size_t k = 0; k < n; ++k) t[k] = c.values[k] ? valueOf(k, *c.values[k]) : baseValues[k];
    return t;
  };
  auto same = [&](const std::vector<std::string>& a, const std::vector<std::string>& b) {
    for (std::size_t k = 0; k < n; ++k)
      if (!sameValue(a[k], b[k])) return false;
    return true;
  };
  if (study.reference == ReferenceKind::Run) {
    Choice r{std::vector<std::optional<YAML::Node>>(n), true};
    for (const Setting& s : study.referenceSettings)
      for (std::size_t k = 0; k < n; ++k)
        if (study.knobs[k].key == s.key) r.values[k] = s.value;
    const auto rt = texts(r);
    bool found = false;
    for (Choice& c : choices)
      if (same(texts(c), rt)) c.reference = found = true;
    if (!found) choices.push_back(std::move(r));
  }

  std::vector<PlannedRun> plan;
  std::vector<std::vector<std::string>> planned;
  for (const Choice& c : choices) {
    const auto t = texts(c);
    bool duplicate = false;
    for (std::size_t i = 0; i < planned.size(); ++i)
      if (same(planned[i], t)) {
        duplicate = true;
        plan[i].reference = plan[i].reference || c.reference;
      }
    if (duplicate) continue;
    planned.push_back(t);

    PlannedRun run;
    run.id = static_cast<int>(plan.size()) + 1;
    run.values = t;
    run.reference = c.reference;
    for (std::size_t k = 0; k < n; ++k)
      if (study.design == StudyDesign::Grid || !sameValue(t[k], baseValues[k]))
        run.label += (run.label.empty() ? "" : " ") + study.knobs[k].key + "=" + t[k];
    if (run.label.empty()) run.label = "base";
    int line = study.knobs.front().line;  // where a bad value is reported: the first value away from the base
    for (std::size_t k = 0; k < n; ++k)
      if (c.values[k] && !sameValue(t[k], baseValues[k])) {
        line = lineOf(*c.values[k], study.knobs[k].line);
        break;
      }

    std::optional<SceneChoice> scene;
    for (std::size_t k = 0; k < n; ++k)
      if (c.values[k] && study.knobs[k].key == kScene) scene = readSceneChoice(*c.values[k], study.file, study.knobs[k].line);
    const std::string baseFile = (scene ? scene->file : study.scene).string();
    YAML::Node root = base(scene ? &*scene : nullptr);
    for (int pass = 0; pass < 2; ++pass)  // plain key paths first, then the numeric derived knobs
      for (std::size_t k = 0; k < n; ++k) {
        const Knob& knob = study.knobs[k];
        if (!c.values[k] || knob.key == kScene || numericKnob(knob.key) != (pass == 1)) continue;
        try {
          if (knob.key == kRefinement) applyGridRefinement(root, *parseNumber(valueText(*c.values[k])));
          else if (knob.key == kTimeScale) applyTimeScale(root, *parseNumber(valueText(*c.values[k])));
          else setKeyPath(root, knob.key, YAML::Clone(*c.values[k]));
        } catch (const std::invalid_argument& e) {
          throw InputError(study.file, lineOf(*c.values[k], knob.line), "knob '" + knob.key + "': " + e.what());
        }
      }
    const std::string what = "run " + std::to_string(run.id) + " (" + run.label + "): ";
    try {
      const YamlMap map(root, baseFile);
      if (study.kind == StudyKind::Mpm) {
        run.scene = mpm::readScene(map);
        try {
          run.particles = mpm::seedParticles(*run.scene).size();
        } catch (const std::invalid_argument& e) {
          throw InputError(baseFile, 1, e.what());
        }
        double speed = 0.0;
        for (const auto& mat : run.scene->materials)
          speed = std::max(speed, std::sqrt(pWaveModulus(mat.elastic) / mat.density));
        const mpm::Grid& g = run.scene->grid;
        if (const auto& implicit = run.scene->solver.implicit) {  // load steps at their largest (they adapt)
          const auto& control = implicit->indirect;
          const double ramp = control ? control->from : run.scene->endTime;
          run.estimatedSteps = (implicit->loadStep > 0.0 ? std::ceil(ramp / implicit->loadStep) : 0.0) +
                               (control ? std::ceil(control->until / control->step) : 0.0);
        } else {
          run.estimatedSteps = run.scene->endTime * speed / (run.scene->solver.explicitScheme.cfl * std::min(g.cellSize[0], g.cellSize[1]));
        }
        if (!study.condition.empty() && !findCondition(run.scene->conditions, study.condition))
          throw InputError(study.file, study.referenceLine, what + "the scene has no condition '" + study.condition + "'");
        if (study.reference == ReferenceKind::BarVibration) {
          try {
            barVibrationClosedForm(*run.scene);
          } catch (const std::invalid_argument& e) {
            throw InputError(study.file, study.referenceLine, what + "closed_form bar_vibration: " + e.what());
          }
        }
      } else {
        run.point = driver::readPointScene(map);
        run.particles = 1;
        run.estimatedSteps = totalIncrements(*run.point);
        if (study.reference == ReferenceKind::UniaxialTension) {
          const driver::PointScene& p = *run.point;
          bool uniaxial = p.material.model == ModelKind::Enriched && p.material.elastic.hypothesis == Hypothesis::PlaneStress;
          double previous = 0.0;
          for (const driver::Segment& seg : p.path) {
            uniaxial = uniaxial && !seg.openingControl && seg.control[0] == driver::Control::Strain &&
                       seg.control[1] == driver::Control::Stress && seg.control[2] == driver::Control::Stress && seg.target[1] == 0.0 &&
                       seg.target[2] == 0.0 && seg.target[0] >= previous;
            previous = seg.target[0];
          }
          if (!uniaxial)
            throw InputError(study.file, study.referenceLine,
                             what + "closed_form uniaxial_tension needs an enriched plane-stress point under monotonic "
                                    "uniaxial tension (eps_xx rising, sig_yy = sig_xy = 0, no opening control)");
        }
      }
    } catch (const InputError& e) {
      if (e.file == study.file) throw;
      throw InputError(study.file, line, what + e.what());
    }
    run.sceneText = "# ecm-study " + study.name + ", run " + std::to_string(run.id) + ": " + run.label +
                    "\n# The base scene " + baseFile + " with the study's values; file references are relative to it.\n" +
                    YAML::Dump(root) + "\n";
    run.sceneFile = baseFile;
    plan.push_back(std::move(run));
  }
  return plan;
}

}  // namespace ecm::study
