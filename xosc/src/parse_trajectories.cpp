// Routes and trajectories (§6.6, §6.7).

#include "parsers.h"

namespace corsa::xosc {
namespace {

Polyline parse_polyline(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Polyline");
  Polyline polyline;
  polyline.source = ctx.source(e);
  for (const Element* vertex : kids.at_least("Vertex", 2)) {
    Children vertex_kids(ctx, vertex, "Vertex");
    polyline.vertices.push_back({ctx.opt_double(vertex, "time"),
                                 parse_position(ctx, vertex_kids.one("Position")),
                                 ctx.source(vertex)});
  }
  return polyline;
}

Clothoid parse_clothoid(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Clothoid");
  Clothoid clothoid;
  clothoid.curvature = ctx.req_double(e, "curvature");
  clothoid.curvature_prime = ctx.opt_double(e, "curvaturePrime");
  if (deprecated_attribute(ctx, e, "curvatureDot", {"curvaturePrime"})) {
    clothoid.curvature_prime =
        clothoid.curvature_prime.value_or(*ctx.opt_double(e, "curvatureDot"));
  }
  clothoid.length = ctx.req_double(e, "length");
  if (clothoid.length <= 0.0) {
    ctx.fail(e, "Clothoid length must be positive");
  }
  clothoid.start_time = ctx.opt_double(e, "startTime");
  clothoid.stop_time = ctx.opt_double(e, "stopTime");
  clothoid.position = parse_position(ctx, kids.one("Position"));
  clothoid.source = ctx.source(e);
  return clothoid;
}

// A curvature of esmini's draft <Segment>: the 1.3 attribute, else the draft's (curvStart,
// curvEnd); nullopt when neither is written.
std::optional<double> draft_curvature(ParseContext& ctx, const Element* s, const char* name,
                                      const char* draft_name) {
  if (s->Attribute(name) != nullptr) return ctx.req_double(s, name);
  return ctx.opt_double(s, draft_name);
}

// esmini's lane-change_clothoid_spline_based_trajectory writes the segments of a ClothoidSpline
// as <Segment curvStart curvEnd>, the names of the prototype the 1.3 ClothoidSplineSegment
// (curvatureStart, curvatureEnd) came from; esmini reads both. In that prototype a curvature
// left out continues the curve: a start the previous segment's end curvature, an end the
// segment's own start curvature (an arc). Read so, with the curvatures named in the warning.
ClothoidSplineSegment parse_draft_segment(ParseContext& ctx, const Element* s,
                                          const ClothoidSpline& spline) {
  ClothoidSplineSegment segment;
  std::optional<double> start = draft_curvature(ctx, s, "curvatureStart", "curvStart");
  std::optional<double> end = draft_curvature(ctx, s, "curvatureEnd", "curvEnd");
  std::string notes;
  if (!start) {
    if (spline.segments.empty()) {
      ctx.fail(s, "the first <Segment> of a <ClothoidSpline> needs curvStart (curvatureStart)");
    }
    start = spline.segments.back().curvature_end;
    notes += ", curvStart left out: the previous segment's end";
  }
  if (!end) {
    end = *start;
    notes += ", curvEnd left out: its start curvature";
  }
  segment.curvature_start = *start;
  segment.curvature_end = *end;
  ctx.lenient(s, "<Segment> in <ClothoidSpline> (a draft name)",
              "<ClothoidSplineSegment curvatureStart=\"" + format_double(*start) +
                  "\" curvatureEnd=\"" + format_double(*end) + "\">" + notes);
  return segment;
}

ClothoidSpline parse_clothoid_spline(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "ClothoidSpline");
  ClothoidSpline spline;
  spline.time_end = ctx.opt_double(e, "timeEnd");
  kids.consume_all();
  std::vector<const Element*> segments;
  for (const Element* s = e->FirstChildElement(); s != nullptr; s = s->NextSiblingElement()) {
    const std::string_view name = s->Name();
    if (name == "ClothoidSplineSegment" || name == "Segment") segments.push_back(s);
  }
  if (segments.empty()) {
    ctx.fail(e, "<ClothoidSpline> needs at least 1 <ClothoidSplineSegment>");
  }
  for (const Element* s : segments) {
    const bool draft = std::string_view(s->Name()) == "Segment";
    Children segment_kids(ctx, s, draft ? "Segment" : "ClothoidSplineSegment");
    ClothoidSplineSegment segment;
    if (draft) {
      segment = parse_draft_segment(ctx, s, spline);
    } else {
      segment.curvature_start = ctx.req_double(s, "curvatureStart");
      segment.curvature_end = ctx.req_double(s, "curvatureEnd");
    }
    segment.length = ctx.req_double(s, "length");
    segment.h_offset = ctx.opt_double(s, "hOffset");
    segment.time_start = ctx.opt_double(s, "timeStart");
    if (const Element* start = segment_kids.opt("PositionStart")) {
      segment.position_start = parse_position(ctx, start);
    }
    segment.source = ctx.source(s);
    spline.segments.push_back(std::move(segment));
  }
  if (!spline.segments.front().position_start) {
    ctx.run_reading(spline.segments.front().source,
                    "the first ClothoidSplineSegment has no PositionStart",
                    "a start at the entity following it");
  }
  spline.source = ctx.source(e);
  return spline;
}

Nurbs parse_nurbs(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "Nurbs");
  Nurbs nurbs;
  nurbs.order = static_cast<uint32_t>(ctx.req_int(e, "order", ParameterType::kUnsignedInt));
  for (const Element* point : kids.at_least("ControlPoint", 2)) {
    Children point_kids(ctx, point, "ControlPoint");
    nurbs.control_points.push_back({parse_position(ctx, point_kids.one("Position")),
                                    ctx.opt_double(point, "time"), ctx.opt_double(point, "weight"),
                                    ctx.source(point)});
  }
  for (const Element* knot : kids.at_least("Knot", 2)) {
    Children(ctx, knot, "Knot");
    nurbs.knots.push_back(ctx.req_double(knot, "value"));
  }
  // A NURBS of order k over n control points has n + k knots (§6.7.2.4).
  if (nurbs.order < 1 || nurbs.knots.size() != nurbs.control_points.size() + nurbs.order) {
    ctx.fail(e, "Nurbs of order " + std::to_string(nurbs.order) + " with " +
                    std::to_string(nurbs.control_points.size()) + " control points needs " +
                    std::to_string(nurbs.control_points.size() + nurbs.order) + " knots, has " +
                    std::to_string(nurbs.knots.size()));
  }
  for (size_t i = 1; i < nurbs.knots.size(); ++i) {
    if (nurbs.knots[i] < nurbs.knots[i - 1]) {
      ctx.fail(e, "Nurbs knot values must not decrease");
    }
  }
  nurbs.source = ctx.source(e);
  return nurbs;
}

}  // namespace

