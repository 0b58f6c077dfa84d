// ecm._ecm: the compiled part of the Python package `ecm` (python/ecm/__init__.py re-exports it).
#include <pybind11/stl/filesystem.h>
#include <yaml-cpp/yaml.h>

#include <charconv>
#include <cmath>
#include <filesystem>
#include <limits>
#include <optional>

#include "io/yaml_input.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

py::object toPython(const nlohmann::json& j) { return py::module_::import("json").attr("loads")(j.dump()); }

namespace {

// Writes a Python value as JSON (which is YAML), one key or item per line, and remembers the key
// path of every line for messages.
class DictWriter {
 public:
  explicit DictWriter(DictText& out) : out_(out) {}

  void value(const py::handle& o, const std::string& path, int depth) {
    const py::module_ numpy = py::module_::import("numpy");  // (imported once by Python, then looked up)
    const py::object pathLike = py::module_::import("os").attr("PathLike");
    const py::object dumps = py::module_::import("json").attr("dumps");
    if (o.is_none()) {
      out_.text += "null";
    } else if (py::isinstance<py::bool_>(o) || py::isinstance(o, numpy.attr("bool_"))) {
      out_.text += PyObject_IsTrue(o.ptr()) == 1 ? "true" : "false";
    } else if (py::isinstance<py::str>(o)) {
      out_.text += dumps(o).cast<std::string>();  // quoted: the readers take it as a string
    } else if (py::isinstance(o, pathLike)) {
      out_.text += dumps(py::module_::import("os").attr("fspath")(o)).cast<std::string>();
    } else if (py::isinstance<py::int_>(o) || py::isinstance(o, numpy.attr("integer"))) {
      out_.text += py::str(py::int_(py::reinterpret_borrow<py::object>(o))).cast<std::string>();
    } else if (py::isinstance<py::float_>(o) || py::isinstance(o, numpy.attr("floating"))) {
      // str() of a NumPy scalar is the shortest text of its own precision (float32(0.1) -> 0.1).
      out_.text += py::str(o).cast<std::string>();
    } else if (py::isinstance<py::dict>(o)) {
      const py::dict d = py::reinterpret_borrow<py::dict>(o);
      open('{', d.size(), path);
      std::size_t i = 0;
      for (const auto& [k, v] : d) {
        if (!py::isinstance<py::str>(k))
          throw py::type_error("key '" + path + "': keys must be strings, got " + py::repr(k).cast<std::string>());
        const std::string key = k.cast<std::string>();
        const std::string child = path.empty() ? key : path + "." + key;
        line(child, depth + 1);
        out_.text += dumps(k).cast<std::string>() + ": ";
        value(v, child, depth + 1);
        if (++i < d.size()) out_.text += ",";
      }
      close('}', d.size(), path, depth);
    } else if (py::isinstance(o, numpy.attr("ndarray"))) {
      value(o.attr("tolist")(), path, depth);
    } else if (py::isinstance<py::list>(o) || py::isinstance<py::tuple>(o)) {
      const py::sequence s = py::reinterpret_borrow<py::sequence>(o);
      open('[', s.size(), path);
      for (std::size_t i = 0; i < s.size(); ++i) {
        const std::string child = path + "[" + std::to_string(i) + "]";
        line(child, depth + 1);
        const py::object item = s[i];
        value(item, child, depth + 1);
        if (i + 1 < s.size()) out_.text += ",";
      }
      close(']', s.size(), path, depth);
    } else {
      throw py::type_error("key '" + path + "': a value of type " + py::str(o.get_type().attr("__name__")).cast<std::string>() +
                           " cannot be read (numbers, strings, booleans, None, lists and dicts can)");
    }
  }

 private:
  void open(char bracket, std::size_t size, const std::string&) {
    out_.text += bracket;
    if (size == 0) out_.text += bracket == '{' ? '}' : ']';
  }
  void close(char bracket, std::size_t size, const std::string& path, int depth) {
    if (size == 0) return;
    line(path, depth);
    out_.text += bracket;
  }
  void line(const std::string& path, int depth) {
    out_.text += "\n" + std::string(static_cast<std::size_t>(depth), ' ');
    out_.keyPathOfLine.push_back(path);
  }
  DictText& out_;
};

}  // namespace

