#pragma once
// The validating YAML reader every input file of ecm goes through. Each value is read with its
// expected type and range; anything wrong is an InputError "FILE:LINE: reason" (LINE 1-based).
// Keys that were never asked for are rejected by finish() ("unknown key 'foo' (allowed: ...)").
#include <yaml-cpp/yaml.h>

#include <array>
#include <concepts>
#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <memory>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace ecm::io {

struct InputError : std::runtime_error {
  InputError(const std::string& file, int line, const std::string& reason);
  std::string file;
  int line;  // 1-based; 1 when the file could not be opened at all
  std::string reason;
};

// A real interval for range checks, printed like "(0, 0.5)" or "[0, inf)".
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool loClosed = false;
  bool hiClosed = false;

  static Range any() { return {}; }
  static Range open(double lo, double hi) { return {lo, hi, false, false}; }
  static Range closed(double lo, double hi) { return {lo, hi, true, true}; }
  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), false, false}; }
  static Range nonNegative() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  bool contains(double v) const;
  std::string str() const;
};

template <class T>
concept YamlScalar = std::same_as<T, double> || std::same_as<T, int> || std::same_as<T, bool> ||
                     std::same_as<T, std::string>;
template <class T>
concept YamlNumber = std::same_as<T, double> || std::same_as<T, int>;

// A YAML map of one file. Copies share the record of which keys were read, so a map can be
// handed to helpers and checked once at the end with finish().
class YamlMap {
 public:
  // `path` is the dotted key path of this map in its file ("" for the top level), used in messages.
  YamlMap(const YAML::Node& node, const std::string& file, const std::string& path = "");

  const std::string& file() const;
  std::filesystem::path directory() const;  // folder of the file (for relative references)
  const std::string& path() const;
  int line() const;                         // line of the map itself
  int line(const std::string& key) const;   // line of the key, or of the map if absent

  // Whether the key is present; also declares it as allowed.
  bool has(const std::string& key) const;

  template <YamlScalar T>
  T get(const std::string& key) const;
  template <YamlNumber T>
  T get(const std::string& key, const Range& range) const;
  template <YamlScalar T>
  T getOr(const std::string& key, const T& fallback) const;
  template <YamlNumber T>
  T getOr(const std::string& key, const T& fallback, const Range& range) const;

  // A string that must be one of `allowed`.
  std::string getEnum(const std::string& key, std::initializer_list<std::string_view> allowed) const;
  std::string getEnumOr(const std::string& key, std::initializer_list<std::string_view> allowed,
                        const std::string& fallback) const;
  // An enum by its spellings (toString of each of `values`, in that order in the error), or
  // `fallback` where the key is absent: the default stays where the settings declare it.
  template <class E, std::size_t N>
  E getEnumOr(const std::string& key, const std::array<E, N>& values, E fallback) const {
    if (!has(key)) return fallback;
    std::array<std::string_view, N> names;
    for (std::size_t i = 0; i < N; ++i) names[i] = toString(values[i]);
    const std::string v = getEnum(key, std::span<const std::string_view>(names));
    for (std::size_t i = 0; i < N; ++i)
      if (v == names[i]) return values[i];
    return fallback;  // not reached: getEnum refused anything else
  }
  std::string getEnum(const std::string& key, std::span<const std::string_view> allowed) const;
  // A sequence of numbers of exactly `size` entries (any non-zero length when size == 0).
  std::vector<double> getVector(const std::string& key, std::size_t size, const Range& range = Range::any()) const;

  YamlMap child(const std::string& key) const;
  std::vector<YamlMap> sequence(const std::string& key) const;  // a sequence of maps
  template <YamlScalar T>
  std::vector<T> scalarSequence(const std::string& key) const;

  // Throws if `key` is present: for keys that are meaningless in the given context.
  void reject(const std::string& key, const std::string& why) const;
  // Throws an InputError at the key's line: "key 'path.key': reason".
  [[noreturn]] void fail(const std::string& key, const std::string& reason) const;
  // Throws an InputError at the map's line.
  [[noreturn]] void failHere(const std::string& reason) const;
  // Throws an InputError for a key path below this map ("solver.cfl", "materials[1].name"), at
  // the line of its deepest part present in the file (a ValueError from a validate()).
  [[noreturn]] void failAt(const std::string& keyPath, const std::string& reason) const;

  // Rejects every key of this map (and of the maps obtained through child()/sequence()) that
  // was never asked for.
  void finish() const;

  const YAML::Node& node() const;

 private:
  struct State;
  std::shared_ptr<State> state_;
  explicit YamlMap(std::shared_ptr<State> s) : state_(std::move(s)) {}
  YAML::Node require(const std::string& key) const;
  std::string qualified(const std::string& key) const;
};

// Reads a YAML file whose top level is a map. Missing files and syntax errors are InputErrors.
YamlMap loadYamlFile(const std::filesystem::path& path);
// The same for text in memory; `name` stands in for the file name in messages.
YamlMap parseYaml(const std::string& text, const std::string& name);

}  // namespace ecm::io
