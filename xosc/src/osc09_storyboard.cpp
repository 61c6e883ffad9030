// The 0.9-to-1.0 mapping (osc09_rewriter.h) of the Storyboard: stories, acts and their
// conditions, sequences, events, esmini's EXT_Quit, and the trigger conditions.

#include "osc09_rewriter.h"

namespace corsa::xosc {

void Osc09Rewriter::storyboard(Element* e) {
  storyboard_ = e;
  if (Element* init = e->FirstChildElement("Init")) {
    if (Element* actions = init->FirstChildElement("Actions")) {
      for (Element* g : osc09_children(actions, "Global")) global_action(g);
      for (Element* u : osc09_children(actions, "UserDefined")) user_defined_action(u);
      for (Element* p : osc09_children(actions, "Private")) {
        move_attribute(p, "object", "entityRef");
        for (Element* action : osc09_children(p, "Action")) {
          rename(action, "PrivateAction");
          action->DeleteAttribute("name");
          if (Element* kind = action->FirstChildElement()) private_action(kind);
        }
      }
    }
  }
  for (Element* story : osc09_children(e, "Story")) this->story(story);
  for (Element* end : osc09_children(e, "End")) trigger(end, "StopTrigger");
  // The 0.9.1 schema's name for it (CARLA's scenarios write it; esmini's 0.9 files write End).
  for (Element* end : osc09_children(e, "EndConditions")) trigger(end, "StopTrigger");
}

// 0.9's Story owner is the entity `$owner` names inside the story.
void Osc09Rewriter::story(Element* e) {
  if (const char* owner = e->Attribute("owner")) {
    const std::string name = owner;
    replace_owner(e, name);
    e->DeleteAttribute("owner");
  }
  for (Element* act : osc09_children(e, "Act")) {
    for (Element* sequence : osc09_children(act, "Sequence")) maneuver_group(sequence);
    act_conditions(act);
  }
}

// Conditions holds Start, End and Cancel; 1.0 has a StartTrigger and one StopTrigger. The 0.9
// draft ends an act by its End conditions and cancels it by its Cancel conditions; 1.0 has the
// StopTrigger for both (so AfterTermination rule="end" of an act is read as its complete state,
// state_condition below).
void Osc09Rewriter::act_conditions(Element* act) {
  for (Element* conditions : osc09_children(act, "Conditions")) {
    note("Conditions");
    Element* stop = nullptr;
    for (Element* c : osc09_children(conditions)) {
      const std::string_view name = c->Name();
      if (name == "Start") {
        trigger(c, "StartTrigger");
        act->InsertAfterChild(conditions, c);
      } else if (stop == nullptr) {
        trigger(c, "StopTrigger");
        act->InsertEndChild(c);
        stop = c;
      } else {
        trigger(c, "StopTrigger");
        for (Element* group : osc09_children(c)) stop->InsertEndChild(group);
        conditions->DeleteChild(c);
      }
    }
    act->DeleteChild(conditions);
  }
  // The StopTrigger follows the StartTrigger in 1.0.
  if (Element* stop = act->FirstChildElement("StopTrigger")) act->InsertEndChild(stop);
}

void Osc09Rewriter::replace_owner(Element* e, const std::string& owner) {
  std::vector<std::string> names;
  for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
    if (std::string_view(a->Value()) == "$owner") names.emplace_back(a->Name());
  }
  for (const std::string& name : names) e->SetAttribute(name.c_str(), owner.c_str());
  for (Element* c : osc09_children(e)) replace_owner(c, owner);
}

void Osc09Rewriter::maneuver_group(Element* e) {
  rename(e, "ManeuverGroup");
  move_attribute(e, "numberOfExecutions", "maximumExecutionCount");
  if (Element* actors = e->FirstChildElement("Actors")) this->actors(actors);
  for (Element* maneuver : osc09_children(e, "Maneuver")) {
    const Osc09ScopeGuard scope(*this, maneuver, false);
    for (Element* event : osc09_children(maneuver, "Event")) this->event(maneuver, event);
  }
}

