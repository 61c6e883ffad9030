#pragma once

// Lane connectivity of a loaded map: one node per lane of every lane section (centre lanes
// excluded), joined end to end across sections, road links and junction connections
// (OpenDRIVE 1.8 §9.4 lane linkage, §8.2 road linkage, §10 junctions), plus lateral neighbours.
// Built by Map::build; read-only afterwards.

#include <cstdint>
#include <optional>
#include <span>
#include <vector>

#include "corsa/xodr/lane_ref.h"
#include "corsa/xodr/model.h"

namespace corsa::xodr {

using LaneNode = uint32_t;
inline constexpr LaneNode kNoLane = UINT32_MAX;

/// One end of a lane: `at_start` is the end at the section's start s, otherwise its end s.
/// Entering a lane at its start means travelling in +s.
struct LaneEnd {
  LaneNode node = kNoLane;
  bool at_start = true;

  friend bool operator==(const LaneEnd&, const LaneEnd&) = default;
};

/// Direction traffic uses a lane in, relative to road s. Right-hand traffic: right lanes (id < 0)
/// run in +s, left lanes in -s; left-hand traffic the other way round; bidirectional lanes both.
enum class TravelDirection : uint8_t { kForward, kBackward, kBoth };

class LaneGraph {
 public:
  struct NodeInfo {
    LaneRef lane;
    LaneType type = LaneType::kNone;
    TravelDirection direction = TravelDirection::kForward;
    double s_start = 0.0;  ///< road s of the section start
    double s_end = 0.0;    ///< road s of the section end
    double length = 0.0;   ///< length of the lane's centre line (m)
  };

  size_t size() const { return nodes_.size(); }
  const NodeInfo& info(LaneNode node) const { return nodes_[node]; }
  /// The node of a lane, or nothing when there is no such lane.
  std::optional<LaneNode> find(const LaneRef& lane) const;

  /// Lane ends joined to the end (s_end) of `node`: where a car driving +s continues.
  std::span<const LaneEnd> successors(LaneNode node) const { return ends(node, false); }
  /// Lane ends joined to the start (s_start) of `node`: where a car driving -s continues.
  std::span<const LaneEnd> predecessors(LaneNode node) const { return ends(node, true); }
  /// Lane ends joined to one end of `node`.
  std::span<const LaneEnd> ends(LaneNode node, bool at_start) const;
  /// The lateral neighbour in the same section toward +t (left) or -t (right), skipping the
  /// centre lane; kNoLane at the road edge.
  LaneNode left(LaneNode node) const { return left_[node]; }
  LaneNode right(LaneNode node) const { return right_[node]; }
  /// Number of end-to-end joins (each counted once).
  size_t join_count() const { return join_count_; }

 private:
  friend class LaneGraphBuilder;
  std::vector<NodeInfo> nodes_;
  std::vector<uint32_t> road_first_node_;     ///< first node of each road
  std::vector<uint32_t> section_first_node_;  ///< per road section, flattened
  std::vector<uint32_t> road_first_section_;  ///< index into section_first_node_
  std::vector<uint32_t> end_offsets_;         ///< CSR offsets, 2 per node (start, end)
  std::vector<LaneEnd> end_targets_;
  std::vector<LaneNode> left_;
  std::vector<LaneNode> right_;
  size_t join_count_ = 0;
};

}  // namespace corsa::xodr
