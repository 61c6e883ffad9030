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
/// full path ends with it, and must match exactly one. Sets resolved_path.
void resolve_storyboard_references(Storyboard& storyboard);

}  // namespace corsa::xosc
