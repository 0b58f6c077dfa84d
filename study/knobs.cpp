// ecm-study: values as text, key paths ("a.b[0].c") on the scene's YAML document, and the
// derived knobs (grid.refinement, time_scale) that rewrite it.
#include <algorithm>
#include <charconv>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "study/study.hpp"
#include "study/internal.hpp"

namespace ecm::study {

namespace detail {

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

// A value as text: scalars as written, sequences and maps in flow style.
std::string valueText(const YAML::Node& n) {
  if (n.IsScalar()) return n.Scalar();
  YAML::Emitter e;
  e.SetSeqFormat(YAML::Flow);
  e.SetMapFormat(YAML::Flow);
  e << n;
  return e.c_str();
}

// ---------------------------------------------------------------------------------------------
// Key paths: "a.b[0].c"

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

}  // namespace detail

using namespace detail;

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

YAML::Node numberNode(double v) { return YAML::Node(numberText(v)); }

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

}  // namespace ecm::study
