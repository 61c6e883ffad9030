// Reading OpenSCENARIO 0.9 drafts (FileHeader revMajor="0" revMinor="9"): a pass over the XML
// tree, before the normal reader, that rewrites the 0.9 forms into their 1.0 equivalents
// (ASAM OpenSCENARIO 1.0 migration notes; the 0.9 schema). Renamed elements keep their own line;
// an element the mapping adds (a wrapper such as <TeleportAction>) takes the line of the 0.9
// element it stands for, so that a later error still points at the original text.

#include "osc09_mapping.h"

#include <algorithm>
#include <map>

namespace corsa::xosc {
namespace {

// tinyxml2 has no setter for a node's line; a pointer to the protected member, formed in a
// derived class, reaches it without touching anything else.
struct Osc09LineAccess : tinyxml2::XMLNode {
  static int tinyxml2::XMLNode::*line_member() { return &Osc09LineAccess::_parseLineNum; }
};

std::vector<Element*> osc09_children(Element* parent, const char* name = nullptr) {
  std::vector<Element*> out;
  for (Element* c = parent->FirstChildElement(name); c != nullptr;
       c = c->NextSiblingElement(name)) {
    out.push_back(c);
  }
  return out;
}

class Osc09Rewriter {
 public:
  explicit Osc09Rewriter(tinyxml2::XMLDocument& document) : document_(document) {}

  const std::vector<std::string>& forms() const { return forms_; }

  void document(Element* root) {
    for (Element* e : osc09_children(root)) {
      const std::string_view name = e->Name();
      if (name == "ParameterDeclaration") {
        parameter_declarations(e);
      } else if (name == "Catalogs") {
        catalogs(e);
      } else if (name == "RoadNetwork") {
        road_network(e);
      } else if (name == "Entities") {
        entities(e);
      } else if (name == "Storyboard") {
        storyboard(e);
      }
    }
  }

 private:
  // --- tree edits ------------------------------------------------------------------------------
  void note(const std::string& form) {
    if (std::find(forms_.begin(), forms_.end(), form) == forms_.end()) forms_.push_back(form);
  }
  void rename(Element* e, const char* name) {
    if (std::string_view(e->Name()) == name) return;
    note(e->Name());
    e->SetName(name);
  }
  static void move_attribute(Element* e, const char* from, const char* to) {
    const char* value = e->Attribute(from);
    if (value == nullptr) return;
    const std::string text = value;
    e->DeleteAttribute(from);
    e->SetAttribute(to, text.c_str());
  }
  static void default_attribute(Element* e, const char* name, const char* value) {
    if (e->Attribute(name) == nullptr) e->SetAttribute(name, value);
  }
  // A new element at the line of `line_of`.
  Element* new_element(const char* name, const Element* line_of) {
    Element* e = document_.NewElement(name);
    e->*Osc09LineAccess::line_member() = line_of->GetLineNum();
    return e;
  }
  // Puts `e` inside a new element `name` standing where `e` stood.
  Element* wrap(Element* e, const char* name) {
    Element* wrapper = new_element(name, e);
    e->Parent()->InsertAfterChild(e, wrapper);
    wrapper->InsertEndChild(e);
    return wrapper;
  }
  static void rename_value(Element* e, const char* attribute,
                           const std::map<std::string, std::string>& table) {
    const char* value = e->Attribute(attribute);
    if (value == nullptr) return;
    if (const auto it = table.find(value); it != table.end()) {
      e->SetAttribute(attribute, it->second.c_str());
    }
  }
  static void rule(Element* e) {
    rename_value(
        e, "rule",
        {{"greater_than", "greaterThan"}, {"less_than", "lessThan"}, {"equal_to", "equalTo"}});
  }

