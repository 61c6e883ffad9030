#include "state/world_update.h"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include "corsa/engine/oriented_box.h"
#include "corsa/xodr/map.h"
#include "state/sim_state.h"

namespace corsa::engine::detail {

namespace {

// The entities whose boxes are not where they were at the last update (moved, appeared, left
// or changed size), into `moved`; records the boxes of now. Returns false when the entities
// are not those of the last update (added or removed): then every box counts as changed.
bool find_moved_boxes(SimState& state, std::vector<uint32_t>& moved) {
  auto& inputs = state.contacts.inputs;
  const auto& entities = state.world.entities;
  moved.clear();
  const bool same_entities = inputs.size() == entities.size();
  inputs.resize(entities.size());
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (!same_entities || !inputs[i].same_as(entities[i])) {
      moved.push_back(i);
      inputs[i] = {entities[i].state.placed, entities[i].state.pose, entities[i].info.box};
    }
  }
  return same_entities;
}

// Whether the entity's box takes part in the contacts.
bool boxed(const Entity& entity) {
  return entity.state.placed && entity.info.box.length > 0.0 && !entity.ghost;
}

// A box in the sweep; the boxes themselves stay apart (`boxes`, by `box`), so that sorting
// moves 40 bytes an item instead of 112.
struct Item {
  double low, high;    ///< extent along x
  double ylow, yhigh;  ///< extent along y
  uint32_t index;      ///< entity
  uint32_t box;        ///< into boxes
};

// Margin (m) by which the y extents are widened before pairs are rejected on them: a pair whose
// boxes the exact test finds overlapping is never rejected for rounding in the extents.
double margin(double v) { return 1e-6 + 1e-12 * std::abs(v); }

bool sweep_order(const Item& a, const Item& b) {
  return a.low < b.low || (a.low == b.low && a.index < b.index);
}

bool y_apart(const Item& a, const Item& b) {
  return b.ylow > a.yhigh + margin(a.yhigh) || a.ylow > b.yhigh + margin(b.yhigh);
}

// !y_apart(a, b) for finite extents, without a branch: most pairs a sweep meets are apart, some
// not, in no pattern a predictor learns (the compiler makes branches of the two comparisons
// however they are combined). For finite u and v, u - v <= 0 exactly when u <= v (a difference
// rounds to 0 only for equal values), so the greater of the two differences is at most 0
// exactly when neither comparison of y_apart holds.
bool y_near_finite(const Item& a, const Item& b) {
  return std::max(b.ylow - (a.yhigh + margin(a.yhigh)), a.ylow - (b.yhigh + margin(b.yhigh))) <=
         0.0;
}

// Calls test(b) for each item b after `a` in `items` (sorted for a sweep) until ends(b) (true
// from some item on), whose pair with a is near(b): the items are gathered by a pass without a
// branch per pair (each index written, the count moved by near), then tested, in the order of
// the sweep.
template <typename Ends, typename Near, typename Test>
void sweep_from(const std::vector<Item>& items, size_t a, Ends ends, Near near, Test test) {
  constexpr size_t kBuffer = 64;
  uint32_t kept[kBuffer];
  size_t count = 0;
  for (size_t b = a + 1; b < items.size() && !ends(items[b]); ++b) {
    kept[count] = static_cast<uint32_t>(b);
    count += static_cast<size_t>(near(items[b]));
    if (count == kBuffer) {
      for (size_t k = 0; k < count; ++k) test(items[kept[k]]);
      count = 0;
    }
  }
  for (size_t k = 0; k < count; ++k) test(items[kept[k]]);
}

// Sorts `items` by `less` (a strict total order), starting from the order of the last sweep
// (`order`, entity indices) when it ran along the same axis: boxes move little in a step, so
// the items are then nearly sorted and an insertion sort takes about one pass. The order is
// unique, so the result is std::sort's. `order` is updated.
template <typename Less>
void sort_from_last(std::vector<Item>& items, std::vector<uint32_t>& order, bool same_axis,
                    size_t entity_count, Less less) {
  if (same_axis && !order.empty()) {
    std::vector<uint32_t> slot(entity_count, UINT32_MAX);
    for (uint32_t k = 0; k < items.size(); ++k) slot[items[k].index] = k;
    std::vector<Item> arranged;
    arranged.reserve(items.size());
    for (const uint32_t entity : order) {
      if (entity < entity_count && slot[entity] != UINT32_MAX) {
        arranged.push_back(items[slot[entity]]);
        slot[entity] = UINT32_MAX;
      }
    }
    for (const Item& item : items) {
      if (slot[item.index] != UINT32_MAX) arranged.push_back(item);  // new since the last sweep
    }
    items.swap(arranged);
    // Insertion sort, given up for std::sort when the order has changed much.
    size_t budget = 8 * items.size() + 64;
    for (size_t k = 1; k < items.size() && budget > 0; ++k) {
      const Item item = items[k];
      size_t j = k;
      for (; j > 0 && less(item, items[j - 1]) && budget > 0; --j, --budget) {
        items[j] = items[j - 1];
      }
      items[j] = item;
    }
    if (budget == 0) std::sort(items.begin(), items.end(), less);
  } else {
    std::sort(items.begin(), items.end(), less);
  }
  order.resize(items.size());
  for (size_t k = 0; k < items.size(); ++k) order[k] = items[k].index;
}

// Records the pairs of `now` (sorted) that `previous` (sorted) does not hold as collisions
// begun at this tick, in entity order.
void record_new_contacts(SimState& state, const std::vector<std::pair<uint32_t, uint32_t>>& now,
                         const std::vector<std::pair<uint32_t, uint32_t>>& previous) {
  for (const auto& pair : now) {
    if (!std::binary_search(previous.begin(), previous.end(), pair)) {
      state.collisions.push_back({state.tick, state.now(), pair.first, pair.second});
    }
  }
}

// The contacts when only the boxes in `sweep.moved` changed since a complete update: the pairs
// of two unmoved boxes are the last update's (neither box changed), and each moved box is
// tested against every other box under the sweep's own filters, so that a pair is tested
// exactly when the sweep would test it, in the sweep's order of the two (the axis chosen as the
// sweep chooses it): the same pairs as a sweep over all boxes. Returns false, having changed
// no pair, when it does not apply: not a complete last update, more moved boxes than pay
// (a sweep is then cheaper), a moved box with extents that are not finite, or a coupled pair
// (a trailer and its tower, whose contacts the sweep sets apart).
bool update_moved_contacts(SimState& state, ContactSweep& sweep) {
  const auto& entities = state.world.entities;
  const size_t count = entities.size();
  const std::vector<uint32_t>& moved = sweep.moved;
  std::vector<OrientedBox>& boxes = state.contacts.boxes;
  // A moved box costs a test of every other box; a sweep costs about a box's making per box.
  constexpr size_t kMovedAlways = 16;
  constexpr size_t kBoxesPerMovedBox = 32;
  if (!sweep.complete || boxes.size() != count || sweep.x_extent.size() != count ||
      (moved.size() > kMovedAlways && moved.size() * kBoxesPerMovedBox > count)) {
    return false;
  }
  for (const Entity& entity : entities) {
    if (entity.towed_by || entity.towing || entity.unhitched_from) {
      return false;
    }
  }
  for (const uint32_t i : moved) {
    if (!boxed(entities[i])) {
      continue;
    }
    boxes[i] = box_of(entities[i].info.box, entities[i].state.pose);
    const Interval x = project(boxes[i], 1.0, 0.0);
    const Interval y = project(boxes[i], 0.0, 1.0);
    if (!std::isfinite(x.low) || !std::isfinite(x.high) || !std::isfinite(y.low) ||
        !std::isfinite(y.high)) {
      return false;  // the sweep's own path for extents without a total order
    }
    sweep.x_extent[i] = x;
    sweep.y_extent[i] = y;
  }
  // The sweep's axis: the spread of all boxes.
  bool any = false;
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  for (uint32_t i = 0; i < count; ++i) {
    if (!boxed(entities[i])) {
      continue;
    }
    const Interval x = sweep.x_extent[i];
    const Interval y = sweep.y_extent[i];
    x0 = any ? std::min(x0, x.low) : x.low;
    x1 = any ? std::max(x1, x.high) : x.high;
    y0 = any ? std::min(y0, y.low) : y.low;
    y1 = any ? std::max(y1, y.high) : y.high;
    any = true;
  }
  const bool along_y = y1 - y0 > x1 - x0;
  sweep.moved_mark.assign(count, 0);
  for (const uint32_t i : moved) {
    sweep.moved_mark[i] = 1;
  }
  std::vector<std::pair<uint32_t, uint32_t>> previous;
  previous.swap(state.contacts.pairs);
  auto& now = state.contacts.pairs;
  for (const auto& pair : previous) {
    if (sweep.moved_mark[pair.first] == 0 && sweep.moved_mark[pair.second] == 0) {
      now.push_back(pair);
    }
  }
  const auto item = [&](uint32_t i) {
    return Item{sweep.x_extent[i].low,
                sweep.x_extent[i].high,
                sweep.y_extent[i].low,
                sweep.y_extent[i].high,
                i,
                i};
  };
  for (const uint32_t m : moved) {
    if (!boxed(entities[m])) {
      continue;
    }
    const Item p = item(m);
    for (uint32_t j = 0; j < count; ++j) {
      // A pair of two moved boxes once, from the lower index.
      if (j == m || !boxed(entities[j]) || (sweep.moved_mark[j] != 0 && j < m)) {
        continue;
      }
      const Item q = item(j);
      const bool p_first = sweep_order(p, q);
      const Item& first = p_first ? p : q;
      const Item& second = p_first ? q : p;
      if (!(second.low <= first.high) || !y_near_finite(p, q)) {
        continue;
      }
      // The sweep tests the pair from the earlier of the two along its axis.
      const bool p_leads =
          along_y ? (p.ylow < q.ylow || (p.ylow == q.ylow && p.index < q.index)) : p_first;
      const bool touching =
          p_leads ? overlap(boxes[p.box], boxes[q.box]) : overlap(boxes[q.box], boxes[p.box]);
      if (touching) {
        now.emplace_back(std::min(m, j), std::max(m, j));
      }
    }
  }
  std::sort(now.begin(), now.end());
  record_new_contacts(state, now, previous);
  return true;
}

}  // namespace

