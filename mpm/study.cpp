#include "mpm/study.hpp"

#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <csignal>
#include <charconv>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "driver/point_output.hpp"
#include "driver/point_scene_yaml.hpp"
#include "io/atomic_file.hpp"
#include "io/gnuplot.hpp"
#include "io/json_summary.hpp"
#include "io/output_dir.hpp"
#include "material/damage_function.hpp"
#include "material/linear_elastic.hpp"
#include "material/uniaxial_closed_form.hpp"
#include "mpm/run.hpp"
#include "mpm/scene_yaml.hpp"
#include "mpm/seeding.hpp"

namespace ecm::mpm {

namespace {

using io::InputError;
using io::Range;
using io::YamlMap;

constexpr const char* kRefinement = "grid.refinement";
constexpr const char* kTimeScale = "time_scale";

bool derivedKnob(const std::string& key) { return key == kRefinement || key == kTimeScale; }

int lineOf(const YAML::Node& n, int fallback) {
  const YAML::Mark m = n.Mark();
  return m.is_null() || m.line < 0 ? fallback : m.line + 1;
}

// Shortest round-trip text of a number.
std::string numberText(double v) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, v);
  return std::string(buf, r.ptr);
}

std::optional<double> parseNumber(const std::string& s) {
  double v = 0.0;
  const char* begin = s.data() + (!s.empty() && s[0] == '+' ? 1 : 0);
  const auto r = std::from_chars(begin, s.data() + s.size(), v);
  if (r.ec != std::errc() || r.ptr != s.data() + s.size() || !std::isfinite(v)) return std::nullopt;
  return v;
}

YAML::Node numberNode(double v) { return YAML::Node(numberText(v)); }

// A value as text: scalars as written, sequences and maps in flow style.
std::string valueText(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e.SetSeqFormat(YAML::Flow);
  e.SetMapFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

bool sameValue(const std::string& a, const std::string& b) {
  if (a == b) return true;
  const auto x = parseNumber(a), y = parseNumber(b);
  return x && y && *x == *y;
}

// ---------------------------------------------------------------------------------------------
// Key paths: "a.b[0].c"

struct PathStep {
  std::string key;
  std::vector<std::size_t> indices;
};

std::vector<PathStep> parsePath(const std::string& path) {
  std::vector<PathStep> steps;
  std::size_t start = 0;
  while (start <= path.size()) {
    const std::size_t dot = std::min(path.find('.', start), path.size());
    const std::string part = path.substr(start, dot - start);
    const std::size_t bracket = part.find('[');
    PathStep step{part.substr(0, bracket), {}};
    if (step.key.empty()) throw std::invalid_argument("key path '" + path + "' has an empty key");
    for (std::size_t b = bracket; b != std::string::npos && b < part.size();) {
      const std::size_t close = part.find(']', b);
      std::size_t index = 0;
      const auto r = close == std::string::npos ? std::from_chars_result{nullptr, std::errc::invalid_argument}
                                                : std::from_chars(part.data() + b + 1, part.data() + close, index);
      if (r.ec != std::errc() || r.ptr != part.data() + close)
        throw std::invalid_argument("key path '" + path + "': expected [index] after '" + step.key + "'");
      step.indices.push_back(index);
      b = close + 1;
      if (b < part.size() && part[b] != '[')
        throw std::invalid_argument("key path '" + path + "': unexpected text after ']'");
    }
    steps.push_back(std::move(step));
    if (dot == path.size()) break;
    start = dot + 1;
  }
  return steps;
}

}  // namespace

void setKeyPath(YAML::Node& root, const std::string& path, const YAML::Node& value) {
  const std::vector<PathStep> steps = parsePath(path);
  YAML::Node cur;
  cur.reset(root);
  std::string where;
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const PathStep& s = steps[i];
    if (!cur.IsMap()) throw std::invalid_argument("'" + where + "' is not a map in the scene");
    where += (where.empty() ? "" : ".") + s.key;
    const bool last = i + 1 == steps.size();
    if (last && s.indices.empty()) {
      cur[s.key] = value;
      return;
    }
    const YAML::Node& constCur = cur;
    if (!constCur[s.key]) {
      if (!s.indices.empty()) throw std::invalid_argument("'" + where + "' is not in the scene");
      cur[s.key] = YAML::Node(YAML::NodeType::Map);
    }
    YAML::Node next = cur[s.key];
    cur.reset(next);
    for (std::size_t j = 0; j < s.indices.size(); ++j) {
      const std::size_t k = s.indices[j];
      if (!cur.IsSequence() || k >= cur.size())
        throw std::invalid_argument("'" + where + "' has no entry [" + std::to_string(k) + "] in the scene");
      where += '[';
      where += std::to_string(k);
      where += ']';
      if (last && j + 1 == s.indices.size()) {
        cur[k] = value;
        return;
      }
      YAML::Node entry = cur[k];
      cur.reset(entry);
    }
  }
}

std::optional<YAML::Node> findKeyPath(const YAML::Node& root, const std::string& path) {
  YAML::Node cur;
  cur.reset(root);
  for (const PathStep& s : parsePath(path)) {
    const YAML::Node& c = cur;
    if (!c.IsMap() || !c[s.key]) return std::nullopt;
    YAML::Node next = c[s.key];
    cur.reset(next);
    for (const std::size_t k : s.indices) {
      const YAML::Node& seq = cur;
      if (!seq.IsSequence() || k >= seq.size()) return std::nullopt;
      YAML::Node entry = seq[k];
      cur.reset(entry);
    }
  }
  return cur;
}

namespace {

// A number of the scene, multiplied in place (left alone if it is not a number: the scene
// reader reports it).
void scaleNumber(YAML::Node map, const char* key, double factor) {
  const YAML::Node& c = map;
  if (!c.IsMap() || !c[key] || !c[key].IsScalar()) return;
  if (const auto v = parseNumber(c[key].Scalar())) map[key] = numberNode(*v * factor);
}

void scaleEntry(YAML::Node seq, std::size_t i, double factor) {
  const YAML::Node& c = seq;
  if (!c.IsSequence() || i >= c.size() || !c[i].IsScalar()) return;
  if (const auto v = parseNumber(c[i].Scalar())) seq[i] = numberNode(*v * factor);
}

// A history map (hold, ramps, table): times x s, values x valueFactor.
void scaleHistory(YAML::Node h, double s, double valueFactor) {
  const YAML::Node& c = h;
  if (!c.IsMap() || !c["type"] || !c["type"].IsScalar()) return;
  const std::string type = c["type"].Scalar();
  if (type == "table") {
    if (!c["points"] || !c["points"].IsSequence()) return;
    YAML::Node points = h["points"];
    for (std::size_t i = 0; i < points.size(); ++i) {
      YAML::Node p = points[i];
      scaleEntry(p, 0, s);
      scaleEntry(p, 1, valueFactor);
    }
    return;
  }
  if (type != "hold") scaleNumber(h, "time", s);
  scaleNumber(h, "value", valueFactor);
}

YAML::Node child(YAML::Node map, const char* key) {
  const YAML::Node& c = map;
  if (!c.IsMap() || !c[key]) return YAML::Node();
  return map[key];
}

YAML::Node flowPair(double a, double b) {
  YAML::Node seq(YAML::NodeType::Sequence);
  seq.push_back(numberNode(a));
  seq.push_back(numberNode(b));
  seq.SetStyle(YAML::EmitterStyle::Flow);
  return seq;
}

}  // namespace

