#include "pose_table.h"

#include <algorithm>
#include <cmath>

namespace corsa::xodr::detail {
namespace {

bool positive_zero(double value) { return value == 0.0 && !std::signbit(value); }

// Whether every record evaluates to +0 wherever |s| <= PoseTable::kZeroBound (none: poly_value
// gives 0.0).
bool all_positive_zero(const std::vector<Poly3>& records) {
  return std::all_of(records.begin(), records.end(), [](const Poly3& p) {
    return positive_zero(p.a) && positive_zero(p.b) && positive_zero(p.c) && positive_zero(p.d) &&
           std::abs(p.s) <= PoseTable::kZeroBound;
  });
}

}  // namespace

[[gnu::hot]] size_t PolyRun::index(double s) const {
  const double* it = std::upper_bound(starts, starts + count, s);
  return it == starts ? 0 : static_cast<size_t>(it - starts) - 1;
}

void PoseTable::build(const std::vector<Road>& roads) {
  roads_.clear();
  geometries_.clear();
  polys_.clear();
  keys_.clear();
  for (const Road& road : roads) {
    PoseRoad packed;
    packed.key_first = static_cast<uint32_t>(keys_.size());
    packed.length = road.length;
    packed.has_shapes = !road.shapes.empty();
    packed.zero_offsets = all_positive_zero(road.lane_offsets);
    packed.level = all_positive_zero(road.superelevation);
    packed.geometry_first = static_cast<uint32_t>(geometries_.size());
    packed.geometry_count = static_cast<uint32_t>(road.plan_view.size());
    for (const Geometry& geometry : road.plan_view) {
      geometries_.push_back(PoseGeometry{geometry, std::cos(geometry.hdg), std::sin(geometry.hdg)});
      keys_.push_back(geometry.s);
    }
    const auto append = [&](const std::vector<Poly3>& records, uint32_t& first, uint32_t& count) {
      first = static_cast<uint32_t>(polys_.size());
      count = static_cast<uint32_t>(records.size());
      polys_.insert(polys_.end(), records.begin(), records.end());
      for (const Poly3& record : records) {
        keys_.push_back(record.s);
      }
    };
    append(road.lane_offsets, packed.offset_first, packed.offset_count);
    append(road.elevation, packed.elevation_first, packed.elevation_count);
    append(road.superelevation, packed.roll_first, packed.roll_count);
    roads_.push_back(packed);
  }
}

[[gnu::hot]] const PoseGeometry* PoseTable::geometry_before(const PoseRoad& road, double s) const {
  const double* starts = keys_.data() + road.key_first;
  const double* it = std::upper_bound(starts, starts + road.geometry_count, s);
  return it == starts ? nullptr
                      : &geometries_[road.geometry_first + static_cast<size_t>(it - starts) - 1];
}

[[gnu::hot]] const PoseGeometry& PoseTable::geometry_at(const PoseRoad& road, double s) const {
  const double* starts = keys_.data() + road.key_first;
  const double* it = std::upper_bound(starts, starts + road.geometry_count, s);
  return geometries_[road.geometry_first +
                     (it == starts ? 0 : static_cast<size_t>(it - starts) - 1)];
}

}  // namespace corsa::xodr::detail