// 0.9 Actors of Entity name elements and a ByCondition actor: 1.0's Actors of EntityRef
// elements, selectTriggeringEntities as ASAM's 0.9.1-to-1.0 migration sets it: true for
// actor="triggeringEntity"; false for "anyEntity", which 1.0 has no word for (the migration calls
// it de-supported), with a warning; false without a ByCondition.
void Osc09Rewriter::actors(Element* e) {
  for (Element* entity : osc09_children(e, "Entity")) {
    rename(entity, "EntityRef");
    move_attribute(entity, "name", "entityRef");
  }
  for (Element* by : osc09_children(e, "ByCondition")) {
    note("ByCondition");
    const std::string actor = value_of(by, "actor").value_or("");
    if (actor == "triggeringEntity") {
      e->SetAttribute("selectTriggeringEntities", "true");
    } else if (actor == "anyEntity") {
      const bool listed = e->FirstChildElement("EntityRef") != nullptr;
      ctx_.lenient(by, "0.9 Actors ByCondition actor=\"anyEntity\" has no 1.0 form",
                   std::string("selectTriggeringEntities=\"false\", as ASAM's 0.9.1-to-1.0 "
                               "migration: ") +
                       (listed ? "the Entity elements listed are the actors"
                               : "no Entity is listed, so the sequence has no actors"));
      e->SetAttribute("selectTriggeringEntities", "false");
    } else {
      ctx_.attribute_error(
          by, "actor",
          "0.9 ByCondition actor '" + clip(actor) + "' is neither triggeringEntity nor anyEntity");
    }
    e->DeleteChild(by);
  }
  default_attribute(e, "selectTriggeringEntities", "false");
}

void Osc09Rewriter::event(Element* maneuver, Element* e) {
  // 0.9's priority "overwrite" is what 1.2 renamed "override". "following" (start once the
  // running event ends) has no 1.0 form: ASAM's 0.9.1-to-1.0 migration empties it.
  if (value_of(e, "priority") == std::optional<std::string>("following")) {
    ctx_.attribute_error(e, "priority",
                         "0.9 Event priority 'following' has no 1.0 form (ASAM's 0.9.1-to-1.0 "
                         "migration removes it; 1.0 has override, skip and parallel)");
  }
  map_value(e, "priority", {{"overwrite", "override"}});
  bool quits = false;
  for (Element* action : osc09_children(e, "Action")) {
    if (Element* p = action->FirstChildElement("Private")) {
      rename(p, "PrivateAction");
      if (Element* kind = p->FirstChildElement()) private_action(kind);
    } else if (Element* g = action->FirstChildElement("Global")) {
      // EXT_Quit ends the simulation, which only a scenario's Storyboard can stand for; in a
      // catalog maneuver it is left for the reader to refuse.
      if (g->FirstChildElement("EXT_Quit") != nullptr && storyboard_ != nullptr) {
        quits = true;
        e->DeleteChild(action);
      } else {
        global_action(g);
      }
    } else if (Element* u = action->FirstChildElement("UserDefined")) {
      user_defined_action(u);
    }
  }
  for (Element* start : osc09_children(e, "StartConditions")) trigger(start, "StartTrigger");
  if (quits) quit_event(maneuver, e);
}

// esmini's EXT_Quit ends the simulation when its event starts. An event of EXT_Quit alone
// gives its start conditions to the Storyboard's StopTrigger; one with other actions keeps
// them, and the StopTrigger waits for the event's start.
void Osc09Rewriter::quit_event(Element* maneuver, Element* event) {
  note("EXT_Quit");
  Element* stop = storyboard_->FirstChildElement("StopTrigger");
  if (stop == nullptr) {
    if (Element* end = storyboard_->FirstChildElement("End")) {
      trigger(end, "StopTrigger");
      stop = end;
    } else {
      stop = new_element("StopTrigger", event);
      storyboard_->InsertEndChild(stop);
    }
  }
  if (event->FirstChildElement("Action") != nullptr) {
    stop->InsertEndChild(started_condition_group(event));
    return;
  }
  if (Element* start = event->FirstChildElement("StartTrigger")) {
    for (Element* group : osc09_children(start, "ConditionGroup")) stop->InsertEndChild(group);
  }
  maneuver->DeleteChild(event);
}

