// The 0.9-to-1.0 mapping (osc09_rewriter.h) of routing: 0.9's Routing actions, Route and
// Trajectory definitions (inline in an action or a RoutePosition, or catalog entries), and an
// axle's maxSteering. Checked against the 0.9.1 schema (VIRES OpenSCENARIO_TypeDefs.xsd, draft
// 0.9.1, as CARLA ships it) and ASAM's migration0_9_1to1_0.xslt.

#include <cstdio>
#include <numbers>

#include "osc09_rewriter.h"

namespace corsa::xosc {

// Routing holds one of FollowRoute (a Route or a CatalogReference), FollowTrajectory and
// AcquirePosition.
void Osc09Rewriter::routing(Element* e) {
  rename(e, "RoutingAction");
  for (Element* follow : osc09_children(e, "FollowRoute")) {
    rename(follow, "AssignRouteAction");
    inline_definitions(follow);
  }
  for (Element* follow : osc09_children(e, "FollowTrajectory")) follow_trajectory(follow);
  for (Element* acquire : osc09_children(e, "AcquirePosition")) {
    rename(acquire, "AcquirePositionAction");
    for (Element* p : osc09_children(acquire, "Position")) position(p);
  }
}

void Osc09Rewriter::inline_definitions(Element* e) {
  for (Element* r : osc09_children(e, "Route")) {
    note("inline Route");
    const Osc09ScopeGuard scope(*this, r, false);
    route(r);
  }
  for (Element* t : osc09_children(e, "Trajectory")) {
    const Osc09ScopeGuard scope(*this, t, false);
    trajectory(t);
  }
}

// 0.9 Route: Waypoint strategy, 1.0's routeStrategy; name and closed as in 1.0.
void Osc09Rewriter::route(Element* e) {
  for (Element* waypoint : osc09_children(e, "Waypoint")) {
    move_attribute(waypoint, "strategy", "routeStrategy");
    for (Element* p : osc09_children(waypoint, "Position")) position(p);
  }
}

// 0.9 Trajectory (name, closed, domain time|distance) of Vertex elements (reference, Position,
// and a Shape of its own: Polyline, Clothoid or Spline); 1.0's Trajectory has one Shape. As
// ASAM's migration does, the vertices become one Polyline, a vertex's reference its time when the
// domain is time (a distance reference has no 1.0 place: no times). The 0.9 shape of each vertex
// goes, which the warning at the Trajectory says (an error under --strict).
void Osc09Rewriter::trajectory(Element* e) {
  const std::vector<Element*> vertices = osc09_children(e, "Vertex");
  if (vertices.empty() || e->FirstChildElement("Shape") != nullptr) return;  // a 1.0 form
  note("Trajectory Vertex");
  const bool timed = value_of(e, "domain").value_or("time") == "time";
  e->DeleteAttribute("domain");
  Element* shape = new_element("Shape", vertices.front());
  Element* polyline = new_element("Polyline", vertices.front());
  shape->InsertEndChild(polyline);
  e->InsertAfterChild(vertices.back(), shape);
  std::string curves;
  for (Element* vertex : vertices) {
    if (Element* own = vertex->FirstChildElement("Shape")) {
      const Element* kind = own->FirstChildElement();
      if (kind != nullptr && std::string_view(kind->Name()) != "Polyline" &&
          curves.find(kind->Name()) == std::string::npos) {
        curves += (curves.empty() ? "" : ", ") + std::string(kind->Name());
      }
      vertex->DeleteChild(own);
    }
    if (timed) {
      move_attribute(vertex, "reference", "time");
    } else {
      vertex->DeleteAttribute("reference");
    }
    for (Element* p : osc09_children(vertex, "Position")) position(p);
    polyline->InsertEndChild(vertex);
  }
  ctx_.lenient(
      e,
      "0.9 Trajectory of " + std::to_string(vertices.size()) +
          " Vertex elements, each with a Shape of its own" +
          (curves.empty() ? std::string() : " (" + curves + " among them)"),
      std::string("a 1.0 Polyline through the vertices, as ASAM's 0.9.1-to-1.0 migration") +
          (timed ? ", each reference its vertex's time" : ", without times (domain distance)"));
}

// 0.9 FollowTrajectory: a Trajectory or CatalogReference, Longitudinal of None or Timing (domain
// scale offset), Lateral purpose (position, steering); 1.0's FollowTrajectoryAction with
// TimeReference (Timing domainAbsoluteRelative) and TrajectoryFollowingMode (followingMode
// position, else follow, as ASAM's migration).
void Osc09Rewriter::follow_trajectory(Element* e) {
  rename(e, "FollowTrajectoryAction");
  inline_definitions(e);
  for (Element* longitudinal : osc09_children(e, "Longitudinal")) {
    rename(longitudinal, "TimeReference");
    for (Element* timing : osc09_children(longitudinal, "Timing")) {
      move_attribute(timing, "domain", "domainAbsoluteRelative");
    }
  }
  for (Element* lateral : osc09_children(e, "Lateral")) {
    rename(lateral, "TrajectoryFollowingMode");
    map_value(lateral, "purpose", {{"steering", "follow"}});
    move_attribute(lateral, "purpose", "followingMode");
  }
}

// The 0.9.1 schema types maxSteering as a bare double; ASAM's migration copies it unchanged into
// 1.0's radians. esmini's 0.9 vehicle catalog wrote 30 where its 1.0 catalog writes 0.5236 (30
// degrees): a value above pi/2 rad (a wheel turned past square) cannot be radians and is read as
// degrees, with a warning at the attribute (an error under --strict).
void Osc09Rewriter::axle(Element* e) {
  const char* raw = e->Attribute("maxSteering");
  if (raw == nullptr || raw[0] == '$') return;  // a parameter's value: as written
  const auto value = double_value(e, "maxSteering");
  if (!value || !(*value > std::numbers::pi / 2)) return;
  const double radians = *value * std::numbers::pi / 180.0;
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", radians);
  ctx_.lenient(attribute_source(e, "maxSteering"),
               "0.9 maxSteering=\"" + clip(e->Attribute("maxSteering")) +
                   "\" is more than pi/2 rad (a wheel turned past square)",
               std::string("degrees: ") + text + " rad");
  e->SetAttribute("maxSteering", text);
}

}  // namespace corsa::xosc
