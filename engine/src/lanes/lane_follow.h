#pragma once

// Lane following for the default controller: an entity held on a lane (LaneFollow) moves along
// it in its direction of travel, through lane sections, road links and junction connections
// (OpenDRIVE 1.8 §9.4 lane linkage, §10 junctions), following the lane graph of the map.

#include <cstddef>
#include <optional>
#include <span>
#include <vector>

#include "corsa/xodr/lane_graph.h"
#include "corsa/xodr/map.h"
#include "state/entity.h"

namespace corsa::engine::detail {

/// A lane end joined to another lane of the followed lane's section, at the same s, that the
/// entity takes instead of the ends of its own lane (LaneChooser::redirect).
struct LaneRedirect {
  xodr::LaneEnd end;
  int via_lane = 0;  ///< the lane of the followed section whose end `end` is joined to
};

/// Picks where to continue at a lane end among the joined lane ends. The default picks the
/// straightest; a route (motion/route_chooser.h) picks the one on the route.
class LaneChooser {
 public:
  virtual ~LaneChooser() = default;
  /// Index into `candidates` (never empty).
  virtual size_t choose(const xodr::Map& map, const LaneFollow& lane,
                        std::span<const xodr::LaneEnd> candidates) const = 0;
  /// Where to go on from another lane's end instead of the candidates (none by default).
  virtual std::optional<LaneRedirect> redirect(
      const xodr::Map& /*map*/, const LaneFollow& /*lane*/,
      std::span<const xodr::LaneEnd> /*candidates*/) const {
    return std::nullopt;
  }
};

/// The deterministic default: prefer drivable lanes entered in their own travel direction, then
/// the one whose far end keeps the heading closest to the current one; ties to the first.
size_t choose_straightest(const xodr::Map& map, const LaneFollow& lane,
                          std::span<const xodr::LaneEnd> candidates);

/// `lane` moved `delta` lanes toward higher ids (negative: lower ids), skipping the centre lane 0.
int step_lane_id(int lane, int delta);

/// Heading of travel (rad) for a road at s in direction dir (+1: +s).
double travel_heading(const xodr::Map& map, uint32_t road, double s, int dir);

/// t (m) of the centre of `lane` at road s, or nothing when the section has no such lane.
std::optional<double> lane_center_t(const xodr::Map& map, uint32_t road, double s, int lane);

/// t (m) of the centre of `lane` in the lane section `follow` is in, at follow.s (also at the
/// section's very end, where the map's s lookup would already answer for the next section).
std::optional<double> followed_lane_center_t(const xodr::Map& map, const LaneFollow& follow,
                                             int lane);

/// Holds `follow` on `lane` of `road` at (s, t): direction from `heading` (facing +s or -s),
/// lateral offset from the lane centre. Returns false when the lane does not exist at s.
bool attach_to_lane(const xodr::Map& map, LaneFollow& follow, uint32_t road, double s, double t,
                    int lane, double heading);

struct AdvanceResult {
  double travelled = 0.0;  ///< metres actually moved along the lanes (signed like distance)
  bool hit_end = false;    ///< stopped at a lane end without successor
  bool changed_road = false;
};

/// At a lane end: picks among the joined `ends` (never empty) with `chooser` (or the
/// straightest) and puts `follow` at the start of the chosen lane in its direction of travel.
/// When the chooser redirects it to a neighbouring lane's successor, the lateral offset moves by
/// the distance between the two lanes' centres (LaneFollow::frame_shift), keeping the place.
void enter_next_lane(const xodr::Map& map, LaneFollow& follow, std::span<const xodr::LaneEnd> ends,
                     const LaneChooser* chooser);

/// Moves `follow` by `distance` metres along its lanes (negative: backwards).
AdvanceResult advance_along_lanes(const xodr::Map& map, LaneFollow& follow, double distance,
                                  const LaneChooser* chooser);

/// The world pose and road coordinates of a followed lane position. `spans` is scratch space.
struct LanePose {
  xodr::WorldPose pose;  ///< heading is the direction of travel plus heading_offset
  double t = 0.0;
  std::optional<int> lane_at;  ///< lane containing the point, nothing when outside every lane
};
/// `spans` is left holding every lane's span at follow.s.
LanePose lane_pose(const xodr::Map& map, const LaneFollow& follow,
                   std::vector<xodr::LaneSpan>& spans);

/// The same pose, evaluating the lanes only out to the followed one when the point is strictly
/// inside it (the common case); `scratch` is scratch space, left in no particular state.
LanePose lane_pose_of(const xodr::Map& map, const LaneFollow& follow,
                      std::vector<xodr::LaneSpan>& scratch);

/// t (m) of a followed lane position: the followed lane's centre in its section at follow.s
/// plus the lateral offset in the direction of travel.
double followed_t(const xodr::Map& map, const LaneFollow& follow);

}  // namespace corsa::engine::detail
