#include "state/lenient.h"

#include <string>

#include "state/sim_state.h"

namespace corsa::engine::detail {

void lenient(bool strict, Diagnostics& diagnostics, const xosc::Source& where,
             std::string_view message, std::string_view read_as) {
  if (strict) {
    throw InputError(where.error(std::string(message) +
                                 " (an error under --strict; otherwise read as " +
                                 std::string(read_as) + ")"));
  }
  const std::string text = std::string(message) + " (read as " + std::string(read_as) + ")";
  diagnostics.add_once(
      "lenient:" + where.file_name() + ":" + std::to_string(where.line) + ":" + text,
      where.warning(text));
}

void lenient(const SimState& state, const xosc::Source& where, std::string_view message,
             std::string_view read_as) {
  lenient(state.options.strict, state.diagnostics, where, message, read_as);
}

}  // namespace corsa::engine::detail
