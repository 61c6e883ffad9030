// Position and its kinds (OpenSCENARIO 1.3 §6.4).

#include <numbers>

#include "parsers.h"

namespace corsa::xosc {
namespace {

std::optional<Orientation> optional_orientation(ParseContext& ctx, Children& kids) {
  if (const Element* element = kids.opt("Orientation")) {
    return parse_orientation(ctx, element);
  }
  return std::nullopt;
}

WorldPosition parse_world(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "WorldPosition");
  return WorldPosition{ctx.req_double(e, "x"), ctx.req_double(e, "y"), ctx.opt_double(e, "z"),
                       ctx.opt_double(e, "h"), ctx.opt_double(e, "p"), ctx.opt_double(e, "r"),
                       ctx.source(e)};
}

// An offset left out of a relative position is no offset: the entity's own place (esmini's
// clothoid example writes <RelativeObjectPosition entityRef="Car"/>, its traj-heading-trig
// <RelativeRoadPosition entityRef="Car0"/>, for "where the car is"), as dz already is.
double offset_or_zero(ParseContext& ctx, const Element* e, const char* type, const char* axis) {
  if (e->Attribute(axis) == nullptr) {
    ctx.lenient(e, std::string("<") + type + "> without " + axis, std::string(axis) + " 0");
    return 0.0;
  }
  return ctx.req_double(e, axis);
}

template <class T>
T parse_relative_xyz(ParseContext& ctx, const Element* e, const char* type) {
  Children kids(ctx, e, type);
  T position;
  position.entity_ref = ctx.req_str(e, "entityRef");
  ctx.use_entity(e, position.entity_ref, "entityRef");
  position.dx = offset_or_zero(ctx, e, type, "dx");
  position.dy = offset_or_zero(ctx, e, type, "dy");
  position.dz = ctx.opt_double(e, "dz");
  position.orientation = optional_orientation(ctx, kids);
  position.source = ctx.source(e);
  return position;
}

RoadPosition parse_road(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RoadPosition");
  RoadPosition position{ctx.req_str(e, "roadId"), ctx.req_double(e, "s"), ctx.req_double(e, "t"),
                        optional_orientation(ctx, kids), ctx.source(e)};
  ctx.use_road({"RoadPosition", position.road_id, std::nullopt, position.s, position.source});
  return position;
}

RelativeRoadPosition parse_relative_road(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RelativeRoadPosition");
  RelativeRoadPosition position;
  position.entity_ref = ctx.req_str(e, "entityRef");
  position.ds = offset_or_zero(ctx, e, "RelativeRoadPosition", "ds");
  position.dt = offset_or_zero(ctx, e, "RelativeRoadPosition", "dt");
  position.orientation = optional_orientation(ctx, kids);
  position.source = ctx.source(e);
  ctx.use_entity(e, position.entity_ref, "entityRef");
  return position;
}

LanePosition parse_lane(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "LanePosition");
  LanePosition position{ctx.req_str(e, "roadId"),        ctx.req_str(e, "laneId"),
                        ctx.req_double(e, "s"),          ctx.opt_double(e, "offset"),
                        optional_orientation(ctx, kids), ctx.source(e)};
  ctx.use_road({"LanePosition", position.road_id, position.lane_id, position.s, position.source});
  return position;
}

RelativeLanePosition parse_relative_lane(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RelativeLanePosition");
  RelativeLanePosition position;
  position.entity_ref = ctx.req_str(e, "entityRef");
  ctx.use_entity(e, position.entity_ref, "entityRef");
  if (e->Attribute("dLane") == nullptr) {
    ctx.lenient(e, "<RelativeLanePosition> without dLane", "dLane 0");
    position.d_lane = 0;
  } else {
    position.d_lane = static_cast<int>(ctx.req_int(e, "dLane"));
  }
  position.ds = ctx.opt_double(e, "ds");
  position.ds_lane = ctx.opt_double(e, "dsLane");
  if (position.ds && position.ds_lane) {
    ctx.fail(e, "<RelativeLanePosition> takes ds or dsLane, not both");
  }
  if (!position.ds && !position.ds_lane) {
    ctx.lenient(e, "<RelativeLanePosition> without ds or dsLane", "ds 0");
    position.ds = 0.0;
  }
  position.offset = ctx.opt_double(e, "offset");
  position.orientation = optional_orientation(ctx, kids);
  position.source = ctx.source(e);
  return position;
}

