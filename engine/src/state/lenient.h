#pragma once

// A rule of the standard broken at run time in a way whose meaning is clear (an s past the road's
// end, ...): the run goes on as the author meant, with one `(read as ...)` warning at the element,
// or stops with an error under SimulationOptions::strict (`--strict`). The load's own readings
// are in corsa_xosc (docs/openscenario.md, "Lenient reading").

#include <string_view>

#include "corsa/core/diagnostic.h"
#include "corsa/xosc/common.h"

namespace corsa::engine::detail {

struct SimState;

/// Warns `message (read as read_as)` once at `where` into `diagnostics`; throws InputError when
/// `strict`. The checks `corsa validate` makes before a run (road_network_check.h) warn with it.
void lenient(bool strict, Diagnostics& diagnostics, const xosc::Source& where,
             std::string_view message, std::string_view read_as);

/// Warns `message (read as read_as)` once at `where`; throws InputError under --strict.
void lenient(const SimState& state, const xosc::Source& where, std::string_view message,
             std::string_view read_as);

}  // namespace corsa::engine::detail
