// Entities (§6.2): vehicles, pedestrians, misc objects, controllers, selections.

#include <algorithm>
#include <set>

#include "parsers.h"

namespace corsa::xosc {
namespace {

Performance parse_performance(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "Performance");
  Performance performance;
  // All three limits are required (1.0-1.3 XSD); esmini's pedestrian example leaves maxAcceleration
  // out. A missing one is read as 0, the value the engine takes as "no limit given".
  const auto limit = [&](const char* name) {
    if (e->Attribute(name) == nullptr) {
      ctx.lenient(e, std::string("<Performance> has no ") + name, "0, no limit of its own");
      return 0.0;
    }
    return ctx.req_double(e, name);
  };
  performance.max_speed = limit("maxSpeed");
  performance.max_acceleration = limit("maxAcceleration");
  performance.max_deceleration = limit("maxDeceleration");
  performance.max_acceleration_rate = ctx.opt_double(e, "maxAccelerationRate");
  performance.max_deceleration_rate = ctx.opt_double(e, "maxDecelerationRate");
  performance.source = ctx.source(e);
  return performance;
}

Axle parse_axle(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "Axle");
  return Axle{ctx.req_double(e, "maxSteering"), ctx.req_double(e, "wheelDiameter"),
              ctx.req_double(e, "trackWidth"),  ctx.req_double(e, "positionX"),
              ctx.req_double(e, "positionZ"),   ctx.source(e)};
}

Axles parse_axles(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Axles");
  Axles axles;
  if (const Element* front = kids.opt("FrontAxle")) {
    axles.front_axle = parse_axle(ctx, front);
  }
  axles.rear_axle = parse_axle(ctx, kids.one("RearAxle"));
  for (const Element* extra : kids.all("AdditionalAxle")) {
    axles.additional_axles.push_back(parse_axle(ctx, extra));
  }
  axles.source = ctx.source(e);
  return axles;
}

// esmini's full_e6mini writes <Axels> for <Axles>, holding <Axel> elements. Only this misspelling
// is read: its axles told apart by positionX (measured forward from the reference point, Axle):
// the foremost is the FrontAxle, the rearmost the RearAxle, any others AdditionalAxles.
Axles parse_misspelled_axles(ParseContext& ctx, const Element* e) {
  if (e->FirstChildElement("Axel") == nullptr) {
    ctx.lenient(e, "<Axels> is a misspelling of <Axles>", "<Axles>");
    return parse_axles(ctx, e);
  }
  ctx.lenient(e, "<Axels> of <Axel> elements is a misspelling of <Axles>",
              "<Axles>: the foremost <Axel> (largest positionX) its FrontAxle, the rearmost its "
              "RearAxle, any others AdditionalAxles");
  Children kids(ctx, e, "Axels");
  std::vector<Axle> listed;
  for (const Element* axel : kids.all("Axel")) {
    listed.push_back(parse_axle(ctx, axel));
  }
  std::stable_sort(listed.begin(), listed.end(),
                   [](const Axle& a, const Axle& b) { return a.position_x > b.position_x; });
  Axles axles;
  axles.rear_axle = listed.back();
  if (listed.size() > 1) {
    axles.front_axle = listed.front();
    axles.additional_axles.assign(listed.begin() + 1, listed.end() - 1);
  }
  axles.source = ctx.source(e);
  return axles;
}

TrailerCoupling parse_coupling(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "TrailerCoupling");
  return TrailerCoupling{ctx.req_double(e, "dx"), ctx.opt_double(e, "dz"), ctx.source(e)};
}

Properties optional_properties(ParseContext& ctx, Children& kids, const Element* e) {
  if (const Element* properties = kids.opt("Properties")) {
    return parse_properties(ctx, properties);
  }
  Properties none;
  none.source = ctx.source(e);
  return none;
}

void check_dimensions(ParseContext& ctx, const Element* e, const BoundingBox& box) {
  if (box.width < 0.0 || box.length < 0.0 || box.height < 0.0) {
    ctx.fail(e, "BoundingBox dimensions must not be negative");
  }
}