RoutePosition parse_route_position(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "RoutePosition");
  RoutePosition position;
  const Element* route_ref = kids.one("RouteRef");
  Children ref_kids(ctx, route_ref, "RouteRef");
  position.route = std::make_shared<const Route>(parse_route_choice(ctx, ref_kids.choice()));
  position.orientation = optional_orientation(ctx, kids);
  const Element* in_route = kids.one("InRoutePosition");
  Children in_kids(ctx, in_route, "InRoutePosition");
  const Element* which = in_kids.choice();
  const std::string_view name = which->Name();
  if (name == "FromCurrentEntity") {
    Children(ctx, which, "PositionOfCurrentEntity");
    PositionOfCurrentEntity current{ctx.req_str(which, "entityRef"), ctx.source(which)};
    ctx.use_entity(which, current.entity_ref, "entityRef");
    position.in_route = current;
  } else if (name == "FromRoadCoordinates") {
    Children(ctx, which, "PositionInRoadCoordinates");
    position.in_route = PositionInRoadCoordinates{ctx.req_double(which, "pathS"),
                                                  ctx.req_double(which, "t"), ctx.source(which)};
  } else {
    Children(ctx, which, "PositionInLaneCoordinates");
    position.in_route =
        PositionInLaneCoordinates{ctx.req_str(which, "laneId"), ctx.opt_double(which, "laneOffset"),
                                  ctx.req_double(which, "pathS"), ctx.source(which)};
  }
  position.source = ctx.source(e);
  return position;
}

GeoPosition parse_geo(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "GeoPosition");
  GeoPosition position;
  position.latitude_deg = ctx.opt_double(e, "latitudeDeg");
  position.longitude_deg = ctx.opt_double(e, "longitudeDeg");
  position.altitude = ctx.opt_double(e, "altitude");
  // 1.0/1.1 gave latitude/longitude in radians and height in metres.
  constexpr double kDegreesPerRadian = 180.0 / std::numbers::pi;
  if (deprecated_attribute(ctx, e, "latitude", {"latitudeDeg"})) {
    position.latitude_deg =
        position.latitude_deg.value_or(*ctx.opt_double(e, "latitude") * kDegreesPerRadian);
  }
  if (deprecated_attribute(ctx, e, "longitude", {"longitudeDeg"})) {
    position.longitude_deg =
        position.longitude_deg.value_or(*ctx.opt_double(e, "longitude") * kDegreesPerRadian);
  }
  if (deprecated_attribute(ctx, e, "height", {"altitude"})) {
    position.altitude = position.altitude.value_or(*ctx.opt_double(e, "height"));
  }
  if (!position.latitude_deg || !position.longitude_deg) {
    ctx.fail(e, "<GeoPosition> needs latitudeDeg and longitudeDeg");
  }
  if (const auto selection = ctx.opt_int(e, "verticalRoadSelection")) {
    position.vertical_road_selection = static_cast<int>(*selection);
  }
  position.orientation = optional_orientation(ctx, kids);
  position.source = ctx.source(e);
  return position;
}

TrajectoryPosition parse_trajectory_position(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TrajectoryPosition");
  TrajectoryPosition position;
  const Element* ref = kids.one("TrajectoryRef");
  Children ref_kids(ctx, ref, "TrajectoryRef");
  position.trajectory =
      std::make_shared<const Trajectory>(parse_trajectory_choice(ctx, ref_kids.choice()));
  position.s = ctx.req_double(e, "s");
  position.t = ctx.opt_double(e, "t");
  position.orientation = optional_orientation(ctx, kids);
  position.source = ctx.source(e);
  return position;
}

}  // namespace

Orientation parse_orientation(ParseContext& ctx, const Element* e) {
  Children(ctx, e, "Orientation");
  return Orientation{ctx.opt_double(e, "h"), ctx.opt_double(e, "p"), ctx.opt_double(e, "r"),
                     ctx.opt_enum<ReferenceContext>(e, "type"), ctx.source(e)};
}

Position parse_position(ParseContext& ctx, const Element* element) {
  Children kids(ctx, element, "Position");
  const Element* e = kids.choice();
  const std::string_view name = e->Name();
  Position position;
  position.source = ctx.source(element);
  if (name == "WorldPosition") {
    position.kind = parse_world(ctx, e);
  } else if (name == "RelativeWorldPosition") {
    position.kind = parse_relative_xyz<RelativeWorldPosition>(ctx, e, "RelativeWorldPosition");
  } else if (name == "RelativeObjectPosition") {
    position.kind = parse_relative_xyz<RelativeObjectPosition>(ctx, e, "RelativeObjectPosition");
  } else if (name == "RoadPosition") {
    position.kind = parse_road(ctx, e);
  } else if (name == "RelativeRoadPosition") {
    position.kind = parse_relative_road(ctx, e);
  } else if (name == "LanePosition") {
    position.kind = parse_lane(ctx, e);
  } else if (name == "RelativeLanePosition") {
    position.kind = parse_relative_lane(ctx, e);
  } else if (name == "RoutePosition") {
    position.kind = parse_route_position(ctx, e);
  } else if (name == "GeoPosition") {
    position.kind = parse_geo(ctx, e);
  } else {
    position.kind = parse_trajectory_position(ctx, e);
  }
  return position;
}

}  // namespace corsa::xosc
