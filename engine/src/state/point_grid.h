#pragma once

// Points (entity reference points) in a uniform grid of square cells, hashed by cell: "who is
// near (x, y)" in time proportional to the points nearby instead of all of them. Used where
// traffic is placed (spawn points at least a clearance from every entity) and where generated
// traffic looks around itself (controllers/npc_caution.h).

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace corsa::engine::detail {

class PointGrid {
 public:
  /// `cell`: side of a cell (m, > 0); queries reaching a few cells are the cheapest.
  explicit PointGrid(double cell);

  void clear();
  /// Adds point `id` at (x, y) (m). Non-finite coordinates go to one overflow list that every
  /// query returns.
  void add(double x, double y, uint32_t id);
  /// Appends to `out` the ids of every point within `radius` (m) of (x, y) in both axes, and
  /// possibly some beyond (callers test the exact distance); in no particular order.
  void query(double x, double y, double radius, std::vector<uint32_t>& out) const;
  /// Appends to `out` the ids of every point in [x_min, x_max] x [y_min, y_max] (m), and
  /// possibly some beyond; in no particular order.
  void query_box(double x_min, double y_min, double x_max, double y_max,
                 std::vector<uint32_t>& out) const;

 private:
  double cell_;
  std::unordered_map<uint64_t, std::vector<uint32_t>> cells_;
  std::vector<uint32_t> overflow_;
};

}  // namespace corsa::engine::detail
