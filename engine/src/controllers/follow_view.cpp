#include "controllers/follow_view.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "corsa/xodr/map.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

[[gnu::hot]] void FollowView::fill(const SimState& state, uint32_t i) {
  const Entity& entity = state.world.entities[i];
  FollowTarget& target = targets_[i];
  const bool visible = i >= state.controls.size() || state.controls[i].traffic_visible;
  target.present = entity.state().placed && visible;
  target.usable = target.present && entity.state().road.has_value();
  target.generated = generated_[i] != 0;
  if (!target.present) {
    return;
  }
  target.x = entity.state().pose.x;
  target.y = entity.state().pose.y;
  target.h = entity.state().pose.h;
  target.speed = entity.state().speed;
  target.rear = entity.info.box.center_x - 0.5 * entity.info.box.length;
  target.vehicle = entity.info.kind == ObjectKind::kVehicle;
  target.length = entity.info.box.length;
  if (has_shapes_) {
    // Mostly the entity stands where the contacts boxed it after the last moves.
    const OrientedBox* boxed = state.contacts.unmoved_box(i, entity);
    target.shape =
        FlatBox::of(boxed != nullptr ? *boxed : box_of(entity.info.box, entity.state().pose));
    // The reach and offset (hypots) are made again only when the box has changed since they
    // were made: a box of zeros (reach_boxes_' default) has both 0 (their default).
    const Box& box = entity.info.box;
    if (!same_bits(reach_boxes_[i], box)) {
      reach_[i] = std::hypot(0.5 * box.length, 0.5 * box.width);
      offset_[i] = std::hypot(box.center_x, box.center_y);
      reach_boxes_[i] = box;
    }
  }
  if (!target.usable) {
    return;
  }
  const RoadCoordinates& road = *entity.state().road;
  target.road = road.road;
  target.section = road.section;
  target.lane = road.lane;
  target.s = road.s;
  // Mostly the entity is in the lane it follows, whose node it knows.
  const LaneFollow& follow = entity.lane;
  const bool followed = follow.on_road && follow.node != xodr::kNoLane &&
                        follow.road == target.road && follow.section == target.section &&
                        follow.lane == target.lane;
  const xodr::LaneGraph* graph = state.map != nullptr ? &state.map->lane_graph() : nullptr;
  const auto node = followed ? std::optional<xodr::LaneNode>(follow.node)
                    : graph != nullptr
                        ? graph->find(xodr::LaneRef{target.road, target.section, target.lane})
                        : std::nullopt;
  nodes_[i] = node.value_or(xodr::kNoLane);
}

[[gnu::hot]] void FollowView::build(const SimState& state, bool neighbours) {
  begin(state, neighbours);
  const auto count = static_cast<uint32_t>(targets_.size());
  for (uint32_t i = 0; i < count; ++i) fill(state, i);
  finish();
}

void FollowView::begin(const SimState& state, bool neighbours) {
  const auto& entities = state.world.entities;
  const auto count = static_cast<uint32_t>(entities.size());
  targets_.resize(count);
  nodes_.resize(count);
  reach_.resize(count);
  offset_.resize(count);
  reach_boxes_.resize(count);
  unindexed_.clear();
  grid_.clear();
  scenario_vehicles_.clear();
  has_scenario_vehicles_ = false;
  max_reach_ = 0.0;
  max_offset_ = 0.0;
  max_length_ = 0.0;
  has_shapes_ = neighbours;
  const xodr::LaneGraph* graph = state.map != nullptr ? &state.map->lane_graph() : nullptr;
  // The lanes' entities are added in the order of the last index, those not in it after them
  // in index order (LaneIndex::finish).
  lane_order_.clear();
  lanes_.order(lane_order_);
  lanes_.reset(graph != nullptr ? graph->size() : 0);
  least_rear_ = std::numeric_limits<double>::infinity();
  // Which entities traffic generated: lifetimes only ever gain keys, so the set changes only
  // when their number does.
  const auto& lifetimes = state.traffic.lifetimes;
  if (generated_.size() != entities.size() || generated_seen_ != lifetimes.size()) {
    generated_.assign(entities.size(), 0);
    for (const auto& [index, lives] : lifetimes) {
      if (index < generated_.size()) {
        generated_[index] = 1;
      }
    }
    generated_seen_ = lifetimes.size();
  }
}

[[gnu::hot]] void FollowView::finish() {
  const auto count = static_cast<uint32_t>(targets_.size());
  const bool neighbours = has_shapes_;
  for (uint32_t i = 0; i < count; ++i) {
    const FollowTarget& target = targets_[i];
    if (!target.present) {
      continue;
    }
    if (neighbours) {
      grid_.add(target.shape.cx, target.shape.cy, i);
      // NaN stays out of the maxima (std::max keeps the first); the tests of
      // controllers/npc_caution.cpp reject such a box anyway, as a scan would.
      max_reach_ = std::max(max_reach_, reach_[i]);
      max_offset_ = std::max(max_offset_, offset_[i]);
      max_length_ = std::max(max_length_, target.length);
    }
    if (!target.usable) {
      continue;
    }
    // NaN stays out of the minimum (no bound then: see below).
    least_rear_ = std::min(least_rear_, target.rear);
    if (std::isnan(target.rear)) {
      least_rear_ = -std::numeric_limits<double>::infinity();
    }
    if (nodes_[i] == xodr::kNoLane) {
      unindexed_.push_back(i);
    }
  }
  const auto in_lane = [&](uint32_t i) {
    return targets_[i].present && targets_[i].usable && nodes_[i] != xodr::kNoLane;
  };
  in_index_.assign(count, 0);
  for (const uint32_t i : lane_order_) {
    if (i < count && in_lane(i)) {
      lanes_.add(nodes_[i], targets_[i].s, i);
      in_index_[i] = 1;
    }
  }
  for (uint32_t i = 0; i < count; ++i) {
    if (!in_index_[i] && in_lane(i)) {
      lanes_.add(nodes_[i], targets_[i].s, i);
    }
  }
  lanes_.finish();
  if (neighbours) {
    for (uint32_t i = 0; i < targets_.size(); ++i) {
      const FollowTarget& target = targets_[i];
      if (target.present && target.vehicle && !target.generated) {
        scenario_vehicles_.add(target.shape.cx, target.shape.cy, i);
        has_scenario_vehicles_ = true;
      }
    }
  }
  grid_.finish();
  scenario_vehicles_.finish();
}

void FollowView::near(double x_min, double y_min, double x_max, double y_max,
                      std::vector<uint32_t>& out) const {
  grid_.query_box(x_min, y_min, x_max, y_max, out);
}

void FollowView::near_scenario_vehicles(double x_min, double y_min, double x_max, double y_max,
                                        std::vector<uint32_t>& out) const {
  scenario_vehicles_.query_box(x_min, y_min, x_max, y_max, out);
}

}  // namespace corsa::engine::detail
