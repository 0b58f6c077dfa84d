#include "io/yaml_input.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>
#include <fstream>
#include <optional>
#include <set>
#include <sstream>

#include "io/utf8.hpp"
#include "material/parameter_check.hpp"

namespace ecm::io {

InputError::InputError(const std::string& f, int l, const std::string& r)
    : std::runtime_error(f + ":" + std::to_string(l) + ": " + r), file(f), line(l), reason(r) {}

// ---------------------------------------------------------------------------------------------
// Range

bool Range::contains(double v) const {
  const bool aboveLo = loClosed ? v >= lo : v > lo;
  const bool belowHi = hiClosed ? v <= hi : v < hi;
  return aboveLo && belowHi;
}

std::string Range::str() const {
  std::ostringstream s;  // (a stream: GCC 12 warns falsely, -Wrestrict, on "(" + std::string&&)
  s << (loClosed ? "[" : "(") << numberText(lo, 12) << ", " << numberText(hi, 12) << (hiClosed ? "]" : ")");
  return s.str();
}

// ---------------------------------------------------------------------------------------------
// Scalar conversion

namespace {

int lineOf(const YAML::Node& n, int fallback) {
  const YAML::Mark m = n.Mark();
  return m.is_null() || m.line < 0 ? fallback : m.line + 1;
}

bool quoted(const YAML::Node& n) { return n.Tag() == "!"; }

std::string describe(const YAML::Node& n) {
  switch (n.Type()) {
    case YAML::NodeType::Map: return "a map";
    case YAML::NodeType::Sequence: return "a sequence";
    case YAML::NodeType::Null: return "no value";
    case YAML::NodeType::Undefined: return "nothing";
    case YAML::NodeType::Scalar: break;
  }
  return (quoted(n) ? "the string '" : "'") + n.Scalar() + "'";
}

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

// A YAML 1.2 core-schema float (".inf" and ".nan" recognised so that they can be refused).
std::optional<double> parseNumber(const std::string& text) {
  std::string s = text;
  bool negative = false;
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) {
    negative = s[0] == '-';
    s.erase(0, 1);
  }
  const std::string l = lower(s);
  if (l == ".inf" || l == "inf" || l == "infinity")
    return negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity();
  if (l == ".nan" || l == "nan") return std::numeric_limits<double>::quiet_NaN();
  if (s.empty() || s[0] == '+' || s[0] == '-') return std::nullopt;
  double v = 0.0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return negative ? -v : v;
}

template <class T>
T convert(const YAML::Node& n, const std::string& file, int line, const std::string& key);

template <>
double convert<double>(const YAML::Node& n, const std::string& file, int line, const std::string& key) {
  const std::string where = "key '" + key + "': ";
  if (!n.IsScalar() || quoted(n)) throw InputError(file, line, where + "expected a number, got " + describe(n));
  const std::optional<double> v = parseNumber(n.Scalar());
  if (!v) throw InputError(file, line, where + "expected a number, got " + describe(n));
  if (!std::isfinite(*v)) throw InputError(file, line, where + "expected a finite number, got " + describe(n));
  return *v;
}

template <>
int convert<int>(const YAML::Node& n, const std::string& file, int line, const std::string& key) {
  const std::string where = "key '" + key + "': ";
  if (!n.IsScalar() || quoted(n)) throw InputError(file, line, where + "expected an integer, got " + describe(n));
  std::string s = n.Scalar();
  if (!s.empty() && s[0] == '+') s.erase(0, 1);
  long long v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (ec == std::errc() && end == s.data() + s.size()) {
    if (v < std::numeric_limits<int>::min() || v > std::numeric_limits<int>::max())
      throw InputError(file, line, where + "integer " + n.Scalar() + " is too large");
    return static_cast<int>(v);
  }
  throw InputError(file, line, where + "expected an integer, got " + describe(n));
}

template <>
bool convert<bool>(const YAML::Node& n, const std::string& file, int line, const std::string& key) {
  if (n.IsScalar() && !quoted(n)) {
    const std::string& s = n.Scalar();
    if (s == "true" || s == "True" || s == "TRUE") return true;
    if (s == "false" || s == "False" || s == "FALSE") return false;
  }
  throw InputError(file, line, "key '" + key + "': expected true or false, got " + describe(n));
}

template <>
std::string convert<std::string>(const YAML::Node& n, const std::string& file, int line, const std::string& key) {
  if (!n.IsScalar()) throw InputError(file, line, "key '" + key + "': expected a string, got " + describe(n));
  // Names go into summary.json and file names: only text (found by fuzz/fuzz_point_scene.cpp).
  if (const std::optional<std::size_t> at = firstInvalidUtf8(n.Scalar()))
    throw InputError(file, line, "key '" + key + "': is not valid UTF-8 text (a stray byte at byte " + std::to_string(*at + 1) + ")");
  return n.Scalar();
}

void checkRange(double v, const Range& r, const std::string& file, int line, const std::string& key) {
  if (r.contains(v)) return;
  throw InputError(file, line, "key '" + key + "': value " + numberText(v, 12) + " is outside the allowed range " + r.str());
}

std::string joined(const std::set<std::string>& names) {
  if (names.empty()) return "none";
  std::string s;
  for (const auto& k : names) s += (s.empty() ? "" : ", ") + k;
  return s;
}

struct Entry {
  YAML::Node key;
  YAML::Node value;
};

std::optional<Entry> find(const YAML::Node& map, const std::string& key) {
  for (auto it = map.begin(); it != map.end(); ++it)
    if (it->first.IsScalar() && it->first.Scalar() == key) return Entry{it->first, it->second};
  return std::nullopt;
}

}  // namespace

