#include "values.h"

#include <cstdint>
#include <variant>

namespace corsa::python {
namespace py = pybind11;

py::object to_python(const xosc::Value& value) {
  return std::visit(
      [&](const auto& v) -> py::object {
        using T = std::decay_t<decltype(v)>;
        if constexpr (std::is_same_v<T, bool>) {
          return py::bool_(v);
        } else if constexpr (std::is_same_v<T, int64_t>) {
          return py::int_(v);
        } else if constexpr (std::is_same_v<T, double>) {
          return py::float_(v);
        } else {
          return py::str(v);
        }
      },
      value.data);
}

std::optional<xosc::Value> from_python(const py::handle& value, std::string_view what) {
  if (value.is_none()) {
    return std::nullopt;
  }
  // bool before int: Python's bool is an int.
  if (py::isinstance<py::bool_>(value)) {
    return xosc::Value{xosc::ParameterType::kBoolean, value.cast<bool>()};
  }
  if (py::isinstance<py::int_>(value)) {
    return xosc::Value{xosc::ParameterType::kInt, value.cast<int64_t>()};
  }
  if (py::isinstance<py::float_>(value)) {
    return xosc::Value{xosc::ParameterType::kDouble, value.cast<double>()};
  }
  if (py::isinstance<py::str>(value)) {
    return xosc::Value{xosc::ParameterType::kString, value.cast<std::string>()};
  }
  throw py::type_error(std::string(what) + " must be a bool, int, float or str (or None), not " +
                       std::string(py::str(value.get_type().attr("__name__"))));
}

std::string parameter_text(const py::handle& value, std::string_view what) {
  if (py::isinstance<py::bool_>(value)) {
    return value.cast<bool>() ? "true" : "false";
  }
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value) ||
      py::isinstance<py::str>(value)) {
    // Python's str() of a float is its shortest round-trip text, as the command line reads it.
    return std::string(py::str(value));
  }
  throw py::type_error(std::string(what) + " must be a bool, int, float or str, not " +
                       std::string(py::str(value.get_type().attr("__name__"))));
}

}  // namespace corsa::python
