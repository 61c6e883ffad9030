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

[[gnu::hot]] void LaneIndex::add(xodr::LaneNode node, double s, uint32_t entity) {
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

[[gnu::hot]] void LaneIndex::finish() {
  // A strict total order (no NaN s is added, an entity once): every sort gives the same order.
  const auto before = [](const Entry& a, const Entry& b) {
    return a.s < b.s || (a.s == b.s && a.entity < b.entity);
  };
  for (const xodr::LaneNode node : used_) {
    auto& lane = lanes_[node];
    size_t budget = 4 * lane.size() + 16;
    for (size_t k = 1; k < lane.size() && budget > 0; ++k) {
      const Entry entry = lane[k];
      size_t j = k;
      for (; j > 0 && budget > 0 && before(entry, lane[j - 1]); --j, --budget) {
        lane[j] = lane[j - 1];
      }
      lane[j] = entry;
    }
    if (budget == 0) {
      std::sort(lane.begin(), lane.end(), before);
    }
  }
}

[[gnu::hot]] void LaneIndex::order(std::vector<uint32_t>& out) const {
  for (const xodr::LaneNode node : used_) {
    for (const Entry& entry : lanes_[node]) out.push_back(entry.entity);
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

[[gnu::hot]] std::span<const LaneIndex::Entry> LaneIndex::lane(xodr::LaneNode node) const {
  return node < lanes_.size() ? std::span<const Entry>(lanes_[node]) : std::span<const Entry>();
}

}  // namespace corsa::engine::detail