void update_contacts(SimState& state, ContactSweep& sweep) {
  // Nothing moved, appeared or left: the contacts are those of the last update, and none is new.
  const bool same_entities = find_moved_boxes(state, sweep.moved);
  if (sweep.moved.empty()) {
    return;
  }
  if (same_entities && update_moved_contacts(state, sweep)) {
    return;
  }
  const auto& entities = state.world.entities;
  std::vector<std::pair<uint32_t, uint32_t>> previous;
  previous.swap(state.contacts.pairs);
  // Boxes whose extents along x overlap (sweep and prune) are tested exactly. Pairs apart along
  // y (with a rounding margin) cannot overlap and are skipped.
  std::vector<Item> items;
  items.reserve(entities.size());
  // Each box depends only on its entity: made on several threads when the sweep may share
  // them out; gathered below in index order, so the result is the same on any number.
  std::vector<OrientedBox>& boxes = state.contacts.boxes;
  boxes.resize(entities.size());
  sweep.x_extent.resize(entities.size());
  sweep.y_extent.resize(entities.size());
  const auto make_boxes = [&](size_t begin, size_t end) {
    for (size_t i = begin; i < end; ++i) {
      if (!boxed(entities[i])) {
        continue;
      }
      boxes[i] = box_of(entities[i].info.box, entities[i].state.pose);
      sweep.x_extent[i] = project(boxes[i], 1.0, 0.0);
      sweep.y_extent[i] = project(boxes[i], 0.0, 1.0);
    }
  };
  if (sweep.share) {
    sweep.share(entities.size(), make_boxes);
  } else {
    make_boxes(0, entities.size());
  }
  bool finite = true;
  double x0 = 0.0, x1 = 0.0, y0 = 0.0, y1 = 0.0;
  for (uint32_t i = 0; i < entities.size(); ++i) {
    if (!boxed(entities[i])) {
      continue;
    }
    const Interval x = sweep.x_extent[i];
    const Interval y = sweep.y_extent[i];
    finite = finite && std::isfinite(x.low) && std::isfinite(x.high) && std::isfinite(y.low) &&
             std::isfinite(y.high);
    x0 = items.empty() ? x.low : std::min(x0, x.low);
    x1 = items.empty() ? x.high : std::max(x1, x.high);
    y0 = items.empty() ? y.low : std::min(y0, y.low);
    y1 = items.empty() ? y.high : std::max(y1, y.high);
    items.push_back({x.low, x.high, y.low, y.high, i, i});
  }
  auto& now = state.contacts.pairs;
  std::vector<std::pair<uint32_t, uint32_t>> touching;  // coupled pairs whose boxes overlap
  // A trailer and the vehicle towing it meet at the hitch (also for a while after they were
  // disconnected, until they part): that is no collision.
  const auto record = [&](const Item& p, const Item& q) {
    const Entity& first = entities[p.index];
    const bool coupled = first.towed_by == q.index || first.towing == q.index ||
                         first.unhitched_from == q.index ||
                         entities[q.index].unhitched_from == p.index;
    (coupled ? touching : now).emplace_back(std::min(p.index, q.index), std::max(p.index, q.index));
  };
  auto& order = sweep.order;
  if (finite && y1 - y0 > x1 - x0) {
    // Spread more along y (a road running north): sweep along y instead, and test a pair when
    // the x sweep would have (the later of the two in x order starts before the earlier ends).
    sort_from_last(items, order, sweep.along_y, entities.size(), [](const Item& a, const Item& b) {
      return a.ylow < b.ylow || (a.ylow == b.ylow && a.index < b.index);
    });
    sweep.along_y = true;
    for (size_t a = 0; a < items.size(); ++a) {
      const Item& p = items[a];
      const double reach = p.yhigh + margin(p.yhigh);
      sweep_from(
          items, a, [&](const Item& q) { return !(q.ylow <= reach); },
          [&](const Item& q) {
            // sweep_order(p, q), and the x extents' test for the pair in that order.
            const bool p_first = (p.low < q.low) | ((p.low == q.low) & (p.index < q.index));
            const double first_high = p_first ? p.high : q.high;
            const double second_low = p_first ? q.low : p.low;
            return (second_low <= first_high) & y_near_finite(p, q);
          },
          [&](const Item& q) {
            if (overlap(boxes[p.box], boxes[q.box])) record(p, q);
          });
    }
  } else {
    if (finite) {
      sort_from_last(items, order, !sweep.along_y, entities.size(), sweep_order);
      sweep.along_y = false;
    } else {
      // NaN or infinite extents: no total order to start from.
      std::sort(items.begin(), items.end(), sweep_order);
      order.clear();
    }
    for (size_t a = 0; a < items.size(); ++a) {
      const Item& p = items[a];
      const auto ends = [&](const Item& q) { return !(q.low <= p.high); };
      const auto test = [&](const Item& q) {
        if (overlap(boxes[p.box], boxes[q.box])) record(p, q);
      };
      if (finite) {
        sweep_from(
            items, a, ends, [&](const Item& q) { return y_near_finite(p, q); }, test);
      } else {
        sweep_from(
            items, a, ends, [&](const Item& q) { return !y_apart(p, q); }, test);
      }
    }
  }
  // A disconnected trailer that no longer touches its former tower can collide with it again.
  for (uint32_t i = 0; i < entities.size(); ++i) {
    const auto other = state.world.entities[i].unhitched_from;
    if (!other) continue;
    const bool still = std::any_of(touching.begin(), touching.end(), [&](const auto& pair) {
      return (pair.first == i && pair.second == *other) ||
             (pair.first == *other && pair.second == i);
    });
    if (!still) state.world.entities[i].unhitched_from.reset();
  }
  // Entity order, independent of the sweep order; new contacts are recorded in that order.
  std::sort(now.begin(), now.end());
  record_new_contacts(state, now, previous);
  sweep.complete = finite;
}

