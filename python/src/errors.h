#pragma once

// How Corsa's errors and warnings reach Python. Bad input (corsa::InputError) becomes
// corsa.InputError, a ValueError whose text is the command line's `file:line: error: message`
// and whose attributes hold the location; other library exceptions become the Python exceptions
// pybind11 maps them to (std::invalid_argument -> ValueError, anything else -> RuntimeError),
// never a crash of the interpreter. Warnings (corsa::Diagnostics) become Python warnings of the
// category corsa.CorsaWarning, with the same text.

#include <pybind11/pybind11.h>

#include <cstddef>

#include "corsa/core/diagnostic.h"

namespace corsa::python {

/// Adds InputError and CorsaWarning to `module` and registers the exception translator.
void bind_errors(pybind11::module_& module);

/// Raises corsa.InputError for `error` (sets the Python error; the caller then throws
/// pybind11::error_already_set or returns to Python).
void set_input_error(const InputError& error);

/// Issues the diagnostics of `diagnostics` from index `from` on as Python warnings and returns
/// the new count. Needs the GIL; throws pybind11::error_already_set when a warning filter turned
/// one into an exception.
size_t warn_new(const Diagnostics& diagnostics, size_t from);

}  // namespace corsa::python
