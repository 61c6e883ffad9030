#include "state/lane_index.h"

#include <algorithm>
#include <cmath>

namespace corsa::engine::detail {

void LaneIndex::reset(size_t nodes) {
  for (const xodr::LaneNode node : used_) {
    if (node < lanes_.size()) {
      lanes_[node].clear();
    }
  }
  used_.clear();
  lanes_.resize(nodes);
  size_ = 0;
}

void LaneIndex::add(xodr::LaneNode node, double s, uint32_t entity) {
  if (node >= lanes_.size() || std::isnan(s)) {
    return;  // NaN: no range holds it
  }
  auto& lane = lanes_[node];
  if (lane.empty()) {
    used_.push_back(node);
  }
  lane.push_back({s, entity});
  ++size_;
}

void LaneIndex::finish() {
  for (const xodr::LaneNode node : used_) {
    auto& lane = lanes_[node];
    std::sort(lane.begin(), lane.end(), [](const Entry& a, const Entry& b) {
      return a.s < b.s || (a.s == b.s && a.entity < b.entity);
    });
  }
}

void LaneIndex::query(xodr::LaneNode node, double s_low, double s_high,
                      std::vector<uint32_t>& out) const {
  if (node >= lanes_.size()) {
    return;
  }
  const auto& lane = lanes_[node];
  auto it = std::lower_bound(lane.begin(), lane.end(), s_low,
                             [](const Entry& e, double s) { return e.s < s; });
  for (; it != lane.end() && it->s <= s_high; ++it) {
    out.push_back(it->entity);
  }
}

std::span<const LaneIndex::Entry> LaneIndex::lane(xodr::LaneNode node) const {
  return node < lanes_.size() ? std::span<const Entry>(lanes_[node]) : std::span<const Entry>();
}

}  // namespace corsa::engine::detail
