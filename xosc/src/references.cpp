#include "references.h"

#include <algorithm>
#include <set>

namespace corsa::xosc {
namespace {

struct Named {
  StoryboardElementType type;
  std::vector<std::string_view> parts;
  const std::string* path;
  const Source* source;
};

std::vector<std::string_view> split_path(std::string_view path) {
  std::vector<std::string_view> parts;
  size_t start = 0;
  while (true) {
    const size_t end = path.find("::", start);
    parts.push_back(path.substr(start, end == std::string_view::npos ? end : end - start));
    if (end == std::string_view::npos) break;
    start = end + 2;
  }
  return parts;
}

std::vector<Named> collect(const Storyboard& storyboard) {
  std::vector<Named> all;
  auto add = [&](StoryboardElementType type, const std::string& path, const Source& source) {
    all.push_back({type, split_path(path), &path, &source});
  };
  for (const auto& story : storyboard.stories) {
    add(StoryboardElementType::kStory, story.path, story.source);
    for (const auto& act : story.acts) {
      add(StoryboardElementType::kAct, act.path, act.source);
      for (const auto& group : act.maneuver_groups) {
        add(StoryboardElementType::kManeuverGroup, group.path, group.source);
        for (const auto& maneuver : group.maneuvers) {
          add(StoryboardElementType::kManeuver, maneuver.path, maneuver.source);
          for (const auto& event : maneuver.events) {
            add(StoryboardElementType::kEvent, event.path, event.source);
            for (const auto& action : event.actions) {
              add(StoryboardElementType::kAction, action.path, action.source);
            }
          }
        }
      }
    }
  }
  return all;
}

bool ends_with(const std::vector<std::string_view>& path,
               const std::vector<std::string_view>& suffix) {
  if (suffix.size() > path.size()) return false;
  for (size_t i = 0; i < suffix.size(); ++i) {
    if (path[path.size() - suffix.size() + i] != suffix[i]) return false;
  }
  return true;
}

size_t common_prefix(const std::vector<std::string_view>& a,
                     const std::vector<std::string_view>& b) {
  size_t n = 0;
  while (n < a.size() && n < b.size() && a[n] == b[n]) ++n;
  return n;
}

std::string located(const Named& named) {
  return *named.path + " (" + named.source->file_name() + ":" + std::to_string(named.source->line) +
         ")";
}

// Where the condition's storyboardElementRef is written: its own line, also on a later line of
// a tag written over several lines (the tag's line for a condition the loader did not read).
Source reference_source(const ParseContext& ctx, const StoryboardElementStateCondition& condition) {
  const auto it = ctx.storyboard_refs.find(std::tuple(
      condition.source.file.get(), condition.source.line, condition.storyboard_element_ref));
  if (it == ctx.storyboard_refs.end()) return condition.source;
  return Source{condition.source.file, it->second.line()};
}

// `owner` is the path of the element whose trigger holds the condition ("" for the storyboard).
void resolve(ParseContext& ctx, const std::vector<Named>& all, const std::string& owner,
             StoryboardElementStateCondition& condition) {
  const auto wanted = split_path(condition.storyboard_element_ref);
  std::vector<const Named*> matches;
  for (const auto& named : all) {
    if (named.type == condition.type && ends_with(named.parts, wanted)) {
      matches.push_back(&named);
    }
  }
  const std::string kind(to_string(condition.type));
  const Source at = reference_source(ctx, condition);
  if (matches.empty()) {
    ctx.record(
        InputError(at.error("unknown " + kind + " '" + clip(condition.storyboard_element_ref) +
                            "' in StoryboardElementStateCondition")));
    return;
  }
  if (matches.size() > 1) {
    // Names repeat when a maneuver is instantiated twice from a catalog: the element nearest to
    // the condition (sharing the longest enclosing path with it) is the one meant.
    const auto owner_parts = owner.empty() ? std::vector<std::string_view>{} : split_path(owner);
    size_t best = 0;
    for (const Named* named : matches)
      best = std::max(best, common_prefix(named->parts, owner_parts));
    std::vector<const Named*> nearest;
    for (const Named* named : matches) {
      if (common_prefix(named->parts, owner_parts) == best) nearest.push_back(named);
    }
    if (nearest.size() != 1) {
      ctx.record(InputError(at.error("ambiguous " + kind + " reference '" +
                                     clip(condition.storyboard_element_ref) + "' (matches " +
                                     located(*nearest[0]) + " and " + located(*nearest[1]) +
                                     "); qualify it with '::'")));
      return;
    }
    ctx.lenient(at,
                "the " + kind + " name '" + clip(condition.storyboard_element_ref) +
                    "' is not unique (" + std::to_string(matches.size()) + " elements)",
                "the nearest one, " + *nearest[0]->path);
    condition.resolved_path = *nearest[0]->path;
    return;
  }
  condition.resolved_path = *matches[0]->path;
}

void resolve_trigger(ParseContext& ctx, const std::vector<Named>& all, const std::string& owner,
                     std::optional<Trigger>& trigger) {
  if (!trigger) return;
  for (auto& group : trigger->groups) {
    for (auto& condition : group.conditions) {
      if (auto* by_value = std::get_if<ByValueCondition>(&condition.kind)) {
        if (auto* state = std::get_if<StoryboardElementStateCondition>(by_value)) {
          resolve(ctx, all, owner, *state);
        }
      }
    }
  }
}

}  // namespace

void check_entity_references(ParseContext& ctx, const Entities& entities) {
  std::set<std::string_view> names;
  for (const auto& object : entities.objects) names.insert(object.name);
  for (const auto& selection : entities.selections) names.insert(selection.name);
  for (const auto& name : ctx.unreadable_entities) names.insert(name);
  for (const auto& use : ctx.entity_uses()) {
    if (!names.contains(use.name)) {
      ctx.record(
          InputError(use.source.error(use.what + ": unknown entity '" + clip(use.name) + "'")));
    }
  }
}

void resolve_storyboard_references(ParseContext& ctx, Storyboard& storyboard) {
  const std::vector<Named> all = collect(storyboard);
  resolve_trigger(ctx, all, "", storyboard.stop_trigger);
  for (auto& story : storyboard.stories) {
    for (auto& act : story.acts) {
      resolve_trigger(ctx, all, act.path, act.start_trigger);
      resolve_trigger(ctx, all, act.path, act.stop_trigger);
      for (auto& group : act.maneuver_groups) {
        for (auto& maneuver : group.maneuvers) {
          for (auto& event : maneuver.events) {
            resolve_trigger(ctx, all, event.path, event.start_trigger);
          }
        }
      }
    }
  }
}

}  // namespace corsa::xosc
