#pragma once

// Internal: the pass that rewrites an OpenSCENARIO 0.9 draft's XML tree into its 1.0 forms
// (osc09_mapping.h says when it runs). One class, its parts by subject: osc09_mapping.cpp (the
// document, parameters, entities, catalogs), osc09_storyboard.cpp (storyboard and conditions),
// osc09_actions.cpp (actions, dynamics, positions), osc09_routing.cpp (routes, trajectories),
// osc09_global.cpp (global and user-defined actions), osc09_traffic.cpp (selections, traffic and
// signals).

#include <tinyxml2.h>

#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "parse_context.h"

namespace corsa::xosc {

std::vector<Element*> osc09_children(Element* parent, const char* name = nullptr);

class Osc09Rewriter {
 public:
  Osc09Rewriter(ParseContext& ctx, tinyxml2::XMLDocument& document);

  /// The 0.9 element names translated, in the order first met.
  const std::vector<std::string>& forms() const { return forms_; }

  /// A scenario document (FileHeader, ParameterDeclaration, ..., Storyboard).
  void scenario(Element* root);
  /// A catalog document (FileHeader, Catalog of entries).
  void catalog(Element* catalog);

 private:
  using ValueTable = std::map<std::string, std::string, std::less<>>;

  // --- tree edits (osc09_mapping.cpp) ----------------------------------------------------------
  void note(const std::string& form);
  void rename(Element* e, const char* name);
  static void move_attribute(Element* e, const char* from, const char* to);
  static void parameter_ref(Element* e);
  static void default_attribute(Element* e, const char* name, const char* value);
  Element* new_element(const char* name, const Element* line_of);
  Element* wrap(Element* e, const char* name);
  Source attribute_source(const Element* e, const char* attribute) const;

  // --- parameter values (osc09_mapping.cpp) ----------------------------------------------------
  // The mapping judges some attribute values (a rule, an edge, alongRoute). A value written as
  // a `$reference` is judged by the value it stands for: the visible declaration, or the value
  // given from outside (LoadOptions::parameters). Parameters are scoped as the reader scopes
  // them: the document's, a Maneuver's inside them, and a catalog entry's alone (the scenario's
  // globals behind it); a declaration that uses its own name means the outer parameter.
  struct Osc09Parameter {
    std::string value;
    /// Its ParameterDeclaration; null when the value was given from outside.
    Element* declaration = nullptr;
  };
  struct Osc09Scope {
    std::map<std::string, Osc09Parameter, std::less<>> parameters;
    bool isolated = false;  ///< a catalog entry's: the outer scopes but the globals are hidden
  };
  /// The scope of one element's ParameterDeclaration children, open for the guard's lifetime.
  class Osc09ScopeGuard {
   public:
    Osc09ScopeGuard(Osc09Rewriter& rewriter, Element* owner, bool isolated);
    Osc09ScopeGuard(const Osc09ScopeGuard&) = delete;
    Osc09ScopeGuard& operator=(const Osc09ScopeGuard&) = delete;
    ~Osc09ScopeGuard() { rewriter_.scopes_.pop_back(); }

   private:
    Osc09Rewriter& rewriter_;
  };
  void parameter_declarations(Element* e);
  /// The parameter `name` visible from scope `upto - 1` outwards (its scope's index in
  /// `found_in`); null when none is.
  Osc09Parameter* find_parameter(std::string_view name, size_t upto, size_t* found_in);
  /// The parameter holding the plain value that the reference `raw` (`$name`) stands for,
  /// following references held in values; null when a reference in the chain names no visible
  /// parameter or the chain is a cycle.
  Osc09Parameter* referenced_parameter(std::string_view raw);
  /// The value of `attribute` with a `$name` reference resolved; nullopt when the attribute is
  /// absent or its reference names no declared parameter (`unresolved` set then).
  std::optional<std::string> value_of(const Element* e, const char* attribute,
                                      bool* unresolved = nullptr);
  /// Rewrites a 0.9 word of `table` in `attribute` to its 1.0 word. A reference to a parameter
  /// holding such a word stays, and the parameter's declaration gets the 1.0 word (so that a
  /// catalog reference's assignment still replaces it), with a warning at the attribute; a
  /// value given from outside, which no declaration holds, replaces the reference instead.
  void map_value(Element* e, const char* attribute, const ValueTable& table);
  /// A boolean attribute of the 0.9 form judged here (alongRoute); nullopt when absent or in
  /// error (recorded at the attribute).
  std::optional<bool> bool_value(Element* e, const char* attribute);
  /// A double judged here (Meeting offsetTime); nullopt when absent, not a number or an
  /// unresolved reference.
  std::optional<double> double_value(const Element* e, const char* attribute);
  /// The 0.9 words of a rule attribute and their 1.0 words.
  static const ValueTable& rule_words();
  void rule(Element* e);

