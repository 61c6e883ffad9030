// The storyboard (§8.2-8.4): Init, Story, Act, ManeuverGroup, Maneuver, Event, Action.

#include <limits>
#include <set>

#include "parsers.h"

namespace corsa::xosc {
namespace {

// Storyboard element names should be unique among siblings of one parent (§8.1 naming): the
// `::`-qualified references rely on it. Real files repeat them; both elements run, and only a
// reference to the repeated name is an error (references.cpp).
void check_unique(ParseContext& ctx, std::set<std::string>& names, const Element* e,
                  const std::string& name, const char* kind) {
  if (!names.insert(name).second) {
    ctx.lenient(e,
                std::string(kind) + " name '" + clip(name) + "' is used twice in <" +
                    e->Parent()->ToElement()->Name() + ">",
                "two " + std::string(kind) + "s of that name");
  }
}

// maximumExecutionCount is an unsignedInt (§8.4.3 Event, §8.3.2 ManeuverGroup). esmini and
// openPASS document -1 as "any number of times", and their examples write it: read as no limit.
std::optional<uint32_t> execution_count(ParseContext& ctx, const Element* e, bool required) {
  const char* raw = e->Attribute("maximumExecutionCount");
  if (raw != nullptr) {
    const std::optional<std::string> text = ctx.attr(e, "maximumExecutionCount");
    if (text && trim(*text) == "-1") {
      ctx.lenient(e, "maximumExecutionCount -1 is not an unsignedInt", "no limit");
      return std::numeric_limits<uint32_t>::max();
    }
  }
  const std::optional<int64_t> count =
      required ? std::optional<int64_t>(
                     ctx.req_int(e, "maximumExecutionCount", ParameterType::kUnsignedInt))
               : ctx.opt_int(e, "maximumExecutionCount", ParameterType::kUnsignedInt);
  if (!count) return std::nullopt;
  return static_cast<uint32_t>(*count);
}

std::string join(const std::string& parent, const std::string& name) {
  return parent.empty() ? name : parent + "::" + name;
}

Action parse_action(ParseContext& ctx, const Element* e, const std::string& parent) {
  Children kids(ctx, e, "Action");
  Action action;
  if (e->Attribute("name") == nullptr) {
    // name is required (1.0-1.3 XSD); esmini's two_plus_one_road leaves it out of an action
    // nothing refers to. Read as the unnamed Maneuver is: an empty name.
    ctx.lenient(e, "<Action> without name", "an unnamed action nothing can refer to");
  } else {
    action.name = ctx.req_str(e, "name");
  }
  action.path = join(parent, action.name);
  if (e->FirstChildElement() == nullptr) {
    // An Action holds one of the three kinds (§8.4.4). esmini's collision test writes an empty
    // <Action/> in an event that only marks when its trigger fires: an action that does nothing.
    ctx.lenient(e, "<Action> '" + clip(action.name) + "' without an action",
                "an action that does nothing and completes at once");
    action.action = UserDefinedAction{"", "", ctx.source(e)};
    action.source = ctx.source(e);
    return action;
  }
  const Element* a = kids.choice();
  const std::string_view kind = a->Name();
  if (kind == "PrivateAction") {
    action.action = parse_private_action(ctx, a);
  } else if (kind == "GlobalAction") {
    action.action = parse_global_action(ctx, a);
  } else {
    action.action = parse_user_defined_action(ctx, a);
  }
  action.source = ctx.source(e);
  return action;
}

Event parse_event(ParseContext& ctx, const Element* e, const std::string& parent) {
  Children kids(ctx, e, "Event");
  Event event;
  event.name = ctx.req_str(e, "name");
  event.path = join(parent, event.name);
  event.priority = ctx.req_enum<Priority>(e, "priority");
  if (const auto count = execution_count(ctx, e, false)) {
    event.maximum_execution_count = *count;
  }
  std::set<std::string> names;
  for (const Element* action : kids.at_least("Action", 1)) {
    ctx.recover([&] {
      event.actions.push_back(parse_action(ctx, action, event.path));
      check_unique(ctx, names, action, event.actions.back().name, "action");
    });
  }
  if (const Element* start = kids.opt("StartTrigger")) {
    ctx.recover([&] { event.start_trigger = parse_start_trigger(ctx, start); });
  }
  event.source = ctx.source(e);
  return event;
}

// A maneuver's events get their paths once the maneuver's place is known.
void set_paths(Maneuver& maneuver, const std::string& parent) {
  maneuver.path = join(parent, maneuver.name);
  for (auto& event : maneuver.events) {
    event.path = join(maneuver.path, event.name);
    for (auto& action : event.actions) {
      action.path = join(event.path, action.name);
    }
  }
}

void parse_actors(ParseContext& ctx, const Element* e, Actors& actors) {
  Children kids(ctx, e, "Actors");
  actors.select_triggering_entities = ctx.req_bool(e, "selectTriggeringEntities");
  for (const Element* ref : kids.all("EntityRef")) {
    Children(ctx, ref, "EntityRef");
    std::string name = ctx.req_str(ref, "entityRef");
    if (name.empty() && ref->Attribute("entityRef") != nullptr &&
        ref->Attribute("entityRef")[0] == '$') {
      ctx.lenient(ref, "actor entityRef '" + clip(ref->Attribute("entityRef")) + "' is empty",
                  "no actor");
      continue;
    }
    actors.entity_refs.push_back(std::move(name));
    ctx.use_entity(ref, actors.entity_refs.back(), "entityRef");
  }
  actors.source = ctx.source(e);
}

ManeuverGroup parse_maneuver_group(ParseContext& ctx, const Element* e, const std::string& parent) {
  Children kids(ctx, e, "ManeuverGroup");
  ManeuverGroup group;
  group.name = ctx.req_str(e, "name");
  group.path = join(parent, group.name);
  group.maximum_execution_count = *execution_count(ctx, e, true);
  const Element* actors = kids.opt("Actors");
  if (actors == nullptr) {
    // ManeuverGroup: Actors is required (1..1), but it may list no entity at all; esmini's
    // straight_500m_pedestrian leaves it out of a ManeuverGroup that holds nothing, and esmini
    // reads a missing Actors as none. The actions still act on the entities they name.
    ctx.lenient(e, "<ManeuverGroup> '" + clip(group.name) + "' without <Actors>",
                "no actors, selectTriggeringEntities false");
    group.actors.source = ctx.source(e);
  } else {
    parse_actors(ctx, actors, group.actors);
  }
  std::set<std::string> names;
  kids.consume_all();
  // Inline maneuvers and catalog references, in document order.
  for (const Element* child = e->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    const std::string_view kind = child->Name();
    if (kind != "Maneuver" && kind != "CatalogReference") continue;
    ctx.recover([&] {
      if (kind == "Maneuver") {
        group.maneuvers.push_back(parse_maneuver(ctx, child));
      } else {
        group.maneuvers.push_back(expand_catalog_reference<Maneuver>(
            ctx, child, {"Maneuver"}, [&](const Element* entry, CatalogOrigin& origin) {
              Maneuver maneuver =
                  parse_maneuver(ctx, entry, {&origin.assignments, true, "maneuver"});
              maneuver.catalog = origin;
              return maneuver;
            }));
      }
      set_paths(group.maneuvers.back(), group.path);
      check_unique(ctx, names, child, group.maneuvers.back().name, "maneuver");
    });
  }
  group.source = ctx.source(e);
  return group;
}

Act parse_act(ParseContext& ctx, const Element* e, const std::string& parent) {
  Children kids(ctx, e, "Act");
  Act act;
  act.name = ctx.req_str(e, "name");
  act.path = join(parent, act.name);
  std::set<std::string> names;
  if (e->FirstChildElement("ManeuverGroup") == nullptr) {
    // An Act holds 1..n ManeuverGroups (1.0-1.3 XSD); esmini's swarm writes `<Act name="act"/>`,
    // its story only a frame for the swarm its Init starts. An act of no groups has nothing to
    // wait for: it starts with its trigger and completes at once (§8.4.5: an Act ends when all
    // its ManeuverGroups have).
    ctx.lenient(e, "<Act> '" + clip(act.name) + "' without <ManeuverGroup>",
                "an empty act, which completes as soon as it starts");
  }
  for (const Element* group : kids.all("ManeuverGroup")) {
    ctx.recover([&] {
      act.maneuver_groups.push_back(parse_maneuver_group(ctx, group, act.path));
      check_unique(ctx, names, group, act.maneuver_groups.back().name, "maneuver group");
    });
  }
  if (const Element* start = kids.opt("StartTrigger")) {
    ctx.recover([&] { act.start_trigger = parse_start_trigger(ctx, start); });
  }
  if (const Element* stop = kids.opt("StopTrigger")) {
    ctx.recover([&] {
      act.stop_trigger = parse_trigger(ctx, stop);
      if (act.stop_trigger->groups.empty()) act.stop_trigger.reset();  // never fires either way
    });
  }
  act.source = ctx.source(e);
  return act;
}

Story parse_story(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Story");
  Story story;
  story.parameters = open_scope(ctx, kids, {});
  ScopeGuard guard(ctx);
  if (e->Attribute("name") == nullptr) {
    // name is required (1.0-1.3 XSD); esmini's straight_500m_pedestrian leaves it out of its one
    // story, which nothing refers to. Read as the unnamed Maneuver is: an empty name, so its
    // acts' paths are their own names and a second unnamed story is a repeated name.
    ctx.lenient(e, "<Story> without name", "an unnamed story nothing can refer to");
  } else {
    story.name = ctx.req_str(e, "name");
  }
  story.path = story.name;
  std::set<std::string> names;
  if (e->FirstChildElement("Act") == nullptr) {
    // A Story holds 1..n Acts (1.0-1.3 XSD); esmini's source writes an empty story, its traffic
    // coming from the Init's TrafficSourceAction and its end from the Storyboard's StopTrigger. A
    // story of no acts has nothing to wait for: it completes when the storyboard starts.
    ctx.lenient(e, "<Story> '" + clip(story.name) + "' without <Act>",
                "an empty story, which completes at once");
  }
  for (const Element* act : kids.all("Act")) {
    ctx.recover([&] {
      story.acts.push_back(parse_act(ctx, act, story.path));
      check_unique(ctx, names, act, story.acts.back().name, "act");
    });
  }
  story.source = ctx.source(e);
  return story;
}

Init parse_init(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Init");
  Init init;
  init.source = ctx.source(e);
  const Element* actions = kids.one("Actions");
  Children action_kids(ctx, actions, "InitActions");
  for (const Element* global : action_kids.all("GlobalAction")) {
    ctx.recover([&] { init.global_actions.push_back(parse_global_action(ctx, global)); });
  }
  for (const Element* user : action_kids.all("UserDefinedAction")) {
    ctx.recover([&] { init.user_defined_actions.push_back(parse_user_defined_action(ctx, user)); });
  }
  for (const Element* p : action_kids.all("Private")) {
    ctx.recover([&] {
      Children private_kids(ctx, p, "Private");
      InitPrivate entry;
      entry.entity_ref = ctx.req_str(p, "entityRef");
      ctx.use_entity(p, entry.entity_ref, "entityRef");
      for (const Element* action : private_kids.at_least("PrivateAction", 1)) {
        ctx.recover([&] { entry.actions.push_back(parse_private_action(ctx, action, true)); });
        // A 1.0 ControllerAction's override, after its AssignControllerAction.
        if (const Element* override_values = controller_override_pair(action)) {
          ctx.recover(
              [&] { entry.actions.push_back(parse_controller_override(ctx, override_values)); });
        }
      }
      entry.source = ctx.source(p);
      init.privates.push_back(std::move(entry));
    });
  }
  return init;
}

}  // namespace

Maneuver parse_maneuver(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Maneuver");
  Maneuver maneuver;
  maneuver.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  if (e->Attribute("name") == nullptr) {
    // name is required (§8.3.3); esmini's alks_pedestrian leaves it out of the one maneuver it
    // has, which nothing refers to.
    ctx.lenient(e, "<Maneuver> without name", "an unnamed maneuver nothing can refer to");
  } else {
    maneuver.name = ctx.req_str(e, "name");
  }
  std::set<std::string> names;
  for (const Element* event : kids.at_least("Event", 1)) {
    ctx.recover([&] {
      maneuver.events.push_back(parse_event(ctx, event, maneuver.name));
      check_unique(ctx, names, event, maneuver.events.back().name, "event");
    });
  }
  maneuver.source = ctx.source(e);
  set_paths(maneuver, "");
  return maneuver;
}

Storyboard parse_storyboard(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Storyboard");
  Storyboard storyboard;
  ctx.recover([&] { storyboard.init = parse_init(ctx, kids.one("Init")); });
  std::set<std::string> names;
  for (const Element* story : kids.all("Story")) {
    ctx.recover([&] {
      storyboard.stories.push_back(parse_story(ctx, story));
      check_unique(ctx, names, story, storyboard.stories.back().name, "story");
    });
  }
  if (const Element* stop = kids.opt("StopTrigger")) {
    ctx.recover([&] {
      // An empty StopTrigger never fires. Without stories it is kept, so the run goes on until
      // its duration (a run that only moves traffic). With stories it is dropped, so the run
      // ends with its last story: 1.0 required a Storyboard StopTrigger, and `<StopTrigger/>`
      // was how "no stop condition" was written (esmini ends such runs when all acts are done).
      storyboard.stop_trigger = parse_trigger(ctx, stop);
      if (storyboard.stop_trigger->groups.empty() && !storyboard.stories.empty()) {
        storyboard.stop_trigger.reset();
      }
    });
  }
  storyboard.source = ctx.source(e);
  return storyboard;
}

}  // namespace corsa::xosc
