#include "positions/relative_distance.h"

#include <cmath>

#include "corsa/engine/oriented_box.h"
#include "lanes/lane_follow.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {
namespace {

// A target reduced to what the distance needs: its reference point, road coordinates and box.
struct Target {
  double x = 0.0, y = 0.0;
  std::optional<RoadCoordinates> road;
  std::optional<OrientedBox> box;  ///< none for a point
};

// Gap between two extents along an axis: the signed centre distance shrunk by the parts of the
// boxes that reach toward each other; 0 when they overlap along the axis.
double free_gap(double centre_distance, const Interval& a, double a_ref, const Interval* b,
                double b_ref) {
  const double reach_a = centre_distance >= 0.0 ? a.high - a_ref : a_ref - a.low;
  const double reach_b = b == nullptr             ? 0.0
                         : centre_distance >= 0.0 ? b_ref - b->low
                                                  : b->high - b_ref;
  const double gap = std::abs(centre_distance) - reach_a - reach_b;
  return gap <= 0.0 ? 0.0 : std::copysign(gap, centre_distance);
}

double combine(const DistanceSpec& spec, double along, double across) {
  switch (spec.type) {
    case xosc::RelativeDistanceType::kLongitudinal:
      return along;
    case xosc::RelativeDistanceType::kLateral:
      return across;
    case xosc::RelativeDistanceType::kEuclidianDistance:
      return std::hypot(along, across);
  }
  return along;
}

// Components along the axes u (along) and n (across) through `from`, with free-space gaps when
// asked for.
double axis_distance(const Entity& from, const Target& to, const DistanceSpec& spec, double along,
                     double across, double ux, double uy) {
  if (!spec.freespace) {
    return combine(spec, along, across);
  }
  const OrientedBox a = box_of(from.info.box, from.state().pose);
  if (spec.type == xosc::RelativeDistanceType::kEuclidianDistance) {
    return to.box ? box_distance(a, *to.box) : box_point_distance(a, to.x, to.y);
  }
  const double nx = -uy, ny = ux;
  const double a_along = from.state().pose.x * ux + from.state().pose.y * uy;
  const double a_across = from.state().pose.x * nx + from.state().pose.y * ny;
  const double b_along = to.x * ux + to.y * uy;
  const double b_across = to.x * nx + to.y * ny;
  Interval b_u, b_n;
  if (to.box) {
    b_u = project(*to.box, ux, uy);
    b_n = project(*to.box, nx, ny);
  }
  const double gap_along =
      free_gap(along, project(a, ux, uy), a_along, to.box ? &b_u : nullptr, b_along);
  const double gap_across =
      free_gap(across, project(a, nx, ny), a_across, to.box ? &b_n : nullptr, b_across);
  return combine(spec, gap_along, gap_across);
}

double distance_to(const SimState& state, const Entity& from, const Target& to,
                   const DistanceSpec& spec) {
  const Pose& p = from.state().pose;
  const double dx = to.x - p.x;
  const double dy = to.y - p.y;
  switch (spec.system) {
    case xosc::CoordinateSystem::kWorld:
      return axis_distance(from, to, spec, dx, dy, 1.0, 0.0);
    case xosc::CoordinateSystem::kRoad:
    case xosc::CoordinateSystem::kLane:
      if (state.map != nullptr && from.state().road && to.road &&
          from.state().road->road == to.road->road) {
        // Along and across the road, signed by the direction `from` travels in.
        const int dir = from.lane.on_road ? from.lane.dir : 1;
        const double heading =
            travel_heading(*state.map, from.state().road->road, from.state().road->s, dir);
        const double along = (to.road->s - from.state().road->s) * dir;
        const double across = (to.road->t - from.state().road->t) * dir;
        return axis_distance(from, to, spec, along, across, std::cos(heading), std::sin(heading));
      }
      [[fallthrough]];
    case xosc::CoordinateSystem::kEntity:
    case xosc::CoordinateSystem::kTrajectory: {
      const double c = std::cos(p.h), s = std::sin(p.h);
      return axis_distance(from, to, spec, c * dx + s * dy, -s * dx + c * dy, c, s);
    }
  }
  return std::hypot(dx, dy);
}

}  // namespace

void EntityDistanceInputs::take(const Entity& from, const Entity& to) {
  from_ = Party{from.state().pose, from.state().road, from.state_changes()};
  to_ = Party{to.state().pose, to.state().road, to.state_changes()};
  from_on_road_ = from.lane.on_road;
  from_dir_ = from.lane.dir;
  taken_ = true;
}

[[gnu::hot]] bool EntityDistanceInputs::same_as(const Entity& from, const Entity& to) const {
  if (!taken_ || from_on_road_ != from.lane.on_road || from_dir_ != from.lane.dir) {
    return false;
  }
  // Neither state written since: the poses and road coordinates taken.
  if (from_.changes == from.state_changes() && to_.changes == to.state_changes()) {
    return true;
  }
  return (double_bits_diff<0, 6>(from_.pose, from.state().pose) |
          double_bits_diff<0, 6>(to_.pose, to.state().pose)) == 0 &&
         same_bits(from_.road, from.state().road) && same_bits(to_.road, to.state().road);
}

[[gnu::hot]] double entity_distance(const SimState& state, const Entity& from, const Entity& to,
                                    const DistanceSpec& spec) {
  Target target;
  target.x = to.state().pose.x;
  target.y = to.state().pose.y;
  target.road = to.state().road;
  target.box = box_of(to.info.box, to.state().pose);
  return distance_to(state, from, target, spec);
}

double position_distance(const SimState& state, const Entity& from, const ResolvedPosition& to,
                         const DistanceSpec& spec) {
  Target target;
  target.x = to.pose.x;
  target.y = to.pose.y;
  if (to.road) {
    target.road =
        RoadCoordinates{to.road->road, 0, to.road->lane.value_or(0), to.road->s, to.road->t};
  }
  return distance_to(state, from, target, spec);
}

xosc::CoordinateSystem coordinate_system(std::optional<xosc::CoordinateSystem> system,
                                         std::optional<bool> along_route) {
  if (system) {
    return *system;
  }
  return along_route.value_or(false) ? xosc::CoordinateSystem::kRoad
                                     : xosc::CoordinateSystem::kEntity;
}

}  // namespace corsa::engine::detail
