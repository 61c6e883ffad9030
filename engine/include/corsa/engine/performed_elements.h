#pragma once

// Which OpenSCENARIO elements the engine acts on while a scenario runs, as opposed to those it
// only reads as data for them (positions, entities, catalogs, ...). docs/osc-coverage.md marks
// exactly these "performed" (tests/engine/coverage_test.cpp keeps the two in step).

#include <span>
#include <string_view>

namespace corsa::engine {

/// XML element names, sorted: the storyboard's elements (§8.4), every concrete action the action
/// factory builds (§7.4–7.6) and every condition the condition factory builds (§8.3).
std::span<const std::string_view> performed_elements();

}  // namespace corsa::engine