// ---------------------------------------------------------------------------------------------
// YamlMap

struct YamlMap::State {
  YAML::Node node;
  std::string file;
  std::string path;
  int line = 1;
  std::set<std::string> known;  // every key asked for
  std::vector<std::shared_ptr<State>> children;
};

YamlMap::YamlMap(const YAML::Node& node, const std::string& file, const std::string& path)
    : state_(std::make_shared<State>()) {
  state_->node = node;
  state_->file = file;
  state_->path = path;
  state_->line = lineOf(node, 1);
  const std::string what = path.empty() ? "the top level" : "key '" + path + "'";
  if (!node.IsMap()) throw InputError(file, state_->line, what + ": expected a map, got " + describe(node));
  std::set<std::string> seen;
  for (auto it = node.begin(); it != node.end(); ++it) {
    const int l = lineOf(it->first, state_->line);
    if (!it->first.IsScalar()) throw InputError(file, l, what + ": keys must be plain names, got " + describe(it->first));
    if (!seen.insert(it->first.Scalar()).second)
      throw InputError(file, l, "duplicate key '" + qualified(it->first.Scalar()) + "'");
  }
}

const std::string& YamlMap::file() const { return state_->file; }
std::filesystem::path YamlMap::directory() const { return std::filesystem::path(state_->file).parent_path(); }
const std::string& YamlMap::path() const { return state_->path; }
int YamlMap::line() const { return state_->line; }
const YAML::Node& YamlMap::node() const { return state_->node; }

int YamlMap::line(const std::string& key) const {
  const auto e = find(state_->node, key);
  return e ? lineOf(e->key, state_->line) : state_->line;
}

std::string YamlMap::qualified(const std::string& key) const {
  return state_->path.empty() ? key : state_->path + "." + key;
}

bool YamlMap::has(const std::string& key) const {
  state_->known.insert(key);
  return find(state_->node, key).has_value();
}

void YamlMap::fail(const std::string& key, const std::string& reason) const {
  throw InputError(state_->file, line(key), "key '" + qualified(key) + "': " + reason);
}

void YamlMap::failHere(const std::string& reason) const {
  throw InputError(state_->file, state_->line, (state_->path.empty() ? "" : "key '" + state_->path + "': ") + reason);
}