EntitySelection parse_selection(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "EntitySelection");
  EntitySelection selection;
  selection.name = ctx.req_str(e, "name");
  const Element* members = kids.one("Members");
  Children member_kids(ctx, members, "SelectedEntities");
  for (const Element* ref : member_kids.all("EntityRef")) {
    Children(ctx, ref, "EntityRef");
    selection.entity_refs.push_back(ctx.req_str(ref, "entityRef"));
    ctx.use_entity(ref, selection.entity_refs.back(), "entityRef");
  }
  for (const Element* by_type : member_kids.all("ByType")) {
    Children(ctx, by_type, "ByType");
    selection.by_type.push_back(
        {ctx.req_enum<ObjectType>(by_type, "objectType"), ctx.source(by_type)});
  }
  selection.source = ctx.source(e);
  return selection;
}

}  // namespace

BoundingBox parse_bounding_box(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "BoundingBox");
  const Element* center = kids.one("Center");
  const Element* dimensions = kids.one("Dimensions");
  Children(ctx, center, "Center");
  Children(ctx, dimensions, "Dimensions");
  BoundingBox box{ctx.req_double(center, "x"),
                  ctx.req_double(center, "y"),
                  ctx.req_double(center, "z"),
                  ctx.req_double(dimensions, "width"),
                  ctx.req_double(dimensions, "length"),
                  ctx.req_double(dimensions, "height"),
                  ctx.source(e)};
  check_dimensions(ctx, dimensions, box);
  return box;
}

namespace {

// Whether `attribute` of `e` resolves to an empty text (a parameter left empty).
bool empty_reference(ParseContext& ctx, const Element* e, const char* attribute) {
  const auto value = ctx.opt_str(e, attribute);
  return value && value->empty();
}

}  // namespace

// §6.2.4 Trailer: <Trailer> (an inline ScenarioObject) or <TrailerRef entityRef>. esmini's
// catalogs (OpenSCENARIO 1.1, before trailers were standard) write <EntityRef>, a <Vehicle> or a
// <CatalogReference> there instead, often with a parameter left empty to mean "no trailer":
// their meaning is clear, so they are read leniently; the first that names a trailer counts.
std::optional<Trailer> parse_trailer(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Trailer");
  kids.consume_all();
  Trailer value;
  value.source = ctx.source(e);
  for (const Element* which = e->FirstChildElement(); which != nullptr;
       which = which->NextSiblingElement()) {
    const std::string_view kind = which->Name();
    if (kind == "Trailer") {
      value.trailer = std::make_shared<const ScenarioObject>(parse_scenario_object(ctx, which));
      return value;
    }
    if (kind == "TrailerRef" || kind == "EntityRef") {
      Children(ctx, which, "EntityRef");
      if (kind == "EntityRef") {
        ctx.lenient(which, "<EntityRef> in <Trailer> (esmini's form)", "<TrailerRef>");
      }
      const std::string ref = ctx.req_str(which, "entityRef");
      if (ref.empty()) {
        ctx.lenient(which, "the trailer's entityRef is empty", "no trailer");
        continue;
      }
      value.trailer_ref = ref;
      ctx.use_entity(which, ref, "entityRef");
      return value;
    }
    if (kind == "CatalogReference" && empty_reference(ctx, which, "entryName")) {
      ctx.lenient(which, "the trailer's catalog entryName is empty", "no trailer");
      continue;
    }
    if (kind == "Vehicle" || kind == "CatalogReference") {
      ctx.lenient(which, "<" + std::string(kind) + "> directly in <Trailer> (esmini's form)",
                  "<Trailer><Trailer> holding it");
      ScenarioObject object;
      object.object = parse_entity_object(ctx, which);
      object.name = std::visit([](const auto& o) { return o.name; }, object.object);
      object.source = ctx.source(which);
      value.trailer = std::make_shared<const ScenarioObject>(std::move(object));
      value.named_by_file = false;
      return value;
    }
  }
  return std::nullopt;
}

Vehicle parse_vehicle(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Vehicle");
  Vehicle vehicle;
  vehicle.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  vehicle.name = ctx.req_str(e, "name");
  vehicle.category = ctx.req_enum<VehicleCategory>(e, "vehicleCategory");
  vehicle.role = ctx.opt_enum<Role>(e, "role");
  vehicle.mass = ctx.opt_double(e, "mass");
  vehicle.model3d = ctx.opt_str(e, "model3d");
  vehicle.bounding_box = parse_bounding_box(ctx, kids.one("BoundingBox"));
  vehicle.performance = parse_performance(ctx, kids.one("Performance"));
  if (e->FirstChildElement("Axels") != nullptr && e->FirstChildElement("Axles") == nullptr) {
    vehicle.axles = parse_misspelled_axles(ctx, kids.one("Axels"));
  } else {
    vehicle.axles = parse_axles(ctx, kids.one("Axles"));
  }
  vehicle.properties = optional_properties(ctx, kids, e);
  if (const Element* hitch = kids.opt("TrailerHitch")) {
    vehicle.trailer_hitch = parse_coupling(ctx, hitch);
  }
  if (const Element* coupler = kids.opt("TrailerCoupler")) {
    vehicle.trailer_coupler = parse_coupling(ctx, coupler);
  }
  if (const Element* trailer = kids.opt("Trailer")) {
    vehicle.trailer = parse_trailer(ctx, trailer);
  }
  vehicle.source = ctx.source(e);
  return vehicle;
}