Route parse_route(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Route");
  Route route;
  route.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  route.name = ctx.req_str(e, "name");
  route.closed = ctx.req_bool(e, "closed");
  for (const Element* waypoint : kids.at_least("Waypoint", 2)) {
    Children waypoint_kids(ctx, waypoint, "Waypoint");
    route.waypoints.push_back({parse_position(ctx, waypoint_kids.one("Position")),
                               ctx.req_enum<RouteStrategy>(waypoint, "routeStrategy"),
                               ctx.source(waypoint)});
  }
  route.source = ctx.source(e);
  return route;
}

Trajectory parse_trajectory(ParseContext& ctx, const Element* e, const EntryScope& scope) {
  Children kids(ctx, e, "Trajectory");
  Trajectory trajectory;
  trajectory.parameters = open_scope(ctx, kids, scope);
  ScopeGuard guard(ctx);
  trajectory.name = ctx.req_str(e, "name");
  trajectory.closed = ctx.req_bool(e, "closed");
  const Element* shape = kids.one("Shape");
  Children shape_kids(ctx, shape, "Shape");
  const Element* kind = shape_kids.choice();
  const std::string_view name = kind->Name();
  if (name == "Polyline") {
    trajectory.shape = parse_polyline(ctx, kind);
  } else if (name == "Clothoid") {
    trajectory.shape = parse_clothoid(ctx, kind);
  } else if (name == "ClothoidSpline") {
    trajectory.shape = parse_clothoid_spline(ctx, kind);
  } else {
    trajectory.shape = parse_nurbs(ctx, kind);
  }
  trajectory.source = ctx.source(e);
  return trajectory;
}

Route parse_route_choice(ParseContext& ctx, const Element* e) {
  if (std::string_view(e->Name()) == "Route") {
    return parse_route(ctx, e);
  }
  return expand_catalog_reference<Route>(
      ctx, e, {"Route"}, [&](const Element* entry, CatalogOrigin& origin) {
        Route route = parse_route(ctx, entry, {&origin.assignments, true, "route"});
        route.catalog = origin;
        return route;
      });
}

Trajectory parse_trajectory_choice(ParseContext& ctx, const Element* e) {
  if (std::string_view(e->Name()) == "Trajectory") {
    return parse_trajectory(ctx, e);
  }
  return expand_catalog_reference<
      Trajectory>(ctx, e, {"Trajectory"}, [&](const Element* entry, CatalogOrigin& origin) {
    Trajectory trajectory = parse_trajectory(ctx, entry, {&origin.assignments, true, "trajectory"});
    trajectory.catalog = origin;
    return trajectory;
  });
}

TimeReference parse_time_reference(ParseContext& ctx, const Element* e) {
  Children kids(ctx, e, "TimeReference");
  TimeReference reference;
  reference.source = ctx.source(e);
  if (e->FirstChildElement() == nullptr) {
    // An empty <TimeReference/> says no more than <None/>: the trajectory is not timed.
    ctx.lenient(e, "<TimeReference> without <None> or <Timing>", "<None/>: the path is not timed");
    return reference;
  }
  const Element* kind = kids.choice();
  if (std::string_view(kind->Name()) == "None") {
    Children(ctx, kind, "None");
    return reference;
  }
  Children(ctx, kind, "Timing");
  reference.timing =
      Timing{ctx.req_enum<ReferenceContext>(kind, "domainAbsoluteRelative"),
             ctx.req_double(kind, "offset"), ctx.req_double(kind, "scale"), ctx.source(kind)};
  return reference;
}

}  // namespace corsa::xosc