void applyGridRefinement(YAML::Node& scene, double factor) {
  if (!(factor > 0.0)) throw std::invalid_argument("grid.refinement must be positive");
  const auto cells = findKeyPath(scene, "grid.cells"), size = findKeyPath(scene, "grid.cell_size");
  auto pair = [](const std::optional<YAML::Node>& n) -> std::optional<std::pair<double, double>> {
    if (!n || !n->IsSequence() || n->size() != 2 || !(*n)[0].IsScalar() || !(*n)[1].IsScalar()) return std::nullopt;
    const auto a = parseNumber((*n)[0].Scalar()), b = parseNumber((*n)[1].Scalar());
    if (!a || !b) return std::nullopt;
    return std::pair{*a, *b};
  };
  const auto c = pair(cells), h = pair(size);
  if (!c || !h) throw std::invalid_argument("grid.refinement needs grid: {cell_size: [dx, dy], cells: [nx, ny]} in the scene");
  YAML::Node grid = scene["grid"];
  grid["cells"] = flowPair(std::ceil(c->first * factor - 1e-9), std::ceil(c->second * factor - 1e-9));
  grid["cell_size"] = flowPair(h->first / factor, h->second / factor);
}

void applyTimeScale(YAML::Node& scene, double s) {
  if (!(s > 0.0)) throw std::invalid_argument("time_scale must be positive");
  scaleNumber(scene, "end_time", s);
  scaleNumber(scene, "output_interval", s);
  if (YAML::Node conditions = child(scene, "conditions"); conditions.IsSequence()) {
    for (std::size_t i = 0; i < conditions.size(); ++i) {
      YAML::Node c = conditions[i];
      for (const auto& [key, factor] : {std::pair{"displacement", 1.0}, std::pair{"velocity", 1.0 / s}})
        if (YAML::Node d = child(c, key); d.IsMap())
          for (const char* comp : {"x", "y"})
            if (YAML::Node h = child(d, comp); h.IsMap()) scaleHistory(h, s, factor);
      if (YAML::Node f = child(c, "velocity_field"); f.IsMap()) {
        // v = scale(t) G (x - origin): G / s, and the scale's times x s.
        if (YAML::Node g = child(f, "gradient"); g.IsSequence())
          for (std::size_t r = 0; r < g.size(); ++r) {
            YAML::Node row = g[r];
            scaleEntry(row, 0, 1.0 / s);
            scaleEntry(row, 1, 1.0 / s);
          }
        if (YAML::Node h = child(f, "scale"); h.IsMap()) scaleHistory(h, s, 1.0);
      }
    }
  }
  if (YAML::Node loads = child(scene, "loads"); loads.IsSequence()) {
    for (std::size_t i = 0; i < loads.size(); ++i)
      if (YAML::Node h = child(loads[i], "history"); h.IsMap()) scaleHistory(h, s, 1.0);
  }
}

// ---------------------------------------------------------------------------------------------
// The study file

std::vector<std::string> availableMetrics(StudyKind kind, ReferenceKind reference) {
  if (kind == StudyKind::Point) return {"stress_path", "dissipation", "peak_stress"};
  if (reference == ReferenceKind::BarVibration) return {"period", "amplitude"};
  return {"peak_load", "peak_reaction", "dissipated_energy"};
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

  const YamlMap knobs = m.child("knobs");
  for (const Setting& k : readSettings(knobs)) {
    if (!k.value.IsSequence() || k.value.size() == 0)
      knobs.fail(k.key, "expected a non-empty sequence of values, e.g. [0.1, 0.3]");
    if (derivedKnob(k.key) && s.kind != StudyKind::Mpm) knobs.fail(k.key, "applies to mpm scenes only");
    Knob knob{k.key, {}, k.line};
    for (std::size_t i = 0; i < k.value.size(); ++i) {
      const YAML::Node v = k.value[i];
      if (v.IsNull()) throw InputError(m.file(), lineOf(v, k.line), "key 'knobs." + k.key + "': a value is empty");
      if (derivedKnob(k.key)) positiveNumber(knobs, k.key, v);
      for (const YAML::Node& earlier : knob.values)
        if (sameValue(valueText(earlier), valueText(v)))
          throw InputError(m.file(), lineOf(v, k.line), "key 'knobs." + k.key + "': value " + valueText(v) + " is given twice");
      knob.values.push_back(v);
    }
    s.knobs.push_back(std::move(knob));
  }
  if (s.knobs.empty()) m.fail("knobs", "needs at least one knob (key path: [values])");

  const YamlMap ref = m.child("reference");
  s.referenceLine = ref.line();
  if (ref.has("closed_form") == ref.has("run")) ref.failHere("give exactly one of closed_form and run");
  if (ref.has("closed_form")) {
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
      if (derivedKnob(r.key)) positiveNumber(run, r.key, r.value);
    }
  }
  std::vector<std::string> available = availableMetrics(s.kind, s.reference);
  if (s.kind == StudyKind::Mpm && s.reference == ReferenceKind::Run && s.condition.empty())
    available.erase(std::find(available.begin(), available.end(), "peak_reaction"));  // needs a condition
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
  } else if (s.kind == StudyKind::Mpm && s.reference == ReferenceKind::Run) {
    s.metrics = {s.condition.empty() ? "peak_load" : "peak_reaction", "dissipated_energy"};
  } else {
    s.metrics = available;
  }
  s.repeat = m.getOr<int>("repeat", 1, Range::closed(1.0, 100.0));
  m.finish();
  return s;
}

Study loadStudyFile(const std::filesystem::path& path) { return readStudy(io::loadYamlFile(path)); }

// ---------------------------------------------------------------------------------------------
// The plan

