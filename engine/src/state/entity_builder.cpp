#include "state/entity_builder.h"

#include <type_traits>

#include "corsa/xosc/scenario.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

EntityCategory vehicle_category(xosc::VehicleCategory category) {
  switch (category) {
    case xosc::VehicleCategory::kBicycle:
      return EntityCategory::kBicycle;
    case xosc::VehicleCategory::kBus:
      return EntityCategory::kBus;
    case xosc::VehicleCategory::kCar:
      return EntityCategory::kCar;
    case xosc::VehicleCategory::kMotorbike:
      return EntityCategory::kMotorbike;
    case xosc::VehicleCategory::kSemitrailer:
      return EntityCategory::kSemitrailer;
    case xosc::VehicleCategory::kTrailer:
      return EntityCategory::kTrailer;
    case xosc::VehicleCategory::kTrain:
      return EntityCategory::kTrain;
    case xosc::VehicleCategory::kTram:
      return EntityCategory::kTram;
    case xosc::VehicleCategory::kTruck:
      return EntityCategory::kTruck;
    case xosc::VehicleCategory::kVan:
      return EntityCategory::kVan;
  }
  return EntityCategory::kCar;
}

EntityCategory pedestrian_category(xosc::PedestrianCategory category) {
  switch (category) {
    case xosc::PedestrianCategory::kAnimal:
      return EntityCategory::kAnimal;
    case xosc::PedestrianCategory::kWheelchair:
      return EntityCategory::kWheelchair;
    case xosc::PedestrianCategory::kPedestrian:
      return EntityCategory::kPedestrian;
  }
  return EntityCategory::kPedestrian;
}

Box box_of(const xosc::BoundingBox& box) {
  return Box{box.center_x, box.center_y, box.center_z, box.length, box.width, box.height};
}

}  // namespace

EntityInfo describe_object(const xosc::ScenarioObject& object, Diagnostics& diagnostics) {
  EntityInfo info;
  info.name = object.name;
  std::visit(
      [&](const auto& o) {
        using T = std::decay_t<decltype(o)>;
        if constexpr (std::is_same_v<T, xosc::Vehicle>) {
          info.kind = ObjectKind::kVehicle;
          info.category = vehicle_category(o.category);
          info.model3d = o.model3d.value_or("");
          info.box = box_of(o.bounding_box);
          info.max_speed = o.performance.max_speed;
          info.max_acceleration = o.performance.max_acceleration;
          info.max_deceleration = o.performance.max_deceleration;
          info.max_acceleration_rate = o.performance.max_acceleration_rate.value_or(0.0);
          info.max_deceleration_rate = o.performance.max_deceleration_rate.value_or(0.0);
        } else if constexpr (std::is_same_v<T, xosc::Pedestrian>) {
          info.kind = ObjectKind::kPedestrian;
          info.category = pedestrian_category(o.category);
          info.model3d = o.model3d.value_or("");
          info.box = box_of(o.bounding_box);
        } else if constexpr (std::is_same_v<T, xosc::MiscObject>) {
          info.kind = ObjectKind::kMiscObject;
          info.category = EntityCategory::kObstacle;
          info.model3d = o.model3d.value_or("");
          info.box = box_of(o.bounding_box);
        } else {
          info.kind = ObjectKind::kExternal;
          info.category = EntityCategory::kObstacle;
          diagnostics.add_once("external-object",
                               o.source.warning("ExternalObjectReference '" + o.name +
                                                "' is unknown to this engine: it has no size"));
        }
      },
      object.object);
  return info;
}

ObjectKind object_kind(xosc::ObjectType type) {
  switch (type) {
    case xosc::ObjectType::kVehicle:
      return ObjectKind::kVehicle;
    case xosc::ObjectType::kPedestrian:
      return ObjectKind::kPedestrian;
    case xosc::ObjectType::kMiscellaneous:
      return ObjectKind::kMiscObject;
    case xosc::ObjectType::kExternal:
      return ObjectKind::kExternal;
  }
  return ObjectKind::kVehicle;
}

void build_entities(SimState& state) {
  const auto& objects = state.scenario.entities.objects;
  state.world.entities.reserve(objects.size());
  for (const xosc::ScenarioObject& object : objects) {
    Entity entity(describe_object(object, state.diagnostics));
    entity.object = &object;
    const auto index = static_cast<uint32_t>(state.world.entities.size());
    if (!state.world.by_name.emplace(object.name, index).second) {
      throw InputError(object.source.error("a second entity is called '" + object.name + "'"));
    }
    state.world.entities.push_back(std::move(entity));
  }
  // A trailer defined inside a Vehicle (§6.2.4 Trailer) is an entity of its own, named as its
  // ScenarioObject (or "<tower>_trailer" when that name is taken), connected at Init. esmini's
  // form without a ScenarioObject (a <Vehicle> or <CatalogReference> directly in <Trailer>)
  // names none: such a trailer is "<tower>+", as esmini names it. The loop
  // sees the entities it appends, so a trailer's own trailer is added too.
  for (uint32_t i = 0; i < state.world.entities.size(); ++i) {
    const xosc::ScenarioObject* tower = state.world.entities[i].object;
    const auto* vehicle = tower ? std::get_if<xosc::Vehicle>(&tower->object) : nullptr;
    if (vehicle == nullptr || !vehicle->trailer || !vehicle->trailer->trailer) continue;
    const xosc::ScenarioObject& object = *vehicle->trailer->trailer;
    EntityInfo info = describe_object(object, state.diagnostics);
    if (!vehicle->trailer->named_by_file) {
      info.name = state.world.entities[i].info.name + "+";
    }
    if (state.world.by_name.contains(info.name)) {
      info.name = state.world.entities[i].info.name + "_trailer";
    }
    const auto index = static_cast<uint32_t>(state.world.entities.size());
    if (!state.world.by_name.emplace(info.name, index).second) {
      throw InputError(object.source.error("a second entity is called '" + info.name + "'"));
    }
    Entity trailer(std::move(info));
    trailer.object = &object;
    state.world.entities[i].initial_trailer = index;
    state.world.entities.push_back(std::move(trailer));
  }
}

}  // namespace corsa::engine::detail