namespace {

// Off the road: on no lane, or on a lane of type none. OpenDRIVE 1.8 §9.5.3: a lane of type none
// "describes the space on the outermost edge of the road and does not have actual content. Its
// only purpose is for applications to register that ASAM OpenDRIVE is still present in case the
// (human) driver leaves the road". esmini's OffroadCondition counts it off the road too (the road
// width without such lanes).
bool off_road(const SimState& state, const Entity& entity) {
  if (!entity.state.road) return true;
  if (state.map == nullptr || entity.state.road->lane == 0) return false;
  const RoadCoordinates& at = *entity.state.road;
  const LaneFollow& follow = entity.lane;
  if (follow.node != xodr::kNoLane && follow.road == at.road && follow.section == at.section &&
      follow.lane == at.lane) {
    // The lane it follows (nearly always): its type from the lane graph's node, one read
    // instead of a search through the road's lanes every step.
    return state.map->lane_graph().info(follow.node).type == xodr::LaneType::kNone;
  }
  const xodr::Lane* lane = state.map->lane(xodr::LaneRef{at.road, at.section, at.lane});
  return lane != nullptr && lane->type == xodr::LaneType::kNone;
}

// Below this speed (m/s) an entity stands still. StandStillCondition (1.3): true "if the
// triggering entity/entities stands still for a given amount of time"; the text names no speed,
// and an entity slowed by a controller or a relative target only nears 0. esmini's threshold
// (ScenarioEngine.cpp STAND_STILL_THRESHOLD, -1e-3 < v < 1e-3), taken under both readings, as
// every reading the standard leaves open.
constexpr double kStandStillSpeed = 1e-3;

}  // namespace

void update_timers(SimState& state, bool advance) {
  const double dt = advance ? state.time.dt() : 0.0;
  for (Entity& entity : state.world.entities) {
    // Each timer counts the time since its condition began: 0 at the first tick it holds.
    const bool was_still = entity.standing_still;
    entity.standing_still = std::abs(entity.state.speed) < kStandStillSpeed;
    entity.standstill_time =
        entity.standing_still ? (was_still ? entity.standstill_time + dt : 0.0) : 0.0;
    const bool offroad = off_road(state, entity);
    entity.offroad_time = offroad ? (entity.was_offroad ? entity.offroad_time + dt : 0.0) : 0.0;
    entity.was_offroad = offroad;
    entity.end_of_road_time =
        entity.end_of_road ? (entity.was_at_end ? entity.end_of_road_time + dt : 0.0) : 0.0;
    entity.was_at_end = entity.end_of_road;
  }
}

}  // namespace corsa::engine::detail