void YamlMap::failAt(const std::string& keyPath, const std::string& reason) const {
  YAML::Node node;
  node.reset(state_->node);  // reset() rebinds; operator= would write into the document
  int line = state_->line;
  std::size_t at = 0;
  while (at < keyPath.size()) {  // segments "key" or "key[i]", separated by '.'
    const std::size_t dot = std::min(keyPath.find('.', at), keyPath.size());
    const std::string segment = keyPath.substr(at, dot - at);
    at = dot + 1;
    const std::size_t bracket = segment.find('[');
    const auto e = node.IsMap() ? find(node, segment.substr(0, bracket)) : std::nullopt;
    if (!e) break;
    line = lineOf(e->key, line);
    node.reset(e->value);
    if (bracket == std::string::npos) continue;
    const std::size_t i = std::stoul(segment.substr(bracket + 1));
    if (!node.IsSequence() || i >= node.size()) break;
    const YAML::Node item = node[i];
    line = lineOf(item, line);
    node.reset(item);
  }
  const std::string full = state_->path.empty() || keyPath.empty() ? state_->path + keyPath : state_->path + "." + keyPath;
  throw InputError(state_->file, line, (full.empty() ? "" : "key '" + full + "': ") + reason);
}

YAML::Node YamlMap::require(const std::string& key) const {
  state_->known.insert(key);
  const auto e = find(state_->node, key);
  if (!e) throw InputError(state_->file, state_->line, "missing key '" + qualified(key) + "'");
  if (e->value.IsNull()) fail(key, "has no value");
  return e->value;
}

template <YamlScalar T>
T YamlMap::get(const std::string& key) const {
  const YAML::Node v = require(key);
  return convert<T>(v, state_->file, line(key), qualified(key));
}

template <YamlNumber T>
T YamlMap::get(const std::string& key, const Range& range) const {
  const T v = get<T>(key);
  checkRange(static_cast<double>(v), range, state_->file, line(key), qualified(key));
  return v;
}

template <YamlScalar T>
T YamlMap::getOr(const std::string& key, const T& fallback) const {
  return has(key) ? get<T>(key) : fallback;
}

template <YamlNumber T>
T YamlMap::getOr(const std::string& key, const T& fallback, const Range& range) const {
  return has(key) ? get<T>(key, range) : fallback;
}

template double YamlMap::get<double>(const std::string&) const;
template int YamlMap::get<int>(const std::string&) const;
template bool YamlMap::get<bool>(const std::string&) const;
template std::string YamlMap::get<std::string>(const std::string&) const;
template double YamlMap::get<double>(const std::string&, const Range&) const;
template int YamlMap::get<int>(const std::string&, const Range&) const;
template double YamlMap::getOr<double>(const std::string&, const double&) const;
template int YamlMap::getOr<int>(const std::string&, const int&) const;
template bool YamlMap::getOr<bool>(const std::string&, const bool&) const;
template std::string YamlMap::getOr<std::string>(const std::string&, const std::string&) const;
template double YamlMap::getOr<double>(const std::string&, const double&, const Range&) const;
template int YamlMap::getOr<int>(const std::string&, const int&, const Range&) const;

std::string YamlMap::getEnum(const std::string& key, std::initializer_list<std::string_view> allowed) const {
  return getEnum(key, std::span<const std::string_view>(allowed.begin(), allowed.size()));
}

std::string YamlMap::getEnum(const std::string& key, std::span<const std::string_view> allowed) const {
  const std::string v = get<std::string>(key);
  std::string list;
  for (const auto a : allowed) {
    if (v == a) return v;
    list += (list.empty() ? "" : ", ") + std::string(a);
  }
  fail(key, "'" + v + "' is not one of: " + list);
}

std::string YamlMap::getEnumOr(const std::string& key, std::initializer_list<std::string_view> allowed,
                               const std::string& fallback) const {
  return has(key) ? getEnum(key, allowed) : fallback;
}