  // --- top level -------------------------------------------------------------------------------
  // 0.9 declared `name="$X"` and typed it with `type`; 1.0 declares `name="X"` with
  // `parameterType`, and references stay `$X`.
  void parameter_declarations(Element* e) {
    rename(e, "ParameterDeclarations");
    for (Element* p : osc09_children(e, "Parameter")) {
      rename(p, "ParameterDeclaration");
      move_attribute(p, "type", "parameterType");
      if (const char* name = p->Attribute("name"); name != nullptr && name[0] == '$') {
        const std::string bare = name + 1;
        p->SetAttribute("name", bare.c_str());
      }
    }
  }

  // 0.9 allowed an empty catalog element for "no catalog"; its DriverCatalog became 1.0's
  // ControllerCatalog.
  void catalogs(Element* e) {
    rename(e, "CatalogLocations");
    for (Element* c : osc09_children(e)) {
      if (c->FirstChildElement("Directory") == nullptr) {
        e->DeleteChild(c);
      } else if (std::string_view(c->Name()) == "DriverCatalog") {
        rename(c, "ControllerCatalog");
      }
    }
  }

  void road_network(Element* e) {
    for (Element* c : osc09_children(e, "Logics")) rename(c, "LogicFile");
    for (Element* c : osc09_children(e, "SceneGraph")) rename(c, "SceneGraphFile");
  }

  // esmini's 0.9 files mark a default-controlled entity with the property control="internal",
  // which is what 1.0 means by an entity without an ObjectController.
  void entities(Element* e) {
    for (Element* object : osc09_children(e, "Object")) {
      rename(object, "ScenarioObject");
      for (Element* properties : osc09_children(object, "Properties")) {
        const Element* property = properties->FirstChildElement("Property");
        if (property != nullptr && property->NextSiblingElement() == nullptr &&
            property->Attribute("name", "control") && property->Attribute("value", "internal")) {
          object->DeleteChild(properties);
        }
      }
    }
  }