DictText dictText(const py::handle& mapping, const std::string& name) {
  DictText t;
  t.name = name;
  t.keyPathOfLine.push_back("");  // line 1: the opening brace
  DictWriter(t).value(mapping, "", 0);
  return t;
}

std::string DictText::keyPath(int line) const {
  return line >= 1 && static_cast<std::size_t>(line) <= keyPathOfLine.size() ? keyPathOfLine[static_cast<std::size_t>(line) - 1]
                                                                             : std::string();
}

DictInputError::DictInputError(const DictText& t, const io::InputError& e)
    : std::runtime_error(t.name + ": " +
                         (e.reason.find("key '") != std::string::npos || t.keyPath(e.line).empty()
                              ? e.reason
                              : "key '" + t.keyPath(e.line) + "': " + e.reason)) {}

namespace {

// A scalar as the tools' reader types it (io/yaml_input.cpp): quoted -> str; true/false -> bool;
// an integer -> int; a YAML 1.2 core-schema float -> float; anything else -> str.
py::object scalar(const YAML::Node& n) {
  const std::string& s = n.Scalar();
  if (n.Tag() == "!") return py::str(s);
  if (s == "true" || s == "True" || s == "TRUE") return py::bool_(true);
  if (s == "false" || s == "False" || s == "FALSE") return py::bool_(false);
  const std::string digits = !s.empty() && s[0] == '+' ? s.substr(1) : s;
  long long i = 0;
  if (const auto [end, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), i);
      ec == std::errc() && end == digits.data() + digits.size())
    return py::int_(i);
  std::string body = digits;
  const bool negative = !body.empty() && body[0] == '-';
  if (negative) body.erase(0, 1);
  std::string lower = body;
  for (char& c : lower) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".inf" || lower == "inf" || lower == "infinity")
    return py::float_(negative ? -std::numeric_limits<double>::infinity() : std::numeric_limits<double>::infinity());
  if (lower == ".nan" || lower == "nan") return py::float_(std::numeric_limits<double>::quiet_NaN());
  double v = 0.0;
  if (const auto [end, ec] = std::from_chars(body.data(), body.data() + body.size(), v);
      !body.empty() && body[0] != '+' && body[0] != '-' && ec == std::errc() && end == body.data() + body.size())
    return py::float_(negative ? -v : v);
  return py::str(s);
}

// A YAML node as Python objects; a map's relative `file` reference that exists next to the file
// becomes absolute, so that the dict reads the same from any working directory.
py::object toPythonValue(const YAML::Node& n, const std::filesystem::path& folder) {
  switch (n.Type()) {
    case YAML::NodeType::Map: {
      py::dict d;
      for (auto it = n.begin(); it != n.end(); ++it) {
        const std::string key = it->first.Scalar();
        py::object v = toPythonValue(it->second, folder);
        if (key == "file" && py::isinstance<py::str>(v)) {
          const std::filesystem::path ref = v.cast<std::string>();
          std::error_code ec;
          if (ref.is_relative() && std::filesystem::is_regular_file(folder / ref, ec))
            v = py::str((folder / ref).lexically_normal().string());
        }
        d[py::str(key)] = v;
      }
      return d;
    }
    case YAML::NodeType::Sequence: {
      py::list l;
      for (const auto& item : n) l.append(toPythonValue(item, folder));
      return l;
    }
    case YAML::NodeType::Scalar: return scalar(n);
    default: return py::none();
  }
}

}  // namespace

py::dict loadYamlAsDict(const std::filesystem::path& file) {
  const io::YamlMap map = io::loadYamlFile(file);  // missing file, syntax error: InputError with FILE:LINE
  return toPythonValue(map.node(), std::filesystem::absolute(file).parent_path()).cast<py::dict>();
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
  m.def("_load_yaml", &ecm::python::loadYamlAsDict, pybind11::arg("path"));
}
