#pragma once

// Entities by the lane they are in, each lane's entities in s order: the neighbour structure
// behind car following (who is ahead on the lanes I will drive) and lane-bound neighbour
// queries. Rebuilt from the entities' road coordinates when asked (O(n log n) in entities);
// lanes are lane-graph nodes (xodr/lane_graph.h), so a query for a lane is an array access and a
// binary search.

#include <cstdint>
#include <span>
#include <vector>

#include "corsa/xodr/lane_graph.h"

namespace corsa::engine::detail {

class LaneIndex {
 public:
  /// Empties the index for a map of `nodes` lane-graph nodes (only the lanes used last time are
  /// touched, so a sparse index on a large map costs what it holds).
  void reset(size_t nodes);
  /// Entity `entity` is in lane `node` at road s `s` (m). Call finish() after the last add.
  void add(xodr::LaneNode node, double s, uint32_t entity);
  /// Sorts every lane's entities by (s, entity). An insertion sort (std::sort past a budget of
  /// moves): entities added in the order of the last index (order()) are nearly sorted, as
  /// vehicles seldom pass each other within a lane in a step, and then take about one
  /// comparison each, where a sort of entities added in index order compares them in no
  /// pattern a branch predictor learns.
  void finish();
  /// Appends to `out` the entities of the index, lane after lane, each lane's in s order.
  void order(std::vector<uint32_t>& out) const;

  struct Entry {
    double s = 0.0;  ///< m, road s
    uint32_t entity = 0;
  };

  /// Appends to `out` the entities in lane `node` with s in [s_low, s_high] (m), in s order.
  void query(xodr::LaneNode node, double s_low, double s_high, std::vector<uint32_t>& out) const;
  /// The entities in lane `node`, by (s, entity); empty for a lane without any.
  std::span<const Entry> lane(xodr::LaneNode node) const;

  /// Entities in the index.
  size_t size() const { return size_; }

 private:
  std::vector<std::vector<Entry>> lanes_;  ///< by lane-graph node
  std::vector<xodr::LaneNode> used_;       ///< nodes with entries
  size_t size_ = 0;
};

}  // namespace corsa::engine::detail
