#pragma once

// Helpers shared by the position kinds (position_resolver.cpp, route_path.cpp,
// trajectory_path.cpp): lookups that fail with a located error, and the orientation rules.

#include <cstdint>
#include <optional>
#include <string>

#include "corsa/xodr/map.h"
#include "corsa/xosc/positions.h"
#include "positions/position_resolver.h"
#include "state/entity.h"

namespace corsa::engine::detail {

struct SimState;

[[noreturn]] void fail(const xosc::Source& source, const std::string& message);
/// Whether the run reads positions as esmini does (`--semantics esmini`).
bool esmini_reading(const SimState& state);
const xodr::Map& need_map(const SimState& state, const xosc::Source& source, const char* kind);
/// The named entity; it must exist and have a position already.
const Entity& need_entity(const SimState& state, const std::string& name,
                          const xosc::Source& source);
uint32_t need_road(const xodr::Map& map, const std::string& id, const xosc::Source& source);
/// `s` on road `road`: an s past either end, however far, is read as that end with a
/// lenient-reading warning (the author meant the road's end); an error under --strict.
double checked_s(const SimState& state, const xodr::Map& map, uint32_t road, double s,
                 const xosc::Source& source);
/// checked_s with the strictness and the diagnostics given apart (`corsa validate`'s check).
double checked_s(bool strict, Diagnostics& diagnostics, const xodr::Map& map, uint32_t road,
                 double s, const xosc::Source& source);
/// A lane id: a non-zero integer, or 0 (the centre lane, the reference line) when `allow_center`.
int parse_lane_id(const std::string& text, const xosc::Source& source, bool allow_center = false);
double need_lane_center(const xodr::Map& map, uint32_t road, double s, int lane,
                        const xosc::Source& source);
/// The lane `d` lanes over from `lane`, the centre lane not counted: from lane 1, d = -1 is lane
/// -1 (esmini's lane steps; 1.3's dLane is a difference of lane ids, where it would be lane 0).
/// Lane 0 or d = 0 give lane + d.
int lane_across_centre(int lane, int d);
bool lane_runs_backward(const xodr::Map& map, uint32_t road, double s, int lane);
/// What a relative Orientation turns from: the road's +s direction, or the lane's direction of
/// travel (esmini's reading of LanePosition and RelativeLanePosition, `--semantics esmini`).
enum class OrientationFrame { kRoad, kLane };
/// Orientation of a road-based position: given (type relative: turned from `frame`; otherwise
/// absolute), or by default aligned with the lane's direction of travel.
void orient_on_road(xodr::WorldPose& pose, const std::optional<xosc::Orientation>& orientation,
                    bool backward, OrientationFrame frame = OrientationFrame::kRoad);
/// A position on a road at (s, t), oriented by orient_on_road.
ResolvedPosition on_road(const xodr::Map& map, uint32_t road, double s, double t,
                         std::optional<int> lane,
                         const std::optional<xosc::Orientation>& orientation,
                         OrientationFrame frame = OrientationFrame::kRoad);

}  // namespace corsa::engine::detail