  // --- storyboard ------------------------------------------------------------------------------
  void storyboard(Element* e) {
    storyboard_ = e;
    if (Element* init = e->FirstChildElement("Init")) {
      if (Element* actions = init->FirstChildElement("Actions")) {
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
  }

  // 0.9's Story owner is the entity `$owner` names inside the story.
  void story(Element* e) {
    if (const char* owner = e->Attribute("owner")) {
      const std::string name = owner;
      replace_owner(e, name);
      e->DeleteAttribute("owner");
    }
    for (Element* act : osc09_children(e, "Act")) {
      for (Element* sequence : osc09_children(act, "Sequence")) maneuver_group(sequence);
      // Conditions holds Start, End and Cancel; 1.0 has StartTrigger and one StopTrigger.
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
  }

  static void replace_owner(Element* e, const std::string& owner) {
    std::vector<std::string> names;
    for (const tinyxml2::XMLAttribute* a = e->FirstAttribute(); a != nullptr; a = a->Next()) {
      if (std::string_view(a->Value()) == "$owner") names.emplace_back(a->Name());
    }
    for (const std::string& name : names) e->SetAttribute(name.c_str(), owner.c_str());
    for (Element* c : osc09_children(e)) replace_owner(c, owner);
  }

  void maneuver_group(Element* e) {
    rename(e, "ManeuverGroup");
    move_attribute(e, "numberOfExecutions", "maximumExecutionCount");
    if (Element* actors = e->FirstChildElement("Actors")) {
      default_attribute(actors, "selectTriggeringEntities", "false");
      for (Element* entity : osc09_children(actors, "Entity")) {
        rename(entity, "EntityRef");
        move_attribute(entity, "name", "entityRef");
      }
    }
    for (Element* maneuver : osc09_children(e, "Maneuver")) {
      for (Element* event : osc09_children(maneuver, "Event")) this->event(maneuver, event);
    }
  }

  void event(Element* maneuver, Element* e) {
    // 0.9's priority "overwrite" is what 1.2 renamed "override".
    rename_value(e, "priority", {{"overwrite", "override"}});
    bool quits = false;
    for (Element* action : osc09_children(e, "Action")) {
      if (Element* p = action->FirstChildElement("Private")) {
        rename(p, "PrivateAction");
        if (Element* kind = p->FirstChildElement()) private_action(kind);
      } else if (Element* g = action->FirstChildElement("Global")) {
        if (g->FirstChildElement("EXT_Quit") != nullptr) {
          quits = true;
          e->DeleteChild(action);
        } else {
          rename(g, "GlobalAction");
        }
      }
    }
    for (Element* start : osc09_children(e, "StartConditions")) trigger(start, "StartTrigger");
    if (quits) quit_event(maneuver, e);
  }

  // esmini's EXT_Quit ends the simulation when its event starts. An event of EXT_Quit alone
  // gives its start conditions to the Storyboard's StopTrigger; one with other actions keeps
  // them, and the StopTrigger waits for the event's start.
  void quit_event(Element* maneuver, Element* event) {
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
  Element* started_condition_group(const Element* event) {
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

  // --- actions ---------------------------------------------------------------------------------
  void private_action(Element* e) {
    const std::string_view name = e->Name();
    if (name == "Position") {
      wrap(e, "TeleportAction");
      position(e);
      note("Position");
    } else if (name == "Longitudinal") {
      rename(e, "LongitudinalAction");
      for (Element* speed : osc09_children(e, "Speed")) speed_action(speed);
    } else if (name == "Lateral") {
      rename(e, "LateralAction");
      for (Element* change : osc09_children(e, "LaneChange")) lane_change_action(change);
    } else if (name == "Routing") {
      rename(e, "RoutingAction");
      for (Element* follow : osc09_children(e, "FollowRoute")) rename(follow, "AssignRouteAction");
    } else if (name == "Meeting") {
      meeting(e);
    } else if (name == "EXT_Synchronize") {
      synchronize(e);
    }
  }

  // 0.9 Dynamics carried the shape and one of time, rate or distance; a step has none.
  void dynamics(Element* e, const char* name) {
    rename(e, name);
    move_attribute(e, "shape", "dynamicsShape");
    for (const char* dimension : {"time", "rate", "distance"}) {
      if (e->Attribute(dimension) != nullptr) {
        move_attribute(e, dimension, "value");
        e->SetAttribute("dynamicsDimension", dimension);
      }
    }
    if (e->Attribute("dynamicsDimension") == nullptr) {
      e->SetAttribute("dynamicsDimension", "time");
      e->SetAttribute("value", "0");
    }
  }

  void speed_action(Element* e) {
    rename(e, "SpeedAction");
    for (Element* d : osc09_children(e, "Dynamics")) dynamics(d, "SpeedActionDynamics");
    for (Element* target : osc09_children(e, "Target")) {
      rename(target, "SpeedActionTarget");
      for (Element* a : osc09_children(target, "Absolute")) rename(a, "AbsoluteTargetSpeed");
      for (Element* r : osc09_children(target, "Relative")) {
        rename(r, "RelativeTargetSpeed");
        move_attribute(r, "object", "entityRef");
        move_attribute(r, "valueType", "speedTargetValueType");
        default_attribute(r, "speedTargetValueType", "delta");
        default_attribute(r, "continuous", "false");
      }
    }
  }

  void lane_change_action(Element* e) {
    rename(e, "LaneChangeAction");
    for (Element* d : osc09_children(e, "Dynamics")) dynamics(d, "LaneChangeActionDynamics");
    for (Element* target : osc09_children(e, "Target")) {
      rename(target, "LaneChangeTarget");
      for (Element* a : osc09_children(target, "Absolute")) rename(a, "AbsoluteTargetLane");
      for (Element* r : osc09_children(target, "Relative")) {
        rename(r, "RelativeTargetLane");
        move_attribute(r, "object", "entityRef");
      }
    }
  }

  // 0.9 Meeting (own Position, Relative master with its Position) is 1.0's SynchronizeAction.
  // A time offset has no 1.0 form: such a Meeting is left for the reader to refuse.
  void meeting(Element* e) {
    Element* relative = e->FirstChildElement("Relative");
    Element* own = e->FirstChildElement("Position");
    // A parameter in offsetTime ($T) is not known here: such a Meeting is left alone too.
    double offset = 0.0;
    const bool offset_zero =
        relative != nullptr &&
        (relative->Attribute("offsetTime") == nullptr ||
         (relative->QueryDoubleAttribute("offsetTime", &offset) == tinyxml2::XML_SUCCESS &&
          offset == 0.0));
    if (relative == nullptr || own == nullptr || !offset_zero) return;
    rename(e, "SynchronizeAction");
    e->DeleteAttribute("mode");
    move_attribute(relative, "object", "masterEntityRef");
    if (const char* master = relative->Attribute("masterEntityRef")) {
      e->SetAttribute("masterEntityRef", master);
    }
    if (Element* master = relative->FirstChildElement("Position")) {
      rename(master, "TargetPositionMaster");
      e->InsertFirstChild(master);
      position(master);
    }
    e->DeleteChild(relative);
    rename(own, "TargetPosition");
    position(own);
  }

  void synchronize(Element* e) {
    rename(e, "SynchronizeAction");
    move_attribute(e, "masterObject", "masterEntityRef");
    for (Element* p : osc09_children(e, "TargetPositionMaster")) position(p);
    for (Element* p : osc09_children(e, "TargetPosition")) position(p);
    for (Element* speed : osc09_children(e, "TargetSpeed")) {
      rename(speed, "FinalSpeed");
      for (Element* a : osc09_children(speed, "Absolute")) rename(a, "AbsoluteSpeed");
      for (Element* r : osc09_children(speed, "RelativeMaster")) {
        rename(r, "RelativeSpeedToMaster");
        move_attribute(r, "valueType", "speedTargetValueType");
      }
    }
  }

  // --- positions -------------------------------------------------------------------------------
  // `e` holds one 0.9 position kind.
  void position(Element* e) {
    Element* kind = e->FirstChildElement();
    if (kind == nullptr) return;
    static const std::map<std::string, std::string> kinds = {
        {"World", "WorldPosition"},
        {"RelativeWorld", "RelativeWorldPosition"},
        {"RelativeObject", "RelativeObjectPosition"},
        {"Road", "RoadPosition"},
        {"RelativeRoad", "RelativeRoadPosition"},
        {"Lane", "LanePosition"},
        {"RelativeLane", "RelativeLanePosition"}};
    const std::string name = kind->Name();
    if (const auto it = kinds.find(name); it != kinds.end()) {
      rename(kind, it->second.c_str());
      move_attribute(kind, "object", "entityRef");
    } else if (name == "Route") {
      rename(kind, "RoutePosition");
      for (Element* in_route : osc09_children(kind, "Position")) {
        rename(in_route, "InRoutePosition");
        for (Element* c : osc09_children(in_route, "LaneCoord")) rename(c, "FromLaneCoordinates");
        for (Element* c : osc09_children(in_route, "RoadCoord")) rename(c, "FromRoadCoordinates");
        for (Element* c : osc09_children(in_route, "Current")) {
          rename(c, "FromCurrentEntity");
          move_attribute(c, "object", "entityRef");
        }
      }
    }
  }

  // --- conditions ------------------------------------------------------------------------------
  void trigger(Element* e, const char* name) {
    rename(e, name);
    for (Element* group : osc09_children(e, "ConditionGroup")) {
      for (Element* condition : osc09_children(group, "Condition")) this->condition(condition);
    }
  }

  void condition(Element* e) {
    move_attribute(e, "edge", "conditionEdge");
    default_attribute(e, "conditionEdge", "none");
    rename_value(e, "conditionEdge", {{"any", "risingOrFalling"}});
    if (Element* by_value = e->FirstChildElement("ByValue")) {
      rename(by_value, "ByValueCondition");
      for (Element* c : osc09_children(by_value, "SimulationTime")) {
        rename(c, "SimulationTimeCondition");
        rule(c);
      }
    } else if (Element* by_state = e->FirstChildElement("ByState")) {
      rename(by_state, "ByValueCondition");
      for (Element* c : osc09_children(by_state)) state_condition(c);
    } else if (Element* by_entity = e->FirstChildElement("ByEntity")) {
      entity_condition(by_entity);
    }
  }

  // AtStart and AfterTermination: 1.0's StoryboardElementStateCondition.
  void state_condition(Element* e) {
    const std::string_view name = e->Name();
    const char* state = nullptr;
    if (name == "AtStart") {
      // "has started": an event of the act it names is only looked at once that act runs, after
      // its start transition, so the running state is what holds then, already true when first
      // looked at (which no rising edge follows).
      state = "runningState";
      if (Element* condition = e->Parent()->Parent()->ToElement()) {
        condition->SetAttribute("conditionEdge", "none");
      }
    } else if (name == "AfterTermination") {
      const std::string_view how = e->Attribute("rule") ? e->Attribute("rule") : "any";
      state = how == "end" ? "endTransition" : how == "cancel" ? "stopTransition" : "completeState";
    } else {
      return;
    }
    rename(e, "StoryboardElementStateCondition");
    e->DeleteAttribute("rule");
    move_attribute(e, "type", "storyboardElementType");
    move_attribute(e, "name", "storyboardElementRef");
    rename_value(e, "storyboardElementType", {{"sequence", "maneuverGroup"}});
    e->SetAttribute("state", state);
  }

  void entity_condition(Element* e) {
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
    for (Element* c : osc09_children(conditions)) {
      const std::string_view name = c->Name();
      if (name == "RelativeDistance") {
        rename(c, "RelativeDistanceCondition");
        move_attribute(c, "entity", "entityRef");
        move_attribute(c, "type", "relativeDistanceType");
        rename_value(c, "relativeDistanceType", {{"inertial", "cartesianDistance"}});
        // alongRoute="true" measured in road coordinates, 1.1's coordinateSystem="road".
        if (c->BoolAttribute("alongRoute", false)) c->SetAttribute("coordinateSystem", "road");
        c->DeleteAttribute("alongRoute");
        rule(c);
      } else if (name == "TimeHeadway") {
        rename(c, "TimeHeadwayCondition");
        move_attribute(c, "entity", "entityRef");
        rule(c);
      }
    }
  }

  tinyxml2::XMLDocument& document_;
  Element* storyboard_ = nullptr;
  std::vector<std::string> forms_;
};

bool says_osc09(const Element* root) {
  const Element* header = root->FirstChildElement("FileHeader");
  return header != nullptr && header->IntAttribute("revMajor", -1) == 0 &&
         header->IntAttribute("revMinor", -1) == 9;
}

}  // namespace

void map_osc09_to_osc10(ParseContext& ctx, tinyxml2::XMLDocument& document) {
  Element* root = document.RootElement();
  if (root == nullptr || !says_osc09(root)) return;
  Osc09Rewriter rewriter(document);
  rewriter.document(root);
  if (rewriter.forms().empty()) return;  // a 0.9 header over 1.0 forms: read as before
  Element* header = root->FirstChildElement("FileHeader");
  std::string forms;
  for (const std::string& form : rewriter.forms()) {
    forms += (forms.empty() ? "" : ", ") + form;
  }
  ctx.lenient(header, "OpenSCENARIO 0.9 draft", "1.0 by the 0.9-to-1.0 mapping: " + forms);
  // The header now says what the document has become, so that it is not warned about twice.
  header->SetAttribute("revMajor", 1);
  header->SetAttribute("revMinor", 0);
}

}  // namespace corsa::xosc
