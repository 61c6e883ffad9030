#include "references.h"

#include <set>

namespace corsa::xosc {
namespace {

struct Named {
  StoryboardElementType type;
  std::vector<std::string_view> parts;
  const std::string* path;
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
  auto add = [&](StoryboardElementType type, const std::string& path) {
    all.push_back({type, split_path(path), &path});
  };
  for (const auto& story : storyboard.stories) {
    add(StoryboardElementType::kStory, story.path);
    for (const auto& act : story.acts) {
      add(StoryboardElementType::kAct, act.path);
      for (const auto& group : act.maneuver_groups) {
        add(StoryboardElementType::kManeuverGroup, group.path);
        for (const auto& maneuver : group.maneuvers) {
          add(StoryboardElementType::kManeuver, maneuver.path);
          for (const auto& event : maneuver.events) {
            add(StoryboardElementType::kEvent, event.path);
            for (const auto& action : event.actions) {
              add(StoryboardElementType::kAction, action.path);
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

void resolve(const std::vector<Named>& all, StoryboardElementStateCondition& condition) {
  const auto wanted = split_path(condition.storyboard_element_ref);
  std::vector<const Named*> matches;
  for (const auto& named : all) {
    if (named.type == condition.type && ends_with(named.parts, wanted)) {
      matches.push_back(&named);
    }
  }
  const std::string kind(to_string(condition.type));
  if (matches.empty()) {
    throw InputError(condition.source.error("unknown " + kind + " '" +
                                            condition.storyboard_element_ref +
                                            "' in StoryboardElementStateCondition"));
  }
  if (matches.size() > 1) {
    throw InputError(condition.source.error(
        "ambiguous " + kind + " reference '" + condition.storyboard_element_ref + "' (matches " +
        *matches[0]->path + " and " + *matches[1]->path + "); qualify it with '::'"));
  }
  condition.resolved_path = *matches[0]->path;
}

void resolve_trigger(const std::vector<Named>& all, std::optional<Trigger>& trigger) {
  if (!trigger) return;
  for (auto& group : trigger->groups) {
    for (auto& condition : group.conditions) {
      if (auto* by_value = std::get_if<ByValueCondition>(&condition.kind)) {
        if (auto* state = std::get_if<StoryboardElementStateCondition>(by_value)) {
          resolve(all, *state);
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
  for (const auto& use : ctx.entity_uses()) {
    if (!names.contains(use.name)) {
      throw InputError(use.source.error(use.what + ": unknown entity '" + use.name + "'"));
    }
  }
}

void resolve_storyboard_references(Storyboard& storyboard) {
  const std::vector<Named> all = collect(storyboard);
  resolve_trigger(all, storyboard.stop_trigger);
  for (auto& story : storyboard.stories) {
    for (auto& act : story.acts) {
      resolve_trigger(all, act.start_trigger);
      resolve_trigger(all, act.stop_trigger);
      for (auto& group : act.maneuver_groups) {
        for (auto& maneuver : group.maneuvers) {
          for (auto& event : maneuver.events) {
            resolve_trigger(all, event.start_trigger);
          }
        }
      }
    }
  }
}

}  // namespace corsa::xosc
