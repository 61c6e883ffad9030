#include "positions/position_common.h"

#include <algorithm>
#include <cmath>
#include <numbers>

#include "corsa/core/strings.h"
#include "corsa/xodr/lane_graph.h"
#include "geometry/angle.h"
#include "lanes/lane_follow.h"
#include "state/lenient.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

[[noreturn]] void fail(const xosc::Source& source, const std::string& message) {
  throw InputError(source.error(message));
}

bool esmini_reading(const SimState& state) { return state.options.semantics == Semantics::kEsmini; }

const xodr::Map& need_map(const SimState& state, const xosc::Source& source, const char* kind) {
  if (state.map == nullptr) {
    fail(source, std::string(kind) + " needs a road network, but the scenario has no LogicFile");
  }
  return *state.map;
}

const Entity& need_entity(const SimState& state, const std::string& name,
                          const xosc::Source& source) {
  const auto index = state.world.find(name);
  if (!index) {
    fail(source, "unknown entity '" + name + "'");
  }
  const Entity& entity = state.world.entities[*index];
  if (!entity.state().placed) {
    if (!entity.removed) {
      fail(source, "entity '" + name + "' is referenced before it has a position");
    }
    // A deleted entity has no position (§7.5.4 DeleteEntityAction); esmini's add_delete_entity
    // adds an entity again relative to where it was deleted.
    lenient(state, source, "entity '" + name + "' is referenced after it was deleted",
            "the position it was deleted at");
  }
  return entity;
}

uint32_t need_road(const xodr::Map& map, const std::string& id, const xosc::Source& source) {
  const auto road = map.find_road(id);
  if (!road) {
    fail(source, "road '" + id + "' does not exist in the road network");
  }
  return static_cast<uint32_t>(*road);
}

double checked_s(const SimState& state, const xodr::Map& map, uint32_t road, double s,
                 const xosc::Source& source) {
  return checked_s(state.options.strict, state.diagnostics, map, road, s, source);
}

double checked_s(bool strict, Diagnostics& diagnostics, const xodr::Map& map, uint32_t road,
                 double s, const xosc::Source& source) {
  const double length = map.road(road).length;
  if (s >= -1e-9 && s <= length + 1e-9) return std::clamp(s, 0.0, length);
  // An s past the road's end, however far: esmini's ltap-od-relative-speed puts a sync point at
  // s 455 on fabriksgatan's 304 m road 2 (a later version of the file moved it onto a route).
  // Read as the road's end, with the warning that says where; --strict refuses it.
  const std::string where = "s = " + format_double(s) + " is outside road '" + map.road(road).id +
                            "' (length " + format_double(length) + " m)";
  const double end = s < 0.0 ? 0.0 : length;
  lenient(strict, diagnostics, source, where, "s = " + format_double(end) + ", the road's end");
  return end;
}

int parse_lane_id(const std::string& text, const xosc::Source& source, bool allow_center) {
  const auto id = parse_int(text);
  if (!id || (*id == 0 && !allow_center) || *id > 1000 || *id < -1000) {
    fail(source, "laneId '" + text + "' is not a lane id (a non-zero integer)");
  }
  return static_cast<int>(*id);
}

double need_lane_center(const xodr::Map& map, uint32_t road, double s, int lane,
                        const xosc::Source& source) {
  const auto center = lane_center_t(map, road, s, lane);
  if (!center) {
    fail(source, "road '" + map.road(road).id + "' has no lane " + std::to_string(lane) +
                     " at s = " + format_double(s));
  }
  return *center;
}

int lane_across_centre(int lane, int d) {
  int target = lane + d;
  if (lane != 0 && d != 0 && (target == 0 || (target > 0) != (lane > 0))) {
    target += d > 0 ? 1 : -1;
  }
  return target;
}

bool lane_runs_backward(const xodr::Map& map, uint32_t road, double s, int lane) {
  const auto section = static_cast<uint32_t>(map.section_index(road, s));
  const auto node = map.lane_graph().find(xodr::LaneRef{road, section, lane});
  return node && map.lane_graph().info(*node).direction == xodr::TravelDirection::kBackward;
}

void orient_on_road(xodr::WorldPose& pose, const std::optional<xosc::Orientation>& orientation,
                    bool backward, OrientationFrame frame) {
  // Without an Orientation: along the lane's direction of travel, which a lane-frame relative
  // one turns from too.
  if (backward && (!orientation || frame == OrientationFrame::kLane)) {
    pose.h = wrap_angle(pose.h + std::numbers::pi);
    pose.p = -pose.p;
    pose.r = -pose.r;
  }
  if (!orientation) {
    return;
  }
  if (orientation->type == xosc::ReferenceContext::kRelative) {
    pose.h = wrap_angle(pose.h + orientation->h.value_or(0.0));
    pose.p += orientation->p.value_or(0.0);
    pose.r += orientation->r.value_or(0.0);
  } else {
    pose.h = orientation->h.value_or(0.0);
    pose.p = orientation->p.value_or(0.0);
    pose.r = orientation->r.value_or(0.0);
  }
}

ResolvedPosition on_road(const xodr::Map& map, uint32_t road, double s, double t,
                         std::optional<int> lane,
                         const std::optional<xosc::Orientation>& orientation,
                         OrientationFrame frame) {
  ResolvedPosition out;
  out.pose = map.world_pose(road, s, t);
  if (!lane) {
    lane = map.lane_at(road, s, t);
  }
  orient_on_road(out.pose, orientation, lane && lane_runs_backward(map, road, s, *lane), frame);
  out.road = RoadPoint{road, s, t, lane};
  return out;
}

}  // namespace corsa::engine::detail