  // --- document parts (osc09_mapping.cpp) ------------------------------------------------------
  void catalog_locations(Element* e);
  void road_network(Element* e);
  void entities(Element* e);
  void catalog_references(Element* e);
  void entity_body(Element* entry);
  void vehicle(Element* e);
  void bounding_box(Element* e);

  // --- storyboard and conditions (osc09_storyboard.cpp) ----------------------------------------
  void storyboard(Element* e);
  void story(Element* e);
  void act_conditions(Element* act);
  static void replace_owner(Element* e, const std::string& owner);
  void maneuver_group(Element* e);
  void actors(Element* e);
  void event(Element* maneuver, Element* e);
  void quit_event(Element* maneuver, Element* event);
  Element* started_condition_group(const Element* event);
  void trigger(Element* e, const char* name);
  void condition(Element* e);
  void state_condition(Element* e);
  void entity_condition(Element* e);
  void entity_condition_kind(Element* c);
  void collision_condition(Element* c);
  void time_to_collision_condition(Element* c);
  void value_condition(Element* c);

  // --- actions and positions (osc09_actions.cpp) -----------------------------------------------
  void private_action(Element* e);
  void longitudinal_action(Element* e);
  void lateral_action(Element* e);
  void distance_action(Element* e, const char* name);
  void lane_offset_action(Element* e);
  void autonomous(Element* e);
  void controller_action(Element* e);
  /// The Driver or PedestrianController children of `e`: 1.0 Controllers.
  void controllers(Element* e);
  void dynamics(Element* e, const char* name, const std::vector<const char*>& precedence);
  void speed_action(Element* e);
  void lane_change_action(Element* e);
  /// The 0.9 Target children of `e` (Absolute value, Relative object value) as 1.0's `name` of
  /// `absolute` or `relative entityRef`; the targets.
  std::vector<Element*> targets(Element* e, const char* name, const char* absolute,
                                const char* relative);
  void meeting(Element* e);
  void synchronize(Element* e);
  void position(Element* e);

  // --- routes and trajectories (osc09_routing.cpp) --------------------------------------------
  void routing(Element* e);
  /// A Route (inline or a catalog entry; its ParameterDeclaration in the caller's scope).
  void route(Element* e);
  /// A Trajectory (inline or a catalog entry; its ParameterDeclaration in the caller's scope).
  void trajectory(Element* e);
  void follow_trajectory(Element* e);
  /// The Route or Trajectory child of `e`, in a parameter scope of its own.
  void inline_definitions(Element* e);
  /// 0.9 maxSteering of an axle: degrees where radians cannot be meant.
  void axle(Element* e);

  // --- selections, traffic and signals (osc09_traffic.cpp) ------------------------------------
  void selection(Element* e);
  void signals(Element* e);
  void infrastructure_action(Element* e);
  void traffic_action(Element* e);
  void traffic_definition(Element* e);

  // --- global actions (osc09_global.cpp) -------------------------------------------------------
  void global_action(Element* e);
  void environment(Element* e);
  void entity_action(Element* e);
  void parameter_action(Element* e);
  /// 0.9 UserDefined: a Command is 1.0's CustomCommandAction; a Script has no 1.0 form.
  void user_defined_action(Element* e);
  /// A 0.9 Time (hour min sec) and Date (day month year) under `e` as 1.0's dateTime attribute;
  /// false (left as written, for the reader to refuse) when they are not plain numbers.
  bool date_time(Element* e);

  ParseContext& ctx_;
  tinyxml2::XMLDocument& document_;
  Element* storyboard_ = nullptr;
  std::vector<std::string> forms_;
  /// The open parameter scopes, outermost first.
  std::vector<Osc09Scope> scopes_;
};

}  // namespace corsa::xosc