// A ConditionGroup true when `event` starts (a StoryboardElementStateCondition on its name),
// at the event's line.
Element* Osc09Rewriter::started_condition_group(const Element* event) {
  Element* group = new_element("ConditionGroup", event);
  Element* condition = new_element("Condition", event);
  condition->SetAttribute("name", "EXT_Quit");
  condition->SetAttribute("delay", "0");
  condition->SetAttribute("conditionEdge", "none");
  Element* by_value = new_element("ByValueCondition", event);
  Element* state = new_element("StoryboardElementStateCondition", event);
  state->SetAttribute("storyboardElementType", "event");
  const char* name = event->Attribute("name");
  state->SetAttribute("storyboardElementRef", name != nullptr ? name : "");
  state->SetAttribute("state", "startTransition");
  by_value->InsertEndChild(state);
  condition->InsertEndChild(by_value);
  group->InsertEndChild(condition);
  return group;
}

// --- conditions ----------------------------------------------------------------------------------
void Osc09Rewriter::trigger(Element* e, const char* name) {
  rename(e, name);
  for (Element* group : osc09_children(e, "ConditionGroup")) {
    for (Element* condition : osc09_children(group, "Condition")) this->condition(condition);
  }
}

// 0.9's edge "any" is a change either way: esmini's 0.9 reader (OSCCondition::CheckEdge, 2019)
// fires it when the value differs from the last one, 1.0's risingOrFalling. No edge written is
// 1.0's none.
void Osc09Rewriter::condition(Element* e) {
  move_attribute(e, "edge", "conditionEdge");
  default_attribute(e, "conditionEdge", "none");
  map_value(e, "conditionEdge", {{"any", "risingOrFalling"}});
  if (Element* by_value = e->FirstChildElement("ByValue")) {
    rename(by_value, "ByValueCondition");
    for (Element* c : osc09_children(by_value, "SimulationTime")) {
      rename(c, "SimulationTimeCondition");
      rule(c);
    }
    for (Element* c : osc09_children(by_value, "Parameter")) {
      rename(c, "ParameterCondition");
      parameter_ref(c);
      rule(c);
    }
    for (Element* c : osc09_children(by_value, "TimeOfDay")) {
      date_time(c);
      rename(c, "TimeOfDayCondition");
      rule(c);
    }
  } else if (Element* by_state = e->FirstChildElement("ByState")) {
    rename(by_state, "ByValueCondition");
    for (Element* c : osc09_children(by_state)) state_condition(c);
    for (Element* c : osc09_children(by_state)) value_condition(c);
  } else if (Element* by_entity = e->FirstChildElement("ByEntity")) {
    entity_condition(by_entity);
  }
}

// AtStart and AfterTermination: 1.0's StoryboardElementStateCondition.
void Osc09Rewriter::state_condition(Element* e) {
  const std::string_view name = e->Name();
  std::string state;
  if (name == "AtStart") {
    // "has started": an event of the act it names is only looked at once that act runs, after
    // its start transition, so the running state is what holds then, already true when first
    // looked at (which no rising edge follows).
    state = "runningState";
    if (Element* condition = e->Parent()->Parent()->ToElement()) {
      condition->SetAttribute("conditionEdge", "none");
    }
  } else if (name == "AfterTermination") {
    bool unresolved = false;
    const std::string how = value_of(e, "rule", &unresolved).value_or("any");
    const std::string type = value_of(e, "type").value_or("");
    if (unresolved) {
      ctx_.attribute_error(
          e, "rule", "attribute rule: undefined parameter '" + clip(e->Attribute("rule")) + "'");
    } else if (how != "end" && how != "cancel" && how != "any") {
      ctx_.attribute_error(e, "rule",
                           "attribute rule: '" + clip(how) +
                               "' is not a valid 0.9 AfterTermination rule (end, cancel, any)");
    }
    // An act's End conditions end it, which 1.0's StopTrigger does with a stop transition: its
    // "end" is the complete state, reached by either transition (esmini's 0.9 reader, which
    // ignores the rule, fires on the act's end however it came). Other elements end by
    // themselves (endTransition) or are cancelled (stopTransition).
    if (how == "end") {
      state = type == "act" ? "completeState" : "endTransition";
    } else if (how == "cancel") {
      state = "stopTransition";
    } else {
      state = "completeState";
    }
  } else {
    return;
  }
  // The 0.9.1 schema calls a Sequence "scene" here; "sequence" is the element's own name.
  map_value(e, "type", {{"sequence", "maneuverGroup"}, {"scene", "maneuverGroup"}});
  rename(e, "StoryboardElementStateCondition");
  e->DeleteAttribute("rule");
  move_attribute(e, "type", "storyboardElementType");
  move_attribute(e, "name", "storyboardElementRef");
  e->SetAttribute("state", state.c_str());
}

