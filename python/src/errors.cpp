// The library's exceptions as Python exceptions, with the same message the command-line tools
// print after "error: " (for input: "FILE:LINE: reason").
#include <cerrno>
#include <string>

#include "calibration/calibration_error.hpp"
#include "io/output_error.hpp"
#include "io/value_error.hpp"
#include "io/yaml_input.hpp"
#include "material/parameter_check.hpp"
#include "material/smeared_crack.hpp"
#include "mpm/explicit/explicit_checkpoint.hpp"
#include "python/src/bindings.hpp"

namespace ecm::python {

namespace {
// The reason io gives for a file that does not exist (io/yaml_input.cpp, io/csv_reader.cpp).
const std::string kMissingFile = "cannot open file: it does not exist";
}  // namespace

void bindErrors(py::module_& m) {
  // Bad input of any kind is a ValueError: a file's key or value (InputError, "FILE:LINE: reason"),
  // a value out of range given in code (ParameterError, io::ValueError), a calibration that
  // cannot be made (CalibrationError, RegularisationError).
  static py::exception<io::InputError> inputError(m, "InputError", PyExc_ValueError);
  static py::exception<ParameterError> parameterError(m, "ParameterError", PyExc_ValueError);
  static py::exception<calibration::CalibrationError> calibrationError(m, "CalibrationError", PyExc_ValueError);
  static py::exception<io::OutputError> outputError(m, "OutputError", PyExc_OSError);
  static py::exception<mpm::CheckpointError> checkpointError(m, "CheckpointError", PyExc_RuntimeError);
  inputError.attr("__doc__") =
      "Bad input (a ValueError): a key or value of a file, dict or keywords, as 'FILE:LINE: reason' for files and "
      "'<dict>: key 'a.b': reason' for dicts; the message the tools print after 'error: '.";
  parameterError.attr("__doc__") =
      "A parameter out of its range given in code (a ValueError), naming the parameter, its value and the range.";
  calibrationError.attr("__doc__") =
      "A calibration that cannot be made (a ValueError): e.g. no E_p dissipates G_F for the given n, or an element "
      "size above H_crit for the crack-band regularisation.";
  outputError.attr("__doc__") = "An output folder or file that could not be written (an OSError).";
  checkpointError.attr("__doc__") =
      "A checkpoint that cannot be used for a restart (a RuntimeError): missing, damaged, or of another scene.";
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const io::InputError& e) {
      if (e.reason == kMissingFile) {  // a file that is not there is Python's FileNotFoundError
        py::object error = py::module_::import("builtins").attr("FileNotFoundError")(ENOENT, "No such file: " + e.file, e.file);
        PyErr_SetObject(PyExc_FileNotFoundError, error.ptr());
        return;
      }
      inputError(e.what());
    } catch (const DictInputError& e) {
      inputError(e.what());
    } catch (const io::ValueError& e) {
      inputError(e.what());
    } catch (const ParameterError& e) {
      parameterError(e.what());
    } catch (const RegularisationError& e) {
      calibrationError(e.what());
    } catch (const calibration::CalibrationError& e) {
      calibrationError(e.what());
    } catch (const io::OutputError& e) {
      outputError(e.what());
    } catch (const mpm::CheckpointError& e) {
      checkpointError(e.what());
    }
  });
}

}  // namespace ecm::python
