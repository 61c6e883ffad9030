#pragma once

// Entities (§6.2): scenario objects (Vehicle, Pedestrian, MiscObject, ExternalObjectReference),
// their controllers, and entity selections. Catalog references are expanded on load; the
// `catalog` member says where an expanded object came from.

#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "corsa/xosc/common.h"
#include "corsa/xosc/enums.h"
#include "corsa/xosc/parameters.h"
#include "corsa/xosc/trajectories.h"

namespace corsa::xosc {

/// BoundingBox: centre in the entity's local frame (x forward from the reference point, y left,
/// z up) and its dimensions, metres.
struct BoundingBox {
  double center_x = 0.0;
  double center_y = 0.0;
  double center_z = 0.0;
  double width = 0.0;
  double length = 0.0;
  double height = 0.0;
  Source source;
};

/// Performance: m/s, m/s^2 (deceleration positive), m/s^3 for the rates.
struct Performance {
  double max_speed = 0.0;
  double max_acceleration = 0.0;
  double max_deceleration = 0.0;
  std::optional<double> max_acceleration_rate;
  std::optional<double> max_deceleration_rate;
  Source source;
};

/// Axle: max steering (rad), wheel diameter, track width and position (m, vehicle frame).
struct Axle {
  double max_steering = 0.0;
  double wheel_diameter = 0.0;
  double track_width = 0.0;
  double position_x = 0.0;
  double position_z = 0.0;
  Source source;
};
struct Axles {
  std::optional<Axle> front_axle;
  Axle rear_axle;
  std::vector<Axle> additional_axles;
  Source source;
};

/// TrailerHitch (on the towing vehicle) / TrailerCoupler (on the trailer): dx, dz in metres.
struct TrailerCoupling {
  double dx = 0.0;
  std::optional<double> dz;
  Source source;
};

struct ScenarioObject;

/// Trailer: a trailer object defined inline, or a reference to an entity.
struct Trailer {
  std::shared_ptr<const ScenarioObject> trailer;  ///< set for <Trailer><Trailer ...>
  std::optional<std::string> trailer_ref;         ///< set for <TrailerRef entityRef=...>
  /// False for esmini's <Vehicle> / <CatalogReference> directly in <Trailer> (a lenient
  /// reading): no ScenarioObject names the trailer, and `trailer->name` is the vehicle's.
  bool named_by_file = true;
  Source source;
};

struct Vehicle {
  std::string name;
  VehicleCategory category = VehicleCategory::kCar;
  std::optional<Role> role;
  std::optional<double> mass;  ///< kg
  std::optional<std::string> model3d;
  std::vector<ParameterDeclaration> parameters;
  BoundingBox bounding_box;
  Performance performance;
  Axles axles;
  Properties properties;
  std::optional<TrailerCoupling> trailer_hitch;
  std::optional<TrailerCoupling> trailer_coupler;
  std::optional<Trailer> trailer;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

struct Pedestrian {
  std::string name;
  PedestrianCategory category = PedestrianCategory::kPedestrian;
  double mass = 0.0;                   ///< kg
  std::optional<std::string> model3d;  ///< also the deprecated `model` attribute
  std::optional<Role> role;
  std::vector<ParameterDeclaration> parameters;
  BoundingBox bounding_box;
  Properties properties;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

struct MiscObject {
  std::string name;
  MiscObjectCategory category = MiscObjectCategory::kNone;
  double mass = 0.0;  ///< kg
  std::optional<std::string> model3d;
  std::vector<ParameterDeclaration> parameters;
  BoundingBox bounding_box;
  Properties properties;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

/// ExternalObjectReference (1.2): an object the simulator knows by name (e.g. from the map).
struct ExternalObjectReference {
  std::string name;
  Source source;
};

using EntityObject = std::variant<Vehicle, Pedestrian, MiscObject, ExternalObjectReference>;

struct Controller {
  std::string name;
  std::optional<ControllerType> controller_type;
  std::vector<ParameterDeclaration> parameters;
  Properties properties;
  std::optional<CatalogOrigin> catalog;
  Source source;
};

/// ObjectController: a named controller (inline or expanded from a catalog).
struct ObjectController {
  std::optional<std::string> name;
  Controller controller;
  Source source;
};

struct ScenarioObject {
  std::string name;
  EntityObject object;
  std::vector<ObjectController> controllers;
  Source source;
};

/// ByType selector: every object of a type.
struct ByType {
  ObjectType object_type = ObjectType::kVehicle;
  Source source;
};

/// EntitySelection: a named group of entities (by name, nested selections, or by type).
struct EntitySelection {
  std::string name;
  std::vector<std::string> entity_refs;  ///< members given by EntityRef
  std::vector<ByType> by_type;           ///< members given by ByType
  Source source;
};

struct Entities {
  std::vector<ScenarioObject> objects;
  std::vector<EntitySelection> selections;
  Source source;

  const ScenarioObject* find_object(const std::string& name) const;
  const EntitySelection* find_selection(const std::string& name) const;
};

}  // namespace corsa::xosc