Pedestrian parse_pedestrian(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Pedestrian");
  Pedestrian pedestrian;
  pedestrian.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  pedestrian.name = ctx.req_str(e, "name");
  pedestrian.category = ctx.req_enum<PedestrianCategory>(e, "pedestrianCategory");
  pedestrian.mass = ctx.req_double(e, "mass");
  pedestrian.model3d = ctx.opt_str(e, "model3d");
  if (const auto model = ctx.opt_str(e, "model")) {
    ctx.deprecated(e, "attribute Pedestrian.model", "model3d");
    pedestrian.model3d = pedestrian.model3d.value_or(*model);
  }
  pedestrian.role = ctx.opt_enum<Role>(e, "role");
  pedestrian.bounding_box = parse_bounding_box(ctx, kids.one("BoundingBox"));
  pedestrian.properties = optional_properties(ctx, kids, e);
  pedestrian.source = ctx.source(e);
  return pedestrian;
}

MiscObject parse_misc_object(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "MiscObject");
  MiscObject object;
  object.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  object.name = ctx.req_str(e, "name");
  object.category = ctx.req_enum<MiscObjectCategory>(e, "miscObjectCategory");
  object.mass = ctx.req_double(e, "mass");
  object.model3d = ctx.opt_str(e, "model3d");
  object.bounding_box = parse_bounding_box(ctx, kids.one("BoundingBox"));
  object.properties = optional_properties(ctx, kids, e);
  object.source = ctx.source(e);
  return object;
}

Controller parse_controller(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Controller");
  Controller controller;
  controller.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  controller.name = ctx.req_str(e, "name");
  controller.controller_type = ctx.opt_enum<ControllerType>(e, "controllerType");
  controller.properties = optional_properties(ctx, kids, e);
  controller.source = ctx.source(e);
  return controller;
}

// A controller's CatalogReference whose catalog is at hand but lacks the entry (esmini's
// follow_reference names `followReference`, highway_driver `NaturalDriver`, neither in the
// ControllerCatalog its tree holds). A controller is a driver model the engine may lack anyway
// (it then runs the acc controller in its place, docs/engine.md), and the entry's name names
// that model: read as a controller of that name without properties, which the engine runs as
// its model of that name (esmini's NaturalDriver) or as any controller it lacks. A missing entity
// entry stays an error: nothing could stand in for it.
std::optional<Controller> controller_lacking_entry(ParseContext& ctx, const Element* e) {
  if (ctx.catalogs == nullptr) return std::nullopt;
  const std::string catalog_name = ctx.req_str(e, "catalogName");
  const std::string entry_name = ctx.req_str(e, "entryName");
  const std::optional<std::string> file =
      ctx.catalogs->file_lacking_entry(ctx, catalog_name, entry_name);
  if (!file) return std::nullopt;
  Controller controller;
  controller.catalog = parse_catalog_origin(ctx, e);
  controller.name = entry_name;
  controller.source = ctx.source(e);
  ctx.lenient(e,
              "catalog '" + clip(catalog_name) + "' (" + *file + ") has no controller entry '" +
                  clip(entry_name) + "'",
              "a controller '" + clip(entry_name) +
                  "' without properties: the engine's model of that name, or the acc "
                  "controller in its place once activated");
  return controller;
}

Controller parse_controller_choice(ParseContext& ctx, const Element* e) {
  if (std::string_view(e->Name()) == "Controller") {
    return parse_controller(ctx, e);
  }
  if (std::optional<Controller> lacking = controller_lacking_entry(ctx, e)) {
    return std::move(*lacking);
  }
  return expand_catalog_reference<
      Controller>(ctx, e, {"Controller"}, [&](const Element* entry, CatalogOrigin& origin) {
    Controller controller = parse_controller(ctx, entry, {&origin.assignments, true, "controller"});
    controller.catalog = origin;
    return controller;
  });
}