namespace {

std::string readText(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 1, "cannot open file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// A run's choice: per knob, a value from the study file (or none: the base value).
struct Choice {
  std::vector<std::optional<YAML::Node>> values;
  bool reference = false;
};

}  // namespace

std::vector<PlannedRun> planStudy(const Study& study) {
  const std::string baseText = readText(study.scene);
  const std::string baseFile = study.scene.string();
  auto base = [&] {
    YAML::Node root = io::parseYaml(baseText, baseFile).node();
    for (const Setting& s : study.set) {
      try {
        setKeyPath(root, s.key, YAML::Clone(s.value));
      } catch (const std::invalid_argument& e) {
        throw InputError(study.file, s.line, "set '" + s.key + "': " + e.what());
      }
    }
    return root;
  };
  const std::size_t n = study.knobs.size();
  std::vector<std::string> baseValues(n);
  {
    const YAML::Node root = base();
    for (std::size_t k = 0; k < n; ++k) {
      if (derivedKnob(study.knobs[k].key)) {
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
        if (sameValue(valueText(v), baseValues[k])) continue;
        Choice c{std::vector<std::optional<YAML::Node>>(n), false};
        c.values[k] = v;
        choices.push_back(std::move(c));
      }
  }
  auto texts = [&](const Choice& c) {
    std::vector<std::string> t(n);
    for (std::size_t k = 0; k < n; ++k) t[k] = c.values[k] ? valueText(*c.values[k]) : baseValues[k];
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

    YAML::Node root = base();
    for (int pass = 0; pass < 2; ++pass)  // plain key paths first, then the derived knobs
      for (std::size_t k = 0; k < n; ++k) {
        const Knob& knob = study.knobs[k];
        if (!c.values[k] || derivedKnob(knob.key) != (pass == 1)) continue;
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
        run.scene = readScene(map);
        try {
          run.particles = seedParticles(*run.scene).size();
        } catch (const std::invalid_argument& e) {
          throw InputError(baseFile, 1, e.what());
        }
        double speed = 0.0;
        for (const auto& mat : run.scene->materials)
          speed = std::max(speed, std::sqrt(pWaveModulus(mat.elastic) / mat.density));
        const Grid& g = run.scene->grid;
        run.estimatedSteps = run.scene->endTime * speed / (run.scene->solver.cfl * std::min(g.cellSize[0], g.cellSize[1]));
        const auto& cs = run.scene->conditions;
        if (!study.condition.empty() &&
            std::none_of(cs.begin(), cs.end(), [&](const NodeCondition& x) { return x.name == study.condition; }))
          throw InputError(study.file, study.referenceLine, what + "the scene has no condition '" + study.condition + "'");
        if (study.reference == ReferenceKind::BarVibration) {
          try {
            barVibrationClosedForm(*run.scene);
          } catch (const std::invalid_argument& e) {
            throw InputError(study.file, study.referenceLine, what + "closed_form bar_vibration: " + e.what());
          }
        }
      } else {
        run.point = readPointScene(map);
        run.particles = 1;
        run.estimatedSteps = totalIncrements(*run.point);
        if (study.reference == ReferenceKind::UniaxialTension) {
          const PointScene& p = *run.point;
          bool uniaxial = p.material.model == ModelKind::Enriched && p.material.elastic.hypothesis == Hypothesis::PlaneStress;
          double previous = 0.0;
          for (const Segment& seg : p.path) {
            uniaxial = uniaxial && !seg.openingControl && seg.control[0] == Control::Strain &&
                       seg.control[1] == Control::Stress && seg.control[2] == Control::Stress && seg.target[1] == 0.0 &&
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
    plan.push_back(std::move(run));
  }
  return plan;
}

// ---------------------------------------------------------------------------------------------
// Closed forms and measures

BarVibration barVibrationClosedForm(const Scene& scene) {
  const Body* bar = nullptr;
  for (const Body& b : scene.bodies)
    if (!b.subtract && b.shape.kind == ShapeKind::Rectangle) {
      bar = &b;
      break;
    }
  if (!bar) throw std::invalid_argument("the scene has no rectangular body (the bar, along x)");
  const MaterialParams& m = scene.materials.at(static_cast<std::size_t>(bar->material));
  if (m.model != ModelKind::LinearElastic || m.elastic.poissonRatio != 0.0)
    throw std::invalid_argument("the bar's material must be linear_elastic with poisson_ratio 0 (a one-dimensional bar)");
  const double v0 = bar->initialVelocity[0];
  if (v0 == 0.0 || bar->initialVelocity[1] != 0.0)
    throw std::invalid_argument("the bar needs an initial velocity along x only");
  const double length = bar->shape.max[0] - bar->shape.min[0];
  const double area = (bar->shape.max[1] - bar->shape.min[1]) * scene.thickness;
  const double c = std::sqrt(m.elastic.youngsModulus / m.density);
  return {4.0 * length / c, m.density * c * std::abs(v0) * area};
}

SquareWave measureSquareWave(const std::vector<double>& t, const std::vector<double>& r, double amplitude) {
  SquareWave w;
  std::vector<double> crossings;
  int state = 0;
  double lastZero = NAN;
  for (std::size_t i = 1; i < t.size() && i < r.size(); ++i) {
    if ((r[i - 1] < 0.0) != (r[i] < 0.0) && r[i] != r[i - 1])
      lastZero = t[i - 1] + (t[i] - t[i - 1]) * r[i - 1] / (r[i - 1] - r[i]);
    const int now = r[i] > 0.5 * amplitude ? 1 : (r[i] < -0.5 * amplitude ? -1 : state);
    if (now != state) {
      if (state != 0 && std::isfinite(lastZero)) crossings.push_back(lastZero);
      state = now;
    }
  }
  w.crossings = static_cast<int>(crossings.size());
  if (crossings.empty()) return w;
  w.period = crossings.size() == 1 ? 2.0 * crossings[0]
                                   : 2.0 * (crossings.back() - crossings.front()) / static_cast<double>(crossings.size() - 1);
  double sum = 0.0;
  int count = 0;
  for (std::size_t i = 0; i < t.size() && i < r.size(); ++i) {
    const double phase = std::fmod(t[i] / (0.5 * w.period), 1.0);
    if (t[i] > 0.0 && phase >= 0.25 && phase <= 0.75) sum += std::abs(r[i]), ++count;
  }
  if (count > 0) w.amplitude = sum / count;
  return w;
}

UniaxialReference uniaxialTensionClosedForm(const MaterialParams& m, double bigH, double strainEnd) {
  const DamageLawParams law = m.band().law();
  const double e = m.elastic.youngsModulus, nu = m.elastic.poissonRatio, ft = m.tensileStrength, h = m.bandWidth;
  auto at = [&](double x) {
    const UniaxialBandPoint p = uniaxialBandResponse(law, nu, h, x);
    return std::pair{uniaxialMacroStrain(p, e, bigH), p.stress};
  };
  UniaxialReference ref;
  const double onset = ft / e;
  const int elastic = 50;
  for (int i = 0; i <= elastic; ++i) {
    const double eps = std::min(strainEnd, onset) * i / elastic;
    ref.strain.push_back(eps);
    ref.stress.push_back(e * eps);
  }
  ref.peakStress = e * std::min(strainEnd, onset);
  if (strainEnd <= onset) return ref;
  // The integrity at the end: eps(x) rises as x falls (below the snap-back size); bisection in ln x.
  const double xMin = 1e-15;
  double xEnd = xMin;
  if (at(xMin).first > strainEnd) {
    double lo = std::log(xMin), hi = 0.0;  // eps(lo) > strainEnd >= eps(hi)
    for (int it = 0; it < 200 && hi - lo > 1e-15; ++it) {
      const double mid = 0.5 * (lo + hi);
      (at(std::exp(mid)).first > strainEnd ? lo : hi) = mid;
    }
    xEnd = std::exp(0.5 * (lo + hi));
  }
  // Samples: damage D = 1 - x log-spaced from 1e-10 (the peak region), and x log-spaced (the tail).
  std::vector<double> xs;
  const int count = 800;
  for (int i = 0; i <= count; ++i) {
    const double d = std::exp(std::log(1e-10) + (std::log(1.0 - xEnd) - std::log(1e-10)) * i / count);
    xs.push_back(1.0 - d);
    xs.push_back(std::exp(std::log(xEnd) * i / count));
  }
  std::sort(xs.begin(), xs.end(), std::greater<>());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  double previous = onset;
  std::vector<double> damage;  // D of each sample of the band branch
  for (const double x : xs) {
    if (x >= 1.0) continue;
    const auto [eps, sigma] = at(x);
    if (eps < previous - 1e-15 * onset)
      throw std::invalid_argument("the macro curve turns back (H beyond the snap-back size): no closed form as a function of strain");
    previous = eps;
    ref.strain.push_back(eps);
    ref.stress.push_back(sigma);
    damage.push_back(1.0 - x);
  }
  // The peak: the largest sample, refined by golden section in ln D between its neighbours.
  const std::size_t k = static_cast<std::size_t>(std::max_element(ref.stress.begin(), ref.stress.end()) - ref.stress.begin());
  ref.peakStress = ref.stress[k];
  const std::size_t first = elastic + 1;  // ref.stress[first + j] belongs to damage[j]
  if (k >= first && !damage.empty()) {
    const std::size_t j = k - first;
    auto stressAtLogD = [&](double u) { return at(1.0 - std::exp(u)).second; };
    double a = std::log(damage[j > 0 ? j - 1 : 0]), b = std::log(damage[std::min(j + 1, damage.size() - 1)]);
    const double g = 0.5 * (std::sqrt(5.0) - 1.0);
    double c = b - g * (b - a), d = a + g * (b - a);
    for (int it = 0; it < 200 && std::abs(b - a) > 1e-12; ++it) {
      if (stressAtLogD(c) > stressAtLogD(d)) b = d;
      else a = c;
      c = b - g * (b - a), d = a + g * (b - a);
    }
    ref.peakStress = std::max(ref.peakStress, stressAtLogD(0.5 * (a + b)));
  }
  ref.dissipation = h / bigH * dissipationBetween(law, 1.0, xEnd);
  return ref;
}

double maxDeviation(const std::vector<double>& x, const std::vector<double>& y, const std::vector<double>& cx,
                    const std::vector<double>& cy) {
  double worst = 0.0;
  if (cx.size() < 2) return NAN;
  std::size_t j = 1;
  for (std::size_t i = 0; i < x.size(); ++i) {
    if (x[i] < cx.front() || x[i] > cx.back()) continue;
    if (j > 1 && cx[j - 1] > x[i]) j = 1;  // samples out of order: search from the start
    while (j + 1 < cx.size() && cx[j] < x[i]) ++j;
    const double span = cx[j] - cx[j - 1];
    const double s = span > 0.0 ? (x[i] - cx[j - 1]) / span : 1.0;
    worst = std::max(worst, std::abs(y[i] - (cy[j - 1] + s * (cy[j] - cy[j - 1]))));
  }
  return worst;
}

std::vector<bool> paretoFront(const std::vector<double>& cost, const std::vector<double>& error) {
  const std::size_t n = std::min(cost.size(), error.size());
  std::vector<bool> front(cost.size(), false);
  for (std::size_t i = 0; i < n; ++i) {
    if (!std::isfinite(cost[i]) || !std::isfinite(error[i])) continue;
    bool dominated = false;
    for (std::size_t j = 0; j < n && !dominated; ++j)
      dominated = j != i && std::isfinite(cost[j]) && std::isfinite(error[j]) && cost[j] <= cost[i] &&
                  error[j] <= error[i] && (cost[j] < cost[i] || error[j] < error[i]);
    front[i] = !dominated;
  }
  return front;
}

// ---------------------------------------------------------------------------------------------
// Running

namespace {

std::string sanitize(const std::string& label) {
  std::string s;
  for (const char c : label) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '=' || c == '-' || c == '_') s += c;
    else if (c == ' ' || c == ',') s += '_';
  }
  return s.substr(0, 80);
}

std::string runDirectory(const PlannedRun& r) {
  char id[16];
  std::snprintf(id, sizeof id, "%03d", r.id);
  return std::string("runs/") + id + "-" + sanitize(r.label);
}

double parentRssMb() {
  std::ifstream statm("/proc/self/statm");
  long pages = 0, resident = 0;
  if (!(statm >> pages >> resident)) return NAN;
  return static_cast<double>(resident) * static_cast<double>(::sysconf(_SC_PAGESIZE)) / (1024.0 * 1024.0);
}

nlohmann::json jsonValue(double v) { return std::isfinite(v) ? nlohmann::json(v) : nlohmann::json(); }

double jsonNumber(const nlohmann::json& j, const char* key) {
  const auto it = j.find(key);
  return it != j.end() && it->is_number() ? it->get<double>() : NAN;
}

// What the reference of a study provides to the error measures.
struct ReferenceData {
  bool available = false;
  double peakLoad = NAN, peakReaction = NAN, dissipated = NAN;  // mpm run reference
  PointRun point;                            // point run reference
  std::vector<double> pathParameter;         // point: strain path arc length of the reference rows
  double peakStress = NAN;
};

// Arc length of the strain path along the rows (engineering shear components).
std::vector<double> strainArcLength(const PointRun& run) {
  std::vector<double> s;
  double total = 0.0;
  for (std::size_t i = 0; i < run.history.size(); ++i) {
    if (i > 0) total += (run.history[i].strain - run.history[i - 1].strain).norm();
    s.push_back(total);
  }
  return s;
}

double relative(double value, double reference) {
  return std::isfinite(value) && std::isfinite(reference) && reference != 0.0 ? value / reference - 1.0 : NAN;
}

class Executor {
 public:
  Executor(const Study& s, const StudyOptions& o, const std::filesystem::path& dir) : study_(s), options_(o), dir_(dir) {}

  RunRecord run(const PlannedRun& p, ReferenceData& ref, nlohmann::json& refJson) {
    RunRecord r;
    r.id = p.id;
    r.label = p.label;
    r.values = p.values;
    r.reference = p.reference;
    r.directory = runDirectory(p);
    r.metrics.assign(study_.metrics.size(), NAN);
    const std::filesystem::path dir = io::prepareOutputDir(dir_ / r.directory);
    std::error_code ec;
    const bool reuse = options_.resume && study_.kind == StudyKind::Mpm && std::filesystem::exists(dir / "scene.yaml", ec) &&
                       readText(dir / "scene.yaml") == p.sceneText && std::filesystem::exists(dir / "study_run.json", ec) &&
                       std::filesystem::exists(dir / "summary.json", ec);
    if (!reuse) io::writeFileAtomically(dir / "scene.yaml", p.sceneText);
    r.reused = reuse;
    if (study_.kind == StudyKind::Mpm) runMpm(p, dir, reuse, r, ref, refJson);
    else runPointScene(p, dir, r, ref, refJson);
    double worst = NAN;
    for (const double m : r.metrics)
      if (std::isfinite(m)) worst = std::isnan(worst) ? std::abs(m) : std::max(worst, std::abs(m));
    bool all = true;
    for (const double m : r.metrics) all = all && std::isfinite(m);
    r.error = all ? worst : NAN;
    return r;
  }

 private:
  const Study& study_;
  const StudyOptions& options_;
  std::filesystem::path dir_;

  void setMetric(RunRecord& r, const std::string& name, double value) const {
    for (std::size_t i = 0; i < study_.metrics.size(); ++i)
      if (study_.metrics[i] == name) r.metrics[i] = value;
  }

  struct Usage {
    double peakRssMb = NAN, cpuTime = NAN;
  };

  // One execution of an mpm run; when isolated, the peak RSS (MB) and CPU time (s) of its process.
  Usage executeMpm(const Scene& scene, const std::filesystem::path& dir) const {
    RunOptions o;
    o.outputDir = dir;
    o.threads = options_.threads;
    o.snapshots = false;
    o.plot = false;
    o.progress = false;
    if (!options_.isolate) {
      try {
        runScene(scene, o);
      } catch (const std::exception& e) {  // an invalid scene (e.g. seeding): the run fails, the study goes on
        std::ofstream(dir / "error.txt") << e.what() << "\n";
      }
      return {};
    }
    std::fflush(nullptr);
    std::cout.flush();
    std::cerr.flush();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed: cannot start a run");
    if (pid == 0) {
      ::prctl(PR_SET_PDEATHSIG, SIGTERM);  // a run does not outlive its study
      int code = 3;
      try {
        code = runScene(scene, o).completed ? 0 : 1;
      } catch (const std::exception& e) {
        std::ofstream(dir / "error.txt") << e.what() << "\n";
      } catch (...) {
        std::ofstream(dir / "error.txt") << "unknown exception\n";
      }
      ::_exit(code);
    }
    int status = 0;
    struct rusage usage {};
    while (::wait4(pid, &status, 0, &usage) < 0) {
      if (errno != EINTR) throw std::runtime_error("waiting for a run failed");
    }
    if (WIFSIGNALED(status))
      std::ofstream(dir / "error.txt") << "the run's process was killed by signal " << WTERMSIG(status) << "\n";
    auto seconds = [](const timeval& t) { return static_cast<double>(t.tv_sec) + 1e-6 * static_cast<double>(t.tv_usec); };
    return {static_cast<double>(usage.ru_maxrss) / 1024.0,  // Linux: kilobytes
            seconds(usage.ru_utime) + seconds(usage.ru_stime)};
  }

  // What an mpm run's outputs give the error measures.
  struct MpmOutcome {
    double peakLoad = NAN, peakReaction = NAN, dissipated = NAN;
  };

  // Fills r from the run's summary.json; false (r failed, with the reason) when there is none.
  static bool readSummary(const std::filesystem::path& dir, RunRecord& r, MpmOutcome& out) {
    nlohmann::json j;
    try {
      std::ifstream in(dir / "summary.json");
      if (!in) throw std::runtime_error("no summary.json");
      j = nlohmann::json::parse(in);
    } catch (const std::exception& e) {
      r.status = "failed";
      std::ifstream err(dir / "error.txt");
      std::string why;
      std::getline(err, why);
      r.message = why.empty() ? std::string("the run left no summary: ") + e.what() : why;
      return false;
    }
    r.status = j.value("status", std::string("failed"));
    r.message = j.value("error", std::string());
    r.wallTime = jsonNumber(j, "wall_time_s");
    r.updatesPerSecond = jsonNumber(j, "particle_updates_per_s");
    r.steps = jsonNumber(j, "steps");
    r.particles = jsonNumber(j, "particles");
    r.substepped = jsonNumber(j, "substepped_updates");
    const double intact = jsonNumber(j, "bytes_per_particle_uncracked"), cracked = jsonNumber(j, "bytes_per_particle_cracked");
    const double crackedCount = jsonNumber(j, "cracked_particles");
    if (r.particles > 0.0) r.bytesPerParticle = intact + (cracked - intact) * crackedCount / r.particles;
    out.peakLoad = jsonNumber(j, "peak_load");
    if (j.contains("energies_Nmm")) out.dissipated = jsonNumber(j["energies_Nmm"], "dissipated");
    return true;
  }

  // The largest |reaction| of a condition over the rows of history.csv.
  static double peakReaction(const io::CsvTable& h, const std::string& condition) {
    const auto x = std::find(h.header.begin(), h.header.end(), condition + "_rx_N") - h.header.begin();
    const auto y = std::find(h.header.begin(), h.header.end(), condition + "_ry_N") - h.header.begin();
    if (static_cast<std::size_t>(x) >= h.header.size() || static_cast<std::size_t>(y) >= h.header.size())
      throw std::runtime_error("no columns " + condition + "_rx_N, " + condition + "_ry_N");
    double peak = 0.0;
    for (const auto& row : h.rows) peak = std::max(peak, std::hypot(row[static_cast<std::size_t>(x)], row[static_cast<std::size_t>(y)]));
    return peak;
  }

  void runMpm(const PlannedRun& p, const std::filesystem::path& dir, bool reuse, RunRecord& r, ReferenceData& ref,
              nlohmann::json& refJson) const {
    std::error_code ec;
    MpmOutcome out;
    if (reuse) {  // --resume: the outputs of an earlier study of the same scene text
      std::ifstream in(dir / "study_run.json");
      const nlohmann::json j = nlohmann::json::parse(in, nullptr, false);
      if (!readSummary(dir, r, out)) return;
      r.wallTime = jsonNumber(j, "wall_time_s");
      r.updatesPerSecond = jsonNumber(j, "updates_per_s");
      r.peakRssMb = jsonNumber(j, "peak_rss_mb");
      r.cpuTime = jsonNumber(j, "cpu_time_s");
    } else {
      double wall = NAN, ups = NAN, cpu = NAN;
      for (int rep = 0; rep < study_.repeat; ++rep) {
        std::filesystem::remove(dir / "summary.json", ec);
        std::filesystem::remove(dir / "error.txt", ec);
        std::filesystem::remove(dir / "study_run.json", ec);
        const Usage use = executeMpm(*p.scene, dir);
        if (std::isfinite(use.peakRssMb)) r.peakRssMb = std::isnan(r.peakRssMb) ? use.peakRssMb : std::max(r.peakRssMb, use.peakRssMb);
        r.cpuTime = use.cpuTime;
        if (!readSummary(dir, r, out)) return;
        if (std::isnan(wall) || r.wallTime < wall) wall = r.wallTime, ups = r.updatesPerSecond, cpu = use.cpuTime;
        if (r.status != "completed") break;
      }
      r.wallTime = wall;
      r.updatesPerSecond = ups;
      r.cpuTime = cpu;
      io::writeJsonSummary({{"wall_time_s", jsonValue(r.wallTime)},
                            {"updates_per_s", jsonValue(r.updatesPerSecond)},
                            {"peak_rss_mb", jsonValue(r.peakRssMb)},
                            {"cpu_time_s", jsonValue(r.cpuTime)},
                            {"repeat", study_.repeat}},
                           dir / "study_run.json");
    }
    if (r.status != "completed") return;
    if (study_.reference == ReferenceKind::BarVibration) {
      const BarVibration cf = barVibrationClosedForm(*p.scene);
      refJson = {{"closed_form", "bar_vibration"},
                 {"condition", study_.condition},
                 {"period_s", cf.period},
                 {"reaction_amplitude_N", cf.amplitude},
                 {"formula", "T = 4 L / c, R = rho c v0 A, c = sqrt(E / rho)"}};
      try {
        const io::CsvTable h = io::readCsv(dir / "history.csv");
        const auto col = std::find(h.header.begin(), h.header.end(), study_.condition + "_rx_N") - h.header.begin();
        if (static_cast<std::size_t>(col) >= h.header.size()) throw std::runtime_error("no column " + study_.condition + "_rx_N");
        std::vector<double> t, reaction;
        for (const auto& row : h.rows) t.push_back(row[0]), reaction.push_back(row[static_cast<std::size_t>(col)]);
        const SquareWave w = measureSquareWave(t, reaction, cf.amplitude);
        setMetric(r, "period", relative(w.period, cf.period));
        setMetric(r, "amplitude", relative(w.amplitude, cf.amplitude));
        if (w.crossings == 0) r.message = "no sign change of the reaction: end_time shorter than half a period?";
      } catch (const std::exception& e) {
        r.message = std::string("history.csv: ") + e.what();
      }
      return;
    }
    if (!study_.condition.empty()) {
      try {
        out.peakReaction = peakReaction(io::readCsv(dir / "history.csv"), study_.condition);
      } catch (const std::exception& e) {
        r.message = std::string("history.csv: ") + e.what();
      }
    }
    if (p.reference) {
      ref.available = true;
      ref.peakLoad = out.peakLoad;
      ref.peakReaction = out.peakReaction;
      ref.dissipated = out.dissipated;
      refJson = {{"run", r.id},
                 {"label", r.label},
                 {"peak_load_N", jsonValue(out.peakLoad)},
                 {"dissipated_energy_Nmm", jsonValue(out.dissipated)}};
      if (!study_.condition.empty()) refJson["peak_reaction_" + study_.condition + "_N"] = jsonValue(out.peakReaction);
    }
    if (ref.available) {
      setMetric(r, "peak_load", relative(out.peakLoad, ref.peakLoad));
      setMetric(r, "peak_reaction", relative(out.peakReaction, ref.peakReaction));
      setMetric(r, "dissipated_energy", relative(out.dissipated, ref.dissipated));
    }
  }

  void runPointScene(const PlannedRun& p, const std::filesystem::path& dir, RunRecord& r, ReferenceData& ref,
                     nlohmann::json& refJson) const {
    const PointScene& scene = *p.point;
    PointRun run;
    for (int rep = 0; rep < study_.repeat; ++rep) {
      const auto start = std::chrono::steady_clock::now();
      run = runPoint(scene);
      const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
      r.wallTime = std::isnan(r.wallTime) ? wall : std::min(r.wallTime, wall);
    }
    writeHistoryCsv(run, dir / "history.csv");
    io::writeJsonSummary(pointSummaryJson(scene, run), dir / "summary.json");
    r.status = run.completed ? "completed" : "failed";
    r.message = run.failure;
    const int increments = run.history.empty() ? 0 : run.history.back().increment;
    r.steps = increments;
    r.particles = 1;
    r.updatesPerSecond = r.wallTime > 0.0 ? increments / r.wallTime : NAN;
    r.substepped = static_cast<double>(
        std::count_if(run.history.begin(), run.history.end(), [](const HistoryRow& h) { return h.substeps > 1; }));
    if (!run.completed || run.history.empty()) return;
    const double ft = scene.material.tensileStrength > 0.0 ? scene.material.tensileStrength : 1.0;
    const PointSummary sum = summarise(scene, run);
    if (study_.reference == ReferenceKind::UniaxialTension) {
      try {
        const UniaxialReference cf =
            uniaxialTensionClosedForm(scene.material, scene.effectiveSize, run.history.back().strain[0]);
        std::vector<double> x, y;
        for (const HistoryRow& h : run.history) x.push_back(h.strain[0]), y.push_back(h.stress[0]);
        setMetric(r, "stress_path", maxDeviation(cf.strain, cf.stress, x, y) / ft);
        setMetric(r, "dissipation", relative(run.history.back().dissipation, cf.dissipation));
        setMetric(r, "peak_stress", relative(sum.peakStress, cf.peakStress));
        if (refJson.is_null())
          refJson = {{"closed_form", "uniaxial_tension"},
                     {"peak_stress_MPa", cf.peakStress},
                     {"dissipation_per_volume_MPa", cf.dissipation},
                     {"strain_end", run.history.back().strain[0]},
                     {"source", "material/uniaxial_closed_form.hpp"}};
      } catch (const std::invalid_argument& e) {
        r.message = e.what();
      }
      return;
    }
    if (p.reference) {
      ref.available = true;
      ref.point = run;
      ref.pathParameter = strainArcLength(run);
      ref.peakStress = sum.peakStress;
      refJson = {{"run", r.id},
                 {"label", r.label},
                 {"peak_stress_MPa", sum.peakStress},
                 {"dissipation_per_volume_MPa", run.history.back().dissipation}};
    }
    if (!ref.available) return;
    const std::vector<double> s = strainArcLength(run);
    double worst = 0.0;
    for (int c = 0; c < 3; ++c) {
      std::vector<double> refY, y;
      for (const HistoryRow& h : ref.point.history) refY.push_back(h.stress[c]);
      for (const HistoryRow& h : run.history) y.push_back(h.stress[c]);
      worst = std::max(worst, maxDeviation(ref.pathParameter, refY, s, y));
    }
    setMetric(r, "stress_path", worst / ft);
    setMetric(r, "dissipation", relative(run.history.back().dissipation, ref.point.history.back().dissipation));
    setMetric(r, "peak_stress", relative(sum.peakStress, ref.peakStress));
  }
};

// ---------------------------------------------------------------------------------------------
// Outputs

std::string csvField(const std::string& s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string q = "\"";
  for (const char c : s) q += c == '"' ? std::string("\"\"") : (c == '\n' ? std::string(" ") : std::string(1, c));
  return q + "\"";
}

std::string csvNumber(double v) { return std::isfinite(v) ? numberText(v) : ""; }

void cell(std::string& text, const std::string& field) {
  text += ',';
  text += field;
}

std::string shortNumber(double v, int precision = 3) {
  if (!std::isfinite(v)) return "-";
  std::ostringstream s;
  s << std::setprecision(precision) << v;
  return s.str();
}

void writeTableCsv(const Study& study, const StudyResult& result, const std::filesystem::path& path) {
  std::string text = "id,label";
  for (const Knob& k : study.knobs) text += "," + csvField(k.key);
  text += ",reference,status,wall_time_s,cpu_time_s,steps,particles,updates_per_s,bytes_per_particle,peak_rss_mb,substepped";
  for (const std::string& m : study.metrics) text += "," + m + "_error";
  text += ",error,pareto,directory,message\n";
  for (const RunRecord& r : result.runs) {
    text += std::to_string(r.id) + "," + csvField(r.label);
    for (const std::string& v : r.values) cell(text, csvField(v));
    text += std::string(",") + (r.reference ? "1" : "0") + "," + r.status;
    for (const double v : {r.wallTime, r.cpuTime, r.steps, r.particles, r.updatesPerSecond, r.bytesPerParticle, r.peakRssMb, r.substepped})
      cell(text, csvNumber(v));
    for (const double m : r.metrics) cell(text, csvNumber(m));
    text += "," + csvNumber(r.error) + "," + (r.pareto ? "1" : "0") + "," + csvField(r.directory) + "," + csvField(r.message) + "\n";
  }
  io::writeFileAtomically(path, text);
}

void writeTable(const Study& study, const StudyResult& result, std::ostream& out) {
  std::vector<std::string> header{"id"};
  for (const Knob& k : study.knobs) header.push_back(k.key);
  for (const char* h : {"status", "time_s", "cpu_s", "steps", "particles", "B/particle", "rss_MB"}) header.push_back(h);
  for (const std::string& m : study.metrics) header.push_back(m);
  header.push_back("error");
  header.push_back("pareto");
  std::vector<std::vector<std::string>> rows;
  for (const RunRecord& r : result.runs) {
    std::vector<std::string> row{std::to_string(r.id) + (r.reference ? "R" : "")};
    for (const std::string& v : r.values) row.push_back(v);
    row.push_back(r.status);
    row.push_back(shortNumber(r.wallTime));
    row.push_back(shortNumber(r.cpuTime));
    row.push_back(shortNumber(r.steps, 6));
    row.push_back(shortNumber(r.particles, 7));
    row.push_back(shortNumber(r.bytesPerParticle, 4));
    row.push_back(shortNumber(r.peakRssMb, 3));
    for (const double m : r.metrics) row.push_back(shortNumber(m, 3));
    row.push_back(shortNumber(r.error, 3));
    row.push_back(r.pareto ? "*" : "");
    rows.push_back(std::move(row));
  }
  std::vector<std::size_t> width(header.size(), 0);
  for (std::size_t c = 0; c < header.size(); ++c) {
    width[c] = header[c].size();
    for (const auto& row : rows) width[c] = std::max(width[c], row[c].size());
  }
  auto line = [&](const std::vector<std::string>& cells) {
    for (std::size_t c = 0; c < cells.size(); ++c) out << (c ? "  " : "") << std::setw(static_cast<int>(width[c])) << cells[c];
    out << "\n";
  };
  line(header);
  for (const auto& row : rows) line(row);
}

void plotPareto(const Study& study, const StudyResult& result, const std::filesystem::path& dir) {
  std::string all = "wall_time_s,error,id\n", front = all;
  std::vector<const RunRecord*> onFront;
  int points = 0;
  for (const RunRecord& r : result.runs) {
    if (!(r.wallTime > 0.0) || !std::isfinite(r.error) || (r.reference && study.reference == ReferenceKind::Run)) continue;
    const double e = std::max(r.error, 1e-16);  // log axis: an exact result is drawn at 1e-16
    all += numberText(r.wallTime) + "," + numberText(e) + "," + std::to_string(r.id) + "\n";
    ++points;
    if (r.pareto) onFront.push_back(&r);
  }
  std::sort(onFront.begin(), onFront.end(), [](const RunRecord* a, const RunRecord* b) { return a->wallTime < b->wallTime; });
  for (const RunRecord* r : onFront)
    front += numberText(r->wallTime) + "," + numberText(std::max(r->error, 1e-16)) + "," + std::to_string(r->id) + "\n";
  io::writeFileAtomically(dir / "pareto_runs.csv", all);
  io::writeFileAtomically(dir / "pareto_front.csv", front);
  if (points == 0) return;
  io::PlotSpec spec;
  spec.title = study.name + ": error against wall time (labels: run id; line: the non-dominated settings)";
  spec.xLabel = "wall time (s)";
  std::string metrics;
  for (std::string m : study.metrics) {  // gnuplot's enhanced text would read '_' as a subscript
    std::replace(m.begin(), m.end(), '_', ' ');
    metrics += (metrics.empty() ? "" : ", ") + m;
  }
  spec.yLabel = "error: max |" + metrics + "|";
  spec.logX = spec.logY = true;
  spec.series.push_back({"pareto_runs.csv", "1:2", "", "runs", "points pt 7 ps 1 lc rgb '#808080'"});
  spec.series.push_back({"pareto_front.csv", "1:2", "", "non-dominated", "linespoints pt 7 ps 1.6 lw 2 lc rgb '#d62728'"});
  // Every run's id while they are few; only the front's when a grid of runs would bury them.
  spec.series.push_back({points <= 40 ? "pareto_runs.csv" : "pareto_front.csv", "1:2:3", "", "",
                         "labels offset char 0.9,0.6 font ',8' tc rgb '#303030'"});
  io::renderPlot(spec, dir / "pareto.png");
}

nlohmann::json summaryJson(const Study& study, const StudyResult& result, const StudyOptions& options) {
  nlohmann::json knobs = nlohmann::json::array();
  for (const Knob& k : study.knobs) {
    nlohmann::json values = nlohmann::json::array();
    for (const auto& v : k.values) values.push_back(valueText(v));
    knobs.push_back({{"key", k.key}, {"values", values}});
  }
  nlohmann::json runs = nlohmann::json::array(), pareto = nlohmann::json::array();
  for (const RunRecord& r : result.runs) {
    nlohmann::json values, metrics;
    for (std::size_t k = 0; k < study.knobs.size(); ++k) values[study.knobs[k].key] = r.values[k];
    for (std::size_t m = 0; m < study.metrics.size(); ++m) metrics[study.metrics[m]] = jsonValue(r.metrics[m]);
    runs.push_back({{"id", r.id},
                    {"label", r.label},
                    {"values", values},
                    {"reference", r.reference},
                    {"status", r.status},
                    {"message", r.message},
                    {"directory", r.directory},
                    {"wall_time_s", jsonValue(r.wallTime)},
                    {"cpu_time_s", jsonValue(r.cpuTime)},
                    {"steps", jsonValue(r.steps)},
                    {"particles", jsonValue(r.particles)},
                    {"updates_per_s", jsonValue(r.updatesPerSecond)},
                    {"bytes_per_particle", jsonValue(r.bytesPerParticle)},
                    {"peak_rss_mb", jsonValue(r.peakRssMb)},
                    {"substepped", jsonValue(r.substepped)},
                    {"errors", metrics},
                    {"error", jsonValue(r.error)},
                    {"pareto", r.pareto},
                    {"reused", r.reused}});
    if (r.pareto) pareto.push_back(r.id);
  }
  return {{"study", study.name},
          {"file", study.file},
          {"kind", study.kind == StudyKind::Mpm ? "mpm" : "point"},
          {"base_scene", study.scene.string()},
          {"design", study.design == StudyDesign::Grid ? "grid" : "one_at_a_time"},
          {"threads", study.kind == StudyKind::Mpm ? nlohmann::json(options.threads) : nlohmann::json()},
          {"isolated_runs", study.kind == StudyKind::Mpm && options.isolate},
          {"study_process_rss_mb", jsonValue(result.studyRssMb)},
          {"repeat", study.repeat},
          {"knobs", knobs},
          {"metrics", study.metrics},
          {"reference", result.reference},
          {"runs", runs},
          {"pareto", pareto},
          {"all_completed", result.allCompleted},
          {"notes",
           "errors are signed relative errors (stress_path: max deviation / f_t'); error = max |error| of the metrics; "
           "wall times are the shortest of `repeat` runs on a machine shared with other work (noisy; cpu_time_s, the run "
           "process's user + system time, is less sensitive to other work); peak_rss_mb is "
           "the peak resident memory of the run's own process (isolated mpm runs only; it includes the pages shared with the study process, study_process_rss_mb); bytes_per_particle counts the "
           "solver's particle arrays at the end of the run, cracked points' band states included"},
          {"units", "mm, N, MPa, t, s"}};
}

}  // namespace

StudyResult runStudy(const Study& study, const std::vector<PlannedRun>& plan, const StudyOptions& options) {
  const std::filesystem::path dir = io::prepareOutputDir(options.outputDir);
  std::vector<std::size_t> order(plan.size());
  std::iota(order.begin(), order.end(), std::size_t{0});
  std::stable_partition(order.begin(), order.end(), [&](std::size_t i) { return plan[i].reference; });

  StudyResult result;
  result.runs.resize(plan.size());
  ReferenceData ref;
  Executor executor(study, options, dir);
  nlohmann::json refJson;
  for (std::size_t n = 0; n < order.size(); ++n) {
    const PlannedRun& p = plan[order[n]];
    RunRecord r = executor.run(p, ref, refJson);
    result.allCompleted = result.allCompleted && r.status == "completed";
    if (options.progress) {
      std::cerr << "[" << n + 1 << "/" << plan.size() << "] run " << p.id << (p.reference ? " (reference)" : "") << " "
                << p.label << ": " << r.status << ", " << shortNumber(r.wallTime) << " s, error " << shortNumber(r.error)
                << (r.reused ? " (reused)" : "") << (r.message.empty() ? "" : " (" + r.message + ")") << "\n";
    }
    result.runs[order[n]] = std::move(r);
  }
  if (!refJson.is_null()) result.reference = refJson;
  if (options.isolate && study.kind == StudyKind::Mpm) result.studyRssMb = parentRssMb();
  if (study.reference == ReferenceKind::Run && !ref.available)
    result.reference["error"] = "the reference run did not complete: no errors";

  std::vector<double> cost, error;
  for (const RunRecord& r : result.runs) {
    const bool candidate = r.status == "completed" && !(r.reference && study.reference == ReferenceKind::Run);
    cost.push_back(candidate ? r.wallTime : NAN);
    error.push_back(candidate ? r.error : NAN);
  }
  const std::vector<bool> front = paretoFront(cost, error);
  for (std::size_t i = 0; i < result.runs.size(); ++i) result.runs[i].pareto = front[i];

  writeTableCsv(study, result, dir / "study.csv");
  io::writeJsonSummary(summaryJson(study, result, options), dir / "summary.json");
  plotPareto(study, result, dir);
  if (options.table) writeTable(study, result, *options.table);
  return result;
}

}  // namespace ecm::mpm
