#pragma once

// Internal: the checks that need the whole scenario (entity names, storyboard element names).

#include "corsa/xosc/entities.h"
#include "corsa/xosc/storyboard.h"
#include "parse_context.h"

namespace corsa::xosc {

/// Every recorded entity use must name a ScenarioObject or EntitySelection.
void check_entity_references(ParseContext& ctx, const Entities& entities);

/// Resolves every StoryboardElementStateCondition with the standard's name lookup (§8.1): a
/// reference is a name or a `::`-qualified name; it matches the elements of the given type whose
/// full path ends with it, and must match exactly one; of several, the one nearest to the
/// condition (the longest enclosing path shared with it) is taken with a lenient-reading warning,
/// and a tie is an error naming both. Sets resolved_path; errors are recorded in `ctx`.
void resolve_storyboard_references(ParseContext& ctx, Storyboard& storyboard);

}  // namespace corsa::xosc