ObjectController parse_object_controller(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ObjectController");
  ObjectController controller;
  controller.name = ctx.opt_str(e, "name");
  controller.controller = parse_controller_choice(ctx, kids.choice());
  controller.source = ctx.source(e);
  return controller;
}

EntityObject parse_entity_object(ParseContext& ctx, const Element* e) {
  const std::string_view name = e->Name();
  if (name == "Vehicle") return parse_vehicle(ctx, e);
  if (name == "Pedestrian") return parse_pedestrian(ctx, e);
  if (name == "MiscObject") return parse_misc_object(ctx, e);
  if (name == "ExternalObjectReference") {
    Children(ctx, e, "ExternalObjectReference");
    return ExternalObjectReference{ctx.req_str(e, "name"), ctx.source(e)};
  }
  return expand_catalog_reference<EntityObject>(
      ctx, e, {"Vehicle", "Pedestrian", "MiscObject"},
      [&](const Element* entry, CatalogOrigin& origin) -> EntityObject {
        const std::string_view kind = entry->Name();
        if (kind == "Vehicle") {
          Vehicle vehicle = parse_vehicle(ctx, entry, {&origin.assignments, true, "vehicle"});
          vehicle.catalog = origin;
          return vehicle;
        }
        if (kind == "Pedestrian") {
          Pedestrian pedestrian =
              parse_pedestrian(ctx, entry, {&origin.assignments, true, "pedestrian"});
          pedestrian.catalog = origin;
          return pedestrian;
        }
        MiscObject object = parse_misc_object(ctx, entry, {&origin.assignments, true, "object"});
        object.catalog = origin;
        return object;
      });
}

ScenarioObject parse_scenario_object(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ScenarioObject");
  ScenarioObject object;
  object.name = ctx.req_str(e, "name");
  kids.consume_all();
  const Element* definition = nullptr;
  const std::string_view kinds[] = {"CatalogReference", "Vehicle", "Pedestrian", "MiscObject",
                                    "ExternalObjectReference"};
  for (const Element* child = e->FirstChildElement(); child != nullptr;
       child = child->NextSiblingElement()) {
    if (std::find(std::begin(kinds), std::end(kinds), child->Name()) == std::end(kinds)) {
      continue;  // ObjectController, or an unknown element (reported)
    }
    if (definition != nullptr) {
      ctx.fail(child, "<ScenarioObject> takes one object definition, found <" +
                          std::string(definition->Name()) + "> and <" + child->Name() + ">");
    }
    definition = child;
  }
  if (definition == nullptr) {
    ctx.fail(e, "<ScenarioObject> '" + object.name +
                    "' needs a Vehicle, Pedestrian, MiscObject, ExternalObjectReference or "
                    "CatalogReference");
  }
  object.object = parse_entity_object(ctx, definition);
  for (const Element* controller : kids.all("ObjectController")) {
    ctx.recover([&] { object.controllers.push_back(parse_object_controller(ctx, controller)); });
  }
  object.source = ctx.source(e);
  return object;
}

Entities parse_entities(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Entities");
  Entities entities;
  entities.source = ctx.source(e);
  std::set<std::string> names;
  // An entity whose definition has errors (a missing catalog, say) is reported and left out;
  // its name stays known, so that its uses do not add errors of their own.
  for (const Element* object : kids.all("ScenarioObject")) {
    const bool read =
        ctx.recover([&] { entities.objects.push_back(parse_scenario_object(ctx, object)); });
    if (!read) {
      if (const char* name = object->Attribute("name")) ctx.unreadable_entities.insert(name);
      continue;
    }
    if (!names.insert(entities.objects.back().name).second) {
      ctx.error(object, "entity name '" + clip(entities.objects.back().name) + "' is used twice");
    }
  }
  for (const Element* selection : kids.all("EntitySelection")) {
    const bool read =
        ctx.recover([&] { entities.selections.push_back(parse_selection(ctx, selection)); });
    if (!read) {
      if (const char* name = selection->Attribute("name")) ctx.unreadable_entities.insert(name);
      continue;
    }
    if (!names.insert(entities.selections.back().name).second) {
      ctx.error(selection,
                "entity name '" + clip(entities.selections.back().name) + "' is used twice");
    }
  }
  return entities;
}

}  // namespace corsa::xosc
