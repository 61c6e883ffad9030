#include "errors.h"

#include <exception>
#include <string>

namespace corsa::python {
namespace py = pybind11;
namespace {

// The exception and warning classes, created once when the module is imported (the module
// lives until the interpreter ends, as do these references).
PyObject* input_error_type = nullptr;
PyObject* warning_type = nullptr;

py::dict diagnostic_dict(const Diagnostic& d) {
  py::dict out;
  out["severity"] = std::string(severity_name(d.severity));
  out["file"] = d.file;
  out["line"] = d.line > 0 ? py::object(py::int_(d.line)) : py::object(py::none());
  out["record"] = d.record >= 0 ? py::object(py::int_(d.record)) : py::object(py::none());
  out["path"] = d.path;
  out["message"] = d.message;
  out["text"] = d.format();
  return out;
}

}  // namespace

void set_input_error(const InputError& error) {
  const Diagnostic& d = error.diagnostic();
  py::object exception =
      py::reinterpret_steal<py::object>(PyObject_CallFunction(input_error_type, "s", error.what()));
  if (!exception) {
    return;  // the call set a Python error (out of memory)
  }
  exception.attr("file") = d.file.empty() ? py::object(py::none()) : py::object(py::str(d.file));
  exception.attr("line") = d.line > 0 ? py::object(py::int_(d.line)) : py::object(py::none());
  exception.attr("record") =
      d.record >= 0 ? py::object(py::int_(d.record)) : py::object(py::none());
  exception.attr("path") = d.path;
  exception.attr("message") = d.message;
  py::list diagnostics;
  diagnostics.append(diagnostic_dict(d));
  exception.attr("diagnostics") = diagnostics;
  PyErr_SetObject(input_error_type, exception.ptr());
}

size_t warn_new(const Diagnostics& diagnostics, size_t from) {
  if (diagnostics.size() <= from) {
    return from;
  }
  const std::vector<Diagnostic> all = diagnostics.all();
  for (size_t i = from; i < all.size(); ++i) {
    const std::string text = all[i].format();
    // stacklevel 2: the warning points at the user's line that called into Corsa.
    if (PyErr_WarnEx(warning_type, text.c_str(), 2) != 0) {
      throw py::error_already_set();
    }
  }
  return all.size();
}

void bind_errors(py::module_& module) {
  input_error_type = PyErr_NewExceptionWithDoc(
      "corsa.InputError",
      "Bad input: a scenario, map, rig, suite or option Corsa cannot use. str() is the command "
      "line's 'file:line: error: message'; the attributes file, line (None when unknown), "
      "record (DBF record, or None), path (element path), message and diagnostics (a list of "
      "dicts, one per error) hold its parts.",
      PyExc_ValueError, nullptr);
  warning_type = PyErr_NewExceptionWithDoc(
      "corsa.CorsaWarning",
      "A warning from Corsa about its input (text as the command line prints it).",
      PyExc_UserWarning, nullptr);
  if (input_error_type == nullptr || warning_type == nullptr) {
    throw py::error_already_set();
  }
  module.add_object("InputError", py::handle(input_error_type));
  module.add_object("CorsaWarning", py::handle(warning_type));
  py::register_exception_translator([](std::exception_ptr pointer) {
    try {
      if (pointer) {
        std::rethrow_exception(pointer);
      }
    } catch (const InputError& error) {
      set_input_error(error);
    }
  });
}

}  // namespace corsa::python