std::vector<double> YamlMap::getVector(const std::string& key, std::size_t size, const Range& range) const {
  const YAML::Node seq = require(key);
  if (!seq.IsSequence()) fail(key, "expected a sequence of numbers, got " + describe(seq));
  if ((size > 0 && seq.size() != size) || seq.size() == 0)
    fail(key, "expected " + (size > 0 ? std::to_string(size) : std::string("at least one")) + " numbers, got " +
                  std::to_string(seq.size()));
  std::vector<double> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const std::string name = qualified(key) + "[" + std::to_string(i) + "]";
    const int l = lineOf(seq[i], line(key));
    out.push_back(convert<double>(seq[i], state_->file, l, name));
    checkRange(out.back(), range, state_->file, l, name);
  }
  return out;
}

YamlMap YamlMap::child(const std::string& key) const {
  const YAML::Node v = require(key);
  if (!v.IsMap()) fail(key, "expected a map, got " + describe(v));
  YamlMap c(v, state_->file, qualified(key));
  c.state_->line = line(key);
  state_->children.push_back(c.state_);
  return c;
}

std::vector<YamlMap> YamlMap::sequence(const std::string& key) const {
  const YAML::Node seq = require(key);
  if (!seq.IsSequence()) fail(key, "expected a sequence of maps, got " + describe(seq));
  std::vector<YamlMap> out;
  for (std::size_t i = 0; i < seq.size(); ++i) {
    const std::string name = qualified(key) + "[" + std::to_string(i) + "]";
    if (!seq[i].IsMap())
      throw InputError(state_->file, lineOf(seq[i], line(key)), "key '" + name + "': expected a map, got " + describe(seq[i]));
    YamlMap c(seq[i], state_->file, name);
    state_->children.push_back(c.state_);
    out.push_back(c);
  }
  return out;
}

template <YamlScalar T>
std::vector<T> YamlMap::scalarSequence(const std::string& key) const {
  const YAML::Node seq = require(key);
  if (!seq.IsSequence()) fail(key, "expected a sequence, got " + describe(seq));
  std::vector<T> out;
  for (std::size_t i = 0; i < seq.size(); ++i)
    out.push_back(convert<T>(seq[i], state_->file, lineOf(seq[i], line(key)), qualified(key) + "[" + std::to_string(i) + "]"));
  return out;
}

template std::vector<double> YamlMap::scalarSequence<double>(const std::string&) const;
template std::vector<int> YamlMap::scalarSequence<int>(const std::string&) const;
template std::vector<bool> YamlMap::scalarSequence<bool>(const std::string&) const;
template std::vector<std::string> YamlMap::scalarSequence<std::string>(const std::string&) const;

void YamlMap::reject(const std::string& key, const std::string& why) const {
  if (find(state_->node, key)) fail(key, why);
}

void YamlMap::finish() const {
  for (auto it = state_->node.begin(); it != state_->node.end(); ++it) {
    const std::string k = it->first.Scalar();
    if (state_->known.count(k)) continue;
    throw InputError(state_->file, lineOf(it->first, state_->line),
                     "unknown key '" + k + "'" + (state_->path.empty() ? "" : " in '" + state_->path + "'") +
                         " (allowed: " + joined(state_->known) + ")");
  }
  for (const auto& c : state_->children) YamlMap(c).finish();
}

// ---------------------------------------------------------------------------------------------
// Loading

YamlMap parseYaml(const std::string& text, const std::string& name) {
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::ParserException& e) {
    throw InputError(name, e.mark.is_null() ? 1 : e.mark.line + 1, "invalid YAML: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw InputError(name, e.mark.is_null() ? 1 : e.mark.line + 1, "invalid YAML: " + e.msg);
  }
  if (root.IsNull() || !root.IsDefined()) throw InputError(name, 1, "the file is empty (expected a map of keys)");
  return YamlMap(root, name);
}

YamlMap loadYamlFile(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw InputError(path.string(), 1, "cannot open file: it does not exist");
  if (!std::filesystem::is_regular_file(path, ec)) throw InputError(path.string(), 1, "cannot open file: not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path.string(), 1, "cannot open file for reading");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw InputError(path.string(), 1, "read error");
  return parseYaml(text.str(), path.string());
}

}  // namespace ecm::io