void Osc09Rewriter::entity_condition(Element* e) {
  rename(e, "ByEntityCondition");
  if (Element* triggering = e->FirstChildElement("TriggeringEntities")) {
    move_attribute(triggering, "rule", "triggeringEntitiesRule");
    for (Element* entity : osc09_children(triggering, "Entity")) {
      rename(entity, "EntityRef");
      move_attribute(entity, "name", "entityRef");
    }
  }
  Element* conditions = e->FirstChildElement("EntityCondition");
  if (conditions == nullptr) return;
  for (Element* c : osc09_children(conditions)) entity_condition_kind(c);
}

// One 0.9 EntityCondition, by the 0.9.1 schema's names (checked against VIRES'
// OpenSCENARIO_TypeDefs.xsd, draft 0.9.1, and ASAM's migration0_9_1to1_0.xslt).
void Osc09Rewriter::entity_condition_kind(Element* c) {
  const std::string_view name = c->Name();
  if (name == "RelativeDistance") {
    rename(c, "RelativeDistanceCondition");
    move_attribute(c, "entity", "entityRef");
    map_value(c, "type", {{"inertial", "cartesianDistance"}});
    move_attribute(c, "type", "relativeDistanceType");
    // alongRoute (esmini's files; not in the 0.9.1 schema) ="true": measured in road
    // coordinates, 1.1's coordinateSystem="road"; a parameter is judged by its value.
    if (bool_value(c, "alongRoute").value_or(false)) c->SetAttribute("coordinateSystem", "road");
    c->DeleteAttribute("alongRoute");
    rule(c);
  } else if (name == "TimeHeadway" || name == "RelativeSpeed") {
    rename(c, (std::string(name) + "Condition").c_str());
    move_attribute(c, "entity", "entityRef");
    rule(c);
  } else if (name == "Speed" || name == "Acceleration") {
    rename(c, (std::string(name) + "Condition").c_str());
    rule(c);
  } else if (name == "StandStill" || name == "TraveledDistance" || name == "EndOfRoad" ||
             name == "Offroad") {
    // The same attributes in 1.0 (duration; TraveledDistance's value).
    rename(c, (std::string(name) + "Condition").c_str());
  } else if (name == "ReachPosition" || name == "Distance") {
    // ReachPosition tolerance, Distance value freespace alongRoute rule: as in 1.0.
    rename(c, (std::string(name) + "Condition").c_str());
    for (Element* p : osc09_children(c, "Position")) position(p);
    rule(c);
  } else if (name == "Collision") {
    collision_condition(c);
  } else if (name == "TimeToCollision") {
    time_to_collision_condition(c);
  }
}

// Collision of ByEntity name or ByType type: 1.0's EntityRef entityRef or ByType type.
void Osc09Rewriter::collision_condition(Element* c) {
  rename(c, "CollisionCondition");
  for (Element* by : osc09_children(c, "ByEntity")) {
    rename(by, "EntityRef");
    move_attribute(by, "name", "entityRef");
  }
}

// TimeToCollision value freespace alongRoute rule with a Target of a Position or an Entity name.
void Osc09Rewriter::time_to_collision_condition(Element* c) {
  rename(c, "TimeToCollisionCondition");
  rule(c);
  for (Element* target : osc09_children(c, "Target")) {
    rename(target, "TimeToCollisionConditionTarget");
    for (Element* p : osc09_children(target, "Position")) position(p);
    for (Element* entity : osc09_children(target, "Entity")) {
      rename(entity, "EntityRef");
      move_attribute(entity, "name", "entityRef");
    }
  }
}

// ByState's Command, Signal and Controller, as ASAM's migration reads them: a
// UserDefinedValueCondition that the command was given, a TrafficSignalCondition, a
// TrafficSignalControllerCondition on the controller's phase.
void Osc09Rewriter::value_condition(Element* c) {
  const std::string_view name = c->Name();
  if (name == "Command") {
    rename(c, "UserDefinedValueCondition");
    c->SetAttribute("rule", "equalTo");
    c->SetAttribute("value", "true");
  } else if (name == "Signal") {
    rename(c, "TrafficSignalCondition");
  } else if (name == "Controller") {
    rename(c, "TrafficSignalControllerCondition");
    move_attribute(c, "name", "trafficSignalControllerRef");
    move_attribute(c, "state", "phase");
  }
}

}  // namespace corsa::xosc
