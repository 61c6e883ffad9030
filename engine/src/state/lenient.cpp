#include "state/lenient.h"

#include <string>

#include "state/sim_state.h"

namespace corsa::engine::detail {

void lenient(const SimState& state, const xosc::Source& where, std::string_view message,
             std::string_view read_as) {
  if (state.options.strict) {
    throw InputError(where.error(std::string(message) +
                                 " (an error under --strict; otherwise read as " +
                                 std::string(read_as) + ")"));
  }
  const std::string text = std::string(message) + " (read as " + std::string(read_as) + ")";
  state.diagnostics.add_once(
      "lenient:" + where.file_name() + ":" + std::to_string(where.line) + ":" + text,
      where.warning(text));
}

}  // namespace corsa::engine::detail
