#pragma once

// Where the paths through a junction cross or merge, for generated traffic giving way
// (controllers/give_way.h). Worked out once per map from the connecting lanes' centre lines
// (OpenDRIVE 1.8 §10 junctions): where the centre lines of two drivable connecting lanes of one
// junction come within kConflictDistance of each other, each lane has a conflict zone, the
// stretch of its s where the other is that near. Lanes entered from the same lane are not in
// conflict (they diverge; car following keeps them apart).
//
// Each connecting lane also has a right of way: from the signs on its incoming road facing the
// junction (§14: give way 205 or stop 206 lower it, priority road 306 or priority 301 raise it);
// where they say nothing, from the junction's <priority high low> elements (§10, only needed
// where signs do not say): a connecting road named only as high is raised, one named only as
// low lowered.

#include <cstdint>
#include <span>
#include <vector>

#include "corsa/xodr/lane_graph.h"

namespace corsa::xodr {
class Map;
}

namespace corsa::engine::detail {

/// m: centre lines nearer than this are in conflict (two cars 1.8-2 m wide on them would touch
/// or nearly so).
inline constexpr double kConflictDistance = 2.5;

/// One lane's side of a conflict: the stretch [s_min, s_max] (road s, m) of its lane where the
/// other lane's centre line is within kConflictDistance.
struct ConflictZone {
  uint32_t conflict = 0;  ///< index of the conflict (the pair of lanes)
  uint32_t side = 0;      ///< 0 or 1: which of the two lanes this is
  double s_min = 0.0;
  double s_max = 0.0;
};

/// Right of way of a connecting lane: lower goes first.
enum class RightOfWay : uint8_t { kPriority = 0, kNormal = 1, kGiveWay = 2 };

class JunctionConflicts {
 public:
  /// Every junction of `map` (direct and virtual junctions have no connecting lanes to cross).
  static JunctionConflicts build(const xodr::Map& map);

  /// The conflict zones of lane `node`, by s_min (none for lanes outside junctions).
  std::span<const ConflictZone> zones(xodr::LaneNode node) const {
    if (node >= first_.size() - 1) {
      return {};
    }
    return {zones_.data() + first_[node], zones_.data() + first_[node + 1]};
  }
  RightOfWay right_of_way(xodr::LaneNode node) const {
    return node < rights_.size() ? rights_[node] : RightOfWay::kNormal;
  }
  size_t conflict_count() const { return conflicts_; }
  /// The most zones one lane has.
  size_t most_zones() const;

 private:
  std::vector<uint32_t> first_ = {0};  ///< by lane node, into zones_ (one more than nodes)
  std::vector<ConflictZone> zones_;
  std::vector<RightOfWay> rights_;  ///< by lane node
  size_t conflicts_ = 0;
};

}  // namespace corsa::engine::detail
